// `frugal-lab soak`'s runs: many frames and many create/destroy cycles in one process, on every
// backend, with resident memory sampled and every image checked (lab/SoakReport.h says what is
// judged). The frames are rendered by frugal::Renderer, the library's entry point that `frugal
// render` runs, so whatever it keeps per frame the soak sees; the create/destroy cycles open
// stages (renderer/Stage.h: backend, target, uploads) as the renderer does.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <frugal/Camera.h>
#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>

#include "lab/SoakReport.h"

namespace frugal {

struct SoakSettings {
    std::string scene;  // the scene's name in the report
    // The stage of every run (size, threads, interp, depth format, background); backend: one kind,
    // or Auto for every backend that opens here (software, egl-device, egl-surfaceless, osmesa).
    Settings render;
    Camera camera;
    std::optional<double> time;  // every frame at this scene time, else frames loop over `period`
    double fps = 30.0;           // scene time of frame f: (f mod period) / fps
    int period = 1;              // frames per loop of the animation
    std::int64_t firstFrame = 0;              // frame f (f = firstFrame, ...) is drawn at scene time
    std::int64_t frames = 100000, cycles = 1000;  // (f mod period) / fps; frames per backend
    std::optional<std::int64_t> warmup;       // default 1 % of frames, at least one period
    std::optional<std::int64_t> sampleEvery;  // default frames / 1000, at least 1
    bool ids = false;
    bool minimal = false;  // the frames drawn by lab/MinimalFrame.h instead of the Renderer; no cycles
    double maxGrowthPct = 5.0;
};

// VmRSS and VmHWM from /proc/self/status; nothing when they cannot be read (not Linux).
std::optional<MemoryUse> currentMemoryUse();

// Runs the frames, then the cycles, of every backend. `progress` receives a line every few seconds
// at most ("egl-surfaceless: frame 2000 of 100000, RSS 89.2 MiB, 0 mismatched"). A run that fails
// its checks is in the report (passed() judges it); errors are what stops a run: a frame that
// cannot be rendered, "soak: no backend available" (BackendUnavailable), "minimal: <why>", "soak:
// cannot read VmRSS and VmHWM from /proc/self/status (Linux only)".
Result<SoakReport> runSoak(const Scene& scene, const SoakSettings& settings,
                           const std::function<void(const std::string&)>& progress);

}  // namespace frugal
