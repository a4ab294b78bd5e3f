// `frugal hsr-bench`: paper 003's hidden-surface modes (src/hsr/Plan.h) against the z-buffer on one
// backend. Per frame the three modes plan and draw the same frame back to back (the first mode
// rotating from frame to frame, so that drift in the machine's speed hits all alike), each timed
// from the plan to glFinish; then each image is read back (untimed) and compared with the
// z-buffer's, colour, tolerance 0. The plan's time is part of the frame's: it is what the method
// costs on the CPU that the paper's IPAQ also ran it on.
#include <chrono>
#include <filesystem>
#include <optional>
#include <ostream>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "app/HsrSupport.h"
#include "app/ReportOutputs.h"
#include "io/ImageIO.h"
#include "lab/HsrReport.h"
#include "report/ImageCompare.h"

namespace frugal {

const char* hsrBenchHelp() {
    return R"(usage: frugal hsr-bench [SCENE] [options]

Paper 003's hidden-surface modes against the exact z-buffer, on one backend (--backend, default
auto; software for the reference rasterizer). SCENE defaults to builtin:cubes (the paper's 28
spinning cubes, 168 polygons) and --size to the paper's 240x320. Per frame each mode plans and
draws the frame, timed back to back (plan + draw + finish, no read-back):
  zbuffer     the submission order, every polygon depth-tested (the exact render)
  depthsort   polygons back to front by average depth, no depth test (the painter's method)
  adaptive    the same order; only polygons whose x, y and z extents overlap another's are
              depth-tested (the paper's Fig. 7; src/hsr/Plan.h says when it equals the z-buffer)
  adaptive-convex  adaptive, the front faces of one convex solid not flagged against each other
  sorted-zbuffer  not a mode: depthsort's draws with the depth test on, which splits depthsort's
              difference from zbuffer into the cost of its order and draws (sorted-zbuffer ÷
              zbuffer) and the saving of leaving out the depth test (depthsort ÷ sorted-zbuffer)
then each image is compared with the z-buffer's (colour, tolerance 0). Prints per mode fps
(1000 / mean ms), the median frame time, the plan's median time, the speed-up over zbuffer beside
the paper's Table 1 (IPAQ 3660: z-buffer 14.20, depth sort 52.13, adaptive 27.83 fps), the pixels
that differ from the z-buffer render (summed over frames, and the worst frame), and the share of
polygons drawn with the depth test (flagged_share: 1 for zbuffer, 0 for depthsort), and the draw
calls a frame makes (draws: the sorted order splits instances into runs).
)";
}

int runHsrBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    options.scene = "builtin:cubes";
    options.width = 240;
    options.height = 320;
    ReportPaths outputs;
    std::string masksDir;
    int repeat = 1, warmup = 3;
    CommandLine command{"hsr-bench", hsrBenchHelp(), &options};
    command.flags = {{"", {
        flag::frames("--frames", "the frames (default 0:99, at the scene's fps)", options.frames),
        flag::whole("--repeat", "K", "times each frame's modes are drawn and timed (default 1); the report holds every "
                    "timed frame", repeat, 1, 10000),
        flag::whole("--warmup", "N", "untimed rounds of frame A in every mode first (default 3: llvmpipe compiles its "
                    "shader variants)", warmup, 0, 10000),
        flag::text("--masks", "DIR", "for depthsort, adaptive and adaptive-convex, the mask of the frame with the most "
                   "differing pixels: DIR/MODE_mask.png (red where the colour differs from the z-buffer render, the "
                   "z-buffer image in grey elsewhere), and the frame's images DIR/MODE.png and DIR/zbuffer.png",
                   masksDir, "a folder name"),
    }}};
    for (Flag& f : reportFlags(outputs,
                               "{\"scene\",\"size\",\"backend\",\"modes\":[{\"mode\",\"fps\",\"median_ms\","
                               "\"plan_ms\",\"speedup\",\"paper_speedup\",\"differing_px\",\"flagged_share\",...}]}",
                               "one row per mode",
                               "measured and paper speed-up per mode, drawn by gnuplot from the CSV (--csv, or FILE.csv "
                               "beside the plot); the script is written as FILE.gp"))
        command.flags[0].flags.push_back(std::move(f));
    command.positional = sceneArgument(options);
    command.finish = [&](ArgCursor& cursor) {
        if (const std::string problem = plotProblem(outputs); !problem.empty())
            cursor.fail(problem);
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;
    if (!options.frames) options.frames = FrameRange{0, 99, true};

    Result<Scene> loaded = loadForRender(options, err);
    if (!loaded) {
        err << "error: " << loaded.error() << "\n";
        return kExitError;
    }
    const Scene& scene = *loaded;
    std::variant<Session, int> started = startSession(options, scene, err);
    if (const int* status = std::get_if<int>(&started)) return *status;
    Session& session = std::get<Session>(started);
    Backend& backend = *session.backend;
    SceneRenderer& renderer = *session.renderer;
    const hsr::Planner planner(scene);

    // The three modes, and a diagnostic row: depthsort's draws with the depth test on, which splits
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
    HsrReport report;
    report.scene = options.scene;
    report.backend = backend.name();
    report.renderer = backend.renderer();
    report.width = options.width;
    report.height = options.height;
    report.firstFrame = options.frames->first;
    report.lastFrame = options.frames->last;
    report.repeat = repeat;
    report.polygons = planner.polygonCount();
    report.triangles = scene.triangleCount();
    for (const Variant& variant : kModes) report.modes.push_back(HsrModeResult{variant.name, {}, {}, {}, {}, {}, {}});

    using Clock = std::chrono::steady_clock;
    const auto drawMode = [&](const Variant& variant, const FrameSetup& setup, hsr::PlanStats& stats) {
        backend.finish();
        const auto t0 = Clock::now();
        if (variant.mode == hsr::Mode::ZBuffer) {
            renderer.renderFrame(session.target, options.width, options.height, setup.params, setup.world,
                                 options.background);
            stats = hsr::PlanStats{};
            stats.draws = renderer.fullList().size();
        } else {
            DrawList list = planner.plan(variant.mode, setup.params, setup.world, renderer.fullList(), options.width,
                                         options.height, &stats);
            if (variant.depthTested)
                for (DrawCommand& draw : list) draw.depth = DepthMode::Test;
            renderer.renderFrame(session.target, options.width, options.height, setup.params, setup.world,
                                 options.background, list);
        }
        backend.finish();
        return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    };

    // Worst frame per mode, for --masks: its number and differing pixels.
    struct Worst {
        int frame = -1;
        std::size_t px = 0;
    } worst[kModeCount];
    const int frameCount = options.frames->last - options.frames->first + 1;
    for (int frame = options.frames->first; frame <= options.frames->last; ++frame) {
        Result<FrameSetup> setup = setUpFrame(options, scene, frame, false);
        if (!setup) {
            err << "error: " << setup.error() << "\n";
            return kExitError;
        }
        hsr::PlanStats stats[kModeCount];
        if (frame == options.frames->first)
            for (int w = 0; w < warmup; ++w)
                for (int m = 0; m < kModeCount; ++m) drawMode(kModes[m], *setup, stats[m]);
        for (int r = 0; r < repeat; ++r)
            for (int k = 0; k < kModeCount; ++k) {
                const int m = (k + frame + r) % kModeCount;
                const double ms = drawMode(kModes[m], *setup, stats[m]);
                report.modes[std::size_t(m)].ms.push_back(ms);
                report.modes[std::size_t(m)].planMs.push_back(stats[m].ms);
            }
        // The images, untimed: each mode drawn once more and read back.
        Buffers images[kModeCount];
        for (int m = 0; m < kModeCount; ++m) {
            drawMode(kModes[m], *setup, stats[m]);
            images[m] = backend.readBack(session.target);
            HsrModeResult& result = report.modes[std::size_t(m)];
            const std::size_t px = differingColorPixels(images[m], images[0]);
            result.differingPx.push_back(px);
            result.zbufferedShare.push_back(kModes[m].depthTested ? 1.0 : stats[m].zbufferedShare(kModes[m].mode));
            result.polygons.push_back(stats[m].polygons);
            result.draws.push_back(stats[m].draws);
            if (worst[m].frame < 0 || px > worst[m].px) worst[m] = Worst{frame, px};
        }
        if (!options.quiet && (frame == options.frames->last || (frame - options.frames->first + 1) % 10 == 0))
            err << "frame " << frame << " (" << (frame - options.frames->first + 1) << "/" << frameCount << ")\n";
    }

    if (!masksDir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(masksDir, ec);
        if (ec) {
            err << "error: --masks " << masksDir << ": cannot create the folder: " << ec.message() << "\n";
            return kExitError;
        }
        OutputSet files;
        const std::filesystem::path dir(masksDir);
        for (int m = 1; m <= 3; ++m) {  // depthsort, adaptive, adaptive-convex
            Result<FrameSetup> setup = setUpFrame(options, scene, worst[m].frame, false);
            if (!setup) {
                err << "error: " << setup.error() << "\n";
                return kExitError;
            }
            hsr::PlanStats stats;
            drawMode(kModes[0], *setup, stats);
            const Buffers reference = backend.readBack(session.target);
            drawMode(kModes[m], *setup, stats);
            const Buffers actual = backend.readBack(session.target);
            Result<ImageComparison> compared = compareBuffers(actual, reference, CompareOptions{});
            if (!compared) {
                err << "error: --masks: " << compared.error() << "\n";
                return kExitError;
            }
            const std::string name = kModes[m].name;
            files.add((dir / (name + "_mask.png")).string(), encodeMaskPng(*compared));
            files.add((dir / (name + ".png")).string(), encodeColorPng(actual));
            if (m == 1) files.add((dir / "zbuffer.png").string(), encodeColorPng(reference));
        }
        if (Result<bool> written = files.commit(); !written) {
            err << "error: " << written.error() << "\n";
            return kExitError;
        }
    }

    out << hsrReportText(report);
    const ReportTexts texts{[&report] { return hsrReportJson(report); }, [&report] { return hsrReportCsv(report); },
                            [&report](const std::string& csv, const std::string& svg) {
                                return hsrReportGnuplot(csv, svg, report);
                            }};
    return writeReportFiles(outputs, texts, err);
}

}  // namespace frugal
