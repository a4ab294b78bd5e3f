// `frugal-lab reuse-bench`: what temporal reuse (paper 000, src/reuse/Reuse.h) saves, frame by frame.
// The measurement is lab/ReuseBench.h's (the full render, the reuse frame and its two oracles,
// timed back to back over rounds, and every reuse frame checked against the full render); this
// parses the flags, runs it, writes the report's files and prints its summary.
#include <optional>
#include <ostream>

#include "app/Cli.h"
#include "app/Command.h"
#include "commands/LabCommands.h"
#include "app/ReportOutputs.h"
#include "lab/ReuseBench.h"
#include "lab/ReuseReport.h"

namespace frugal {

const char* reuseBenchHelp() {
    return R"(usage: frugal-lab reuse-bench [SCENE] --frames A:B [options]

Measures temporal reuse on frames A to B of SCENE (default builtin:default): per frame the full
render, the reuse frame (plan + execution) and two oracles, each the frame's static image (made
beforehand) copied and only the dynamic instances drawn on it, timed back to back and given as
medians over the rounds:
  oracle (cells)  copies only what reuse copies: the cells where anything dynamic was or is (the
                  whole image on frames that are no reuse frame); the floor for reuse at this cell
                  size, the tighter one (oracle_ms, reuse/oracle)
  oracle (whole)  copies the whole image every frame: the issue's literal definition, the floor no
                  reuse method can beat (oracle_whole_ms, reuse/whole)
Also per frame: the planner's state counts (p_dd, p_ds, p_sd, p_ss: triangles), the pixels it
copied and cleared, the triangles it drew, the time of its overlap (⊗) tests; and the paper's cost
model fitted to the measurements, its prediction beside the measured time.
Every reuse frame is compared with the full render of the same frame: pixels where a static and a
dynamic triangle tie in depth may differ (tie_px); any other difference is an error (exit status 1).
Prints a summary; --json/--csv/--plot write the whole report.
)";
}

namespace {

struct ReuseBenchArgs {
    RenderOptions options;  // settings.reuse is always on: every frame after the first may reuse
    ReportPaths outputs;
    int repeat = 5;
    bool ids = false;
};

// Parses `args` into `a`: nothing when the command should go on, else the exit status.
std::optional<int> parseReuseBench(ReuseBenchArgs& a, const std::vector<std::string>& args, std::ostream& out,
                                   std::ostream& err) {
    RenderOptions& options = a.options;
    options.settings.reuse = true;
    CommandLine command{"reuse-bench", reuseBenchHelp(), &options};
    const Flag cull = settingFlag("cull", options.settings, options.given,
                                  "full and reuse frames draw that method's list (not occlusion, occlusion-ahead or "
                                  "oracle)");
    const Flag cullBins = settingFlag("cull-bins", options.settings, options.given);
    std::vector<Flag> reuse = topicFlags(options, "reuse");
    std::erase_if(reuse, [](const Flag& f) { return f.canonical() == "--reuse"; });
    reuse.push_back(cameraPathFlag(options));
    command.flags = {
        {"frames and timing", {
            flag::frames("--frames", "the frames, inclusive (required; A has no predecessor: it is a rebuild)",
                         options.frames),
            flag::whole("--repeat", "K", "timed rounds over the whole sequence, after one untimed warm-up round that "
                        "also checks the frames (default 5); medians over the rounds", a.repeat, 1, 10000),
            flag::on("--ids", "write triangle ids in every render (and compare them); default off, as 'frugal render' "
                     "without --ids", a.ids),
            cull,
            cullBins,
        }},
        {"outputs (each written whole or not at all)",
         reportFlags(a.outputs, "the report: frames, summary (medians, speed-up, ratios to both oracles, the fitted "
                     "cost model)", "one row per frame",
                     "plots drawn by gnuplot from the CSV (--csv, or FILE.csv beside the plot): speed-up against the "
                     "static share, and the times per frame; the gnuplot script is written beside it as FILE.gp, to "
                     "restyle and rerun")},
        {"temporal reuse (with a still camera only what changed is redrawn; src/reuse/Reuse.h)",
         reuse},
    };
    command.positional = sceneArgument(options);
    command.finish = [&](ArgCursor& cursor) {
        if (!options.frames)
            cursor.fail("--frames: reuse-bench needs a frame range A:B (each frame after A may reuse the one before)");
        else if (const std::string problem = plotProblem(a.outputs); !problem.empty())
            cursor.fail(problem);
    };
    return parseCommandLine(command, args, out, err);
}

ReuseBenchSettings settingsOf(const ReuseBenchArgs& a) {
    ReuseBenchSettings s;
    s.scene = a.options.scene;
    s.render = a.options.settings;
    s.render.ids = a.ids;
    s.firstFrame = a.options.frames->first;
    s.lastFrame = a.options.frames->last;
    s.repeat = a.repeat;
    return s;
}

}  // namespace

int runReuseBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    ReuseBenchArgs a;
    if (std::optional<int> status = parseReuseBench(a, args, out, err)) return *status;
    Result<Scene> loaded = loadForRender(a.options, err);
    if (!loaded) return fail(err, loaded.error());
    const FrameSetupOf setupOf = frameSetups(a.options, *loaded, a.ids);
    Result<ReuseMeasurement> measured = measureReuse(*loaded, settingsOf(a), setupOf, [&](const std::string& line) {
        if (!a.options.quiet) err << line << "\n";
    });
    if (!measured) return fail(err, measured.error());

    const ReuseBench& bench = measured->report;
    const int first = a.options.frames->first;
    const ReportTexts texts{[&bench] { return reuseReportJson(bench); }, [&bench] { return reuseReportCsv(bench); },
                            [first](const std::string& csvPath, const std::string& svgPath) {
                                return reuseReportGnuplot(csvPath, svgPath, first);
                            }};
    if (const int status = writeReportFiles(a.outputs, texts, err); status != kExitOk) return status;
    out << reuseReportSummary(bench);
    if (const std::optional<Error> failure = reuseFailure(*measured)) return fail(err, *failure);
    return kExitOk;
}

}  // namespace frugal
