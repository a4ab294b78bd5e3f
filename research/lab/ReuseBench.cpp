#include "lab/ReuseBench.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <utility>
#include <vector>

#include "renderer/Research.h"
#include "lab/CullMeasure.h"
#include "lab/ReuseCheck.h"

namespace frugal {

namespace {

using Clock = std::chrono::steady_clock;
using Progress = std::function<void(const std::string&)>;

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

std::string sizeText(const Settings& s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

// The culling of s.cull prepared (prepareCulling); nothing for none. The hull is built for paper
// alone (the only method using it).
std::optional<SceneCuller> cullingOf(Scene& scene, const Settings& s, const Progress& progress) {
    if (!traitsOf(s.cull).prepares) return std::nullopt;
    MapParams bins{s.cullBinsTheta, s.cullBinsPhi};
    bins.hull = traitsOf(s.cull).hull;
    return prepareCulling(scene, bins, progress);
}

// The targets besides the stage's (which the full render uses). Declared after the stage, so they
// go before its backend.
struct Targets {
    OwnedTarget render, statics;  // the reuse frame's render target and static pair
    OwnedTarget oracle, image;    // the cells oracle's target, and the static image
    OwnedTarget oracleWhole;      // the whole oracle's target (the same static image)
    explicit Targets(Backend& b) : render(b), statics(b), oracle(b), image(b), oracleWhole(b) {}

    // Checks the memory they and the compared read-backs take, then makes the five.
    Result<bool> make(Backend& backend, const Settings& s) {
        const std::uint64_t needed = std::uint64_t(s.width) * std::uint64_t(s.height) *
                                     (5 * kTargetBytesPerPixel + kFrameBytesPerPixel - kTargetBytesPerPixel);
        if (const std::optional<std::string> problem = memoryProblem(needed))
            return Error{"size " + sizeText(s) + ": the benchmark needs about " + gigabytes(needed) +
                             " more (five more targets, and the read-backs it compares), " + *problem,
                         ErrorKind::OutOfMemory, true};
        for (OwnedTarget* t : {&render, &statics, &oracle, &image, &oracleWhole}) {
            t->reset(backend.createTarget(s.width, s.height, s.depthFormat));
            if (t->get() == kNoHandle)
                return Error{"size " + sizeText(s) + ": " + backend.name() +
                                 " could not create the benchmark's six targets (the full render's, the reuse "
                                 "frame's, its static pair, the two oracles' and their static image)",
                             ErrorKind::BadInput, true};
        }
        return true;
    }
};

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
    if (!rects.empty())
        oracle.push_back({PlanStep::Op::Copy, PlanTarget::Static, PlanTarget::Render, std::move(rects), {}});
    if (!dynamics.empty())
        oracle.push_back({PlanStep::Op::Draw, PlanTarget::Render, PlanTarget::Render, {}, std::move(dynamics)});
    return oracle;
}

// The whole oracle of a frame (the literal floor): the whole static image copied into its
// own target and the dynamic instances drawn on it; stateless, every frame alike.
FramePlan makeWholeOraclePlan(const Rect& whole, DrawList dynamics) {
    FramePlan oracle;
    oracle.push_back({PlanStep::Op::Copy, PlanTarget::Static, PlanTarget::Render, {whole}, {}});
    if (!dynamics.empty())
        oracle.push_back({PlanStep::Op::Draw, PlanTarget::Render, PlanTarget::Render, {}, std::move(dynamics)});
    return oracle;
}

// What the planner did in a frame, as the report's row (the times are filled in later).
ReuseBenchFrame describeFrame(int frame, const ReuseFrameStats& stats, std::size_t draws, std::size_t fullDraws) {
    ReuseBenchFrame result;
    result.frame = frame;
    result.mode = toString(stats.mode);
    result.reason = stats.reason;
    result.pDD = stats.triangles.dd;
    result.pDS = stats.triangles.ds;
    result.pSD = stats.triangles.sd;
    result.pSS = stats.triangles.ss;
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

// "frame N: the <which> differs from the full render at M pixels (depth)", or nothing.
std::optional<std::string> checkOracle(int frame, const char* which, const Buffers& oracle, const Buffers& full) {
    const FrameMatch match = matchFrames(oracle, full);
    if (match.errors() == 0) return std::nullopt;
    return "frame " + std::to_string(frame) + ": the " + which + " differs from the full render at " +
           std::to_string(match.errors()) + " pixels (depth)";
}

// The warm-up's line of a frame: what the planner did, and how the reuse frame matched.
std::string frameLine(const ReuseBenchFrame& row, int index, int frameCount, const ReuseFrameStats& stats,
                      const FrameMatch& match) {
    std::string line = "frame " + std::to_string(row.frame) + " (" + std::to_string(index + 1) + "/" +
                       std::to_string(frameCount) + "): " + row.mode + ", " + std::to_string(stats.redrawnTris) +
                       " of " + std::to_string(stats.drawnTris) + " triangles drawn";
    if (stats.mode == ReuseMode::Reuse)
        line +=
            ", " + std::to_string(stats.copiedPx) + " px copied, " + std::to_string(stats.clearedPx) + " px cleared";
    else
        line += " (" + stats.reason + ")";
    if (match.ties) line += ", " + std::to_string(match.ties) + " tie px";
    if (match.errors()) line += ", " + std::to_string(match.errors()) + " px differ from the full render (depth)";
    return line;
}

// One frame, ready to be timed: its set-up, the culling method's list (with culling), the reuse
// plan (and the time it took) and the oracles' plans.
struct PlannedFrame {
    FrameSetup setup;
    DrawList culled;
    FramePlan plan, oracle, oracleWhole;
    double planMs = 0.0;
    ReuseFrameStats stats;
    std::size_t draws = 0;  // draw commands the reuse plan issues
};

// A frame's four times, in milliseconds.
struct FrameTimes {
    double full = 0.0, execute = 0.0, oracle = 0.0, oracleWhole = 0.0, clear = 0.0;
};

// The rounds over the frames, on one stage with its extra targets.
class ReuseRun {
public:
    ReuseRun(const Scene& scene, const ReuseBenchSettings& settings, Stage& stage,
             const std::optional<SceneCuller>& culler, const Targets& targets)
        : scene_(scene),
          s_(settings),
          r_(settings.render),
          stage_(stage),
          culler_(culler),
          targets_(targets),
          count_(settings.lastFrame - settings.firstFrame + 1),
          frames_(std::size_t(count_)),
          samples_(std::size_t(count_)),
          dirty_(r_.width, r_.height, r_.reuseSettings.cell) {}

    // Round -1 is the warm-up: untimed, it describes and checks every frame. Then the timed rounds.
    Result<bool> runRound(int round, const FrameSetupOf& setupOf, const Progress& progress) {
        TemporalReuse reuse(scene_, r_.width, r_.height, reuseOptionsFrom(r_.reuseSettings));
        std::vector<double> full, reused, oracle, oracleWhole;
        for (int i = 0; i < count_; ++i) {
            const int frame = s_.firstFrame + i;
            Result<FrameSetup> setup = setupOf(frame);
            if (!setup) return Error{"frame " + std::to_string(frame) + ": " + setup.error().message, setup.error().kind};
            const PlannedFrame planned = planFrame(reuse, std::move(*setup));
            const FrameTimes t = timeFrame(round, planned);
            if (round < 0) {
                progress(checkFrame(i, frame, planned));
                continue;
            }
            Samples& s = samples_[std::size_t(i)];
            s.full.push_back(t.full);
            s.reuse.push_back(planned.planMs + t.execute);
            s.plan.push_back(planned.planMs);
            s.oracle.push_back(t.oracle);
            s.oracleWhole.push_back(t.oracleWhole);
            s.overlap.push_back(planned.stats.overlapMs);
            clears_.push_back(t.clear);
            full.push_back(t.full);
            reused.push_back(planned.planMs + t.execute);
            oracle.push_back(t.oracle);
            oracleWhole.push_back(t.oracleWhole);
        }
        if (round >= 0)
            progress("round " + std::to_string(round + 1) + "/" + std::to_string(s_.repeat) + ": full " +
                     fmt(median(full)) + " ms, reuse " + fmt(median(reused)) + " ms, oracle " + fmt(median(oracle)) +
                     " ms, whole oracle " + fmt(median(oracleWhole)) + " ms (medians of " + std::to_string(count_) +
                     " frames)");
        return true;
    }

    // The report, with the medians over the timed rounds; once, after the last round.
    ReuseMeasurement result() {
        for (std::size_t i = 0; i < frames_.size(); ++i) {
            const Samples& s = samples_[i];
            frames_[i].fullMs = median(s.full);
            frames_[i].reuseMs = median(s.reuse);
            frames_[i].planMs = median(s.plan);
            frames_[i].oracleMs = median(s.oracle);
            frames_[i].oracleWholeMs = median(s.oracleWhole);
            frames_[i].overlapMs = median(s.overlap);
        }
        ReuseMeasurement measured;
        ReuseBench& bench = measured.report;
        bench.scene = s_.scene;
        bench.width = r_.width;
        bench.height = r_.height;
        bench.backend = stage_.backend().name();
        bench.renderer = stage_.backend().renderer();
        bench.repeat = s_.repeat;
        bench.cull = toString(r_.cull);
        bench.grain = r_.reuseSettings.grain;
        bench.cell = r_.reuseSettings.cell;
        bench.fallback = r_.reuseSettings.fallback;
        bench.ids = r_.ids;
        bench.staticPairBytes = std::uint64_t(r_.width) * std::uint64_t(r_.height) * kTargetBytesPerPixel;
        bench.clearMs = median(clears_);
        bench.frames = std::move(frames_);
        measured.oracleError = std::move(oracleError_);
        return measured;
    }

private:
    struct Samples {
        std::vector<double> full, reuse, plan, oracle, oracleWhole, overlap;
    };

    // What the full render of `f` draws: the culling method's list, or every instance.
    const DrawList& listOf(const PlannedFrame& f) const { return culler_ ? f.culled : stage_.renderer().fullList(); }

    // The frame's list and reuse plan (the plan timed alone: CPU work, nothing of the backend's
    // pending), and the oracles' static image drawn (untimed) with their plans.
    PlannedFrame planFrame(TemporalReuse& reuse, FrameSetup setup) {
        PlannedFrame f{std::move(setup), {}, {}, {}, {}, 0.0, {}, 0};
        const FrameParams& params = f.setup.params;
        const std::vector<glm::mat4>& world = f.setup.world;
        SceneRenderer& renderer = stage_.renderer();
        if (culler_) f.culled = culler_->cull(r_.cull, scene_, world, f.setup.view);
        const DrawList& list = listOf(f);
        stage_.backend().finish();
        const auto t0 = Clock::now();
        f.plan = culler_ ? reuse.plan(params, world, list, r_.background) : reuse.plan(params, world, r_.background);
        f.planMs = msSince(t0);
        f.stats = reuse.stats();

        // The oracles' static image: the instances static in this frame alone.
        DrawList statics, dynamics;
        for (const DrawCommand& draw : list) (reuse.dynamicNow(draw.instance) ? dynamics : statics).push_back(draw);
        renderer.renderFrame(targets_.image.get(), r_.width, r_.height, params, world, r_.background, statics);
        const Rect whole{0, 0, r_.width, r_.height};
        f.oracleWhole = makeWholeOraclePlan(whole, dynamics);
        f.oracle = makeOraclePlan(f.plan, f.stats.mode, dirty_, whole, std::move(dynamics));
        for (const PlanStep& step : f.plan) f.draws += step.list ? step.list->size() : step.draws.size();
        return f;
    }

    // Timed back to back, the order rotated from round to round: a whole-target clear (t_w, of
    // another target) with the full render right after it, the reuse frame, the cells oracle, the
    // whole oracle.
    FrameTimes timeFrame(int round, const PlannedFrame& f) {
        Backend& backend = stage_.backend();
        SceneRenderer& renderer = stage_.renderer();
        const FrameParams& params = f.setup.params;
        const std::vector<glm::mat4>& world = f.setup.world;
        const glm::vec4& background = r_.background;
        const int width = r_.width, height = r_.height;
        const Rect whole{0, 0, width, height};
        const DrawList& list = listOf(f);
        const auto time = [&backend](const auto& work) {
            backend.finish();
            const auto start = Clock::now();
            work();
            backend.finish();
            return msSince(start);
        };
        FrameTimes t;
        for (int step = 0; step < 4; ++step) {
            switch ((step + std::max(round, 0)) % 4) {
                case 0:
                    // t_w on the whole oracle's target (its plan overwrites all of it): a clear of the
                    // full render's own target just before it would warm that target's cache.
                    t.clear = time([&] {
                        backend.clear(targets_.oracleWhole.get(), whole, background, farDepth(params.depthFormat));
                    });
                    t.full = time(
                        [&] { renderer.renderFrame(stage_.target(), width, height, params, world, background, list); });
                    break;
                case 1:
                    t.execute = time([&] {
                        renderer.execute(f.plan, targets_.render.get(), targets_.statics.get(), params, world,
                                         background);
                    });
                    break;
                case 2:
                    t.oracle = time([&] {
                        renderer.execute(f.oracle, targets_.oracle.get(), targets_.image.get(), params, world,
                                         background);
                    });
                    break;
                default:
                    t.oracleWhole = time([&] {
                        renderer.execute(f.oracleWhole, targets_.oracleWhole.get(), targets_.image.get(), params, world,
                                         background);
                    });
                    break;
            }
        }
        return t;
    }

    // The warm-up's check of frame `i`: the reuse frame against the full render (ties allowed),
    // and both oracles, which are exact too (a tie aside) or no floor of anything. Gives the line.
    std::string checkFrame(int i, int frame, const PlannedFrame& f) {
        Backend& backend = stage_.backend();
        ReuseBenchFrame& row = frames_[std::size_t(i)];
        row = describeFrame(frame, f.stats, f.draws, listOf(f).size());
        const Buffers fullImage = backend.readBack(stage_.target());
        const FrameMatch match = matchFrames(backend.readBack(targets_.render.get()), fullImage);
        row.tiePx = match.ties;
        row.errorPx = match.errors();
        if (!oracleError_)
            oracleError_ = checkOracle(frame, "oracle", backend.readBack(targets_.oracle.get()), fullImage);
        if (!oracleError_)
            oracleError_ = checkOracle(frame, "whole oracle", backend.readBack(targets_.oracleWhole.get()), fullImage);
        return frameLine(row, i, count_, f.stats, match);
    }

    const Scene& scene_;
    const ReuseBenchSettings& s_;
    const Settings& r_;
    Stage& stage_;
    const std::optional<SceneCuller>& culler_;
    const Targets& targets_;
    int count_;
    std::vector<ReuseBenchFrame> frames_;
    std::vector<Samples> samples_;
    std::vector<double> clears_;
    std::optional<std::string> oracleError_;
    reuse::CellGrid dirty_;
};

}  // namespace

Result<ReuseMeasurement> measureReuse(Scene& scene, const ReuseBenchSettings& settings, const FrameSetupOf& setupOf,
                                      const Progress& progress) {
    std::optional<SceneCuller> culler = cullingOf(scene, settings.render, progress);
    Result<Stage> stage = Stage::open(settings.render);
    if (!stage) return stage.error();
    Backend& backend = stage->backend();
    progress("backend: " + describe(backend));
    if (Result<bool> uploaded = stage->upload(scene); !uploaded) return uploaded.error();
    Targets targets(backend);
    if (Result<bool> made = targets.make(backend, settings.render); !made) return made.error();

    ReuseRun run(scene, settings, *stage, culler, targets);
    for (int round = -1; round < settings.repeat; ++round)  // round -1: the warm-up, untimed, and the check
        if (Result<bool> done = run.runRound(round, setupOf, progress); !done) return done.error();
    return run.result();
}

std::optional<Error> reuseFailure(const ReuseMeasurement& measured) {
    if (measured.oracleError) return Error{*measured.oracleError};
    for (const ReuseBenchFrame& f : measured.report.frames)
        if (f.errorPx > 0)
            return Error{"frame " + std::to_string(f.frame) + ": reuse differs from the full render at " +
                         std::to_string(f.errorPx) + " pixels (depth)"};
    return std::nullopt;
}

}  // namespace frugal
