// The culling-accuracy report (`frugal cull-report`): per view and method the set sizes, misses,
// waste, pixel error and times, written as JSON, CSV and a gnuplot script that plots the CSV.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace frugal {

struct MethodResult {
    std::string method;  // none, sphere, ..., occlusion, occlusion-ahead, oracle
    std::size_t tos = 0, pvs = 0, rvs = 0, misses = 0, waste = 0;
    std::size_t pixelsDiffering = 0;   // colour, against the full render of the view, tolerance 0
    double cullMs = 0.0;               // CPU time to make the plan (median of the repeats)
    double drawMs = 0.0;               // clear + draw + finish (median of the repeats)
    double ratioToOracle = 0.0;        // (cull + draw) / oracle draw
    double ratioToFull = 0.0;          // (cull + draw) / full draw
    double ratioToFullCullface = 0.0;  // (cull + draw) / full draw with GL back-face culling on
};

// What the occlusion pass did on one view (cull/Occlusion.h): over the timed frames, and in one more
// untimed pass made to run whatever its policy says (what it removes when it runs, and its buffer).
struct OcclusionView {
    int runs = 0, frames = 0;          // timed frames in which the pass ran, of all timed frames
    double passMs = 0.0;               // median time of the pass where it ran (0: never)
    std::size_t trianglesHidden = 0;   // of the conservative plan (the untimed pass)
    std::size_t clustersHidden = 0, clustersTested = 0;
    std::int64_t drawsSaved = 0;       // the draws its plan no longer makes
    double savedMs = 0.0;              // its estimate of the draw time it saves (triangles and draws × cost)
    std::string image;                 // the buffer's file (--masks), relative to the report; empty: none
};

struct ViewResult {
    int index = 0;
    std::string viewClass;  // "whole", "partial", "grazing", "inside", "pole", "camera", "path"
    glm::vec3 eye{0.0f}, target{0.0f};
    std::vector<MethodResult> methods;
    std::optional<OcclusionView> occlusion;  // when the occlusion method was measured
};

struct CullReport {
    std::string scene;
    int width = 0, height = 0;
    std::string backend;
    std::string timing;  // "cold" (independent views) or "path" (each view with its predecessors' history)
    std::vector<ViewResult> views;
};

// {"scene","size":[w,h],"backend","timing","views":[{"index","class","eye","target","methods":[{
//   "method","tos","pvs","rvs","misses","waste","pixels_differing","cull_ms","draw_ms",
//   "ratio_to_oracle","ratio_to_full","ratio_to_full_cullface"}],
//   "occlusion" (with the occlusion method):{"runs","frames","pass_ms","triangles_hidden",
//   "clusters_hidden","clusters_tested","draws_saved","saved_ms_estimate","image" (null: none)}}],
//  "summary":{METHOD:{"views","median_pvs","median_cull_ms","median_draw_ms","median_ratio_to_oracle",
//   "median_ratio_to_full","median_ratio_to_full_cullface","median_cull_over_draw" (of cull ÷ draw per
//   view: the share of the frame culling takes),"worst_view":{"index","class","ratio_to_oracle"},
//   "total_misses","total_pixels_differing","views_with_misses"}},
//  "by_class":{CLASS:{METHOD:{"views","tos","median_pvs","median_speed_up" (full draw ÷ (cull + draw)),
//   "median_speed_up_over_cullface","total_misses","total_pixels_differing"}}}}
// Medians of an even count are the mean of the two middle values.
std::string cullReportJson(const CullReport& report);

// One header line, then one row per view and method:
// view,class,method,tos,pvs,rvs,misses,waste,pixels_differing,cull_ms,draw_ms,ratio_to_oracle,
// ratio_to_full,ratio_to_full_cullface
std::string cullReportCsv(const CullReport& report);

// A gnuplot script (gnuplot-nox: the svg terminal) that reads `csvPath` and draws into `svgPath`
// two plots: time (cull + draw, ms) against misses per method, and per-view bars of ratio_to_oracle
// per method. Paths are written as given (quoted for gnuplot).
std::string cullReportGnuplot(const std::string& csvPath, const std::string& svgPath);

}  // namespace frugal
