// `frugal report`'s measurement: every method that trades accuracy for speed, as a set of candidate
// Settings, each run through its own frugal::Renderer on the same shots (views, or the frames of a
// sequence), interleaved: per shot every candidate renders in turn, in an order that rotates from
// shot to shot, so machine noise hits all alike. Each candidate's images are judged against the
// plain render's (the default settings on the same stage): pixels that differ, the worst frame,
// PSNR, the worst depth difference. The oracle is timed as the floor of culling and never
// recommended. Recommended: the fastest exact candidate, and the fastest whose worst frame stays
// within a pixel budget, each only when it pays (below kPays of the plain render's median).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <frugal/Camera.h>
#include <frugal/Image.h>
#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>

namespace frugal {

struct TradeCandidate {
    std::string name;    // "plain", "cull conservative", "cull conservative + order key", ...
    std::string family;  // "plain", "cull", "order", "hsr", "interp", "reuse", "combination", "floor"
    Settings settings;
    bool floor = false;  // a lower bound (the oracle), not a method to use
};

// One picture every candidate renders: a view at a time.
struct TradeShot {
    std::string label;  // "view 3 (grazing)", "frame 12"
    Camera camera;
    double time = 0.0;
};

struct TradeSettings {
    std::string scene;  // its name in the report
    std::vector<TradeShot> shots;
    bool sequence = false;         // the shots are consecutive frames: reuse and cost refinement apply
    int repeat = 3;                // timed renders of each shot by each candidate (a sequence: 1)
    std::uint64_t budgetPx = 0;    // --budget-px: differing pixels a frame allowed for the second pick
};

// A candidate counts as paying when its median is below this share of the plain render's.
inline constexpr double kPays = 0.97;

struct TradeRow {
    TradeCandidate candidate;
    std::vector<double> ms;  // every timed render: the frame's render_ms (culling, planning, drawing)
    double medianMs = 0.0;
    std::uint64_t differingPx = 0;   // over all shots, against the plain render
    std::uint64_t worstFramePx = 0;  // the most in one shot
    std::uint64_t misses = 0;        // triangles the plain render shows and this one lacks, over all shots
    double worstPsnr = 0.0;          // the lowest over the shots (RGB; +inf: identical)
    std::uint32_t worstDepth = 0;    // the largest depth difference where both cover, in LSB (d24) or ULP (d32f)
    std::uint64_t extraBytes = 0;    // memory beyond the plain render's (Renderer::extraBytes)
    double prepareMs = 0.0;          // culling preparation, when any
    double submittedShare = 0.0;     // triangles submitted ÷ the scene's, the mean over the timed frames
    double stateChanges = 0.0;       // program, mesh and texture binds and toggles a frame, the mean
    // The error mask (compareBuffers: red where a pixel differs, the plain render in grey elsewhere)
    // of the shot with the most differing pixels, and that shot's label; empty when no colour differs.
    Buffers worstMask;
    std::string worstShot;
    // The same images as the plain render: no colour differs, nor any depth where both cover (the
    // hidden-surface modes draw some polygons without writing depth: colour-exact, depth not).
    bool exact() const { return differingPx == 0 && worstDepth == 0; }
};

struct TradeReport {
    std::string backend;  // describe(Backend) of the plain renderer
    std::vector<TradeRow> rows;  // rows[0] is the plain render
    std::optional<std::size_t> bestExact, bestWithinBudget;  // indices into rows; none: the plain render
    std::vector<std::size_t> pareto;  // the rows on the front of median time against differing pixels

    bool onFront(std::size_t row) const;
    std::optional<double> floorMs() const;  // the floor's (the oracle's) median, when it was measured
    double xPlain(const TradeRow& row) const;                // its median ÷ the plain render's (0 when that is 0)
    std::optional<double> xFloor(const TradeRow& row) const;  // its median ÷ the floor's, when there is one
};

// The candidates for `base` (size, backend, threads, depth format, background): the plain render,
// the culling methods (and the oracle as floor), the orders key and greedy, the hidden-surface modes,
// on the software backend the interpolators, in a sequence reuse, and the useful combinations.
std::vector<TradeCandidate> tradeCandidates(const Settings& base, bool sequence, bool software);

// Renders every shot with every candidate (a Renderer each, on a copy of `scene`). `progress` gets a
// line per shot. Errors: a candidate's Renderer::create or render error, "<name>: <why>".
Result<TradeReport> measureTrades(const Scene& scene, const std::vector<TradeCandidate>& candidates,
                                  const TradeSettings& settings,
                                  const std::function<void(const std::string&)>& progress);

// report.json: {"scene", "shots", "sequence", "repeat", "budget_px", "backend", "rows": [{"name",
// "family", "floor", "median_ms", "x_plain", "x_floor", "differing_px", "worst_frame_px",
// "misses", "worst_psnr", "worst_depth", "extra_bytes", "prepare_ms", "exact", "pareto", "settings"}],
// "recommended": {"exact", "within_budget"}}; report.csv: one line a row; and the two lines
// `frugal report` prints.
std::string tradeReportJson(const TradeReport& report, const TradeSettings& settings);
std::string tradeReportCsv(const TradeReport& report);
std::string tradeRecommendationText(const TradeReport& report, const TradeSettings& settings);

}  // namespace frugal
