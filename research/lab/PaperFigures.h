// The seed papers' published results, for the reports that print them beside ours. Typed once, here,
// from the papers' tables (each figure names its paper, table and setting); every other figure a
// report prints is measured in its own run.
//
//   000: Temporal coherence z-buffer (reuse): software, Pentium II 266 MHz, 50 frames a model.
//   002: Visible sets in spherical coordinates with a convex hull (cull paper): 800x600, Quadro FX5500.
//   003: Adaptive z-buffer (hsr adaptive, depthsort): 28 cubes (168 polygons), 240x320, fixed point.
//   004: Render-state change cost (order key: the high-cost-state sort): a simulation in cost units.
//   001 (the span engine, interp span) has a throughput and a worked example, no result table.
#pragma once

#include <string>
#include <vector>

namespace frugal {

// Paper 003, Table 1, frames a second on the IPAQ 3660 (206 MHz ARM SA1110).
namespace paper003 {
inline constexpr double kZBufferFps = 14.20;
inline constexpr double kDepthSortFps = 52.13;
inline constexpr double kAdaptiveFps = 27.83;
}  // namespace paper003

// One published comparison: a method against the paper's own baseline, as a time ratio (the method's
// time per frame ÷ the baseline's; below 1 is faster), and what the figure counts.
struct PaperFigure {
    std::string method;    // the report's candidate it stands beside ("cull paper", "reuse", ...)
    std::string paper;     // "002"
    std::string source;    // "Table 1, Stanford Bunny, partial views"
    std::string setting;   // machine and scene
    std::string baseline;  // "97 fps, 144,046 triangles"
    std::string result;    // "295 fps, 41,156 triangles"
    double timeRatio = 0;  // result time ÷ baseline time
    std::string unit;      // what the ratio is of: "frame time", "state-change cost (simulated units)"
};

const std::vector<PaperFigure>& paperFigures();

}  // namespace frugal
