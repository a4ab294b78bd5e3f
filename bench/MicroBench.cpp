// Library pieces timed side by side: the software reference on whole frames (1 thread against every
// core), PNG encoding of a full frame, index-range normalisation as a culled draw list needs it, and
// culling: the bunny's pre-processing (map, clusters, sphere, hull) and each method's plan for the
// report's views; the adaptive z-buffer's overlap flags.
// No GL here: GL frames are measured by `frugal-lab bench render`, against the minimal GL program.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <random>
#include <thread>

#include <benchmark/benchmark.h>

#include "cull/Culling.h"
#include "lab/Views.h"
#include "hsr/Flags.h"
#include "io/ImageIO.h"
#include "pipeline/Frame.h"
#include "pipeline/IndexRanges.h"
#include "pipeline/SceneRenderer.h"
#include "reuse/Reuse.h"
#include "scene/Load.h"
#include "software/SoftwareBackend.h"

namespace frugal {
namespace {

// One frame of `spec` at 800×600 on the software backend with `threads` threads (0 = every core).
void softwareFrame(benchmark::State& state, const std::string& spec) {
    if (spec.find(".obj") != std::string::npos && !std::filesystem::exists(spec)) {
        state.SkipWithError("the bunny is missing (Debian package glmark2-data)");
        return;
    }
    Result<Scene> scene = loadScene(spec);
    if (!scene) {
        state.SkipWithError(scene.error().message.c_str());
        return;
    }
    SoftwareOptions options;
    options.threads = int(state.range(0));
    std::unique_ptr<Backend> backend = makeSoftwareBackend(options);
    const TargetHandle target = backend->createTarget(800, 600);
    Result<SceneRenderer> renderer = SceneRenderer::create(*backend, *scene);
    Result<FrameSetup> frame = setUpFrame(*scene, {}, 0.0, 800, 600, false);
    if (!renderer || !frame) {
        state.SkipWithError("scene set-up failed");
        return;
    }
    for (auto _ : state) {
        renderer->renderFrame(target, 800, 600, frame->params, frame->world, glm::vec4(0.1f, 0.1f, 0.1f, 1.0f));
        backend->finish();
    }
    state.counters["triangles"] = double(scene->triangleCount());
}

void BM_SoftwareBunny(benchmark::State& state) { softwareFrame(state, FRUGAL_BUNNY_OBJ); }
void BM_SoftwareDefault(benchmark::State& state) { softwareFrame(state, "builtin:default"); }
const int kCores = int(std::max(1u, std::thread::hardware_concurrency()));
BENCHMARK(BM_SoftwareBunny)->Arg(1)->Arg(kCores)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SoftwareDefault)->Arg(1)->Arg(kCores)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_EncodeColorPng(benchmark::State& state) {
    Buffers frame;
    frame.width = 800;
    frame.height = 600;
    frame.rgba.resize(frame.pixelCount() * 4);
    std::mt19937 rng(1);
    // Half flat background, half noise: compresses like a rendered frame more than either alone.
    for (std::size_t i = frame.rgba.size() / 2; i < frame.rgba.size(); ++i) frame.rgba[i] = std::uint8_t(rng());
    for (auto _ : state) benchmark::DoNotOptimize(encodeColorPng(frame));
    state.SetBytesProcessed(std::int64_t(state.iterations()) * std::int64_t(frame.rgba.size()));
}
BENCHMARK(BM_EncodeColorPng)->Unit(benchmark::kMillisecond);

// `state.range(0)` ranges over a 1M-triangle mesh, a third of them adjacent (mergeable).
void BM_NormalizeRanges(benchmark::State& state) {
    std::mt19937 rng(2);
    std::vector<IndexRange> ranges;
    std::uint32_t at = 0;
    for (std::int64_t i = 0; i < state.range(0); ++i) {
        const std::uint32_t gap = rng() % 3 == 0 ? 0 : 1 + rng() % 64, count = 1 + rng() % 64;
        ranges.push_back({at + gap, count});
        at += gap + count;
    }
    std::vector<IndexRange> out;
    for (auto _ : state) benchmark::DoNotOptimize(normalizeRanges(ranges, at, out));
    state.SetItemsProcessed(std::int64_t(state.iterations()) * state.range(0));
}
BENCHMARK(BM_NormalizeRanges)->Arg(500)->Arg(50000);

std::optional<Scene> loadBunny(benchmark::State& state) {
    Result<Scene> scene = loadScene(FRUGAL_BUNNY_OBJ, LoadOptions{.objDoubleSided = false});
    if (!scene) {
        state.SkipWithError("the bunny is missing (Debian package glmark2-data)");
        return std::nullopt;
    }
    return std::move(*scene);
}

// Everything culling computes once per mesh, before upload (the paper: hull ~5 s, maps 4.8 MB).
void BM_CullPrepareBunny(benchmark::State& state) {
    std::optional<Scene> bunny = loadBunny(state);
    if (!bunny) return;
    PrepStats stats;
    for (auto _ : state) {
        Scene scene = *bunny;
        stats = SceneCuller::prepare(scene).totals();
    }
    state.counters["hull_ms"] = stats.hullMs;
    state.counters["map_ms"] = stats.mapMs;
    state.counters["cluster_ms"] = stats.clusterMs;
    state.counters["sphere_ms"] = stats.sphereMs;
    state.counters["map_MB"] = double(stats.mapBytes) / 1e6;
    state.counters["access_MB"] = double(stats.accessBytes) / 1e6;
}
BENCHMARK(BM_CullPrepareBunny)->Unit(benchmark::kMillisecond);

// One plan per iteration, cycling through the report's 32 default views of the bunny at 800×600.
void BM_CullBunny(benchmark::State& state) {
    std::optional<Scene> scene = loadBunny(state);
    if (!scene) return;
    const SceneCuller culler = SceneCuller::prepare(*scene);
    const Bounds bounds = scene->bounds(0.0);
    std::vector<FrameSetup> frames;
    for (const ReportView& view : reportViews(bounds.center(), bounds.radius(), 32)) {
        Result<FrameSetup> frame = setUpFrame(*scene, view.camera, 0.0, 800, 600, false);
        if (frame) frames.push_back(std::move(*frame));
    }
    const Cull method = kCulls[state.range(0)];
    state.SetLabel(toString(method));
    std::size_t at = 0, submitted = 0;
    for (auto _ : state) {
        const FrameSetup& frame = frames[at++ % frames.size()];
        const DrawList list = culler.cull(method, *scene, frame.world, frame.view);
        submitted += submittedTriangles(*scene, list);
        benchmark::DoNotOptimize(list.data());
    }
    state.counters["pvs"] = benchmark::Counter(double(submitted), benchmark::Counter::kAvgIterations);
}
// The methods that plan from the scene alone (occlusion needs a target, the oracle an id pass).
BENCHMARK(BM_CullBunny)
    ->Apply([](benchmark::internal::Benchmark* b) {
        for (std::size_t i = 0; i < kCulls.size(); ++i)
            if (!traitsOf(kCulls[i]).occlusion && !traitsOf(kCulls[i]).idPass) b->Arg(std::int64_t(i));
    })
    ->Unit(benchmark::kMicrosecond);

// The occlusion pass alone (cull/Occlusion.h) on `scene`'s single-sided meshes seen whole at 800×600,
// run on every call (not adaptive), with `threads` threads (0: every core) and the loops of `simd`:
// its plan against conservative's.
void occlusionPass(benchmark::State& state, const std::string& scenePath, int threads, int simd) {
    if (!std::filesystem::exists(FRUGAL_BUNNY_OBJ)) {
        state.SkipWithError("the bunny is missing (Debian package glmark2-data)");
        return;
    }
    Result<Scene> scene = loadScene(scenePath, LoadOptions{.objDoubleSided = false});
    if (!scene) {
        state.SkipWithError(scene.error().message.c_str());
        return;
    }
    const SceneCuller culler = SceneCuller::prepare(*scene);
    Result<FrameSetup> frame = setUpFrame(*scene, {}, 0.0, 800, 600, false);
    if (!frame) {
        state.SkipWithError(frame.error().message.c_str());
        return;
    }
    OcclusionTarget target{.width = 800, .height = 600, .exactRules = true, .adaptive = false,
                           .threads = threads, .simd = simd != 0, .avx512 = simd == 2};
    std::size_t submitted = 0;
    double passMs = 0.0;
    for (auto _ : state) {
        const DrawList list = culler.cull(Cull::Occlusion, *scene, frame->world, frame->view, target);
        submitted += submittedTriangles(*scene, list);
        passMs += culler.occlusion().stats().ms;
    }
    state.counters["pvs"] = benchmark::Counter(double(submitted), benchmark::Counter::kAvgIterations);
    state.counters["pass_ms"] = benchmark::Counter(passMs, benchmark::Counter::kAvgIterations);
    state.counters["conservative_pvs"] =
        double(submittedTriangles(*scene, culler.cull(Cull::Conservative, *scene, frame->world, frame->view)));
}

// Three bunnies, with 1 thread and with every core, with the scalar loops (simd:0), the AVX2 ones
// (simd:1, where the CPU has them; the quick test gathers each corner) and the AVX2 ones whose quick
// test looks the corners up with AVX-512 permutes (simd:2, where the CPU has AVX-512).
void BM_CullOcclusionThreeBunnies(benchmark::State& state) {
    occlusionPass(state, std::string("builtin:copies?count=3&of=") + FRUGAL_BUNNY_OBJ, int(state.range(0)),
                  int(state.range(1)));
}
BENCHMARK(BM_CullOcclusionThreeBunnies)
    ->ArgsProduct({{1, kCores}, {0, 1, 2}})
    ->ArgNames({"threads", "simd"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// One bunny filling the screen, where the pass has larger triangles to draw into its buffer and
// fewer to hide; with the fastest loops. Argument: threads.
void BM_CullOcclusionBunny(benchmark::State& state) {
    occlusionPass(state, FRUGAL_BUNNY_OBJ, int(state.range(0)), 2);
}
BENCHMARK(BM_CullOcclusionBunny)->Arg(1)->Arg(kCores)->ArgName("threads")->Unit(benchmark::kMillisecond)->UseRealTime();

// The occlusion pass on 4,000 dominoes seen low from the front (docs/occlusion.md's dominoes goal):
// 13,589 clusters of one triangle or two left by the conservative plan, most hidden behind the
// nearest rows; the cost is per cluster and per instance, not per triangle. Argument: threads.
void BM_CullOcclusionDominoes(benchmark::State& state) {
    Result<Scene> scene = loadScene("builtin:dominoes?polygons=24000");
    if (!scene) {
        state.SkipWithError(scene.error().message.c_str());
        return;
    }
    const SceneCuller culler = SceneCuller::prepare(*scene);
    Result<FrameSetup> frame =
        setUpFrame(*scene, Camera::lookAt({0.0f, 3.0f, 70.0f}, {0.0f, 2.0f, 0.0f}), 0.0, 800, 600, false);
    if (!frame) {
        state.SkipWithError(frame.error().message.c_str());
        return;
    }
    OcclusionTarget target{.width = 800, .height = 600, .exactRules = true, .adaptive = false,
                           .threads = int(state.range(0))};
    std::size_t submitted = 0, draws = 0;
    double passMs = 0.0;
    for (auto _ : state) {
        const DrawList list = culler.cull(Cull::Occlusion, *scene, frame->world, frame->view, target);
        submitted += submittedTriangles(*scene, list);
        draws += list.size();
        passMs += culler.occlusion().stats().ms;
    }
    state.counters["pass_ms"] = benchmark::Counter(passMs, benchmark::Counter::kAvgIterations);
    state.counters["pvs"] = benchmark::Counter(double(submitted), benchmark::Counter::kAvgIterations);
    state.counters["draws"] = benchmark::Counter(double(draws), benchmark::Counter::kAvgIterations);
    const DrawList conservative = culler.cull(Cull::Conservative, *scene, frame->world, frame->view);
    state.counters["conservative_pvs"] = double(submittedTriangles(*scene, conservative));
    state.counters["conservative_draws"] = double(conservative.size());
}
BENCHMARK(BM_CullOcclusionDominoes)->Arg(1)->Arg(kCores)->ArgName("threads")->Unit(benchmark::kMillisecond)->UseRealTime();

// Temporal reuse's plan for 100,000 triangles at 1920×1080 (the ⊗ tests' goal: ≤ 5 ms a frame):
// 50,000 domino quads, 1.34 % of the dominoes falling, at the extent grain of the argument (1 = per
// triangle, 0 = per instance). Iterations walk frames 140..147 over and over; the step back from 147
// to 140 is a frame where the fallen ones rise again (the mean includes it).
void BM_ReusePlan(benchmark::State& state) {
    Result<Scene> scene = loadScene("builtin:dominoes?polygons=50000&static=0.9866");
    if (!scene) {
        state.SkipWithError(scene.error().message.c_str());
        return;
    }
    std::vector<FrameSetup> frames;
    for (int f = 140; f < 148; ++f) {
        Result<FrameSetup> frame = setUpFrame(*scene, {}, frameTime(f, scene->fps), 1920, 1080, false);
        if (frame) frames.push_back(std::move(*frame));
    }
    ReuseOptions options;
    options.grain = int(state.range(0));
    options.fallback = false;
    TemporalReuse reuse(*scene, 1920, 1080, options);
    const glm::vec4 background(0.1f, 0.1f, 0.1f, 1.0f);
    for (const FrameSetup& frame : frames) reuse.plan(frame.params, frame.world, background);  // warm: extents
    std::size_t at = 0;
    double overlapMs = 0.0, redrawn = 0.0;
    for (auto _ : state) {
        const FrameSetup& frame = frames[at++ % frames.size()];
        const FramePlan plan = reuse.plan(frame.params, frame.world, background);
        benchmark::DoNotOptimize(plan.data());
        overlapMs += reuse.stats().overlapMs;
        redrawn += double(reuse.stats().staticRedrawnTris);
    }
    state.counters["triangles"] = double(scene->triangleCount());
    state.counters["overlap_ms"] = benchmark::Counter(overlapMs, benchmark::Counter::kAvgIterations);
    state.counters["static_redrawn"] = benchmark::Counter(redrawn, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_ReusePlan)->Arg(1)->Arg(16)->Arg(0)->Unit(benchmark::kMicrosecond);

// The adaptive z-buffer's overlap flags (paper 003; the goal: 100k polygons in ≤ 50 ms on
// one core) for 100,000 random triangles of a 1920×1080 frame: vertices within ±8 px of a uniform
// centre (about 3 layers of triangles over the frame, like a dense mesh), depths within ±0.002 of a
// uniform centre; extents as hsr/Order.h makes them (one pixel of margin). Argument 0: the paper's
// all pairs, 1: the grid.
void BM_HsrFlags(benchmark::State& state) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> cx(0.0f, 1920.0f), cy(0.0f, 1080.0f), cz(0.0f, 1.0f), d(-8.0f, 8.0f),
        dz(-0.002f, 0.002f);
    std::vector<hsr::Extent> extents;
    for (int i = 0; i < 100000; ++i) {
        const float x = cx(rng), y = cy(rng), z = cz(rng);
        float minX = 1e9f, maxX = -1e9f, minY = 1e9f, maxY = -1e9f, minZ = 1.0f, maxZ = 0.0f;
        for (int k = 0; k < 3; ++k) {
            const float vx = x + d(rng), vy = y + d(rng), vz = std::clamp(z + dz(rng), 0.0f, 1.0f);
            minX = std::min(minX, vx); maxX = std::max(maxX, vx);
            minY = std::min(minY, vy); maxY = std::max(maxY, vy);
            minZ = std::min(minZ, vz); maxZ = std::max(maxZ, vz);
        }
        hsr::Extent e{std::max(0, int(std::floor(minX - 1.0f))), std::max(0, int(std::floor(minY - 1.0f))),
                      std::min(1919, int(std::ceil(maxX + 1.0f)) - 1), std::min(1079, int(std::ceil(maxY + 1.0f)) - 1),
                      minZ, maxZ};
        if (e.x0 <= e.x1 && e.y0 <= e.y1) extents.push_back(e);
    }
    const bool grid = state.range(0) == 1;
    std::vector<std::uint8_t> flags;
    for (auto _ : state) {
        flags = grid ? hsr::flagOverlaps(extents) : hsr::flagOverlapsAllPairs(extents);
        benchmark::DoNotOptimize(flags.data());
    }
    state.counters["triangles"] = double(extents.size());
    state.counters["flagged_share"] = double(std::count(flags.begin(), flags.end(), 1)) / double(extents.size());
}
BENCHMARK(BM_HsrFlags)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace frugal
