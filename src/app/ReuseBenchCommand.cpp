// `frugal reuse-bench`: what temporal reuse (paper 000, src/reuse/Reuse.h) saves, frame by frame.
// Per frame four renders are timed back to back: the full render, the reuse frame (the planner's
// plan and its execution), and two oracles, each the frame's static image (rendered beforehand,
// untimed) copied and only the dynamic instances drawn on it: no static triangle redrawn, no ⊗
// test, no copy back.
//  - The cells oracle (oracle_ms, the main floor) copies only what reuse copies: the cells the
//    planner cleared or copied (where anything dynamic was or is), the whole image on frames that
//    are no reuse frame. It is the floor for reuse at this cell size, the tighter of the two.
//  - The whole oracle (oracle_whole_ms) copies the whole image every frame (one full-target copy):
//    the issue's literal definition, the floor no reuse method can beat.
// The planner (and the cells oracle) are stateful, so the whole sequence is run K times (one
// untimed warm-up round, then --repeat rounds), each round with a fresh planner; per frame the
// medians over the rounds. The warm-up round also checks every reuse frame (and both oracles'
// frames) against the full render of the same frame.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <ostream>

#include <nlohmann/json.hpp>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "app/CullSupport.h"
#include "app/ReportOutputs.h"
#include "app/ReuseSupport.h"
#include "base/Stats.h"
#include "lab/ReuseCheck.h"
#include "lab/ReuseReport.h"
#include "renderer/Oracle.h"
#include "reuse/CellGrid.h"
#include "reuse/Reuse.h"

namespace frugal {

const char* reuseBenchHelp() {
    return R"(usage: frugal reuse-bench [SCENE] --frames A:B [options]

Measures temporal reuse on frames A to B of SCENE (default builtin:default): per frame the full
render, the reuse frame (plan + execution) and two oracles, each the frame's static image (made
beforehand) copied and only the dynamic instances drawn on it, timed back to back and given as
medians over the rounds:
  oracle (cells)  copies only what reuse copies: the cells where anything dynamic was or is (the
                  whole image on frames that are no reuse frame); the floor for reuse at this cell
                  size, the tighter one (oracle_ms, reuse/oracle)
  oracle (whole)  copies the whole image every frame: the issue's literal definition, the floor no
                  reuse method can beat (oracle_whole_ms, reuse/whole)
Also per frame: the planner's state counts (p_dd, p_ds, p_sd, p_ss: triangles), the pixels it
copied and cleared, the triangles it drew, the time of its overlap (⊗) tests; and the paper's cost
model fitted to the measurements, its prediction beside the measured time.
Every reuse frame is compared with the full render of the same frame: pixels where a static and a
dynamic triangle tie in depth may differ (tie_px); any other difference is an error (exit status 1).
Prints a summary; --json/--csv/--plot write the whole report.
)";
}

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// The targets besides the session's (which the full render uses), released before the backend.
struct Targets {
    Backend& backend;
    TargetHandle render = kNoHandle, statics = kNoHandle;  // the reuse frame's render target and static pair
    TargetHandle oracle = kNoHandle, image = kNoHandle;    // the cells oracle's target, and the static image
    TargetHandle oracleWhole = kNoHandle;                  // the whole oracle's target (the same static image)
    ~Targets() {
        for (TargetHandle t : {render, statics, oracle, image, oracleWhole})
            if (t != kNoHandle) backend.destroyTarget(t);
    }
};

struct Samples {
    std::vector<double> full, reuse, plan, oracle, oracleWhole, overlap;
};

std::string percent(double share) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f %%", 100.0 * share);
    return buf;
}

// The cells oracle of a frame: its static image (Static) copied into the oracle's target (Render)
// and the dynamic instances drawn on it. On a reuse frame only the cells the planner touches are
// copied (where anything dynamic was before or is now: the previous frame's oracle image is right
// everywhere else); on other frames the whole image. `dirty` is scratch, of the planner's cell size.
FramePlan makeOraclePlan(const FramePlan& plan, ReuseMode mode, reuse::CellGrid& dirty, const Rect& whole,
                         DrawList dynamics) {
    std::vector<Rect> rects{whole};
    if (mode == ReuseMode::Reuse) {
        dirty.reset();
        for (const PlanStep& step : plan)
            if (step.op != PlanStep::Op::Draw)
                for (const Rect& r : step.rects) dirty.mark(reuse::Box{r.x, r.y, r.x + r.width, r.y + r.height}, 1);
        std::int64_t pixels = 0;
        rects = dirty.rects(1, 0, pixels);
    }
    FramePlan oracle;
    if (!rects.empty()) oracle.push_back({PlanStep::Op::Copy, PlanTarget::Static, PlanTarget::Render, std::move(rects), {}});
    if (!dynamics.empty()) oracle.push_back({PlanStep::Op::Draw, PlanTarget::Render, PlanTarget::Render, {}, std::move(dynamics)});
    return oracle;
}

// The whole oracle of a frame (the issue's literal floor): the whole static image copied into its
// own target and the dynamic instances drawn on it; stateless, every frame alike.
FramePlan makeWholeOraclePlan(const Rect& whole, DrawList dynamics) {
    FramePlan oracle;
    oracle.push_back({PlanStep::Op::Copy, PlanTarget::Static, PlanTarget::Render, {whole}, {}});
    if (!dynamics.empty())
        oracle.push_back({PlanStep::Op::Draw, PlanTarget::Render, PlanTarget::Render, {}, std::move(dynamics)});
    return oracle;
}

double numberOr(const nlohmann::json& value, double fallback) {
    return value.is_number() ? value.get<double>() : fallback;
}

// What the planner did in a frame, as the report's row (the times are filled in later).
ReuseBenchFrame describeFrame(int frame, const ReuseFrameStats& stats, std::size_t draws, std::size_t fullDraws) {
    ReuseBenchFrame result;
    result.frame = frame;
    result.mode = toString(stats.mode);
    result.reason = stats.reason;
    result.pDD = stats.triangles[kDD];
    result.pDS = stats.triangles[kDS];
    result.pSD = stats.triangles[kSD];
    result.pSS = stats.triangles[kSS];
    result.copiedPx = stats.copiedPx;
    result.clearedPx = stats.clearedPx;
    result.redrawnTris = stats.redrawnTris;
    result.staticRedrawnTris = stats.staticRedrawnTris;
    result.drawnTris = stats.drawnTris;
    result.rects = stats.rects;
    result.draws = draws;
    result.fullDraws = fullDraws;
    return result;
}

// "error: frame N: the <which> differs from the full render at M pixels (depth)", or nothing.
std::optional<std::string> checkOracle(int frame, const char* which, const Buffers& oracle, const Buffers& full) {
    const FrameMatch match = matchFrames(oracle, full);
    if (match.errors() == 0) return std::nullopt;
    return "error: frame " + std::to_string(frame) + ": the " + which + " differs from the full render at " +
           std::to_string(match.errors()) + " pixels (depth)";
}

// The printed summary: modes, the medians side by side, the fitted cost model, ties and errors.
void printSummary(std::ostream& out, const ReuseBench& bench, const nlohmann::json& summary, Cull method,
                  const FrameRange& range, int frameCount) {
    const nlohmann::json& modes = summary["modes"];
    out << "reuse-bench " << bench.scene << ", " << bench.width << "x" << bench.height << ", " << bench.backend
        << ", frames " << range.first << ".." << range.last << ", " << bench.repeat
        << (bench.repeat == 1 ? " round" : " rounds")
        << (method != Cull::None ? std::string(", cull ") + toString(method) : std::string()) << "\n";
    out << "frames " << frameCount << ": reuse " << modes["reuse"].get<std::size_t>() << ", rebuild "
        << modes["rebuild"].get<std::size_t>() << ", full " << modes["full"].get<std::size_t>() << "; static share "
        << percent(numberOr(summary["static_share"], 0.0)) << " of the triangles (mean over reuse frames)\n";
    // oracle ms: the cells oracle (copies what reuse copies); whole ms: the whole oracle (copies the whole image).
    out << "                frames   full ms  reuse ms  oracle ms  whole ms  plan ms  speed-up  reuse/oracle  reuse/whole\n";
    for (const char* set : {"reuse_frames", "all_frames"}) {
        const nlohmann::json& s = summary[set];
        char line[256];
        std::snprintf(line, sizeof line, "%-14s %7zu %9.3f %9.3f %10.3f %9.3f %8.3f %9.3f %13.3f %12.3f\n",
                      set == std::string("reuse_frames") ? "reuse frames" : "all frames", s["frames"].get<std::size_t>(),
                      numberOr(s["median_full_ms"], kNaN), numberOr(s["median_reuse_ms"], kNaN),
                      numberOr(s["median_oracle_ms"], kNaN), numberOr(s["median_oracle_whole_ms"], kNaN),
                      numberOr(s["median_plan_ms"], kNaN), numberOr(s["speedup"], kNaN),
                      numberOr(s["ratio_to_oracle"], kNaN), numberOr(s["ratio_to_oracle_whole"], kNaN));
        out << line;
    }
    const nlohmann::json& m = summary["model"];
    out << "cost model: full = t_w " << fmt(numberOr(m["t_w_ms"], kNaN)) << " ms + t_r "
        << fmt(numberOr(m["t_r_ns_per_tri"], kNaN)) << " ns/triangle (median error "
        << percent(numberOr(m["median_full_error"], kNaN)) << ")\n";
    out << "            reuse = plan + t_0 " << fmt(numberOr(m["t_0_ms"], kNaN)) << " ms + t_c "
        << fmt(numberOr(m["t_c_ns_per_px"], kNaN)) << " ns/px copied + t_i " << fmt(numberOr(m["t_i_ns_per_px"], kNaN))
        << " ns/px cleared + t_r' " << fmt(numberOr(m["t_r_reuse_ns_per_tri"], kNaN)) << " ns/triangle (fitted on "
        << m["fitted_frames"].get<std::size_t>() << " reuse frames, " << m["excluded_frames"].get<std::size_t>()
        << " full/rebuild left out; R² " << fmt(numberOr(m["r2"], kNaN)) << ", median error "
        << percent(numberOr(m["median_reuse_error"], kNaN)) << ")\n";
    out << "static pair " << summary["static_pair_bytes"].get<std::uint64_t>() << " bytes, max overlap "
        << fmt(numberOr(summary["max_overlap_ms"], 0.0)) << " ms, ties " << summary["total_tie_px"].get<std::uint64_t>()
        << " px, errors " << summary["total_error_px"].get<std::uint64_t>() << " px\n";
    if (summary.contains("note")) out << "note: " << summary["note"].get<std::string>() << "\n";
}

}  // namespace

int runReuseBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    CullOptions cull;
    ReuseCliOptions reuseOptions;
    ReportPaths outputs;
    int repeat = 5;
    bool ids = false;
    CommandLine command{"reuse-bench", reuseBenchHelp(), &options};
    std::vector<Flag> culling = cullFlags(cull, true);
    culling[0].help = "full and reuse frames draw that method's list (none, sphere, backface, cones, paper or "
                      "conservative; not oracle)";
    command.flags = {
        {"frames and timing", {
            flag::frames("--frames", "the frames, inclusive (required; A has no predecessor: it is a rebuild)",
                         options.frames),
            flag::whole("--repeat", "K", "timed rounds over the whole sequence, after one untimed warm-up round that "
                        "also checks the frames (default 5); medians over the rounds", repeat, 1, 10000),
            flag::on("--ids", "write triangle ids in every render (and compare them); default off, as 'frugal render' "
                     "without --ids", ids),
            culling[0],
            culling[1],
        }},
        {"outputs (each written whole or not at all)",
         reportFlags(outputs, "the report: frames, summary (medians, speed-up, ratios to both oracles, the fitted cost "
                     "model)", "one row per frame",
                     "plots drawn by gnuplot from the CSV (--csv, or FILE.csv beside the plot): speed-up against the "
                     "static share, and the times per frame; the gnuplot script is written beside it as FILE.gp, to "
                     "restyle and rerun")},
        {"temporal reuse (with a still camera only what changed is redrawn; src/reuse/Reuse.h)",
         reuseFlags(reuseOptions, options, false)},
    };
    command.positional = sceneArgument(options);
    command.finish = [&](ArgCursor& cursor) {
        if (!options.frames)
            cursor.fail("--frames: reuse-bench needs a frame range A:B (each frame after A may reuse the one before)");
        else if (cull.method == Cull::Oracle)
            cursor.fail("--cull oracle: the oracle is an id pass of each frame, not a plan to reuse");
        else if (const std::string problem = plotProblem(outputs); !problem.empty())
            cursor.fail(problem);
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;

    Result<Scene> loaded = loadForRender(options, err);
    if (!loaded) {
        err << "error: " << loaded.error() << "\n";
        return kExitError;
    }
    Scene& scene = *loaded;
    const Cull method = cull.method.value_or(Cull::None);
    std::optional<SceneCuller> culler = prepareCullOption(scene, cull, err, options.quiet);  // before the upload

    std::variant<Session, int> started = startSession(options, scene, err);
    if (const int* status = std::get_if<int>(&started)) return *status;
    Session& session = std::get<Session>(started);
    Backend& backend = *session.backend;
    SceneRenderer& renderer = *session.renderer;
    const int width = options.width, height = options.height;
    const TargetHandle fullTarget = session.target;
    Targets targets{backend};
    // Five more targets, and the read-backs the frames compare.
    const std::uint64_t needed = std::uint64_t(width) * std::uint64_t(height) *
                                 (5 * kTargetBytesPerPixel + kFrameBytesPerPixel - kTargetBytesPerPixel);
    if (const std::optional<std::string> problem = memoryProblem(needed)) {
        err << "error: --size " << width << "x" << height << ": the benchmark needs about " << gigabytes(needed)
            << " more (five more targets, and the read-backs it compares), " << *problem << "\n";
        return kExitError;
    }
    for (TargetHandle* t : {&targets.render, &targets.statics, &targets.oracle, &targets.image, &targets.oracleWhole}) {
        *t = backend.createTarget(width, height, options.depthFormat);
        if (*t == kNoHandle) {
            err << "error: --size " << width << "x" << height << ": " << backend.name()
                << " could not create the benchmark's six targets (the full render's, the reuse frame's, its static "
                   "pair, the two oracles' and their static image)\n";
            return kExitError;
        }
    }

    const FrameRange range = *options.frames;
    const int frameCount = range.last - range.first + 1;
    const Rect whole{0, 0, width, height};
    const glm::vec4& background = options.background;

    const std::size_t count = std::size_t(frameCount);
    std::vector<ReuseBenchFrame> frames(count);
    std::vector<Samples> samples(count);
    std::vector<double> clears;
    std::optional<std::string> oracleError;
    reuse::CellGrid dirty(width, height, reuseOptions.settings.cell);
    for (int round = -1; round < repeat; ++round) {  // round -1: the warm-up, untimed, and the check
        const bool timed = round >= 0;
        TemporalReuse reuse(scene, width, height, reuseOptionsFrom(reuseOptions.settings));
        std::vector<double> roundFull, roundReuse, roundOracle, roundOracleWhole;
        for (int i = 0; i < frameCount; ++i) {
            const int frame = range.first + i;
            Result<FrameSetup> setup = setUpFrame(options, scene, frame, ids);
            if (!setup) {
                err << "error: frame " << frame << ": " << setup.error() << "\n";
                return kExitError;
            }
            const FrameParams& params = setup->params;
            const std::vector<glm::mat4>& world = setup->world;
            DrawList culled;
            if (culler) culled = culler->cull(method, scene, world, setup->view);
            const DrawList& list = culler ? culled : renderer.fullList();

            // The plan: CPU work only, timed alone (nothing of the backend's is pending).
            backend.finish();
            const auto t0 = Clock::now();
            const FramePlan plan = culler ? reuse.plan(params, world, list, background) : reuse.plan(params, world, background);
            const double planMs = msSince(t0);
            const ReuseFrameStats stats = reuse.stats();

            // The oracles' static image: the instances static in this frame alone (untimed).
            DrawList statics, dynamics;
            for (const DrawCommand& draw : list) (reuse.dynamicNow(draw.instance) ? dynamics : statics).push_back(draw);
            renderer.renderFrame(targets.image, width, height, params, world, background, statics);
            const FramePlan oracleWholePlan = makeWholeOraclePlan(whole, dynamics);
            const FramePlan oraclePlan = makeOraclePlan(plan, stats.mode, dirty, whole, std::move(dynamics));
            std::size_t draws = 0;
            for (const PlanStep& step : plan) draws += step.list ? step.list->size() : step.draws.size();

            // Timed back to back, the order rotated from round to round: a whole-target clear (t_w,
            // of another target) with the full render right after it, the reuse frame, the cells
            // oracle, the whole oracle.
            double fullMs = 0.0, executeMs = 0.0, oracleMs = 0.0, oracleWholeMs = 0.0, clearMs = 0.0;
            const auto time = [&backend](const auto& work) {
                backend.finish();
                const auto start = Clock::now();
                work();
                backend.finish();
                return msSince(start);
            };
            for (int step = 0; step < 4; ++step) {
                switch ((step + std::max(round, 0)) % 4) {
                case 0:
                    // t_w on the whole oracle's target (its plan overwrites all of it): a clear of the
                    // full render's own target just before it would warm that target's cache.
                    clearMs = time(
                        [&] { backend.clear(targets.oracleWhole, whole, background, farDepth(params.depthFormat)); });
                    fullMs = time([&] { renderer.renderFrame(fullTarget, width, height, params, world, background, list); });
                    break;
                case 1:
                    executeMs = time([&] { renderer.execute(plan, targets.render, targets.statics, params, world, background); });
                    break;
                case 2:
                    oracleMs = time([&] { renderer.execute(oraclePlan, targets.oracle, targets.image, params, world, background); });
                    break;
                default:
                    oracleWholeMs = time([&] {
                        renderer.execute(oracleWholePlan, targets.oracleWhole, targets.image, params, world, background);
                    });
                    break;
                }
            }

            ReuseBenchFrame& result = frames[std::size_t(i)];
            if (timed) {
                Samples& s = samples[std::size_t(i)];
                s.full.push_back(fullMs);
                s.reuse.push_back(planMs + executeMs);
                s.plan.push_back(planMs);
                s.oracle.push_back(oracleMs);
                s.oracleWhole.push_back(oracleWholeMs);
                s.overlap.push_back(stats.overlapMs);
                clears.push_back(clearMs);
                roundFull.push_back(fullMs);
                roundReuse.push_back(planMs + executeMs);
                roundOracle.push_back(oracleMs);
                roundOracleWhole.push_back(oracleWholeMs);
                continue;
            }
            // The warm-up: what the planner did, and the reuse frame against the full render.
            result = describeFrame(frame, stats, draws, list.size());
            const Buffers fullImage = backend.readBack(fullTarget);
            const FrameMatch match = matchFrames(backend.readBack(targets.render), fullImage);
            result.tiePx = match.ties;
            result.errorPx = match.errors();
            // Both oracles are exact too (a tie aside), or they are no floor of anything.
            if (!oracleError) oracleError = checkOracle(frame, "oracle", backend.readBack(targets.oracle), fullImage);
            if (!oracleError)
                oracleError = checkOracle(frame, "whole oracle", backend.readBack(targets.oracleWhole), fullImage);
            if (!options.quiet) {
                err << "frame " << frame << " (" << (i + 1) << "/" << frameCount << "): " << result.mode << ", "
                    << stats.redrawnTris << " of " << stats.drawnTris << " triangles drawn";
                if (stats.mode == ReuseMode::Reuse)
                    err << ", " << stats.copiedPx << " px copied, " << stats.clearedPx << " px cleared";
                else
                    err << " (" << stats.reason << ")";
                if (match.ties) err << ", " << match.ties << " tie px";
                if (match.errors()) err << ", " << match.errors() << " px differ from the full render (depth)";
                err << "\n";
            }
        }
        if (timed && !options.quiet)
            err << "round " << (round + 1) << "/" << repeat << ": full " << fmt(median(roundFull)) << " ms, reuse "
                << fmt(median(roundReuse)) << " ms, oracle " << fmt(median(roundOracle)) << " ms, whole oracle "
                << fmt(median(roundOracleWhole)) << " ms (medians of "
                << frameCount << " frames)\n";
    }
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const Samples& s = samples[i];
        frames[i].fullMs = median(s.full);
        frames[i].reuseMs = median(s.reuse);
        frames[i].planMs = median(s.plan);
        frames[i].oracleMs = median(s.oracle);
        frames[i].oracleWholeMs = median(s.oracleWhole);
        frames[i].overlapMs = median(s.overlap);
    }

    ReuseBench bench;
    bench.scene = options.scene;
    bench.width = width;
    bench.height = height;
    bench.backend = backend.name();
    bench.renderer = backend.renderer();
    bench.repeat = repeat;
    bench.cull = toString(method);
    bench.grain = reuseOptions.settings.grain;
    bench.cell = reuseOptions.settings.cell;
    bench.fallback = reuseOptions.settings.fallback;
    bench.ids = ids;
    bench.staticPairBytes = staticPairBytes(width, height);
    bench.clearMs = median(clears);
    bench.frames = std::move(frames);
    const std::string jsonText = reuseReportJson(bench);
    const nlohmann::json json = nlohmann::json::parse(jsonText);

    const ReportTexts texts{[&jsonText] { return jsonText; }, [&bench] { return reuseReportCsv(bench); },
                            [&range](const std::string& csvPath, const std::string& svgPath) {
                                return reuseReportGnuplot(csvPath, svgPath, range.first);
                            }};
    if (const int status = writeReportFiles(outputs, texts, err); status != kExitOk) return status;

    printSummary(out, bench, json["summary"], method, range, frameCount);

    // A reuse frame that differs from the full render other than by a tie is a bug, never a trade-off.
    if (oracleError) {
        err << *oracleError << "\n";
        return kExitError;
    }
    for (const ReuseBenchFrame& f : bench.frames)
        if (f.errorPx > 0) {
            err << "error: frame " << f.frame << ": reuse differs from the full render at " << f.errorPx
                << " pixels (depth)\n";
            return kExitError;
        }
    return kExitOk;
}

}  // namespace frugal
