// `frugal-lab span-bench`'s measurement: the bit-level model of paper 001's shading engine
// (src/span/) — Fig. 11 under every scheme of fig11Schemes(), the error table of the
// interpolators against the exact line (lab/ErrorTable.h), the spans per second of the model beside
// the paper's 59,000 — and, on whole scenes, the software backend's --interp modes against its exact
// render: how span and dda depart from it, and how fast the slow path runs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <frugal/Result.h>

#include "lab/ErrorTable.h"
#include "lab/Fig11.h"

namespace frugal::span {

constexpr int kBenchRenders = 5;          // frames timed per scene and mode; the best one counts
constexpr int kMaxBenchRenderSize = 16384;  // the software backend's largest target, a side

struct BenchSettings {
    ErrorTableSettings table;  // the error table; its seed, DDA register and methods also drive the speeds
    int speedMs = 100;         // each spans-per-second figure timed this long; 0 measures none
    std::vector<std::string> scenes;  // specs as loadScene takes them (OBJ drawn single-sided); may be empty
    int renderWidth = 800, renderHeight = 600;  // every scene's image, 1..kMaxBenchRenderSize a side
};

// fillSpan's speed in one method and span length.
struct SpeedRow {
    Method method;
    int length;
    double spansPerSecond;
};

// One scene rendered in one --interp mode, against the same scene in exact.
struct RenderRow {
    std::string scene;
    int width = 0, height = 0;
    Interp mode = Interp::Exact;
    std::size_t colourPx = 0;        // pixels whose colour differs from exact
    std::size_t idPx = 0;            // pixels another triangle won
    std::uint32_t worstLsb = 0;      // depth, over covered pixels (exact's ids not 0)
    double meanLsb = 0.0;            // depth, over covered pixels
    std::size_t depthChangedPx = 0;  // pixels whose depth differs, anywhere
    std::uint64_t overflow = 0;      // slow-path calls that overflowed, one frame
    std::uint64_t spans = 0;         // slow-path calls (fillSpan), one frame
    double frameMs = 0.0;            // best of kBenchRenders
    double exactFrameMs = 0.0;
    double spansPerSecond = 0.0;     // spans / (frameMs / 1000)
};

struct BenchReport {
    ErrorTableSettings settings;     // the table's, as run
    std::vector<Fig11Result> fig11;  // fig11Schemes()' order: the engine's scheme first
    std::vector<ErrorRow> errors;    // errorTable's rows
    std::optional<double> engineSpeed;  // engineSpansPerSecond; none when speedMs is 0
    std::vector<SpeedRow> speeds;       // by method, then length (settings' order); empty when speedMs is 0
    std::vector<RenderRow> render;      // per scene in order: exact, span, dda
};

// The first setting out of range, as an error about it (Error::aboutSetting, kind BadInput), or none:
//   "dda-bits 24: the DDA register must be wider than every width (24 bits) to hold a fraction"
//   "lengths 1: a span length is 2 to 61440 pixels", "widths 30: a width is 1 to 28 bits",
//   "dda-bits 63: the DDA register is 2 to 62 bits", "render-size 0x600: each side is 1 to 16384 pixels".
std::optional<Error> benchSettingsProblem(const BenchSettings& settings);

// Runs everything the settings ask for. Every scene loads (and sets up its frame 0, with the camera's
// own depth planes) before anything is measured, so a bad one fails the run before any work:
// "<scene>: <why>" (the loader's kind). The renders fail as "<scene>: the software backend cannot
// make a WxH target" (OutOfMemory) or "<scene>: <why the backend refused an upload>". Settings out of
// range fail as benchSettingsProblem says. `progress`, when given, gets one line before each scene's
// renders ("builtin:cubes 800x600: exact, span, dda") and one before the speeds are timed; nothing
// else is written anywhere. Deterministic for the settings but for the timings (engineSpeed, speeds,
// and each render row's frameMs, exactFrameMs and spansPerSecond).
Result<BenchReport> runBenchmark(const BenchSettings& settings, const std::function<void(const std::string&)>& progress = {});

// The report's JSON document: {"fig11", "errors", "settings", "spans_per_second", "render"} (keys
// sorted), indented by 2, with a final line break.
std::string benchJson(const BenchReport& report);
// The error table, one row per width, length and method:
// "width,length,method,worst_lsb,mean_lsb,spans,pixels,overflow_spans".
std::string benchCsv(const BenchReport& report);
// The gnuplot script that draws worst and mean error against span length from the CSV at `csvPath`
// into the SVG at `svgPath`.
std::string benchGnuplot(const BenchReport& report, const std::string& csvPath, const std::string& svgPath);
// The text `frugal-lab span-bench` prints: Fig. 11 and the schemes tried, the error table, the speeds, the renders.
std::string benchText(const BenchReport& report);

}  // namespace frugal::span
