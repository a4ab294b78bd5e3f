// `frugal bench render`: the same frame on every available backend, and with the file's triangle
// order beside the vertex-cache order, in one process; JSON with medians and ratios. Timings cover
// clear + draw + glFinish (no read-back), after warm-up frames that let llvmpipe compile its shaders.
//
// On a GL backend the same frame is also drawn by the minimal GL program (gl/MinimalFrame.h) on a
// context of the same kind, and the timed frames alternate frugal, minimal, frugal, ... so that the
// machine's noise (this runs on shared cores) hits both alike; the context switch between them is
// made before the clock starts. "over_minimal" is frugal ÷ minimal: the backend's overhead.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/Backends.h"
#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "app/HsrSupport.h"
#include "base/Stats.h"
#include "gl/MinimalFrame.h"
#include "render/SceneRenderer.h"

namespace frugal {

const char* benchHelp() {
    return R"(usage: frugal bench render [SCENE] [options]

Renders the same frame repeatedly on each available backend (egl-device, egl-surfaceless, osmesa
and the software reference; or only --backend), once with the vertex-cache triangle order and once
with the file's order, and prints JSON: median/min/max ms per frame, triangles per second, and
ratios.
--threads N sets the thread count of every backend (llvmpipe and software) for a fair comparison.

On each GL backend the frame is also drawn by a minimal GL program on its own context of the same
kind (one program with position and normal, glClear, glDrawElements per instance), its timed frames
alternating with frugal's: rows with "variant": "minimal", the ratios "over_minimal" (frugal ÷
minimal, vertex-cache order) and "over_minimal_file_order", and "minimal_pixels_equal" (both colour
images read back once, after timing). Scenes with textures or vertex colours, and --ids, have no
minimal variant; "skipped" says why.

  --runs N              timed frames per variant (default 30)
  --warmup N            untimed frames first (default 5)
  --ids                 also write triangle ids (the id pass)
  --hsr MODE            zbuffer (default), depthsort or adaptive (see 'frugal help render'); the
                        plan is timed with the frame; the minimal program stays z-buffered
)";
}

namespace {

struct Sample {
    std::string backend, renderer, order;
    const char* variant = "frugal";  // or "minimal"
    std::vector<double> ms;
    std::optional<bool> pixelsEqual;  // minimal: the same colour image as frugal's
};

// The context kind of a GL backend, by its name() ("egl-surfaceless", ...).
std::optional<ContextKind> contextKindNamed(const std::string& name) {
    for (ContextKind kind : {ContextKind::EglDevice, ContextKind::EglSurfaceless, ContextKind::OsMesa})
        if (name == contextKindName(kind)) return kind;
    return std::nullopt;
}

const Sample* find(const std::vector<Sample>& samples, const std::string& backend, const std::string& order,
                   const std::string& variant) {
    for (const Sample& s : samples)
        if (s.backend == backend && s.order == order && s.variant == variant) return &s;
    return nullptr;
}

}  // namespace

int runBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    if (args.empty() || (args[0] != "render" && args[0] != "-h" && args[0] != "--help")) {
        err << "error: bench: expected 'bench render [SCENE] [options]'\n";
        return kExitUsage;
    }
    RenderOptions options;
    bool ids = false;
    int runs = 30, warmup = 5;
    hsr::Mode hsrMode = hsr::Mode::ZBuffer;
    std::vector<std::string> rest(args.begin() + (args[0] == "render" ? 1 : 0), args.end());
    CommandLine command{"bench", benchHelp(), &options};
    command.option = [&](const std::string& flag, ArgCursor& cursor) {
        if (flag == "--runs") {
            if (std::optional<int> n = wholeNumber(flag, cursor, 1, 100000)) runs = *n;
        } else if (flag == "--warmup") {
            if (std::optional<int> n = wholeNumber(flag, cursor, 0, 100000)) warmup = *n;
        } else if (flag == "--ids") {
            ids = true;
        } else if (!parseHsrOption(flag, cursor, hsrMode)) {
            return false;
        }
        return true;
    };
    command.positional = sceneArgument(options);
    if (std::optional<int> status = parseCommandLine(command, rest, out, err)) return *status;

    // Two loads of the same file: the only difference is the triangle order.
    LoadOptions fileOrder = options.load;
    fileOrder.optimizeOrder = false;
    LoadOptions cacheOrder = options.load;
    cacheOrder.optimizeOrder = true;
    Result<Scene> optimized = loadScene(options.scene, cacheOrder);
    if (!optimized) {
        err << "error: " << optimized.error() << "\n";
        return kExitError;
    }
    Result<Scene> original = loadScene(options.scene, fileOrder);
    if (!original) {
        err << "error: " << original.error() << "\n";
        return kExitError;
    }

    // By default every GL context kind and the software reference, side by side.
    std::vector<BackendSelection> choices;
    if (options.backend.software || options.backend.gl != BackendChoice::Auto) {
        choices = {options.backend};
    } else {
        choices = {{false, BackendChoice::EglDevice}, {false, BackendChoice::EglSurfaceless},
                   {false, BackendChoice::OsMesa}, {true, BackendChoice::Auto}};
    }

    nlohmann::json skipped = nlohmann::json::array();
    std::vector<Sample> samples;
    using Clock = std::chrono::steady_clock;
    for (const BackendSelection& choice : choices) {
        Result<Session> opened = openSession(choice, options);
        if (!opened) {
            skipped.push_back(opened.error());
            continue;
        }
        Backend& backend = *opened->backend;
        for (const auto& [order, scene] : {std::pair<const char*, const Scene*>{"optimized", &*optimized}, {"file", &*original}}) {
            Result<FrameSetup> setup = setUpFrame(options, *scene, options.frames ? options.frames->first : 0, ids);
            if (!setup) {
                err << "error: " << setup.error() << "\n";
                return kExitError;
            }
            // Each order is its own upload, drawn into the one target.
            if (int prepared = prepareSession(*opened, options, *scene, err); prepared != kExitOk) return prepared;
            SceneRenderer& renderer = *opened->renderer;
            const TargetHandle target = opened->target;
            Sample sample{backend.name(), backend.renderer(), order, "frugal", {}, std::nullopt};
            std::optional<hsr::Planner> planner;
            if (hsrMode != hsr::Mode::ZBuffer) planner.emplace(*scene);

            // The minimal program on a context of the same kind, for GL backends.
            std::unique_ptr<MinimalFrame> minimal;
            const std::optional<ContextKind> kind = choice.software ? std::nullopt : contextKindNamed(backend.name());
            const std::string minimalLabel = backend.name() + " minimal (" + order + "): ";
            if (kind && ids) {
                skipped.push_back(minimalLabel +
                                  "--ids: the minimal frame writes no ids, so it would not draw the same frame");
            } else if (kind) {
                Result<std::unique_ptr<MinimalFrame>> made =
                    createMinimalFrame(*kind, *scene, options.width, options.height);
                if (made)
                    minimal = std::move(*made);
                else
                    skipped.push_back(minimalLabel + made.error());
            }
            Sample minimalSample{backend.name(), backend.renderer(), order, "minimal", {}, std::nullopt};

            // Each timed frame starts with its context current: backend.finish() makes it so
            // (and waits for nothing), minimal->activate() likewise.
            const auto millisecondsSince = [](Clock::time_point t0) {
                return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
            };
            for (int i = 0; i < warmup + runs; ++i) {
                backend.finish();
                auto t0 = Clock::now();
                if (planner)  // the plan is part of the frame's time
                    renderer.renderFrame(target, options.width, options.height, setup->params, setup->world,
                                         options.background,
                                         planner->plan(hsrMode, setup->params, setup->world, renderer.fullList(),
                                                       options.width, options.height));
                else
                    renderer.renderFrame(target, options.width, options.height, setup->params, setup->world,
                                         options.background);
                backend.finish();
                const double ms = millisecondsSince(t0);
                if (i >= warmup) sample.ms.push_back(ms);
                if (!minimal) continue;
                minimal->activate();
                t0 = Clock::now();
                minimal->render(setup->params, setup->world, options.background);
                minimal->finish();
                const double minimalMs = millisecondsSince(t0);
                if (i >= warmup) minimalSample.ms.push_back(minimalMs);
            }
            if (!options.quiet)
                err << backend.name() << " " << order << ": median " << fmt(median(sample.ms)) << " ms\n";
            samples.push_back(std::move(sample));
            if (minimal) {
                minimalSample.pixelsEqual = backend.readBack(target).rgba == minimal->readBack().rgba;
                if (!options.quiet)
                    err << backend.name() << " " << order << " minimal: median " << fmt(median(minimalSample.ms))
                        << " ms" << (*minimalSample.pixelsEqual ? "" : " (pixels differ from frugal's)") << "\n";
                samples.push_back(std::move(minimalSample));
            }
        }
    }
    if (samples.empty()) {
        err << "error: bench: no backend available:";
        for (const auto& why : skipped) err << " [" << why.get<std::string>() << "]";
        err << "\n";
        return kExitNoBackend;
    }

    const double triangles = double(optimized->triangleCount());
    nlohmann::json results = nlohmann::json::array();
    for (const Sample& s : samples) {
        const double m = median(s.ms);
        nlohmann::json row = {{"backend", s.backend}, {"renderer", s.renderer}, {"order", s.order},
                              {"variant", s.variant}, {"median_ms", m},
                              {"min_ms", *std::min_element(s.ms.begin(), s.ms.end())},
                              {"max_ms", *std::max_element(s.ms.begin(), s.ms.end())},
                              {"triangles_per_second", m > 0 ? triangles / (m / 1000.0) : 0.0}};
        if (s.pixelsEqual) row["minimal_pixels_equal"] = *s.pixelsEqual;
        results.push_back(std::move(row));
    }
    // Ratios, of medians: file order ÷ cache order per backend; every backend ÷ the first, cache
    // order; frugal ÷ the minimal program per GL backend, in each order.
    nlohmann::json ratios = nlohmann::json::object();
    std::vector<std::string> backends;
    for (const Sample& s : samples)
        if (std::find(backends.begin(), backends.end(), s.backend) == backends.end()) backends.push_back(s.backend);
    const auto ratio = [](const Sample* a, const Sample* b) { return median(a->ms) / median(b->ms); };
    const Sample* first = find(samples, backends.front(), "optimized", "frugal");
    for (const std::string& b : backends) {
        const Sample* optimizedRun = find(samples, b, "optimized", "frugal");
        const Sample* fileRun = find(samples, b, "file", "frugal");
        ratios["file_over_optimized"][b] = ratio(fileRun, optimizedRun);
        if (b != backends.front()) ratios["over_" + backends.front()][b] = ratio(optimizedRun, first);
        if (const Sample* minimalRun = find(samples, b, "optimized", "minimal"))
            ratios["over_minimal"][b] = ratio(optimizedRun, minimalRun);
        if (const Sample* minimalRun = find(samples, b, "file", "minimal"))
            ratios["over_minimal_file_order"][b] = ratio(fileRun, minimalRun);
    }

    const char* threads = std::getenv("LP_NUM_THREADS");
    nlohmann::json report = {
        {"command", "bench render"},
        {"scene", options.scene},
        {"size", {options.width, options.height}},
        {"triangles", optimized->triangleCount()},
        {"ids", ids},
        {"hsr", hsr::modeName(hsrMode)},
        {"runs", runs},
        {"warmup", warmup},
        {"threads", options.threads > 0 ? nlohmann::json(options.threads) : nlohmann::json("default")},
        {"lp_num_threads", threads ? nlohmann::json(threads) : nlohmann::json(nullptr)},
        {"results", results},
        {"ratios", ratios},
        {"skipped", skipped},
    };
    out << report.dump(2) << "\n";
    return kExitOk;
}

}  // namespace frugal
