#include "lab/HsrBench.h"

#include <chrono>
#include <cstddef>

#include "lab/ImageCompare.h"
#include "renderer/Research.h"

namespace frugal {

namespace {

// The modes, and a diagnostic row: depthsort's draws with the depth test on, which splits
// depthsort's difference from zbuffer into what the order and the extra draws cost (this row ÷
// zbuffer) and what leaving out the depth test saves (depthsort ÷ this row).
struct Variant {
    const char* name;
    hsr::Mode mode;
    bool depthTested;  // every draw of the plan with DepthMode::Test
};
constexpr Variant kModes[] = {{"zbuffer", hsr::Mode::ZBuffer, true},
                              {"depthsort", hsr::Mode::DepthSort, false},
                              {"adaptive", hsr::Mode::Adaptive, false},
                              {"adaptive-convex", hsr::Mode::AdaptiveConvex, false},
                              {"sorted-zbuffer", hsr::Mode::DepthSort, true}};
constexpr int kModeCount = 5;

// A mode's worst frame: its number and differing pixels.
struct Worst {
    int frame = -1;
    std::size_t px = 0;
};

class Bench {
public:
    Bench(const Scene& scene, const HsrBenchSettings& settings, Stage& stage)
        : s_(settings), stage_(stage), planner_(scene) {}

    // Plans and draws `variant`'s frame, timed from the plan to glFinish (milliseconds).
    double draw(const Variant& variant, const FrameSetup& setup, hsr::PlanStats& stats) const {
        using Clock = std::chrono::steady_clock;
        const Settings& r = s_.render;
        SceneRenderer& renderer = stage_.renderer();
        stage_.backend().finish();
        const auto t0 = Clock::now();
        if (variant.mode == hsr::Mode::ZBuffer) {
            renderer.renderFrame(stage_.target(), r.width, r.height, setup.params, setup.world, r.background);
            stats = hsr::PlanStats{};
            stats.draws = renderer.fullList().size();
        } else {
            DrawList list =
                planner_.plan(variant.mode, setup.params, setup.world, renderer.fullList(), r.width, r.height, &stats);
            if (variant.depthTested)
                for (DrawCommand& command : list) command.depth = DepthMode::Test;
            renderer.renderFrame(stage_.target(), r.width, r.height, setup.params, setup.world, r.background, list);
        }
        stage_.backend().finish();
        return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    }

    // One frame: the warm-up (first frame only), the timed rounds, then the images compared.
    void frame(int frame, const FrameSetup& setup, HsrReport& report, Worst (&worst)[kModeCount]) const {
        hsr::PlanStats stats[kModeCount];
        if (frame == s_.firstFrame)
            for (int w = 0; w < s_.warmup; ++w)
                for (int m = 0; m < kModeCount; ++m) draw(kModes[m], setup, stats[m]);
        for (int r = 0; r < s_.repeat; ++r)
            for (int k = 0; k < kModeCount; ++k) {
                const int m = (k + frame + r) % kModeCount;
                const double ms = draw(kModes[m], setup, stats[m]);
                report.modes[std::size_t(m)].ms.push_back(ms);
                report.modes[std::size_t(m)].planMs.push_back(stats[m].ms);
            }
        // The images, untimed: each mode drawn once more and read back.
        Buffers images[kModeCount];
        for (int m = 0; m < kModeCount; ++m) {
            draw(kModes[m], setup, stats[m]);
            images[m] = stage_.backend().readBack(stage_.target());
            HsrModeResult& result = report.modes[std::size_t(m)];
            const std::size_t px = differingColorPixels(images[m], images[0]);
            result.differingPx.push_back(px);
            result.zbufferedShare.push_back(kModes[m].depthTested ? 1.0 : stats[m].zbufferedShare(kModes[m].mode));
            result.polygons.push_back(stats[m].polygons);
            result.draws.push_back(stats[m].draws);
            if (worst[m].frame < 0 || px > worst[m].px) worst[m] = Worst{frame, px};
        }
    }

    // The worst frame of depthsort, adaptive and adaptive-convex, drawn again beside the z-buffer's.
    Result<std::vector<HsrWorstImages>> worstImages(const Worst (&worst)[kModeCount],
                                                    const FrameSetupOf& setupOf) const {
        std::vector<HsrWorstImages> images;
        for (int m = 1; m <= 3; ++m) {
            Result<FrameSetup> setup = setupOf(worst[m].frame);
            if (!setup) return setup.error();
            hsr::PlanStats stats;
            HsrWorstImages image;
            image.mode = kModes[m].name;
            draw(kModes[0], *setup, stats);
            image.reference = stage_.backend().readBack(stage_.target());
            draw(kModes[m], *setup, stats);
            image.actual = stage_.backend().readBack(stage_.target());
            Result<ImageComparison> compared = compareBuffers(image.actual, image.reference, CompareOptions{});
            if (!compared) return Error{"masks: " + compared.error().message, ErrorKind::BadInput, true};
            image.compared = std::move(*compared);
            images.push_back(std::move(image));
        }
        return images;
    }

    std::size_t polygonCount() const { return planner_.polygonCount(); }

private:
    const HsrBenchSettings& s_;
    Stage& stage_;
    const hsr::Planner planner_;
};

}  // namespace

Result<HsrBenchResult> measureHsr(const Scene& scene, const HsrBenchSettings& settings, const FrameSetupOf& setupOf,
                                  const std::function<void(const std::string&)>& progress) {
    Result<Stage> stage = Stage::open(settings.render);
    if (!stage) return stage.error();
    progress("backend: " + describe(stage->backend()));
    if (Result<bool> uploaded = stage->upload(scene); !uploaded) return uploaded.error();
    const Bench bench(scene, settings, *stage);

    HsrBenchResult result;
    HsrReport& report = result.report;
    report.scene = settings.scene;
    report.backend = stage->backend().name();
    report.renderer = stage->backend().renderer();
    report.width = settings.render.width;
    report.height = settings.render.height;
    report.firstFrame = settings.firstFrame;
    report.lastFrame = settings.lastFrame;
    report.repeat = settings.repeat;
    report.polygons = bench.polygonCount();
    report.triangles = scene.triangleCount();
    for (const Variant& variant : kModes) report.modes.push_back(HsrModeResult{variant.name, {}, {}, {}, {}, {}, {}});

    Worst worst[kModeCount];
    const int first = settings.firstFrame, last = settings.lastFrame, count = last - first + 1;
    for (int frame = first; frame <= last; ++frame) {
        Result<FrameSetup> setup = setupOf(frame);
        if (!setup) return setup.error();
        bench.frame(frame, *setup, report, worst);
        if (frame == last || (frame - first + 1) % 10 == 0)
            progress("frame " + std::to_string(frame) + " (" + std::to_string(frame - first + 1) + "/" +
                     std::to_string(count) + ")");
    }
    if (settings.worstImages) {
        Result<std::vector<HsrWorstImages>> images = bench.worstImages(worst, setupOf);
        if (!images) return images.error();
        result.worst = std::move(*images);
    }
    return result;
}

}  // namespace frugal
