// Library pieces timed side by side: the software reference on whole frames (1 thread against every
// core), PNG encoding of a full frame, and index-range normalisation as a culled draw list needs it.
// No GL here: GL frames are measured by `frugal bench render`, against the minimal GL program.
#include <algorithm>
#include <filesystem>
#include <random>
#include <thread>

#include <benchmark/benchmark.h>

#include "io/ImageIO.h"
#include "render/Frame.h"
#include "render/IndexRanges.h"
#include "render/SceneRenderer.h"
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
        state.SkipWithError(scene.error().c_str());
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

}  // namespace
}  // namespace frugal
