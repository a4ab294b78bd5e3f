// `frugal report`'s measurement: every method that trades accuracy for speed, as a set of candidate
// Settings, each run through its own frugal::Renderer on the same shots (views, or the frames of a
// sequence), interleaved: per shot every candidate renders in turn, in an order that rotates from
// shot to shot, so machine noise hits all alike. Each candidate's images are judged against the
// plain render's (the default settings on the same stage): pixels that differ, the worst frame,
// PSNR, the worst depth difference. The oracle is timed as the floor of culling and never
// recommended. Recommended: the fastest exact candidate, and the fastest whose worst frame stays
// within a pixel budget, each only when it pays: when the 95 % interval of its time paired with the
// plain render's (the same shot, the same round) lies below kPays, and its draws are not the plain
// render's, or those of a candidate it only adds to (a no-op, such as an order of a single draw,
// pays only by noise).
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
#include "lab/ImageCompare.h"
#include "renderer/Research.h"

namespace frugal {

struct TradeCandidate {
    std::string name;    // "plain", "cull conservative", "cull conservative + order key", ...
    std::string family;  // "plain", "cull", "order", "hsr", "interp", "reuse", "combination", "floor", "shading"
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

// A candidate counts as paying when the interval of its paired ratio to the plain render lies below
// this.
inline constexpr double kPays = 0.97;

// The paired comparison (docs/report.md, "When a method pays"). A pair is a candidate's timed
// render and the plain render's of the same shot in the same round; its ratio is the candidate's
// time ÷ the plain render's. A shot's ratio is the median of its rounds' ratios (taken on their
// logarithms); the estimate is the trimmed geometric mean of the shots' ratios: exp of the mean of
// their logarithms once the lowest and the highest kTrim of them are left out. Its interval is a
// percentile bootstrap: kBootstrapResamples times, the shots are drawn with replacement and each
// drawn shot's rounds with replacement, and the estimate taken again; the interval runs from the
// 2.5th to the 97.5th percentile of those. Draws come from SplitMix64 seeded with kBootstrapSeed, so
// the same timings give the same interval everywhere. With fewer than kMinPairs pairs there is no
// interval, and the candidate is not picked.
inline constexpr double kTrim = 0.2;
inline constexpr int kBootstrapResamples = 2000;
inline constexpr double kIntervalLevel = 0.95;
inline constexpr std::uint64_t kBootstrapSeed = 20261203;
inline constexpr std::size_t kMinPairs = 8;

struct PairedRatio {
    double estimate = 0.0;         // the trimmed geometric mean over the shots of their paired ratios
    double low = 0.0, high = 0.0;  // its interval (kIntervalLevel); NaN without one
    std::size_t pairs = 0;         // the pairs measured (shots × rounds)
    bool known() const { return pairs >= kMinPairs; }
};

// `ms` and `plainMs`: per shot, the timed renders in round order (TradeRow::shotMs). A pair with a
// time that is not above 0 is left out.
PairedRatio pairedRatio(const std::vector<std::vector<double>>& ms, const std::vector<std::vector<double>>& plainMs,
                        std::uint64_t seed = kBootstrapSeed);

struct TradeRow {
    TradeCandidate candidate;
    // Every timed render's render_ms (culling, planning, drawing), per shot in round order, and all of
    // them one shot after another (decideTrades fills ms and medianMs from shotMs).
    std::vector<std::vector<double>> shotMs;
    std::vector<double> ms;
    double medianMs = 0.0;
    PairedRatio paired;  // against the plain render, shot by shot and round by round
    // The row whose work this one repeats and adds nothing to: a row it only adds to (every method
    // setting that row changes from the plain render's, this one changes the same way) whose draws
    // it repeated in every timed render (FrameStats::drawFingerprint equal to that row's of the same
    // shot and round: the same triangles in the same order with the same state, the same clears and
    // copies); or the row with its cull alone, when what it does after the cull changed nothing in
    // any timed render (drawFingerprint equal to its own culledFingerprint). 0, the plain render,
    // makes it a no-op (an order of a single draw, a cull that keeps every triangle); another row, a
    // combination whose addition changed nothing ("cull occlusion + order key" on one mesh orders a
    // single draw). It does that row's work and more, so whatever its time says, it does not pay:
    // never picked.
    std::optional<std::size_t> sameDrawsAs;
    bool noOp() const { return sameDrawsAs == std::size_t{0}; }
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
    // Whether a row may be picked: not the plain render, not the floor, no sameDrawsAs, and the
    // interval of its paired ratio lies below kPays.
    bool pays(std::size_t row) const;
    std::optional<double> floorMs() const;  // the floor's (the oracle's) median, when it was measured
    double xPlain(const TradeRow& row) const;                // its median ÷ the plain render's (0 when that is 0)
    std::optional<double> xFloor(const TradeRow& row) const;  // its median ÷ the floor's, when there is one
};

// The candidates for `base` (size, backend, threads, depth format, background): the plain render,
// the culling methods (and the oracle as floor), the orders key and greedy, the hidden-surface modes,
// on the software backend the interpolators, the shading trades (the Lambert approximation; one
// sample where the base has more; no mipmaps), in a sequence reuse, and the useful combinations.
// `mipmapped`: the scene has a texture with mipmaps (then "no mipmaps" is weighed too). `deforms`:
// the scene has meshes the hidden-surface modes do not take, meshes that deform (Scene::deforms) or
// points and lines (they are left out).
std::vector<TradeCandidate> tradeCandidates(const Settings& base, bool sequence, bool software, bool mipmapped = false,
                                            bool deforms = false);

// What a candidate drew in one timed render: FrameStats::drawFingerprint and culledFingerprint.
struct DrawRecord {
    std::uint64_t drawn = 0, culled = 0;
};

// Each candidate's TradeRow::sameDrawsAs, from what every candidate drew in every timed round:
// rounds[r][i] is candidates[i]'s render in round r (every shot's rounds, one after another).
// candidates[0] is the plain render. A round short of a candidate counts as drawing otherwise.
std::vector<std::optional<std::size_t>> repeatedDraws(const std::vector<TradeCandidate>& candidates,
                                                      const std::vector<std::vector<DrawRecord>>& rounds);

// What `report` recommends, from its rows' timings and judgements (measureTrades ends with it):
// each row's paired ratio, then among the rows that pay (TradeReport::pays) the exact one and the
// one within settings.budgetPx differing pixels a frame with the lowest estimate (ties: the lower
// interval's upper end, then the earlier row), and the Pareto front.
void decideTrades(TradeReport& report, const TradeSettings& settings);

// Renders every shot with every candidate (a Renderer each, on a copy of `scene`). `progress` gets a
// line per shot. Errors: a candidate's Renderer::create or render error, "<name>: <why>".
Result<TradeReport> measureTrades(const Scene& scene, const std::vector<TradeCandidate>& candidates,
                                  const TradeSettings& settings,
                                  const std::function<void(const std::string&)>& progress);

// report.json: {"scene", "shots", "sequence", "repeat", "budget_px", "pays_below", "interval":
// {"statistic", "trim", "method", "level", "resamples", "seed", "generator", "min_pairs"}, "backend", "rows":
// [{"name", "family", "floor", "median_ms", "x_plain", "x_floor", "x_plain_paired", "x_plain_low",
// "x_plain_high", "pairs", "no_op", "same_draws_as", "pays", "differing_px", "worst_frame_px", "misses", "worst_psnr",
// "worst_depth", "extra_bytes", "prepare_ms", "submitted_share", "state_changes", "worst_shot",
// "exact", "pareto", "settings", "shot_ms"}], "recommended": {"exact", "within_budget"}};
// report.csv: one line a row (the paired columns last); and the two lines `frugal report` prints,
// each with its pick's interval.
std::string tradeReportJson(const TradeReport& report, const TradeSettings& settings);
std::string tradeReportCsv(const TradeReport& report);
std::string tradeRecommendationText(const TradeReport& report, const TradeSettings& settings);

}  // namespace frugal
