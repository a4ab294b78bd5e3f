// The report of `frugal-lab hsr-bench` (paper 003's hidden-surface modes against the z-buffer): per
// mode the frame times, the plan's share of them, the pixels that differ from the z-buffer render
// and the share of polygons drawn with the depth test; beside each, the paper's Table 1.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace frugal {

struct HsrModeResult {
    std::string mode;                      // "zbuffer", "depthsort", "adaptive"
    std::vector<double> ms;                // per timed frame: plan + draw + finish
    std::vector<double> planMs;            // per timed frame: the plan alone (0 for zbuffer)
    std::vector<std::size_t> differingPx;  // per frame: colour pixels that differ from zbuffer's
    std::vector<double> zbufferedShare;    // per frame: depth-tested polygons ÷ drawn polygons
    std::vector<std::size_t> polygons;     // per frame: polygons drawn (0 for zbuffer: not grouped)
    std::vector<std::size_t> draws;        // per frame: draw commands (backend draw calls)
};

struct HsrReport {
    std::string scene, backend, renderer;
    int width = 0, height = 0;
    int firstFrame = 0, lastFrame = 0, repeat = 1;
    std::size_t polygons = 0;  // the scene's, over all instances
    std::size_t triangles = 0;
    std::vector<HsrModeResult> modes;  // zbuffer first
};

// Paper 003, Table 1 (IPAQ 3660, 28 cubes, 240×320): frames per second, or 0 for an unknown mode.
double paperFps(const std::string& mode);

// Per mode: fps = 1000 ÷ mean ms; speed-up = fps ÷ zbuffer's fps; differing_px summed over frames.
struct HsrModeSummary {
    std::string mode;
    double fps = 0.0, medianMs = 0.0, minMs = 0.0, maxMs = 0.0, planMs = 0.0, speedup = 0.0;
    double paperFps = 0.0, paperSpeedup = 0.0;  // 0 when the paper has none
    std::size_t differingPx = 0, worstFramePx = 0, framesDiffering = 0;
    double flaggedShare = 0.0;  // mean over frames
    double draws = 0.0;         // median over frames
};
std::vector<HsrModeSummary> summarizeHsr(const HsrReport& report);

// {"scene","size","backend","renderer","frames","repeat","polygons","triangles",
//  "modes":[{"mode","fps","median_ms","min_ms","max_ms","plan_ms","speedup","paper_fps",
//            "paper_speedup","differing_px","worst_frame_px","frames_differing","flagged_share","draws",
//            "per_frame":{"ms":[...],"plan_ms":[...],"differing_px":[...],"flagged_share":[...],
//                         "polygons":[...],"draws":[...]}}]}
std::string hsrReportJson(const HsrReport& report);
// One row per mode, the summary's columns.
std::string hsrReportCsv(const HsrReport& report);
// Measured and paper speed-up over the z-buffer per mode, as bars.
std::string hsrReportGnuplot(const std::string& csvPath, const std::string& svgPath, const HsrReport& report);
// The table printed on the terminal.
std::string hsrReportText(const HsrReport& report);

}  // namespace frugal
