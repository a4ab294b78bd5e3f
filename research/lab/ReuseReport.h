// The temporal-reuse benchmark (`frugal-lab reuse-bench`, paper 000): per frame the full render, the
// reuse frame and its two oracles (floors) timed side by side, the planner's state counts and
// work, the check against the full render, and the paper's cost model fitted to the
// measurements; written as JSON, CSV and a gnuplot script that plots the CSV.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace frugal {

struct ReuseBenchFrame {
    int frame = 0;
    std::string mode;    // the planner's: "full", "rebuild" or "reuse"
    std::string reason;  // why that mode
    // Medians over the timed rounds. reuse = plan + execute; plan is also given alone.
    double fullMs = 0.0;   // clear + draw of the frame's draw list + finish
    double reuseMs = 0.0;  // the planner's plan + its execution + finish
    double planMs = 0.0;   // the planner alone (classification, extents, ⊗ tests, rectangles)
    // The two floors, both the frame's static image (made beforehand, untimed) copied and only the
    // dynamic instances drawn on it. The cells oracle copies only what reuse copies (the cells the
    // planner cleared or copied on a reuse frame, the whole image otherwise): the floor at the
    // planner's cell size, the tighter one. The whole oracle copies the whole image every frame: the
    // issue's literal definition, the floor no reuse method can beat.
    double oracleMs = 0.0;       // the cells oracle
    double oracleWholeMs = 0.0;  // the whole oracle (one full-target copy + the dynamic instances)
    double overlapMs = 0.0;      // of the plan: grid marking and the ⊗ tests
    // Triangles of the instances in each state (previous frame, this frame): d = dynamic, s = static.
    std::uint64_t pDD = 0, pDS = 0, pSD = 0, pSS = 0;
    std::uint64_t copiedPx = 0;           // static → render and render → static
    std::uint64_t clearedPx = 0;          // invalidated (the whole target on full and rebuild frames)
    std::uint64_t redrawnTris = 0;        // triangles the reuse frame drew
    std::uint64_t staticRedrawnTris = 0;  // of those, static ones drawn again
    std::uint64_t drawnTris = 0;          // triangles the full render draws
    std::uint64_t rects = 0;              // clear and copy rectangles
    std::uint64_t draws = 0;              // draw commands (instances) the reuse frame issued
    std::uint64_t fullDraws = 0;          // draw commands of the full render
    // Reuse frame against the full render (report/ReuseCheck.h): ties are allowed, errors never.
    std::uint64_t tiePx = 0, errorPx = 0;

    double speedup() const { return fullMs / reuseMs; }
    // Share of the triangles that are static now: (p_ss + p_ds) / all (NaN with no triangles).
    double staticShare() const;
};

struct ReuseBench {
    std::string scene;
    int width = 0, height = 0;
    std::string backend, renderer;
    int repeat = 0;             // timed rounds (the median is over these)
    std::string cull = "none";  // the culling method whose list full and reuse frames draw
    int grain = 0, cell = 0;    // the planner's options
    bool fallback = true;
    bool ids = false;  // triangle ids written (and compared)
    std::uint64_t staticPairBytes = 0;
    double clearMs = 0.0;  // t_w: median time of a whole-target clear, timed in the same rounds
    std::vector<ReuseBenchFrame> frames;
};

// The paper's cost model with pixels for extents (src/reuse/Reuse.h), fitted to a ReuseBench:
//   full frame:  t_old = t_w + t_r · drawn_tris         (t_w measured; t_r fitted over every frame's full render)
//   reuse frame: t_new = plan_ms + t_0 + t_c · copied_px + t_i · cleared_px + t_r' · redrawn_tris
//                (t_0, t_c, t_i, t_r' fitted, non-negative, over the frames in reuse mode only)
// The paper's t_c·(|P_dd|+|P_sd|+|P_ds|) + t_i·|P_sd| become the pixels the plan copies and clears,
// its t_r·(|P_ss⊗P_sd| + |P_ds⊗(P_sd∪P_dd)| + |P_dd|) the triangles the plan draws; t_0 is what a
// frame costs whatever it does (the finish, state set-up), and the plan's own time is measured.
// Frames in full or rebuild mode are predicted by the full model (a rebuild adds t_c for its copy).
struct CostModel {
    double twMs = 0.0;               // a whole-target clear (measured)
    double trNs = 0.0;               // per triangle drawn, full renders (ns)
    double t0Ms = 0.0;               // per reuse frame (ms)
    double tcNs = 0.0;               // per pixel copied (ns)
    double tiNs = 0.0;               // per pixel cleared (ns)
    double trReuseNs = 0.0;          // per triangle drawn, reuse frames (ns)
    std::size_t fittedFrames = 0;    // frames in reuse mode (the reuse fit's rows)
    std::size_t excludedFrames = 0;  // frames in full or rebuild mode, left out of the reuse fit
    double reuseR2 = 0.0;            // of the reuse fit (NaN with fewer than 2 frames or no spread)
    double medianReuseError = 0.0;   // median |model − reuse_ms| / reuse_ms over the fitted frames (NaN: none)
    double medianFullError = 0.0;    // median |model − full_ms| / full_ms over every frame (NaN: none)
};

// Least squares with every coefficient ≥ 0: argmin |A·x − y|² over x ≥ 0, `rows` the rows of A
// (all of the same length n ≤ 8). Exact: every support set is solved unconstrained and the best
// feasible one kept (the fewest coefficients on ties). Columns are scaled to unit norm first; an
// all-zero or dependent column gets 0. Empty input: n zeros.
std::vector<double> nonNegativeLeastSquares(const std::vector<std::vector<double>>& rows, const std::vector<double>& y);

CostModel fitCostModel(const ReuseBench& bench);
// The model's prediction for one frame (reuse frames by the reuse fit, others by the full model).
double modelMs(const CostModel& model, const ReuseBenchFrame& frame);
// The full render's prediction: t_w + t_r · drawn_tris.
double fullModelMs(const CostModel& model, const ReuseBenchFrame& frame);

// {"scene","size":[w,h],"backend","renderer","repeat","cull","reuse":{"grain","cell","fallback"},"ids",
//  "frames":[{"frame","mode","reason","full_ms","reuse_ms","plan_ms","oracle_ms","oracle_whole_ms","model_ms",
//    "full_model_ms",
//    "speedup","static_share","p_dd","p_ds","p_sd","p_ss","copied_px","cleared_px","redrawn_tris",
//    "static_redrawn_tris","drawn_tris","rects","draws","full_draws","overlap_ms","tie_px","error_px"}],
//  "summary":{"frames","modes":{"full","rebuild","reuse"},"speedup","ratio_to_oracle",
//    "ratio_to_oracle_whole" (all three over the frames in reuse mode; null when there is none, with
//    "note" saying so),
//    "reuse_frames":{MEDIANS},"all_frames":{MEDIANS} where MEDIANS = "frames","median_full_ms",
//    "median_reuse_ms","median_oracle_ms","median_oracle_whole_ms","median_plan_ms","speedup" (median
//    full ÷ median reuse),"ratio_to_oracle" (median reuse ÷ median cells oracle),
//    "ratio_to_oracle_whole" (median reuse ÷ median whole oracle),
//    "static_share" (mean over the frames in reuse mode, over all when there is
//    none),"static_pair_bytes","max_overlap_ms","total_tie_px",
//    "total_error_px","frames_with_errors","first_error_frame" (null: none),
//    "model":{"t_w_ms","t_r_ns_per_tri","t_0_ms","t_c_ns_per_px","t_i_ns_per_px","t_r_reuse_ns_per_tri",
//      "fitted_frames","excluded_frames","r2","median_reuse_error","median_full_error"}}}
// Medians of an even count are the mean of the two middle values; NaN and infinities are null.
std::string reuseReportJson(const ReuseBench& bench);

// The summary `frugal-lab reuse-bench` prints: the run (scene, size, backend, frames, rounds, culling),
// the modes and the static share, the medians of the reuse frames and of all frames side by side
// (full, reuse, both oracles, plan, speed-up, ratios), the fitted cost model, the static pair's
// bytes, ties and errors, and the summary's note when it has one. Lines end in '\n'.
std::string reuseReportSummary(const ReuseBench& bench);

// One header line, then one row per frame:
// frame,mode,full_ms,reuse_ms,plan_ms,oracle_ms,oracle_whole_ms,model_ms,full_model_ms,speedup,
// static_share,p_dd,p_ds,p_sd,p_ss,copied_px,cleared_px,redrawn_tris,static_redrawn_tris,drawn_tris,rects,draws,
// full_draws,overlap_ms,tie_px,error_px,reason
std::string reuseReportCsv(const ReuseBench& bench);

// A gnuplot script (svg terminal) that reads `csvPath` and draws into `svgPath` two plots: the
// speed-up (full ÷ reuse) against the static share per frame, by mode, with the paper's two
// results beside them; and full, reuse, both oracles' and model time against the frame number.
// `firstFrame`: the CSV's first frame (where the frame axis of an empty CSV is anchored).
std::string reuseReportGnuplot(const std::string& csvPath, const std::string& svgPath, int firstFrame = 0);

}  // namespace frugal
