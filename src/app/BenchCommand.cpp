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

#include <glm/gtc/matrix_inverse.hpp>
#include <nlohmann/json.hpp>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "app/HsrSupport.h"
#include "base/Stats.h"
#include "lab/MinimalFrame.h"
#include "render/SceneRenderer.h"
#include "renderer/Backends.h"
#include "renderer/StateOrder.h"
#include "renderer/StatsJson.h"
#include "report/ImageCompare.h"

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

The cache order also times the same frame in the other depth format (--depth-format, default d24;
see 'frugal help render'), into a target of its own, interleaved with frugal's frames: a row with
"variant": "d32f" (or "d24"), its "pixels_differing" from frugal's image, and the ratio
"d32f_over_d24". A backend without glClipControl skips it ("skipped" says so).
)";
}

namespace {

struct Sample {
    std::string backend, renderer, order;
    const char* variant = "frugal";  // or "minimal"
    std::vector<double> ms;
    std::optional<bool> pixelsEqual;  // minimal: the same colour image as frugal's
    // unbatched, premerged: against frugal's image; frugal: its --order against submission order
    std::optional<std::size_t> pixelsDiffering;
};

// The context kind of a GL backend, by its name() ("egl-surfaceless", ...).
std::optional<ContextKind> contextKindNamed(const std::string& name) {
    for (ContextKind kind : {ContextKind::EglDevice, ContextKind::EglSurfaceless, ContextKind::OsMesa})
        if (name == contextKindName(kind)) return kind;
    return std::nullopt;
}

// The floor of batching (issue 10): the frame's instances pre-transformed into one mesh per
// material, drawn with one node and no per-instance state. Positions by the world matrix, normals by
// its inverse transpose, in float as the backends would; so its pixels may differ from the frame's
// in the last bit of a vertex (counted, as premerged_pixels_differing). Cameras are kept.
Scene premergedScene(const Scene& scene, const std::vector<glm::mat4>& world) {
    Scene merged;
    merged.source = scene.source + " (pre-transformed)";
    merged.materials = scene.materials;
    merged.textures = scene.textures;
    merged.cameras = scene.cameras;
    merged.fps = scene.fps;
    Node root;
    std::vector<int> meshOfMaterial(scene.materials.size() + 1, -1);  // the last: the default material
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[std::size_t(instance.mesh)];
        const std::size_t slot = mesh.material >= 0 ? std::size_t(mesh.material) : scene.materials.size();
        if (meshOfMaterial[slot] < 0) {
            meshOfMaterial[slot] = int(merged.meshes.size());
            Mesh fresh;
            fresh.name = "premerged";
            fresh.material = mesh.material;
            merged.meshes.push_back(std::move(fresh));
            root.meshes.push_back(meshOfMaterial[slot]);
        }
        Mesh& out = merged.meshes[std::size_t(meshOfMaterial[slot])];
        const glm::mat4& m = world[std::size_t(instance.node)];
        const glm::mat3 n = glm::inverseTranspose(glm::mat3(m));
        const std::uint32_t base = std::uint32_t(out.positions.size());
        // Attributes one mesh has and another lacks get what the backends read for a missing one.
        const bool colours = !mesh.colors.empty() || !out.colors.empty(), uvs = !mesh.uvs.empty() || !out.uvs.empty();
        if (colours && out.colors.size() < base) out.colors.resize(base, glm::vec4(1.0f));
        if (uvs && out.uvs.size() < base) out.uvs.resize(base, glm::vec2(0.0f));
        for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
            out.positions.push_back(glm::vec3(m * glm::vec4(mesh.positions[v], 1.0f)));
            out.normals.push_back(n * mesh.normals[v]);
            if (colours) out.colors.push_back(mesh.colors.empty() ? glm::vec4(1.0f) : mesh.colors[v]);
            if (uvs) out.uvs.push_back(mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[v]);
        }
        for (std::uint32_t index : mesh.indices) out.indices.push_back(base + index);
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
            out.triangleSource.push_back(std::uint32_t(out.triangleSource.size()));
    }
    merged.nodes.push_back(root);
    merged.roots = {0};
    merged.buildInstances();
    return merged;
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
    Order drawOrder = Order::Submit;
    std::vector<std::string> rest(args.begin() + (args[0] == "render" ? 1 : 0), args.end());
    CommandLine command{"bench", benchHelp(), &options};
    command.flags = {{"", {
        flag::whole("--repeat", "N", "timed frames per variant (default 30)", runs, 1, 100000),
        flag::whole("--warmup", "N", "untimed frames first (default 5)", warmup, 0, 100000),
        flag::on("--ids", "also write triangle ids (the id pass)", ids),
        hsrFlag(hsrMode, "zbuffer (default), depthsort or adaptive (see 'frugal help render'); the plan is timed with "
                         "the frame; the minimal program stays z-buffered"),
        orderFlag(drawOrder, "the draw order: submit (default), key, paper, greedy or best (see 'frugal help render'); "
                             "consecutive draws of one mesh are one instanced draw. In the cache order two more rows: "
                             "\"unbatched\" (one draw per instance) and \"premerged\" (the floor: the instances "
                             "pre-transformed into one mesh per material); \"pixels_differing\" says where each image "
                             "differs from frugal's, and for frugal's own row, where --order changed it from "
                             "submission order (exact depth ties); ratios \"unbatched_over_batched\" and "
                             "\"over_premerged\""),
    }}};
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
    if (const std::string warning = fitSizeToCamera(options, *optimized); !warning.empty() && !options.quiet)
        err << "warning: " << warning << "\n";
    // The other depth format, timed beside the asked one.
    RenderOptions otherFormat = options;
    otherFormat.depthFormat = options.depthFormat == DepthFormat::D24 ? DepthFormat::D32F : DepthFormat::D24;
    const std::string otherName = depthFormatName(otherFormat.depthFormat);

    // By default every GL context kind and the software reference, side by side.
    std::vector<BackendKind> choices;
    if (options.backend != BackendKind::Auto)
        choices = {options.backend};
    else
        choices = {BackendKind::EglDevice, BackendKind::EglSurfaceless, BackendKind::OsMesa, BackendKind::Software};

    nlohmann::json skipped = nlohmann::json::array();
    std::vector<Sample> samples;
    using Clock = std::chrono::steady_clock;
    for (const BackendKind choice : choices) {
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
            Sample sample{backend.name(), backend.renderer(), order, "frugal", {}, std::nullopt, std::nullopt};
            std::optional<hsr::Planner> planner;
            if (hsrMode != hsr::Mode::ZBuffer) planner.emplace(*scene);

            // The minimal program on a context of the same kind, for GL backends.
            std::unique_ptr<MinimalFrame> minimal;
            const std::optional<ContextKind> kind =
                choice == BackendKind::Software ? std::nullopt : contextKindNamed(backend.name());
            const std::string minimalLabel = backend.name() + " minimal (" + order + "): ";
            if (kind && ids) {
                skipped.push_back(minimalLabel +
                                  "--ids: the minimal frame writes no ids, so it would not draw the same frame");
            } else if (kind) {
                Result<std::unique_ptr<MinimalFrame>> made =
                    createMinimalFrame(*kind, *scene, options.width, options.height, options.depthFormat);
                if (made)
                    minimal = std::move(*made);
                else
                    skipped.push_back(minimalLabel + made.error());
            }
            Sample minimalSample{backend.name(), backend.renderer(), order, "minimal", {}, std::nullopt, std::nullopt};
            // In the cache order also: the same list unbatched, and the batching floor (premerged).
            const bool variants = std::string(order) == "optimized";
            Result<OrderCosts> orderCosts = startOrderCosts(drawOrder, backend, 0, err, options.quiet);
            if (!orderCosts) {
                err << "error: --order " << toString(drawOrder) << ": " << orderCosts.error() << "\n";
                return kExitError;
            }
            const DrawList list = orderFrameDraws(*scene, renderer.fullList(), drawOrder, orderCosts->costsUs());
            Sample unbatched{backend.name(), backend.renderer(), order, "unbatched", {}, std::nullopt, std::nullopt};
            Sample premerged{backend.name(), backend.renderer(), order, "premerged", {}, std::nullopt, std::nullopt};
            Sample otherSample{backend.name(), backend.renderer(), order, otherName.c_str(), {},
                               std::nullopt,   std::nullopt};
            // The other depth format: its own target and projection, the same uploads.
            ScopedTarget other(backend);
            Result<FrameSetup> otherSetup =
                setUpFrame(otherFormat, *scene, options.frames ? options.frames->first : 0, ids);
            if (!otherSetup) {
                err << "error: " << otherSetup.error() << "\n";
                return kExitError;
            }
            if (variants && backend.supportsDepthFormat(otherFormat.depthFormat)) {
                other.reset(backend.createTarget(options.width, options.height, otherFormat.depthFormat));
                if (other.get() == kNoHandle)
                    skipped.push_back(backend.name() + " " + otherName + ": no target of that size");
            } else if (variants) {
                skipped.push_back(backend.name() + " " + otherName + ": no glClipControl (GL 4.5 or ARB_clip_control)");
            }
            const Scene merged = variants ? premergedScene(*scene, setup->world) : Scene{};
            std::optional<SceneRenderer> mergedRenderer;
            if (variants) {
                Result<SceneRenderer> made = SceneRenderer::create(backend, merged);
                if (!made) {
                    err << "error: bench: the premerged scene: " << made.error() << "\n";
                    return kExitError;
                }
                mergedRenderer.emplace(std::move(*made));
            }
            const auto drawFrameInto = [&](SceneRenderer& r, const DrawList& drawn, TargetHandle into,
                                           const FrameSetup& s) {
                if (planner)  // the plan is part of the frame's time
                    r.renderFrame(into, options.width, options.height, s.params, s.world, options.background,
                                  planner->plan(hsrMode, s.params, s.world, drawn, options.width, options.height));
                else
                    r.renderFrame(into, options.width, options.height, s.params, s.world, options.background, drawn);
            };
            const auto drawFrame = [&](SceneRenderer& r, const DrawList& drawn) {
                drawFrameInto(r, drawn, target, *setup);
            };

            // Each timed frame starts with its context current: backend.finish() makes it so
            // (and waits for nothing), minimal->activate() likewise.
            const auto millisecondsSince = [](Clock::time_point t0) {
                return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
            };
            for (int i = 0; i < warmup + runs; ++i) {
                backend.finish();
                auto t0 = Clock::now();
                drawFrame(renderer, list);
                backend.finish();
                const double ms = millisecondsSince(t0);
                if (i >= warmup) sample.ms.push_back(ms);
                if (variants) {
                    renderer.setBatching(false);
                    t0 = Clock::now();
                    drawFrame(renderer, list);
                    backend.finish();
                    if (i >= warmup) unbatched.ms.push_back(millisecondsSince(t0));
                    renderer.setBatching(true);
                    const std::vector<glm::mat4> identity = merged.worldTransforms(0.0);
                    t0 = Clock::now();
                    mergedRenderer->renderFrame(target, options.width, options.height, setup->params, identity,
                                                options.background);
                    backend.finish();
                    if (i >= warmup) premerged.ms.push_back(millisecondsSince(t0));
                }
                if (other.get() != kNoHandle) {
                    t0 = Clock::now();
                    drawFrameInto(renderer, list, other.get(), *otherSetup);
                    backend.finish();
                    if (i >= warmup) otherSample.ms.push_back(millisecondsSince(t0));
                }
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
            if (variants) {
                // Images, after timing: frugal's, then the unbatched and premerged ones against it.
                drawFrame(renderer, list);
                const Buffers batchedImage = backend.readBack(target);
                renderer.setBatching(false);
                drawFrame(renderer, list);
                renderer.setBatching(true);
                unbatched.pixelsDiffering = differingColorPixels(backend.readBack(target), batchedImage);
                mergedRenderer->renderFrame(target, options.width, options.height, setup->params,
                                            merged.worldTransforms(0.0), options.background);
                premerged.pixelsDiffering = differingColorPixels(backend.readBack(target), batchedImage);
                if (other.get() != kNoHandle) {
                    drawFrameInto(renderer, list, other.get(), *otherSetup);
                    otherSample.pixelsDiffering = differingColorPixels(backend.readBack(other.get()), batchedImage);
                }
                // Draw order decides exact depth ties only: the pixels where it changed the image.
                drawFrame(renderer, renderer.fullList());
                sample.pixelsDiffering = differingColorPixels(backend.readBack(target), batchedImage);
                if (!options.quiet)
                    err << backend.name() << " " << order << " unbatched: median " << fmt(median(unbatched.ms))
                        << " ms; premerged: median " << fmt(median(premerged.ms)) << " ms\n";
            }
            samples.push_back(std::move(sample));
            if (variants) {
                samples.push_back(std::move(unbatched));
                samples.push_back(std::move(premerged));
                if (!otherSample.ms.empty()) samples.push_back(std::move(otherSample));
            }
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
        if (s.pixelsDiffering) row["pixels_differing"] = *s.pixelsDiffering;
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
        if (const Sample* unbatchedRun = find(samples, b, "optimized", "unbatched"))
            ratios["unbatched_over_batched"][b] = ratio(unbatchedRun, optimizedRun);
        if (const Sample* premergedRun = find(samples, b, "optimized", "premerged"))
            ratios["over_premerged"][b] = ratio(optimizedRun, premergedRun);
        if (const Sample* otherRun = find(samples, b, "optimized", otherName.c_str()))
            ratios["d32f_over_d24"][b] =
                options.depthFormat == DepthFormat::D24 ? ratio(otherRun, optimizedRun) : ratio(optimizedRun, otherRun);
    }

    const char* threads = std::getenv("LP_NUM_THREADS");
    nlohmann::json report = {
        {"command", "bench render"},
        {"scene", options.scene},
        {"size", {options.width, options.height}},
        {"triangles", optimized->triangleCount()},
        {"ids", ids},
        {"hsr", toString(hsrMode)},
        {"draw_order", toString(drawOrder)},
        {"depth_format", depthFormatName(options.depthFormat)},
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
