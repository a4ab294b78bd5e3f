// `frugal-lab bench render`'s measurement: the same frame on every available backend, and with the
// vertex-cache triangle order beside the file's, in one process. Timings cover clear + draw +
// glFinish (no read-back), after warm-up frames that let llvmpipe compile its shaders.
//
// On a GL backend the same frame is also drawn by the minimal GL program (lab/MinimalFrame.h) on a
// context of the same kind, and the timed frames alternate frugal, minimal, frugal, ... so that the
// machine's noise (this runs on shared cores) hits both alike; the context switch between them is
// made before the clock starts. "over_minimal" is frugal ÷ minimal: the backend's overhead.
// In the cache order three more variants are timed in the same loop: "unbatched" (one draw per
// instance), "premerged" (the floor of batching: the instances pre-transformed into one mesh per
// material) and the other depth format (d24 or d32f) into a target of its own.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <frugal/Camera.h>
#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>

namespace frugal {

struct RenderBenchSettings {
    std::string scene;  // the scene's name in the report and in messages
    // The stage (size, threads, interp, depth format, background); backend: one kind, or Auto for
    // egl-device, egl-surfaceless, osmesa and the software reference in turn (a kind that does not
    // open here is skipped). ids (the id pass), hsr (its plan timed with the frame; the minimal
    // program stays z-buffered) and order (with paper, greedy and best the costs are measured on
    // each backend, once per triangle order). cull, reuse and refineCosts are not read.
    Settings render;
    int runs = 30;    // timed frames per variant
    int warmup = 5;   // untimed frames first
    Camera camera;    // the frame's camera
    double time = 0;  // and its scene time
};

// One row of the report: a backend, a triangle order, a variant and its frame times.
struct RenderBenchSample {
    std::string backend, renderer;
    std::string order;    // "optimized" (vertex-cache order) or "file"
    std::string variant;  // "frugal", "minimal", "unbatched", "premerged", or the other depth format's name
    std::vector<double> ms;
    std::optional<bool> pixelsEqual;  // minimal: the same colour image as frugal's
    // unbatched, premerged, the other depth format: against frugal's image; frugal (cache order):
    // where its order changed the image from submission order (exact depth ties)
    std::optional<std::size_t> pixelsDiffering;
};

struct RenderBench {
    RenderBenchSettings settings;
    std::size_t triangles = 0;
    std::vector<RenderBenchSample> samples;  // per backend: cache order's rows, then the file order's
    std::vector<std::string> skipped;        // why a backend, a minimal program or a depth format is missing
};

// Measures `cacheOrder` and `fileOrder` (one scene loaded with and without the vertex-cache
// reordering) on every backend of the settings. `progress` receives each backend's cost line
// ("order best: state costs on ...") and medians ("egl-surfaceless optimized: median 0.2 ms").
// Errors: "<scene>: <camera problem>", Stage::open's other than an unavailable backend (about a
// setting), the upload's, "order best: <why>" (about a setting), "bench: the premerged scene:
// <why>"; "bench: no backend available: [why] [why]" (BackendUnavailable).
Result<RenderBench> measureRenderBench(const Scene& cacheOrder, const Scene& fileOrder,
                                       const RenderBenchSettings& settings,
                                       const std::function<void(const std::string&)>& progress);

// The report, indented by 2: {"command","scene","size","triangles","ids","hsr","draw_order",
// "depth_format","runs","warmup","threads","lp_num_threads","results":[{"backend","renderer",
// "order","variant","median_ms","min_ms","max_ms","triangles_per_second","minimal_pixels_equal",
// "pixels_differing"}],"ratios":{"file_over_optimized","over_<first backend>","over_minimal",
// "over_minimal_file_order","unbatched_over_batched","over_premerged","d32f_over_d24"},"skipped"},
// keys sorted, with a final line break.
std::string renderBenchJson(const RenderBench& bench);

}  // namespace frugal
