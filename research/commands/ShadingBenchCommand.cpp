// `frugal-lab shading-bench`: what each shading term costs on one frame (lab/ShadingBench.h).
#include <ostream>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/ReportOutputs.h"
#include "commands/LabCommands.h"
#include "lab/ShadingBench.h"

namespace frugal {

const char* shadingBenchHelp() {
    return R"(usage: frugal-lab shading-bench [SCENE] [options]

Times one frame of SCENE (default builtin:materials) as the settings draw it ("full") and, in the
same run, interleaved, the same frame with one shading term taken away: --shading lambert, the
environment's specular term, the environment, the uniform stand-in for --environment-map, every
texture, the normal maps, blending (BLEND materials drawn opaque); and with multisampling added
(--samples 4, or 1 when the settings ask for more). A term the scene does not use is skipped, with
why. Per variant: the median frame time (clear + draws + finish; min and max), its ratio to full's,
and the pixels where its image differs from full's. Each variant draws on its own stage (a context
of the one backend --backend opens, its own uploads). Prints a line per variant.
)";
}

int runShadingBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    options.scene = "builtin:materials";
    ReportPaths outputs;
    int runs = 20, warmup = 3;
    CommandLine command{"shading-bench", shadingBenchHelp(), &options};
    command.flags = {{"", {
        flag::whole("--repeat", "N", "timed frames per variant (default 20)", runs, 1, 100000),
        flag::whole("--warmup", "N", "untimed frames per variant first (default 3: llvmpipe compiles its variants)",
                    warmup, 0, 100000),
    }}};
    for (Flag& f : reportFlags(outputs,
                               "{\"scene\",\"size\",\"backend\",\"renderer\",\"runs\",\"rows\":[{\"term\",\"change\","
                               "\"median_ms\",\"min_ms\",\"max_ms\",\"pixels_differing\",\"over_full\"}],"
                               "\"skipped\":[{\"term\",\"why\"}]}",
                               "one row per variant",
                               "each variant's median frame time over full's, drawn by gnuplot from the CSV (--csv, or "
                               "FILE.csv beside the plot); the script is written as FILE.gp"))
        command.flags[0].flags.push_back(std::move(f));
    command.positional = sceneArgument(options);
    command.finish = [&outputs](ArgCursor& cursor) {
        if (const std::string problem = plotProblem(outputs); !problem.empty()) cursor.fail(problem);
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;

    Result<Scene> loaded = loadForRender(options, err);
    if (!loaded) return fail(err, loaded.error());
    Result<FrameSetup> setup = frameSetups(options, *loaded, false)(options.frames ? options.frames->first : 0);
    if (!setup) return fail(err, setup.error());
    const ShadingBenchSettings settings{options.scene, options.settings, runs, warmup};
    Result<ShadingBenchResult> measured =
        measureShadingTerms(*loaded, *setup, settings, progressTo(err, options.quiet));
    if (!measured) return fail(err, measured.error());
    out << measured->text;
    const ReportTexts texts{[&measured] { return measured->json; }, [&measured] { return measured->csv; },
                            [&options](const std::string& csvPath, const std::string& svgPath) {
                                return shadingBenchGnuplot(csvPath, svgPath, options.scene);
                            }};
    return writeReportFiles(outputs, texts, err);
}

}  // namespace frugal
