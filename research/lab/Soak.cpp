#include "lab/Soak.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <utility>
#include <vector>

#include <frugal/Renderer.h>

#include "lab/MinimalFrame.h"
#include "renderer/Research.h"

namespace frugal {

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

namespace {

using Clock = std::chrono::steady_clock;
using ProgressFn = std::function<void(const std::string&)>;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

MemorySample sampleNow(std::int64_t index, double msEach) {
    return {index, currentMemoryUse().value_or(MemoryUse{}), msEach};
}

// Room for `count` samples, written once so that their pages are resident before the first
// sample: filling them would otherwise show as growth (32 bytes a sample, a 4 KiB page every 128).
void reserveSamples(std::vector<MemorySample>& samples, std::size_t count) {
    samples.resize(count);
    samples.clear();
}

// Progress: a line when at least a few seconds passed since the last (the first at once).
class Progress {
public:
    explicit Progress(const ProgressFn& out) : out_(out) {}
    template <class Line>
    void maybe(Line&& line) {
        if (printed_ && secondsSince(last_) < 5.0) return;
        out_("soak: " + line());
        last_ = Clock::now();
        printed_ = true;
    }

private:
    const ProgressFn& out_;
    bool printed_ = false;
    Clock::time_point last_;
};

std::string mibText(const MemorySample& sample) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MiB", double(sample.memory.rssKb) / 1024.0);
    return text;
}

// A frame as the soak judges it: the hash of its images and whether it is background only.
struct FrameDigest {
    std::uint64_t hash = 0;
    bool blank = false;
};

// What every run of a soak shares.
class Soak {
public:
    Soak(const Scene& scene, const SoakSettings& settings, const ProgressFn& progress)
        : scene_(scene), s_(settings), out_(progress), progress_(progress), background_(colorBytes(settings.render.background)) {}

    Result<SoakReport> run();

private:
    double timeOfFrame(std::int64_t frame) const {
        if (s_.time) return *s_.time;
        return frameTime(int(frame % s_.period), s_.fps);
    }
    Settings settingsFor(BackendKind kind) const {
        Settings rendering = s_.render;
        rendering.backend = kind;
        rendering.ids = s_.ids;
        return rendering;
    }
    // Draws the frame of scene time `time` on `stage` (into `target`) and reads it back.
    Result<Buffers> drawFrame(Stage& stage, TargetHandle target, double time) const;
    // A cycle's image as a hash; a blank one is a failure (every cycle draws the scene at one time).
    Result<std::uint64_t> cycleImage(Result<Buffers> image) const;
    template <class Draw>
    Result<bool> frames(SoakFrames& run, Draw&& draw);
    template <class Cycle>
    void cycles(std::uint64_t reference, SoakCycles& run, Cycle&& cycle);
    Result<bool> framesOn(BackendKind kind, SoakFrames run, SoakReport& report);
    Result<bool> allCycles(BackendKind kind, const std::string& name, SoakReport& report);

    const Scene& scene_;
    const SoakSettings& s_;
    const ProgressFn& out_;  // every line
    Progress progress_;      // a line every few seconds
    std::array<std::uint8_t, 4> background_;
};

Result<Buffers> Soak::drawFrame(Stage& stage, TargetHandle target, double time) const {
    const Settings& r = s_.render;
    Result<FrameSetup> setup = setUpFrame(scene_, s_.camera, time, r.width, r.height, s_.ids, r.depthFormat);
    if (!setup) return Error{s_.scene + ": " + setup.error().message};
    applyShading(r, setup->params);
    stage.renderer().renderFrame(target, r.width, r.height, setup->params, setup->world, r.background);
    return stage.backend().readBack(target);
}

Result<std::uint64_t> Soak::cycleImage(Result<Buffers> image) const {
    if (!image) return image.error();
    if (isBlank(*image, background_)) return Error{"blank image (background only)"};
    return imageHash(*image);
}

// The frames of one run: `draw(time)` renders the frame of scene time `time` and gives its digest.
template <class Draw>
Result<bool> Soak::frames(SoakFrames& run, Draw&& draw) {
    run.frames = s_.frames;
    run.warmup = s_.warmup.value_or(std::min(s_.frames, std::max<std::int64_t>(s_.period, s_.frames / 100)));
    run.images = EqualTimeImages(s_.period);
    const std::int64_t every = s_.sampleEvery.value_or(std::max<std::int64_t>(1, s_.frames / 1000));
    const auto t0 = Clock::now();
    auto since = t0;
    std::int64_t sinceFrame = 0;
    reserveSamples(run.samples, std::size_t(s_.frames / every) + 3);
    run.samples.push_back(sampleNow(0, 0.0));
    for (std::int64_t f = 0; f < s_.frames; ++f) {
        Result<FrameDigest> image = draw(timeOfFrame(s_.firstFrame + f));
        if (!image) return image.error();
        run.images.add(f, image->hash, image->blank);
        const std::int64_t done = f + 1;
        if (done % every == 0 || done == run.warmup || done == s_.frames) {
            run.samples.push_back(sampleNow(done, 1000.0 * secondsSince(since) / double(done - sinceFrame)));
            since = Clock::now();
            sinceFrame = done;
            progress_.maybe([&] {
                return run.backend + ": frame " + std::to_string(done) + " of " + std::to_string(s_.frames) + ", RSS " +
                       mibText(run.samples.back()) + ", " + std::to_string(run.images.mismatched) + " mismatched";
            });
        }
    }
    run.seconds = secondsSince(t0);
    return true;
}

// The cycles of one kind: `cycle()` does one and gives its image's hash, or why it failed; the image
// must be `reference`.
template <class Cycle>
void Soak::cycles(std::uint64_t reference, SoakCycles& run, Cycle&& cycle) {
    run.cycles = s_.cycles;
    const std::int64_t every = std::max<std::int64_t>(1, s_.cycles / 100);
    run.warmup = every;
    reserveSamples(run.samples, std::size_t(s_.cycles / every) + 2);
    run.before = currentMemoryUse().value_or(MemoryUse{});
    const auto t0 = Clock::now();
    auto since = t0;
    std::int64_t sinceCycle = 0;
    for (std::int64_t i = 0; i < s_.cycles; ++i) {
        Result<std::uint64_t> hash = cycle();
        std::string failure;
        if (!hash)
            failure = hash.error().message;
        else if (*hash != reference)
            failure = "the image differs from the one drawn before the cycles";
        if (!failure.empty()) {
            if (run.failures++ == 0) run.firstFailure = "cycle " + std::to_string(i + 1) + ": " + failure;
        }
        const std::int64_t done = i + 1;
        if (done == 1 || done % every == 0 || done == s_.cycles) {
            run.samples.push_back(sampleNow(done, 1000.0 * secondsSince(since) / double(done - sinceCycle)));
            since = Clock::now();
            sinceCycle = done;
            progress_.maybe([&] {
                return run.backend + ": " + run.kind + " cycle " + std::to_string(done) + " of " +
                       std::to_string(s_.cycles) + ", RSS " + mibText(run.samples.back()) + ", " +
                       std::to_string(run.failures) + " failed";
            });
        }
    }
    run.seconds = secondsSince(t0);
}

// The frames of one backend (`run` names it): only what draws them is alive while they run (the
// Renderer's backend, or the minimal program's context).
Result<bool> Soak::framesOn(BackendKind kind, SoakFrames run, SoakReport& report) {
    const Settings& r = s_.render;
    if (s_.minimal) {
        const ContextKind context = [&] {
            for (ContextKind k : {ContextKind::EglDevice, ContextKind::OsMesa})
                if (run.backend == contextKindName(k)) return k;
            return ContextKind::EglSurfaceless;
        }();
        Result<std::unique_ptr<MinimalFrame>> minimal = createMinimalFrame(context, scene_, r.width, r.height);
        if (!minimal) return Error{"minimal: " + run.backend + ": " + minimal.error().message, ErrorKind::BadInput, true};
        run.backend += " (minimal)";
        MinimalFrame& frame = **minimal;
        const auto draw = [&](double time) -> Result<FrameDigest> {
            Result<FrameSetup> setup = setUpFrame(scene_, s_.camera, time, r.width, r.height, false, r.depthFormat);
            if (!setup) return Error{s_.scene + ": " + setup.error().message};
            applyShading(r, setup->params);
            frame.render(setup->params, setup->world, r.background);
            const Buffers image = frame.readBack();
            return FrameDigest{imageHash(image), isBlank(image, background_)};
        };
        if (Result<bool> done = frames(run, draw); !done) return done;
    } else {
        Result<Renderer> renderer = Renderer::create(scene_, settingsFor(kind));
        if (!renderer) return renderer.error();
        const auto draw = [&](double time) -> Result<FrameDigest> {
            Result<Frame> frame = renderer->render(s_.camera, time);
            if (!frame) return frame.error();
            return FrameDigest{imageHash(*frame), isBlank(frame->color, background_)};
        };
        if (Result<bool> done = frames(run, draw); !done) return done;
    }
    report.frames.push_back(std::move(run));
    return true;
}

// The three kinds of cycles on one backend, each cycle's image compared with the first frame of a
// stage opened before them (a cycle that repeats its predecessor's fault exactly would agree with
// itself).
Result<bool> Soak::allCycles(BackendKind kind, const std::string& name, SoakReport& report) {
    const Settings rendering = settingsFor(kind);
    const double time = timeOfFrame(s_.firstFrame);
    const auto cyclesOf = [&name](const char* cycleKind) {
        SoakCycles run;
        run.backend = name;
        run.kind = cycleKind;
        return run;
    };
    const auto failureText = [](const Error& error) { return (error.aboutSetting ? "--" : "") + error.message; };
    Result<Stage> stage = Stage::open(rendering);
    if (!stage) return stage.error();
    if (Result<bool> uploaded = stage->upload(scene_); !uploaded) return uploaded.error();
    Result<std::uint64_t> reference = cycleImage(drawFrame(*stage, stage->target(), time));
    if (!reference) return Error{"soak: " + name + ": " + reference.error().message};

    SoakCycles backends = cyclesOf("backend");
    cycles(*reference, backends, [&]() -> Result<std::uint64_t> {
        Result<Stage> cycle = Stage::open(rendering);
        if (!cycle) return Error{failureText(cycle.error())};
        if (Result<bool> uploaded = cycle->upload(scene_); !uploaded) return Error{failureText(uploaded.error())};
        return cycleImage(drawFrame(*cycle, cycle->target(), time));
    });
    report.cycles.push_back(std::move(backends));

    SoakCycles targets = cyclesOf("target");
    cycles(*reference, targets, [&]() -> Result<std::uint64_t> {
        Backend& backend = stage->backend();
        const TargetHandle target = backend.createTarget(rendering.width, rendering.height, rendering.depthFormat);
        if (target == kNoHandle) return Error{"createTarget failed"};
        Result<std::uint64_t> hash = cycleImage(drawFrame(*stage, target, time));
        backend.destroyTarget(target);
        return hash;
    });
    report.cycles.push_back(std::move(targets));

    // Each upload releases the one before it first, so that a backend reusing GL names gets the
    // same names back (what a stale state cache would trip over).
    SoakCycles uploads = cyclesOf("scene");
    cycles(*reference, uploads, [&]() -> Result<std::uint64_t> {
        if (Result<bool> uploaded = stage->upload(scene_); !uploaded) return uploaded.error();
        return cycleImage(drawFrame(*stage, stage->target(), time));
    });
    report.cycles.push_back(std::move(uploads));
    return true;
}

Result<SoakReport> Soak::run() {
    if (!currentMemoryUse()) return Error{"soak: cannot read VmRSS and VmHWM from /proc/self/status (Linux only)"};
    std::vector<BackendKind> choices;
    if (s_.render.backend != BackendKind::Auto)
        choices = {s_.render.backend};
    else
        choices = {BackendKind::EglDevice, BackendKind::EglSurfaceless, BackendKind::OsMesa};
    if (!s_.minimal && choices.size() > 1) choices.insert(choices.begin(), BackendKind::Software);

    SoakReport report;
    report.scene = s_.scene;
    report.width = s_.render.width;
    report.height = s_.render.height;
    report.period = s_.period;
    report.fps = s_.fps;
    report.ids = s_.ids;
    report.maxGrowthPct = s_.maxGrowthPct;
    std::vector<std::pair<BackendKind, std::string>> opened;  // the kinds that open, by name
    for (const BackendKind kind : choices) {
        Result<std::unique_ptr<Backend>> backend = openBackend(kind, nullptr, s_.render.threads, s_.render.interp);
        if (!backend) {
            report.skipped.push_back({toString(kind), backend.error().message});
            out_(std::string("skipped ") + toString(kind) + ": " + backend.error().message);
            continue;
        }
        opened.emplace_back(kind, (*backend)->name());
        if (s_.frames == 0) continue;
        SoakFrames run;
        run.backend = (*backend)->name();
        run.renderer = (*backend)->renderer();
        backend->reset();
        if (Result<bool> done = framesOn(kind, std::move(run), report); !done) return done.error();
    }
    if (opened.empty()) return Error{"soak: no backend available", ErrorKind::BackendUnavailable};
    if (s_.cycles > 0 && !s_.minimal)
        for (const auto& [kind, name] : opened)
            if (Result<bool> done = allCycles(kind, name, report); !done) return done.error();
    return report;
}

}  // namespace

Result<SoakReport> runSoak(const Scene& scene, const SoakSettings& settings, const ProgressFn& progress) {
    return Soak(scene, settings, progress).run();
}

}  // namespace frugal
