// `frugal soak` (issue 11): many frames and many create/destroy cycles in one process, on every
// backend, with resident memory sampled and every image checked (report/SoakReport.h says what is
// judged). The frames are rendered by frugal::Renderer, the library's entry point that `frugal
// render` runs, so whatever it keeps per frame the soak sees; the create/destroy cycles open
// backends (openBackend), targets and uploads (SceneRenderer) as the renderer does.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <ostream>
#include <sstream>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "app/ReportOutputs.h"
#include "lab/MinimalFrame.h"
#include "lab/SoakReport.h"

namespace frugal {

const char* soakHelp() {
    return R"(usage: frugal soak [SCENE] [options]

Renders SCENE (default builtin:cubes, 28 spinning cubes) for many frames in one process, then
creates and destroys backends, targets and the scene's uploads many times, on every backend
(software, egl-device, egl-surfaceless, osmesa: those that open here) or only --backend, and
judges what long runs break:
  memory   resident memory (VmRSS, /proc/self/status) sampled as it goes; its growth from the end
           of the warm-up (frames: --warmup; cycles: the first 1 %) to the end must stay within
           --max-growth
  images   the animation is looped every PERIOD frames, so frame f and f + PERIOD show the same
           time: every frame's colour, depth and ids must equal, bit for bit, the first frame of
           its time (64-bit hash); a frame with nothing but background counts as blank
  cycles   each cycle draws one frame, which must equal the first cycle's: "backend" opens a new
           backend with a target and the scene uploaded; "target" creates a target on one
           backend; "scene" uploads the scene's meshes and textures anew (SceneRenderer)
Prints a table per backend and a verdict; exit status 0 when everything passes, 1 otherwise.
Progress goes to stderr, a line every few seconds at most.
)";
}

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// VmRSS and VmHWM from /proc/self/status; nothing when they cannot be read (not Linux).
std::optional<MemoryUse> currentMemoryUse() {
    std::ifstream in("/proc/self/status");
    MemoryUse use;
    bool rss = false, hwm = false;
    std::string key;
    while (in >> key) {
        if (key == "VmRSS:")
            rss = static_cast<bool>(in >> use.rssKb);
        else if (key == "VmHWM:")
            hwm = static_cast<bool>(in >> use.hwmKb);
        in.ignore(1 << 20, '\n');
    }
    if (!rss || !hwm) return std::nullopt;
    return use;
}

MemorySample sampleNow(std::int64_t index, double msEach) {
    return {index, currentMemoryUse().value_or(MemoryUse{}), msEach};
}

// Room for `count` samples, written once so that their pages are resident before the first
// sample: filling them would otherwise show as growth (32 bytes a sample, a 4 KiB page every 128).
void reserveSamples(std::vector<MemorySample>& samples, std::size_t count) {
    samples.resize(count);
    samples.clear();
}

// Progress on stderr: a line when at least a few seconds passed since the last (the first at once).
class Progress {
public:
    Progress(std::ostream& err, bool quiet) : err_(err), quiet_(quiet) {}
    template <class Line>
    void maybe(Line&& line) {
        if (quiet_ || (printed_ && secondsSince(last_) < 5.0)) return;
        err_ << "soak: " << line() << "\n";
        last_ = Clock::now();
        printed_ = true;
    }

private:
    std::ostream& err_;
    bool quiet_;
    bool printed_ = false;
    Clock::time_point last_;
};

std::string mibText(const MemorySample& sample) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MiB", double(sample.memory.rssKb) / 1024.0);
    return text;
}

struct SoakSettings {
    std::int64_t frames = 100000, cycles = 1000;
    std::optional<int> period;
    std::optional<std::int64_t> warmup, sampleEvery;
    bool ids = false;
    bool minimal = false;  // the frames drawn by gl/MinimalFrame.h instead of frugal's backend
};

// What every frame of a run shares.
struct SoakContext {
    const RenderOptions& options;
    const Scene& scene;
    const SoakSettings& settings;
    int period;
    double fps;
    std::array<std::uint8_t, 4> background;
};

double timeOfFrame(const SoakContext& c, std::int64_t frame) {
    if (c.options.time) return *c.options.time;
    return frameTime(int(frame % c.period), c.fps);
}

// Draws the frame of scene time `time` into `target` and reads it back.
Result<Buffers> drawFrame(const SoakContext& c, Backend& backend, SceneRenderer& renderer, TargetHandle target,
                          double time) {
    Result<FrameSetup> setup = setUpFrame(c.scene, c.options.camera, time, c.options.width, c.options.height,
                                          c.settings.ids, c.options.depthFormat);
    if (!setup) return Error{c.options.scene + ": " + setup.error()};
    renderer.renderFrame(target, c.options.width, c.options.height, setup->params, setup->world, c.options.background);
    return backend.readBack(target);
}

// The context kind of a GL backend by its name (Backend::name).
ContextKind contextKindNamed(const std::string& name) {
    for (ContextKind kind : {ContextKind::EglDevice, ContextKind::OsMesa})
        if (name == contextKindName(kind)) return kind;
    return ContextKind::EglSurfaceless;
}

// A frame as the soak judges it: the hash of its images and whether it is background only.
struct FrameDigest {
    std::uint64_t hash = 0;
    bool blank = false;
};

// The frames of one run: `draw(time)` renders the frame of scene time `time` and gives its digest.
// Nothing on success, else the exit status after the error line.
template <class Draw>
std::optional<int> soakFrames(const SoakContext& c, SoakFrames& run, Progress& progress, std::ostream& err,
                              Draw&& draw) {
    const SoakSettings& s = c.settings;
    run.frames = s.frames;
    run.warmup = s.warmup.value_or(std::min(s.frames, std::max<std::int64_t>(c.period, s.frames / 100)));
    run.images = EqualTimeImages(c.period);
    const std::int64_t every = s.sampleEvery.value_or(std::max<std::int64_t>(1, s.frames / 1000));
    const auto t0 = Clock::now();
    auto since = t0;
    std::int64_t sinceFrame = 0;
    reserveSamples(run.samples, std::size_t(s.frames / every) + 3);
    run.samples.push_back(sampleNow(0, 0.0));
    for (std::int64_t f = 0; f < s.frames; ++f) {
        Result<FrameDigest> image = draw(timeOfFrame(c, f));
        if (!image) return fail(err, image.failure());
        run.images.add(f, image->hash, image->blank);
        const std::int64_t done = f + 1;
        if (done % every == 0 || done == run.warmup || done == s.frames) {
            run.samples.push_back(sampleNow(done, 1000.0 * secondsSince(since) / double(done - sinceFrame)));
            since = Clock::now();
            sinceFrame = done;
            progress.maybe([&] {
                return run.backend + ": frame " + std::to_string(done) + " of " + std::to_string(s.frames) + ", RSS " +
                       mibText(run.samples.back()) + ", " + std::to_string(run.images.mismatched) + " mismatched";
            });
        }
    }
    run.seconds = secondsSince(t0);
    return std::nullopt;
}

// The cycles of one kind: `cycle()` does one and gives its image's hash, or why it failed; the image
// must be `reference`.
template <class Cycle>
void soakCycles(const SoakSettings& s, std::uint64_t reference, SoakCycles& run, Progress& progress, Cycle&& cycle) {
    run.cycles = s.cycles;
    const std::int64_t every = std::max<std::int64_t>(1, s.cycles / 100);
    run.warmup = every;
    reserveSamples(run.samples, std::size_t(s.cycles / every) + 2);
    run.before = currentMemoryUse().value_or(MemoryUse{});
    const auto t0 = Clock::now();
    auto since = t0;
    std::int64_t sinceCycle = 0;
    for (std::int64_t i = 0; i < s.cycles; ++i) {
        Result<std::uint64_t> hash = cycle();
        std::string failure;
        if (!hash)
            failure = hash.error();
        else if (*hash != reference)
            failure = "the image differs from the one drawn before the cycles";
        if (!failure.empty()) {
            if (run.failures++ == 0) run.firstFailure = "cycle " + std::to_string(i + 1) + ": " + failure;
        }
        const std::int64_t done = i + 1;
        if (done == 1 || done % every == 0 || done == s.cycles) {
            run.samples.push_back(sampleNow(done, 1000.0 * secondsSince(since) / double(done - sinceCycle)));
            since = Clock::now();
            sinceCycle = done;
            progress.maybe([&] {
                return run.backend + ": " + run.kind + " cycle " + std::to_string(done) + " of " +
                       std::to_string(s.cycles) + ", RSS " + mibText(run.samples.back()) + ", " +
                       std::to_string(run.failures) + " failed";
            });
        }
    }
    run.seconds = secondsSince(t0);
}

// A cycle's image as a hash; a blank one is a failure (every cycle draws the scene at one time).
Result<std::uint64_t> cycleImage(const SoakContext& c, Result<Buffers> image) {
    if (!image) return Error{image.error()};
    if (isBlank(*image, c.background)) return Error{"blank image (background only)"};
    return imageHash(*image);
}

// The three kinds of cycles on one backend selection, each cycle's image compared with the first
// frame of a session opened before them (a cycle that repeats its predecessor's fault exactly would
// agree with itself). Nothing on success, else the exit status after the error line.
std::optional<int> soakAllCycles(const SoakContext& c, BackendKind choice, const std::string& name, SoakReport& report,
                                 Progress& progress, std::ostream& err) {
    const double time = timeOfFrame(c, 0);
    const auto cyclesOf = [&name](const char* kind) {
        SoakCycles run;
        run.backend = name;
        run.kind = kind;
        return run;
    };
    Result<Session> opened = openSession(choice, c.options);
    if (!opened) {
        err << "error: --backend " << name << ": " << opened.error() << "\n";
        return int(kExitNoBackend);
    }
    if (int prepared = prepareSession(*opened, c.options, c.scene, err); prepared != kExitOk) return prepared;
    Session& session = *opened;
    Backend& backend = *session.backend;
    Result<std::uint64_t> reference = cycleImage(c, drawFrame(c, backend, *session.renderer, session.target, time));
    if (!reference) {
        err << "error: soak: " << name << ": " << reference.error() << "\n";
        return int(kExitError);
    }

    SoakCycles backends = cyclesOf("backend");
    soakCycles(c.settings, *reference, backends, progress, [&]() -> Result<std::uint64_t> {
        Result<Session> cycle = openSession(choice, c.options);
        if (!cycle) return Error{cycle.error()};
        std::ostringstream line;  // prepareSession's "error: <why>\n"
        if (prepareSession(*cycle, c.options, c.scene, line) != kExitOk) {
            std::string why = line.str();
            if (why.rfind("error: ", 0) == 0) why.erase(0, 7);
            if (!why.empty() && why.back() == '\n') why.pop_back();
            return Error{why};
        }
        return cycleImage(c, drawFrame(c, *cycle->backend, *cycle->renderer, cycle->target, time));
    });
    report.cycles.push_back(std::move(backends));

    SoakCycles targets = cyclesOf("target");
    soakCycles(c.settings, *reference, targets, progress, [&]() -> Result<std::uint64_t> {
        const TargetHandle target = backend.createTarget(c.options.width, c.options.height, c.options.depthFormat);
        if (target == kNoHandle) return Error{"createTarget failed"};
        Result<std::uint64_t> hash = cycleImage(c, drawFrame(c, backend, *session.renderer, target, time));
        backend.destroyTarget(target);
        return hash;
    });
    report.cycles.push_back(std::move(targets));

    // The uploads are released before the next are made, so that a backend reusing GL names gets
    // the same names back (what a stale state cache would trip over).
    session.renderer.reset();
    SoakCycles uploads = cyclesOf("scene");
    soakCycles(c.settings, *reference, uploads, progress, [&]() -> Result<std::uint64_t> {
        Result<SceneRenderer> renderer = SceneRenderer::create(backend, c.scene);
        if (!renderer) return Error{renderer.error()};
        return cycleImage(c, drawFrame(c, backend, *renderer, session.target, time));
    });
    report.cycles.push_back(std::move(uploads));
    return std::nullopt;
}

}  // namespace

int runSoak(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    options.scene = "builtin:cubes";
    options.width = 64;
    options.height = 48;
    SoakSettings settings;
    ReportPaths outputs;
    double maxGrowth = 5.0;
    CommandLine command{"soak", soakHelp(), &options};
    constexpr long long kMany = 1000000000;
    command.flags = {
        {"", {
            flag::whole("--frames", "N", "frames per backend (default 100000; 0: cycles only)", settings.frames, 0, kMany),
            flag::whole("--cycles", "N", "create/destroy cycles of each kind per backend (default 1000; 0: none)",
                        settings.cycles, 0, kMany),
            flag::whole("--period", "N", "frames per loop of the animation (default: the scene's animation length at "
                        "--fps, e.g. 300 for builtin:cubes; 1 for a still scene or --time)", settings.period, 1, kMany),
            flag::whole("--warmup", "N", "frames before the memory baseline (default 1 % of --frames, at least one "
                        "period: llvmpipe compiles its shader variants in the first frames)", settings.warmup, 0, kMany),
            flag::whole("--sample-every", "N", "frames between memory samples (default --frames / 1000, at least 1); "
                        "cycles are sampled every --cycles / 100", settings.sampleEvery, 1, kMany),
            flag::number("--max-growth", "PCT", "the memory growth allowed after warm-up, in percent (default 5)",
                         maxGrowth, 0, 1000),
            flag::on("--ids", "also write triangle ids every frame (the id pass)", settings.ids),
            flag::on("--minimal", "on each GL backend, the frames are drawn by the minimal GL program of 'frugal "
                     "bench render' (one program, glClear, glDrawElements per instance; gl/MinimalFrame.h) on a "
                     "context of the same kind instead: what Mesa alone does with memory over the same frames. No "
                     "cycles; its rows are named KIND (minimal).", settings.minimal),
            flag::text("--json", "FILE", "{\"scene\",\"size\",\"period\",\"fps\",\"max_growth_pct\",\"passed\","
                       "\"frames\":[{\"backend\",\"frames\",\"warmup\",\"rss_warm_kb\",\"rss_end_kb\",\"growth_pct\","
                       "\"compared_frames\",\"mismatched_frames\",\"blank_frames\",\"passed\",...}],\"cycles\":"
                       "[{\"backend\",\"kind\",\"cycles\",\"failures\",\"rss_warm_kb\",\"rss_end_kb\",\"growth_pct\","
                       "\"passed\",...}],\"skipped\":[...]}", outputs.json),
            flag::text("--csv", "FILE", "every memory sample: run (frames, backend, target, scene), backend, index, "
                       "rss_kb, hwm_kb, ms_each", outputs.csv),
            flag::text("--plot", "FILE.svg|.png", "resident memory over frames and over cycles, drawn by gnuplot from "
                       "the CSV (--csv, or FILE.csv beside the plot); the script is written as FILE.gp", outputs.plot),
            flag::size("--size", "WxH", "image size (default 64x48)", options.width, options.height, 65536,
                       &options.sizeGiven),
            flag::choice("--backend", "NAME", "a backend", "one backend only: software, egl-device, egl-surfaceless "
                         "or osmesa (auto, the default, runs each)", options.backend, kBackendKinds),
        }},
    };
    command.positional = sceneArgument(options);
    command.finish = [&](ArgCursor& cursor) {
        // Besides SVG, --plot takes a .png (gnuplot's pngcairo): a picture a README can show.
        if (const std::string problem = plotProblem(outputs, /*pngToo=*/true); !problem.empty())
            cursor.fail(problem);
        else if (settings.frames == 0 && (settings.cycles == 0 || settings.minimal))
            cursor.fail(settings.minimal ? "--minimal with --frames 0: the minimal GL program only draws frames"
                                         : "--frames 0 with --cycles 0: nothing to do");
        else if (settings.minimal && settings.ids)
            cursor.fail("--minimal with --ids: the minimal GL program draws no ids");
        else if (settings.minimal && options.backend == BackendKind::Software)
            cursor.fail("--minimal with --backend software: the minimal program is a GL program; pick a GL backend");
        else if (settings.warmup && settings.frames > 0 && *settings.warmup >= settings.frames)
            cursor.fail("--warmup " + std::to_string(*settings.warmup) + ": must be less than --frames " +
                        std::to_string(settings.frames));
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;

    if (!currentMemoryUse()) {
        err << "error: soak: cannot read VmRSS and VmHWM from /proc/self/status (Linux only)\n";
        return kExitError;
    }
    Result<Scene> loaded = loadForRender(options, err);
    if (!loaded) {
        err << "error: " << loaded.error() << "\n";
        return kExitError;
    }
    const Scene& scene = *loaded;
    const double fps = options.fps.value_or(scene.fps);
    const int period =
        settings.period.value_or(options.time ? 1 : std::max(1, int(std::lround(scene.duration() * fps))));
    const SoakContext context{options, scene, settings, period, fps, colorBytes(options.background)};

    std::vector<BackendKind> choices;
    if (options.backend != BackendKind::Auto)
        choices = {options.backend};
    else
        choices = {BackendKind::EglDevice, BackendKind::EglSurfaceless, BackendKind::OsMesa};
    if (!settings.minimal && choices.size() > 1) choices.insert(choices.begin(), BackendKind::Software);

    SoakReport report;
    report.scene = options.scene;
    report.width = options.width;
    report.height = options.height;
    report.period = period;
    report.fps = fps;
    report.ids = settings.ids;
    report.maxGrowthPct = maxGrowth;
    Progress progress(err, options.quiet);
    std::vector<std::pair<BackendKind, std::string>> opened;  // the kinds that open, by name
    for (const BackendKind choice : choices) {
        Result<Session> session = openSession(choice, options);
        if (!session) {
            report.skipped.push_back({toString(choice), session.error()});
            if (!options.quiet) err << "skipped " << toString(choice) << ": " << session.error() << "\n";
            continue;
        }
        opened.emplace_back(choice, session->backend->name());
        if (settings.frames == 0) continue;
        SoakFrames run;
        run.backend = session->backend->name();
        run.renderer = session->backend->renderer();
        if (settings.minimal) {
            // Only the minimal program's context is alive while it draws.
            session->backend.reset();
            Result<std::unique_ptr<MinimalFrame>> minimal =
                createMinimalFrame(contextKindNamed(run.backend), scene, options.width, options.height);
            if (!minimal) {
                err << "error: --minimal: " << run.backend << ": " << minimal.error() << "\n";
                return kExitError;
            }
            run.backend += " (minimal)";
            MinimalFrame& frame = **minimal;
            const auto draw = [&](double time) -> Result<FrameDigest> {
                Result<FrameSetup> setup =
                    setUpFrame(scene, options.camera, time, options.width, options.height, false, options.depthFormat);
                if (!setup) return Error{options.scene + ": " + setup.error()};
                frame.render(setup->params, setup->world, options.background);
                const Buffers image = frame.readBack();
                return FrameDigest{imageHash(image), isBlank(image, context.background)};
            };
            if (std::optional<int> failed = soakFrames(context, run, progress, err, draw)) return *failed;
        } else {
            // The frames go through the library's entry point, frugal::Renderer, as `frugal render`'s
            // do: whatever it keeps per frame, the soak sees. Only its backend is alive while it draws.
            session->backend.reset();
            Settings rendering = rendererSettings(options);
            rendering.backend = choice;
            rendering.ids = settings.ids;
            Result<Renderer> renderer = Renderer::create(scene, rendering);
            if (!renderer) return fail(err, renderer.failure());
            const auto draw = [&](double time) -> Result<FrameDigest> {
                Result<Frame> frame = renderer->render(options.camera, time);
                if (!frame) return frame.failure();
                return FrameDigest{imageHash(*frame), isBlank(frame->color, context.background)};
            };
            if (std::optional<int> failed = soakFrames(context, run, progress, err, draw)) return *failed;
        }
        report.frames.push_back(std::move(run));
    }
    if (opened.empty()) {
        err << "error: soak: no backend available\n";
        return kExitNoBackend;
    }
    if (settings.cycles > 0 && !settings.minimal)
        for (const auto& [choice, name] : opened)
            if (std::optional<int> failed = soakAllCycles(context, choice, name, report, progress, err)) return *failed;

    out << soakReportText(report);
    const ReportTexts texts{
        [&report] { return soakReportJson(report); }, [&report] { return soakReportCsv(report); },
        [&report](const std::string& csv, const std::string& plot) { return soakReportGnuplot(csv, plot, report); }};
    if (int written = writeReportFiles(outputs, texts, err); written != kExitOk) return written;
    return passed(report) ? kExitOk : kExitError;
}

}  // namespace frugal
