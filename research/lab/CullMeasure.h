// `frugal cull-report`'s measurement: every culling method on a set of views, each judged against
// the full render of that view on the same backend. The full render's id image gives the really
// visible set (RVS), its colour image the pixels a method changed. Times are medians of interleaved
// repeats (every method once per round, so machine noise hits all alike), with three baselines
// timed in the same rounds: the full draw, the full draw with GL back-face culling on (the fair
// baseline), and the oracle (the RVS from index buffers of its own, built before timing).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <frugal/Renderer.h>
#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>

#include "lab/Views.h"
#include "renderer/Research.h"
#include "lab/CullReport.h"

namespace frugal {

struct CullMeasureSettings {
    std::string scene;  // the scene's name in the report
    // The stage (size, backend, threads, interp, depth format, background), the map's bins
    // (cullBinsTheta × cullBinsPhi) and the hidden-surface mode every row draws in (hsr; the
    // reference stays the z-buffered full render). cull, order and reuse are not read.
    Settings render;
    std::vector<Cull> methods;  // the rows of each view, in this order
    int repeat = 5;             // timed rounds per view (after one untimed warm-up round)
    double time = 0.0;          // scene time of every view
    std::string timing = "cold";  // "cold" (independent views) or "path" (a camera path, in order)
    // Not empty: the occlusion buffer of each view goes to MASKS/occlusion-view-<v>.png (images).
    std::string masksDir;
};

// The report's JSON document (cullReportJson's, with "preprocess", "repeat", "hsr" and "renderer"
// added), and the report itself.
struct CullMeasurement {
    CullReport report;
    std::string json;
    std::vector<std::pair<std::string, Bytes>> images;  // path (masksDir/...), PNG bytes
};

// Prepares the culling on `scene` (reordering its meshes), opens the stage, uploads and measures
// every view. `progress` receives the preparation line ("cull: 1 mesh, ..."), the backend line
// ("backend: egl-surfaceless (...)") and one line per view. Errors: Stage::open's (about a
// setting), "<scene>: <why>" for an upload the backend refuses, "view 3 (grazing): <why>".
Result<CullMeasurement> measureCulling(Scene& scene, const std::vector<ReportView>& views,
                                       const CullMeasureSettings& settings,
                                       const std::function<void(const std::string&)>& progress);

// "cull: 1 mesh, 69666 triangles prepared in 31.2 ms (sphere 2.1, map 9.8, clusters 5.3, hull 14)"
// (the hull only when it was built); no newline.
std::string cullPreparedLine(const Scene& scene, const Renderer::CullPreparation& prep);

// Builds the culling maps of `scene` (reordering its meshes' triangles: before the upload) and
// gives `progress` the preparation line (cullPreparedLine).
SceneCuller prepareCulling(Scene& scene, const MapParams& bins,
                           const std::function<void(const std::string&)>& progress);

// The summary `frugal cull-report` prints: a line per method, then per view class and method.
std::string cullReportSummary(const CullMeasurement& measured, const std::vector<Cull>& methods);

}  // namespace frugal
