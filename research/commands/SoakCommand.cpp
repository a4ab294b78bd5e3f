// `frugal-lab soak`: many frames and many create/destroy cycles in one process, on every backend, with
// resident memory sampled and every image checked (the runs are lab/Soak.h's; lab/SoakReport.h says
// what is judged).
#include <algorithm>
#include <cmath>
#include <optional>
#include <ostream>

#include "app/Cli.h"
#include "app/Command.h"
#include "commands/LabCommands.h"
#include "app/ReportOutputs.h"
#include "lab/Soak.h"
#include "lab/SoakReport.h"

namespace frugal {

const char* soakHelp() {
    return R"(usage: frugal-lab soak [SCENE] [options]

Renders SCENE (default builtin:cubes, 28 spinning cubes) for many frames in one process, then
creates and destroys backends, targets and the scene's uploads many times, on every backend
(software, egl-device, egl-surfaceless, osmesa: those that open here) or only --backend, and
judges what long runs break:
  memory   resident memory (VmRSS, /proc/self/status) sampled as it goes; its growth from the end
           of the warm-up (frames: --warmup; cycles: the first 1 %) to the end must stay within
           --max-growth
  images   the animation is looped every PERIOD frames, so frame f and f + PERIOD show the same
           time: every frame's colour, depth and ids must equal, bit for bit, the first frame of
           its time (64-bit hash); a frame with nothing but background counts as blank
  cycles   each cycle draws one frame, which must equal the first cycle's: "backend" opens a new
           backend with a target and the scene uploaded; "target" creates a target on one
           backend; "scene" uploads the scene's meshes and textures anew (SceneRenderer)
Prints a table per backend and a verdict; exit status 0 when everything passes, 1 otherwise.
Progress goes to stderr, a line every few seconds at most.
)";
}

namespace {

// --frames A:B (frames A to B, each at scene time (f mod period) / fps), or none (cycles only): a
// range, as every command's --frames is.
Flag framesFlag(SoakSettings& settings) {
    constexpr long long kMany = 1000000000;
    return {"--frames", "A:B|none",
            "the frames each backend renders, A to B (default 0:99999, 100,000 frames), frame f at scene time "
            "(f mod --period) / --fps; none: cycles only",
            [&settings](const std::string& text) -> std::string {
                if (text == "none") {
                    settings.firstFrame = settings.frames = 0;
                    return {};
                }
                const std::size_t colon = text.find(':');
                long long first = 0, last = 0;
                if (colon == std::string::npos || !flag::readWhole(text.substr(0, colon), 0, kMany, first).empty() ||
                    !flag::readWhole(text.substr(colon + 1), 0, kMany, last).empty() || last < first)
                    return "is not a frame range (A:B, 0 <= A <= B <= 1000000000) or none";
                settings.firstFrame = first;
                settings.frames = last - first + 1;
                return {};
            }};
}

// A combination of flags soak cannot run, or "".
std::string usageProblem(const SoakSettings& settings, const RenderOptions& options, const ReportPaths& outputs) {
    // Besides SVG, --plot takes a .png (gnuplot's pngcairo): a picture a README can show.
    if (std::string problem = plotProblem(outputs, /*pngToo=*/true); !problem.empty()) return problem;
    if (settings.frames == 0 && (settings.cycles == 0 || settings.minimal))
        return settings.minimal ? "--minimal with --frames none: the minimal GL program only draws frames"
                                : "--frames none with --cycles 0: nothing to do";
    if (settings.minimal && settings.ids) return "--minimal with --ids: the minimal GL program draws no ids";
    if (settings.minimal && options.settings.backend == BackendKind::Software)
        return "--minimal with --backend software: the minimal program is a GL program; pick a GL backend";
    if (settings.warmup && settings.frames > 0 && *settings.warmup >= settings.frames)
        return "--warmup " + std::to_string(*settings.warmup) + ": must be less than the " +
               std::to_string(settings.frames) + " frames of --frames";
    return {};
}

}  // namespace

int runSoak(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    options.scene = "builtin:cubes";
    options.settings.width = 64;
    options.settings.height = 48;
    SoakSettings settings;
    ReportPaths outputs;
    double maxGrowth = 5.0;
    std::optional<int> period;
    CommandLine command{"soak", soakHelp(), &options};
    constexpr long long kMany = 1000000000;
    command.flags = {
        {"", {
            framesFlag(settings),
            flag::whole("--cycles", "N", "create/destroy cycles of each kind per backend (default 1000; 0: none)",
                        settings.cycles, 0, kMany),
            flag::whole("--period", "N", "frames per loop of the animation (default: the scene's animation length at "
                        "--fps, e.g. 300 for builtin:cubes; 1 for a still scene or --time)", period, 1, kMany),
            flag::whole("--warmup", "N", "frames before the memory baseline (default 1 % of --frames, at least one "
                        "period: llvmpipe compiles its shader variants in the first frames)", settings.warmup, 0, kMany),
            flag::whole("--sample-every", "N", "frames between memory samples (default --frames / 1000, at least 1); "
                        "cycles are sampled every --cycles / 100", settings.sampleEvery, 1, kMany),
            flag::number("--max-growth", "PCT", "the memory growth allowed after warm-up, in percent (default 5)",
                         maxGrowth, 0, 1000),
            flag::on("--ids", "also write triangle ids every frame (the id pass)", settings.ids),
            flag::on("--minimal", "on each GL backend, the frames are drawn by the minimal GL program of 'frugal "
                     "bench render' (one program, glClear, glDrawElements per instance; gl/MinimalFrame.h) on a "
                     "context of the same kind instead: what Mesa alone does with memory over the same frames. No "
                     "cycles; its rows are named KIND (minimal).", settings.minimal),
            flag::text("--json", "FILE", "{\"scene\",\"size\",\"period\",\"fps\",\"max_growth_pct\",\"passed\","
                       "\"frames\":[{\"backend\",\"frames\",\"warmup\",\"rss_warm_kb\",\"rss_end_kb\",\"growth_pct\","
                       "\"compared_frames\",\"mismatched_frames\",\"blank_frames\",\"passed\",...}],\"cycles\":"
                       "[{\"backend\",\"kind\",\"cycles\",\"failures\",\"rss_warm_kb\",\"rss_end_kb\",\"growth_pct\","
                       "\"passed\",...}],\"skipped\":[...]}", outputs.json),
            flag::text("--csv", "FILE", "every memory sample: run (frames, backend, target, scene), backend, index, "
                       "rss_kb, hwm_kb, ms_each", outputs.csv),
            flag::text("--plot", "FILE.svg|.png", "resident memory over frames and over cycles, drawn by gnuplot from "
                       "the CSV (--csv, or FILE.csv beside the plot); the script is written as FILE.gp", outputs.plot),
            settingFlag("size", options.settings, options.given, "image size (default 64x48)"),
            settingFlag("backend", options.settings, options.given,
                        "one backend only: software, egl-device, egl-surfaceless or osmesa (auto, the default, runs "
                        "each)"),
        }},
    };
    command.positional = sceneArgument(options);
    command.finish = [&](ArgCursor& cursor) {
        if (const std::string problem = usageProblem(settings, options, outputs); !problem.empty()) cursor.fail(problem);
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;

    Result<Scene> loaded = loadForRender(options, err);
    if (!loaded) return fail(err, loaded.error());
    settings.scene = options.scene;
    settings.render = options.settings;
    settings.camera = options.camera;
    settings.time = options.time;
    settings.fps = options.fps.value_or(loaded->fps);
    settings.period = period.value_or(options.time ? 1 : std::max(1, int(std::lround(loaded->duration() * settings.fps))));
    settings.maxGrowthPct = maxGrowth;
    Result<SoakReport> report = frugal::runSoak(*loaded, settings, progressTo(err, options.quiet));
    if (!report) return fail(err, report.error());

    out << soakReportText(*report);
    const ReportTexts texts{
        [&report] { return soakReportJson(*report); }, [&report] { return soakReportCsv(*report); },
        [&report](const std::string& csv, const std::string& plot) { return soakReportGnuplot(csv, plot, *report); }};
    if (int written = writeReportFiles(outputs, texts, err); written != kExitOk) return written;
    return passed(*report) ? kExitOk : kExitError;
}

}  // namespace frugal
