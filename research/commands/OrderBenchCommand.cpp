// `frugal-lab order-bench`: what draw order buys on a real frame (the measurement is lab/OrderBench.h's).
#include <ostream>

#include "commands/LabCommands.h"
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
    const FrameBenchCommand bench{
        "order-bench",
        orderBenchHelp(),
        "order",
        "{\"scene\",\"size\",\"backends\":[{\"backend\",\"renderer\",\"state_costs_us\",\"orders\":[{\"order\","
        "\"median_ms\",\"min_ms\",\"max_ms\",\"order_ms\",\"state_changes\":{...},\"tie_px\"}]}]}",
        "one row per backend and order",
        "median frame time per backend and order (bars from min to max) and the draws issued, drawn by gnuplot from "
        "the CSV (--csv, or FILE.csv beside the plot); the script is written as FILE.gp",
        [](const Scene& scene, const FrameSetup& setup, const RenderOptions& options, int repeat, int warmup,
           const std::function<void(const std::string&)>& progress) {
            return measureOrders(scene, setup, OrderBenchSettings{options.scene, options.settings, repeat, warmup},
                                 progress);
        },
        orderBenchGnuplot};
    return runFrameBench(bench, args, out, err);
}

}  // namespace frugal
