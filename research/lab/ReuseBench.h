// `frugal-lab reuse-bench`'s measurement: what temporal reuse (paper 000, src/reuse/Reuse.h) saves,
// frame by frame. Per frame four renders are timed back to back: the full render, the reuse frame
// (the planner's plan and its execution), and two oracles, each the frame's static image (rendered
// beforehand, untimed) copied and only the dynamic instances drawn on it: no static triangle
// redrawn, no ⊗ test, no copy back.
//  - The cells oracle (oracle_ms, the main floor) copies only what reuse copies: the cells the
//    planner cleared or copied (where anything dynamic was or is), the whole image on frames that
//    are no reuse frame. It is the floor for reuse at this cell size, the tighter of the two.
//  - The whole oracle (oracle_whole_ms) copies the whole image every frame (one full-target copy):
//    the literal definition, the floor no reuse method can beat.
// The planner (and the cells oracle) are stateful, so the whole sequence is run K times (one
// untimed warm-up round, then `repeat` rounds), each round with a fresh planner; per frame the
// medians over the rounds. The warm-up round also checks every reuse frame (and both oracles'
// frames) against the full render of the same frame (lab/ReuseCheck.h).
#pragma once

#include <functional>
#include <optional>
#include <string>

#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>

#include "lab/ReuseReport.h"
#include "renderer/Research.h"

namespace frugal {

struct ReuseBenchSettings {
    std::string scene;  // the scene's name in the report
    // The stage (size, backend, threads, interp, depth format, background); ids (written in every
    // render, and compared); cull, the list full and reuse frames draw (none, sphere, backface,
    // cones, paper or conservative; not oracle), with its bins; reuseSettings, the planner's.
    // order, hsr, reuse and refineCosts are not read.
    Settings render;
    int firstFrame = 0, lastFrame = 0;  // inclusive; the first has no predecessor (a rebuild)
    int repeat = 5;                     // timed rounds, after the warm-up round
};

struct ReuseMeasurement {
    ReuseBench report;
    // The first frame whose cells oracle or whole oracle differs from the full render other than by
    // a tie: "frame 3: the oracle differs from the full render at 12 pixels (depth)". Either oracle
    // is then no floor of anything.
    std::optional<std::string> oracleError;
};

// Prepares the culling (reordering `scene`'s meshes), opens the stage, uploads `scene` and makes
// five more targets (the reuse frame's, its static pair, the two oracles' and their static image),
// then runs the rounds. `progress` receives the culling's line ("cull: 1 mesh, ..."), the backend's
// ("backend: egl-surfaceless (...)"), one per frame of the warm-up round and one per timed round.
// Errors: Stage::open's and the upload's; "size WxH: the benchmark needs about 1.3 GB more (...)"
// (OutOfMemory) and "size WxH: <backend> could not create the benchmark's six targets (...)",
// both about the size setting; "frame N: <setupOf's error>".
Result<ReuseMeasurement> measureReuse(Scene& scene, const ReuseBenchSettings& settings, const FrameSetupOf& setupOf,
                                      const std::function<void(const std::string&)>& progress);

// What makes a measured run fail once its report is out: the oracle's error, else the first frame
// whose reuse frame differs from the full render other than by a tie ("frame 3: reuse differs from
// the full render at 12 pixels (depth)"); nothing when every frame is exact. Such a difference is a
// bug, never a trade-off.
std::optional<Error> reuseFailure(const ReuseMeasurement& measured);

}  // namespace frugal
