// What the one-frame benchmarks' commands share (order-bench, shading-bench, pose-bench): SCENE, --repeat,
// --warmup, the report outputs, the frame set up from the settings, the measurement's texts written.
#include <ostream>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/ReportOutputs.h"
#include "commands/LabCommands.h"

namespace frugal {

int runFrameBench(const FrameBenchCommand& bench, const std::vector<std::string>& args, std::ostream& out,
                  std::ostream& err) {
    RenderOptions options;
    options.scene = bench.defaultScene;
    ReportPaths outputs;
    int runs = bench.defaultRepeat, warmup = 3;
    const std::string per = " per " + bench.unit;
    CommandLine command{bench.name, bench.help, &options};
    command.flags = {{"", {
        flag::whole("--repeat", "N", "timed frames" + per + " (default " + std::to_string(bench.defaultRepeat) + ")",
                    runs, 1, 100000),
        flag::whole("--warmup", "N", "untimed frames" + per + " first (default 3: llvmpipe compiles its variants)",
                    warmup, 0, 100000),
    }}};
    for (Flag& f : reportFlags(outputs, bench.jsonShape, bench.csvRows, bench.plot))
        command.flags[0].flags.push_back(std::move(f));
    command.positional = sceneArgument(options);
    command.finish = [&outputs](ArgCursor& cursor) {
        if (const std::string problem = plotProblem(outputs); !problem.empty()) cursor.fail(problem);
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;

    Result<Scene> loaded = bench.generated && options.scene == bench.defaultScene ? Result<Scene>(bench.generated())
                                                                                  : loadForRender(options, err);
    if (!loaded) return fail(err, loaded.error());
    Result<FrameSetup> setup = frameSetups(options, *loaded, false)(options.frames ? options.frames->first : 0);
    if (!setup) return fail(err, setup.error());
    Result<BenchTexts> measured = bench.measure(*loaded, *setup, options, runs, warmup, progressTo(err, options.quiet));
    if (!measured) return fail(err, measured.error());
    out << measured->text;
    const ReportTexts texts{[&measured] { return measured->json; }, [&measured] { return measured->csv; },
                            [&bench, &options](const std::string& csvPath, const std::string& svgPath) {
                                return bench.gnuplot(csvPath, svgPath, options.scene);
                            }};
    return writeReportFiles(outputs, texts, err);
}

}  // namespace frugal
