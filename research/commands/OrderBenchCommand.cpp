// `frugal-lab order-bench`: what draw order buys on a real frame (the measurement is lab/OrderBench.h's).
#include <ostream>

#include "app/Cli.h"
#include "app/Command.h"
#include "commands/LabCommands.h"
#include "app/ReportOutputs.h"
#include "lab/OrderBench.h"

namespace frugal {

const char* orderBenchHelp() {
    return R"(usage: frugal-lab order-bench [SCENE] [options]

Times one frame of SCENE (default builtin:materials: 1,000 boxes over 40 meshes, 24 materials and 8
textures, submitted in a random order) in every draw order, on a GL backend and on the software
reference (or only --backend), in one run: per order the median frame time (clear + draws +
finish), the time to compute the order, the state changes the backend issued by kind (draws,
programs, meshes, textures, toggles, uniforms) and the pixels that differ from submission order.
The orders (see 'frugal help render'): submit, key, paper, greedy, best; paper, greedy and best use
the state-change costs measured on each backend at start (printed).
)";
}

int runOrderBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    options.scene = "builtin:materials";
    ReportPaths outputs;
    int runs = 20, warmup = 3;
    CommandLine command{"order-bench", orderBenchHelp(), &options};
    command.flags = {{"", {
        flag::whole("--repeat", "N", "timed frames per order (default 20)", runs, 1, 100000),
        flag::whole("--warmup", "N", "untimed frames per order first (default 3: llvmpipe compiles its variants)",
                    warmup, 0, 100000),
    }}};
    for (Flag& f : reportFlags(outputs,
                               "{\"scene\",\"size\",\"backends\":[{\"backend\",\"renderer\",\"state_costs_us\","
                               "\"orders\":[{\"order\",\"median_ms\",\"min_ms\",\"max_ms\",\"order_ms\","
                               "\"state_changes\":{...},\"tie_px\"}]}]}",
                               "one row per backend and order",
                               "median frame time per backend and order (bars from min to max) and the draws issued, "
                               "drawn by gnuplot from the CSV (--csv, or FILE.csv beside the plot); the script is "
                               "written as FILE.gp"))
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
    const OrderBenchSettings settings{options.scene, options.settings, runs, warmup};
    Result<OrderBenchResult> measured = measureOrders(*loaded, *setup, settings, progressTo(err, options.quiet));
    if (!measured) return fail(err, measured.error());
    out << measured->text;
    const ReportTexts texts{[&measured] { return measured->json; }, [&measured] { return measured->csv; },
                            [&options](const std::string& csvPath, const std::string& svgPath) {
                                return orderBenchGnuplot(csvPath, svgPath, options.scene);
                            }};
    return writeReportFiles(outputs, texts, err);
}

}  // namespace frugal
