// `frugal-lab hsr-bench`'s measurement: paper 003's hidden-surface modes (src/hsr/Plan.h) against the
// z-buffer on one backend. Per frame every mode plans and draws the same frame back to back (the
// first mode rotating from frame to frame, so that drift in the machine's speed hits all alike),
// each timed from the plan to glFinish; then each image is read back (untimed) and compared with the
// z-buffer's, colour, tolerance 0. The plan's time is part of the frame's: it is what the method
// costs on the CPU that the paper's IPAQ also ran it on.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>

#include "lab/HsrReport.h"
#include "lab/ImageCompare.h"
#include "renderer/Research.h"

namespace frugal {

struct HsrBenchSettings {
    std::string scene;           // the scene's name in the report
    Settings render;             // the stage: size, backend, threads, interp, depth format, background
    int firstFrame = 0, lastFrame = 99;
    int repeat = 1;              // timed draws of each mode per frame
    int warmup = 3;              // untimed rounds of the first frame in every mode
    bool worstImages = false;    // keep the worst frame's images of depthsort, adaptive, adaptive-convex
};

// A mode's frame with the most pixels differing from the z-buffer's, drawn again and compared.
struct HsrWorstImages {
    std::string mode;            // depthsort, adaptive, adaptive-convex
    Buffers actual, reference;   // the mode's image, the z-buffer's
    ImageComparison compared;    // actual against reference (for the mask)
};

struct HsrBenchResult {
    HsrReport report;
    std::vector<HsrWorstImages> worst;  // with settings.worstImages
};

// Opens the stage, uploads `scene` and measures every frame. `progress` receives the backend line
// ("backend: egl-surfaceless (...)") and a line every tenth frame ("frame 9 (10/100)"). Errors:
// Stage::open's (about a setting), the upload's, setupOf's; "masks: <why>" (about a setting).
Result<HsrBenchResult> measureHsr(const Scene& scene, const HsrBenchSettings& settings, const FrameSetupOf& setupOf,
                                  const std::function<void(const std::string&)>& progress);

}  // namespace frugal
