// `frugal bench render`: the same frame on every available backend, and with the file's triangle
// order beside the vertex-cache order, in one process; JSON with medians and ratios. Timings cover
// clear + draw + glFinish (no read-back), after warm-up frames that let llvmpipe compile its shaders.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ostream>

#include <nlohmann/json.hpp>

#include "app/Backends.h"
#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "render/SceneRenderer.h"

namespace frugal {

const char* benchHelp() {
    return R"(usage: frugal bench render [SCENE] [options]

Renders the same frame repeatedly on each available backend (egl-device, egl-surfaceless, osmesa
and the software reference; or only --backend), once with the vertex-cache triangle order and once
with the file's order, and prints JSON: median/min/max ms per frame, triangles per second, and
ratios.
--threads N sets the thread count of every backend (llvmpipe and software) for a fair comparison.

  --runs N              timed frames per variant (default 30)
  --warmup N            untimed frames first (default 5)
  --ids                 also write triangle ids (the id pass)
)";
}

namespace {

struct Sample {
    std::string backend, renderer, order;
    std::vector<double> ms;
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
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
    std::vector<std::string> rest(args.begin() + (args[0] == "render" ? 1 : 0), args.end());
    CommandLine command{"bench", benchHelp(), &options};
    command.option = [&](const std::string& flag, ArgCursor& cursor) {
        if (flag == "--runs") {
            if (std::optional<int> n = wholeNumber(flag, cursor, 1, 100000)) runs = *n;
        } else if (flag == "--warmup") {
            if (std::optional<int> n = wholeNumber(flag, cursor, 0, 100000)) warmup = *n;
        } else if (flag == "--ids") {
            ids = true;
        } else {
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
        int status = kExitOk;
        Result<Session> opened = openSession(choice, options, status);
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
            Sample sample{backend.name(), backend.renderer(), order, {}};
            for (int i = 0; i < warmup + runs; ++i) {
                const auto t0 = Clock::now();
                renderer.renderFrame(target, options.width, options.height, setup->params, setup->world, options.background);
                backend.finish();
                const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
                if (i >= warmup) sample.ms.push_back(ms);
            }
            if (!options.quiet)
                err << backend.name() << " " << order << ": median " << fmt(median(sample.ms)) << " ms\n";
            samples.push_back(std::move(sample));
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
        results.push_back({{"backend", s.backend}, {"renderer", s.renderer}, {"order", s.order}, {"median_ms", m},
                           {"min_ms", *std::min_element(s.ms.begin(), s.ms.end())},
                           {"max_ms", *std::max_element(s.ms.begin(), s.ms.end())},
                           {"triangles_per_second", m > 0 ? triangles / (m / 1000.0) : 0.0}});
    }
    // Ratios: file order ÷ cache order per backend; every backend ÷ the first, cache order.
    nlohmann::json ratios = nlohmann::json::object();
    for (std::size_t i = 0; i + 1 < samples.size(); i += 2)
        ratios["file_over_optimized"][samples[i].backend] = median(samples[i + 1].ms) / median(samples[i].ms);
    for (std::size_t i = 2; i < samples.size(); i += 2)
        ratios["over_" + samples[0].backend][samples[i].backend] = median(samples[i].ms) / median(samples[0].ms);

    const char* threads = std::getenv("LP_NUM_THREADS");
    nlohmann::json report = {
        {"command", "bench render"},
        {"scene", options.scene},
        {"size", {options.width, options.height}},
        {"triangles", optimized->triangleCount()},
        {"ids", ids},
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
