// `frugal-lab hsr-bench`: paper 003's hidden-surface modes against the z-buffer on one backend (the
// measurement is lab/HsrBench.h's).
#include <filesystem>
#include <optional>
#include <ostream>

#include <frugal/Files.h>

#include "app/Cli.h"
#include "app/Command.h"
#include "commands/LabCommands.h"
#include "app/ReportOutputs.h"
#include "lab/HsrBench.h"
#include "lab/HsrReport.h"
#include "lab/ImageCompare.h"

namespace frugal {

const char* hsrBenchHelp() {
    return R"(usage: frugal-lab hsr-bench [SCENE] [options]

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

namespace {

// --masks DIR: each mode's mask, DIR/MODE_mask.png, its image DIR/MODE.png, and DIR/zbuffer.png.
Result<bool> writeMasks(const std::string& masksDir, const std::vector<HsrWorstImages>& worst) {
    std::error_code ec;
    std::filesystem::create_directories(masksDir, ec);
    if (ec) return Error{"masks " + masksDir + ": cannot create the folder: " + ec.message(), ErrorKind::Io, true};
    FileSet files;
    const std::filesystem::path dir(masksDir);
    for (const HsrWorstImages& image : worst) {
        files.add((dir / (image.mode + "_mask.png")).string(), encodeMaskPng(image.compared));
        files.add((dir / (image.mode + ".png")).string(), encodeColorPng(image.actual));
        if (&image == &worst.front()) files.add((dir / "zbuffer.png").string(), encodeColorPng(image.reference));
    }
    return files.commit();
}

}  // namespace

int runHsrBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    options.scene = "builtin:cubes";
    options.settings.width = 240;
    options.settings.height = 320;
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
    if (!loaded) return fail(err, loaded.error());
    const HsrBenchSettings settings{options.scene,        options.settings, options.frames->first,
                                    options.frames->last, repeat,                    warmup,
                                    !masksDir.empty()};
    const FrameSetupOf setupOf = frameSetups(options, *loaded, false);
    Result<HsrBenchResult> measured = measureHsr(*loaded, settings, setupOf, progressTo(err, options.quiet));
    if (!measured) return fail(err, measured.error());
    if (!masksDir.empty())
        if (Result<bool> written = writeMasks(masksDir, measured->worst); !written) return fail(err, written.error());

    const HsrReport& report = measured->report;
    out << hsrReportText(report);
    const ReportTexts texts{[&report] { return hsrReportJson(report); }, [&report] { return hsrReportCsv(report); },
                            [&report](const std::string& csv, const std::string& svg) {
                                return hsrReportGnuplot(csv, svg, report);
                            }};
    return writeReportFiles(outputs, texts, err);
}

}  // namespace frugal
