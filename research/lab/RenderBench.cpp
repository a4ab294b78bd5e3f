#include "lab/RenderBench.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <utility>

#include <glm/gtc/matrix_inverse.hpp>
#include <nlohmann/json.hpp>

#include "lab/SceneInfo.h"
#include "lab/ImageCompare.h"
#include "renderer/Research.h"
#include "lab/MinimalFrame.h"

namespace frugal {

namespace {

using Clock = std::chrono::steady_clock;
using Progress = std::function<void(const std::string&)>;

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// The depth format timed beside `format`.
DepthFormat otherFormat(DepthFormat format) {
    return format == DepthFormat::D24 ? DepthFormat::D32F : DepthFormat::D24;
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

const RenderBenchSample* find(const std::vector<RenderBenchSample>& samples, const std::string& backend,
                              const std::string& order, const std::string& variant) {
    for (const RenderBenchSample& s : samples)
        if (s.backend == backend && s.order == order && s.variant == variant) return &s;
    return nullptr;
}

// The frame of `scene` in `format`, or "<scene>: <camera problem>".
Result<FrameSetup> frameOf(const RenderBenchSettings& s, const Scene& scene, DepthFormat format) {
    Result<FrameSetup> setup =
        setUpFrame(scene, s.camera, s.time, s.render.width, s.render.height, s.render.ids, format);
    if (!setup) return Error{s.scene + ": " + setup.error().message, setup.error().kind};
    applyShading(s.render, setup->params);
    return setup;
}

// One triangle order of the scene on one stage: frugal's frame, the minimal program's (GL) and, in
// the cache order, the unbatched, premerged and other-depth-format variants.
class OrderRun {
public:
    OrderRun(const RenderBenchSettings& settings, Stage& stage, const Scene& scene, std::string order,
             const FrameSetup& setup)
        : s_(settings),
          r_(settings.render),
          stage_(stage),
          backend_(stage.backend()),
          renderer_(stage.renderer()),
          scene_(scene),
          order_(std::move(order)),
          variants_(order_ == "optimized"),
          setup_(setup),
          other_(stage.backend()) {
        if (r_.hsr != Hsr::ZBuffer) planner_.emplace(scene);
    }

    // Prepares the variants, times every frame, then compares the images; the rows go to `samples`.
    Result<bool> run(bool software, std::vector<RenderBenchSample>& samples, std::vector<std::string>& skipped,
                     const Progress& progress) {
        makeMinimal(software, skipped);
        Result<OrderCosts> costs = OrderCosts::start(r_.order, backend_, 0);
        if (!costs)
            return Error{std::string("order ") + toString(r_.order) + ": " + costs.error().message, ErrorKind::BadInput, true};
        if (const std::optional<StateCosts> report = costs->report())
            progress(stateCostsLine(r_.order, backend_.name(), *report));
        list_ = orderFrameDraws(scene_, renderer_.fullList(), r_.order, costs->costsUs());
        Result<FrameSetup> otherSetup = frameOf(s_, scene_, otherFormat(r_.depthFormat));
        if (!otherSetup) return otherSetup.error();
        otherSetup_ = std::move(*otherSetup);
        makeOtherTarget(skipped);
        if (variants_) {
            merged_ = premergedScene(scene_, setup_.world);
            Result<SceneRenderer> made = SceneRenderer::create(backend_, merged_);
            if (!made) return Error{"bench: the premerged scene: " + made.error().message};
            mergedRenderer_.emplace(std::move(*made));
        }
        timeFrames();
        progress(backend_.name() + " " + order_ + ": median " + fmt(median(frugal_.ms)) + " ms");
        if (variants_) {
            compareImages();
            progress(backend_.name() + " " + order_ + " unbatched: median " + fmt(median(unbatched_.ms)) +
                     " ms; premerged: median " + fmt(median(premerged_.ms)) + " ms");
        }
        samples.push_back(std::move(frugal_));
        if (variants_) {
            samples.push_back(std::move(unbatched_));
            samples.push_back(std::move(premerged_));
            if (!otherFormat_.ms.empty()) samples.push_back(std::move(otherFormat_));
        }
        if (minimal_) {
            minimalSample_.pixelsEqual = backend_.readBack(stage_.target()).rgba == minimal_->readBack().rgba;
            progress(backend_.name() + " " + order_ + " minimal: median " + fmt(median(minimalSample_.ms)) + " ms" +
                     (*minimalSample_.pixelsEqual ? "" : " (pixels differ from frugal's)"));
            samples.push_back(std::move(minimalSample_));
        }
        return true;
    }

private:
    RenderBenchSample sample(std::string variant) const {
        return {backend_.name(), backend_.renderer(), order_, std::move(variant), {}, std::nullopt, std::nullopt};
    }

    // The minimal program on a context of the same kind, for GL backends (not with ids).
    void makeMinimal(bool software, std::vector<std::string>& skipped) {
        const std::optional<ContextKind> kind = software ? std::nullopt : contextKindNamed(backend_.name());
        const std::string label = backend_.name() + " minimal (" + order_ + "): ";
        if (kind && r_.ids) {
            skipped.push_back(label + "--ids: the minimal frame writes no ids, so it would not draw the same frame");
        } else if (kind && !r_.environmentMap.empty()) {
            skipped.push_back(label + "--environment-map: the minimal frame draws the uniform environment only");
        } else if (kind) {
            Result<std::unique_ptr<MinimalFrame>> made =
                createMinimalFrame(*kind, scene_, r_.width, r_.height, r_.depthFormat);
            if (made)
                minimal_ = std::move(*made);
            else
                skipped.push_back(label + made.error().message);
        }
    }

    // The other depth format (cache order only): its own target and projection, the same uploads.
    void makeOtherTarget(std::vector<std::string>& skipped) {
        const DepthFormat format = otherFormat(r_.depthFormat);
        const std::string name = backend_.name() + " " + depthFormatName(format);
        if (variants_ && backend_.supportsDepthFormat(format)) {
            other_.reset(backend_.createTarget(r_.width, r_.height, format));
            if (other_.get() == kNoHandle) skipped.push_back(name + ": no target of that size");
        } else if (variants_) {
            skipped.push_back(name + ": no glClipControl (GL 4.5 or ARB_clip_control)");
        }
    }

    void drawFrameInto(const DrawList& drawn, TargetHandle into, const FrameSetup& s) {
        if (planner_)  // the plan is part of the frame's time
            renderer_.renderFrame(into, r_.width, r_.height, s.params, s.world, r_.background,
                                  planner_->plan(r_.hsr, s.params, s.world, drawn, r_.width, r_.height));
        else
            renderer_.renderFrame(into, r_.width, r_.height, s.params, s.world, r_.background, drawn);
    }
    void drawFrame(const DrawList& drawn) { drawFrameInto(drawn, stage_.target(), setup_); }

    // Each timed frame starts with its context current: backend.finish() makes it so (and waits
    // for nothing), minimal->activate() likewise.
    void timeFrames() {
        for (int i = 0; i < s_.warmup + s_.runs; ++i) {
            const bool timed = i >= s_.warmup;
            backend_.finish();
            auto t0 = Clock::now();
            drawFrame(list_);
            backend_.finish();
            const double ms = msSince(t0);
            if (timed) frugal_.ms.push_back(ms);
            if (variants_) {
                renderer_.setBatching(false);
                t0 = Clock::now();
                drawFrame(list_);
                backend_.finish();
                if (timed) unbatched_.ms.push_back(msSince(t0));
                renderer_.setBatching(true);
                const std::vector<glm::mat4> identity = merged_.worldTransforms(0.0);
                t0 = Clock::now();
                mergedRenderer_->renderFrame(stage_.target(), r_.width, r_.height, setup_.params, identity,
                                             r_.background);
                backend_.finish();
                if (timed) premerged_.ms.push_back(msSince(t0));
            }
            if (other_.get() != kNoHandle) {
                t0 = Clock::now();
                drawFrameInto(list_, other_.get(), otherSetup_);
                backend_.finish();
                if (timed) otherFormat_.ms.push_back(msSince(t0));
            }
            if (!minimal_) continue;
            minimal_->activate();
            t0 = Clock::now();
            minimal_->render(setup_.params, setup_.world, r_.background);
            minimal_->finish();
            const double minimalMs = msSince(t0);
            if (timed) minimalSample_.ms.push_back(minimalMs);
        }
    }

    // Images, after timing: frugal's, then the unbatched, premerged and other-format ones against it.
    void compareImages() {
        const TargetHandle target = stage_.target();
        drawFrame(list_);
        const Buffers batchedImage = backend_.readBack(target);
        renderer_.setBatching(false);
        drawFrame(list_);
        renderer_.setBatching(true);
        unbatched_.pixelsDiffering = differingColorPixels(backend_.readBack(target), batchedImage);
        mergedRenderer_->renderFrame(target, r_.width, r_.height, setup_.params, merged_.worldTransforms(0.0),
                                     r_.background);
        premerged_.pixelsDiffering = differingColorPixels(backend_.readBack(target), batchedImage);
        if (other_.get() != kNoHandle) {
            drawFrameInto(list_, other_.get(), otherSetup_);
            otherFormat_.pixelsDiffering = differingColorPixels(backend_.readBack(other_.get()), batchedImage);
        }
        // Draw order decides exact depth ties only: the pixels where it changed the image.
        drawFrame(renderer_.fullList());
        frugal_.pixelsDiffering = differingColorPixels(backend_.readBack(target), batchedImage);
    }

    const RenderBenchSettings& s_;
    const Settings& r_;
    Stage& stage_;
    Backend& backend_;
    SceneRenderer& renderer_;
    const Scene& scene_;
    const std::string order_;
    const bool variants_;  // the cache order: unbatched, premerged and the other depth format too
    const FrameSetup& setup_;
    FrameSetup otherSetup_;  // the frame in the other depth format
    std::optional<hsr::Planner> planner_;
    std::unique_ptr<MinimalFrame> minimal_;
    DrawList list_;
    OwnedTarget other_;
    Scene merged_;
    std::optional<SceneRenderer> mergedRenderer_;
    RenderBenchSample frugal_ = sample("frugal"), minimalSample_ = sample("minimal");
    RenderBenchSample unbatched_ = sample("unbatched"), premerged_ = sample("premerged");
    RenderBenchSample otherFormat_ = sample(depthFormatName(otherFormat(r_.depthFormat)));
};

// Both triangle orders on the backend `kind`; a kind that does not open here goes to `bench.skipped`.
Result<bool> measureBackend(BackendKind kind, const Scene& cacheOrder, const Scene& fileOrder, RenderBench& bench,
                            const Progress& progress) {
    const RenderBenchSettings& s = bench.settings;
    Settings stageSettings = s.render;
    stageSettings.backend = kind;
    std::string unavailable;
    Result<std::optional<Stage>> stage = Stage::openIfAvailable(stageSettings, unavailable);
    if (stage && !*stage) {
        bench.skipped.push_back(unavailable);
        return true;
    }
    for (const auto& [order, scene] :
         {std::pair<const char*, const Scene*>{"optimized", &cacheOrder}, {"file", &fileOrder}}) {
        Result<FrameSetup> setup = frameOf(s, *scene, s.render.depthFormat);
        if (!setup) return setup.error();
        if (!stage) return stage.error();  // after the camera's problem, as the command always said them
        Stage& opened = **stage;
        // Each order is its own upload, drawn into the one target.
        if (Result<bool> uploaded = opened.upload(*scene); !uploaded) return uploaded.error();
        OrderRun run(s, opened, *scene, order, *setup);
        if (Result<bool> done = run.run(kind == BackendKind::Software, bench.samples, bench.skipped, progress); !done)
            return done;
    }
    return true;
}

// Ratios, of medians: file order ÷ cache order per backend; every backend ÷ the first, cache
// order; frugal ÷ the minimal program per GL backend, in each order; frugal ÷ its unbatched and
// premerged variants; d32f ÷ d24.
nlohmann::json ratiosJson(const std::vector<RenderBenchSample>& samples, DepthFormat format) {
    nlohmann::json ratios = nlohmann::json::object();
    std::vector<std::string> backends;
    for (const RenderBenchSample& sample : samples)
        if (std::find(backends.begin(), backends.end(), sample.backend) == backends.end())
            backends.push_back(sample.backend);
    const auto ratio = [](const RenderBenchSample* a, const RenderBenchSample* b) {
        return median(a->ms) / median(b->ms);
    };
    const std::string otherName = depthFormatName(otherFormat(format));
    const RenderBenchSample* first = find(samples, backends.front(), "optimized", "frugal");
    for (const std::string& b : backends) {
        const RenderBenchSample* optimizedRun = find(samples, b, "optimized", "frugal");
        const RenderBenchSample* fileRun = find(samples, b, "file", "frugal");
        ratios["file_over_optimized"][b] = ratio(fileRun, optimizedRun);
        if (b != backends.front()) ratios["over_" + backends.front()][b] = ratio(optimizedRun, first);
        if (const RenderBenchSample* minimalRun = find(samples, b, "optimized", "minimal"))
            ratios["over_minimal"][b] = ratio(optimizedRun, minimalRun);
        if (const RenderBenchSample* minimalRun = find(samples, b, "file", "minimal"))
            ratios["over_minimal_file_order"][b] = ratio(fileRun, minimalRun);
        if (const RenderBenchSample* unbatchedRun = find(samples, b, "optimized", "unbatched"))
            ratios["unbatched_over_batched"][b] = ratio(unbatchedRun, optimizedRun);
        if (const RenderBenchSample* premergedRun = find(samples, b, "optimized", "premerged"))
            ratios["over_premerged"][b] = ratio(optimizedRun, premergedRun);
        if (const RenderBenchSample* otherRun = find(samples, b, "optimized", otherName))
            ratios["d32f_over_d24"][b] =
                format == DepthFormat::D24 ? ratio(otherRun, optimizedRun) : ratio(optimizedRun, otherRun);
    }
    return ratios;
}

}  // namespace

Result<RenderBench> measureRenderBench(const Scene& cacheOrder, const Scene& fileOrder,
                                       const RenderBenchSettings& settings, const Progress& progress) {
    RenderBench bench;
    bench.settings = settings;
    bench.triangles = cacheOrder.triangleCount();
    std::vector<BackendKind> kinds{settings.render.backend};
    if (settings.render.backend == BackendKind::Auto)
        kinds = {BackendKind::EglDevice, BackendKind::EglSurfaceless, BackendKind::OsMesa, BackendKind::Software};
    for (const BackendKind kind : kinds)
        if (Result<bool> done = measureBackend(kind, cacheOrder, fileOrder, bench, progress); !done)
            return done.error();
    if (bench.samples.empty()) {
        std::string message = "bench: no backend available:";
        for (const std::string& why : bench.skipped) message += " [" + why + "]";
        return Error{message, ErrorKind::BackendUnavailable};
    }
    return bench;
}

std::string renderBenchJson(const RenderBench& bench) {
    const RenderBenchSettings& s = bench.settings;
    const std::vector<RenderBenchSample>& samples = bench.samples;
    const double triangles = double(bench.triangles);
    nlohmann::json results = nlohmann::json::array();
    for (const RenderBenchSample& sample : samples) {
        const double m = median(sample.ms);
        nlohmann::json row = {{"backend", sample.backend},
                              {"renderer", sample.renderer},
                              {"order", sample.order},
                              {"variant", sample.variant},
                              {"median_ms", m},
                              {"min_ms", *std::min_element(sample.ms.begin(), sample.ms.end())},
                              {"max_ms", *std::max_element(sample.ms.begin(), sample.ms.end())},
                              {"triangles_per_second", m > 0 ? triangles / (m / 1000.0) : 0.0}};
        if (sample.pixelsEqual) row["minimal_pixels_equal"] = *sample.pixelsEqual;
        if (sample.pixelsDiffering) row["pixels_differing"] = *sample.pixelsDiffering;
        results.push_back(std::move(row));
    }
    const char* threads = std::getenv("LP_NUM_THREADS");
    const nlohmann::json report = {
        {"command", "bench render"},
        {"scene", s.scene},
        {"size", {s.render.width, s.render.height}},
        {"triangles", bench.triangles},
        {"ids", s.render.ids},
        {"hsr", toString(s.render.hsr)},
        {"draw_order", toString(s.render.order)},
        {"depth_format", depthFormatName(s.render.depthFormat)},
        {"shading", toString(s.render.shading)},
        {"tonemap", toString(s.render.tonemap)},
        {"runs", s.runs},
        {"warmup", s.warmup},
        {"threads", s.render.threads > 0 ? nlohmann::json(s.render.threads) : nlohmann::json("default")},
        {"lp_num_threads", threads ? nlohmann::json(threads) : nlohmann::json(nullptr)},
        {"results", results},
        {"ratios", ratiosJson(samples, s.render.depthFormat)},
        {"skipped", bench.skipped},
    };
    return report.dump(2) + "\n";
}

}  // namespace frugal
