// `frugal-lab pose-bench`'s measurement: what deforming meshes (skins, morph targets) cost a frame.
// The scene as it is ("deforming": every frame at a new time, so every deforming instance is posed
// on the CPU and its vertices written in place) and, beside it, the same scene with its skins and
// morph targets taken away ("rest pose": the same meshes, still), the frames timed interleaved on
// stages of their own, at the same times, with the same camera. Without a SCENE it times a tube of
// 100,000 triangles on a chain of 64 joints that all turn (poseBenchTube), the case of the skinning
// goal: at most 1.2x the rest pose's frame on the GL path.
#pragma once

#include <functional>
#include <string>

#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>

#include "lab/ReportText.h"
#include "renderer/Research.h"

namespace frugal {

struct PoseBenchSettings {
    std::string scene;  // the scene's name in the report
    Settings render;
    int repeat = 60;  // timed frames per variant, at times spread over the scene's animation
    int warmup = 3;   // untimed frames per variant first
};

// A tube along y of `rings` × `segments` quads (2 triangles each), its vertices weighted to the two
// nearest of `joints` joints in a chain, every joint turning about z by up to `angle` radians over 2 s.
Scene poseBenchTube(int rings = 1250, int segments = 40, int joints = 64, float angle = 0.02f);

// json: {"command","scene","size","backend","renderer","runs","deforming_instances","vertices_posed",
// "rows":[{"variant","median_ms","min_ms","max_ms","over_rest"}]}; csv: one row per variant; text:
// one line per variant. Error: a scene without deforming meshes; the stage's; the upload's.
Result<BenchTexts> measurePoses(const Scene& scene, const FrameSetup& setup, const PoseBenchSettings& settings,
                                const std::function<void(const std::string&)>& progress);

// The gnuplot script that draws the CSV at `csvPath` into `svgPath`: each variant's median frame time.
std::string poseBenchGnuplot(const std::string& csvPath, const std::string& svgPath, const std::string& scene);

}  // namespace frugal
