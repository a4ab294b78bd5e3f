// `frugal order-bench`: what draw order buys on a real frame (issue 10, paper 004). On each backend
// (a GL one and the software reference, or --backend), the state-change costs are measured once,
// the frame's draw list is put in every order, and the orders' frames are timed interleaved (the
// first order rotating from run to run), each with the state changes the backend issued, by kind,
// and the pixels where its image differs from submission order's (exact depth ties: opaque geometry
// renders the same in every order otherwise).
#include <chrono>
#include <cstdio>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "app/ReportOutputs.h"
#include "base/Stats.h"
#include "lab/ReportText.h"
#include "renderer/StateOrder.h"
#include "renderer/StatsJson.h"
#include "report/ImageCompare.h"

namespace frugal {

const char* orderBenchHelp() {
    return R"(usage: frugal order-bench [SCENE] [options]

Times one frame of SCENE (default builtin:materials: 1,000 boxes over 40 meshes, 24 materials and 8
textures, submitted in a random order) in every draw order, on a GL backend and on the software
reference (or only --backend), in one run: per order the median frame time (clear + draws +
finish), the time to compute the order, the state changes the backend issued by kind (draws,
programs, meshes, textures, toggles, uniforms) and the pixels that differ from submission order.
The orders (see 'frugal help render'): submit, key, paper, greedy, best; paper, greedy and best use
the state-change costs measured on each backend at start (printed).
)";
}

namespace {

constexpr int kOrderCount = 5;

std::string orderBenchGnuplot(const std::string& csvPath, const std::string& svgPath, const std::string& scene) {
    using reporttext::gnuplotQuoted;
    return "# frugal order-bench: frame time and draws per backend and draw order.\n"
           "# Drawn from the CSV; run gnuplot on this file to draw it again.\n"
           "set terminal svg size 760,440 dynamic background rgb 'white'\n"
           "set output " + gnuplotQuoted(svgPath) + "\n"
           "set datafile separator ','\n"
           "set title " + gnuplotQuoted("draw orders: " + scene) + " noenhanced\n"
           "set ylabel 'frame ms (median; bar: min to max)'\n"
           "set y2label 'draws issued'\n"
           "set ytics nomirror\n"
           "set y2tics\n"
           "set yrange [0:*]\n"
           "set y2range [0:*]\n"
           "set style fill solid 0.6 border -1\n"
           "set boxwidth 0.7\n"
           "set xtics rotate by -35 noenhanced\n"
           "set grid ytics\n"
           "set key top center\n"
           "plot " + gnuplotQuoted(csvPath) + " skip 1 using 0:3:xtic(sprintf('%s %s', strcol(1), strcol(2))) "
           "with boxes title 'frame ms', '' skip 1 using 0:3:4:5 with yerrorbars lc rgb 'black' pt 0 notitle, "
           "'' skip 1 using 0:7 axes x1y2 with points pt 7 ps 1.2 title 'draws'\n";
}

}  // namespace

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
    if (!loaded) {
        err << "error: " << loaded.error() << "\n";
        return kExitError;
    }
    const Scene& scene = *loaded;
    Result<FrameSetup> setup = setUpFrame(options, scene, options.frames ? options.frames->first : 0, false);
    if (!setup) {
        err << "error: " << setup.error() << "\n";
        return kExitError;
    }
    std::vector<BackendKind> choices;
    if (options.backend != BackendKind::Auto)
        choices = {options.backend};
    else
        choices = {BackendKind::Auto, BackendKind::Software};

    using Clock = std::chrono::steady_clock;
    const auto msSince = [](Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); };
    nlohmann::json backends = nlohmann::json::array();
    std::ostringstream csv;
    csv << "backend,order,median_ms,min_ms,max_ms,order_ms,draws,programs,meshes,textures,toggles,uniforms,tie_px\n";
    for (const BackendKind choice : choices) {
        Result<Session> opened = openSession(choice, options);
        if (!opened) {
            if (!options.quiet) err << "skipped " << toString(choice) << ": " << opened.error() << "\n";
            continue;
        }
        if (int prepared = prepareSession(*opened, options, scene, err); prepared != kExitOk) return prepared;
        Backend& backend = *opened->backend;
        SceneRenderer& renderer = *opened->renderer;
        Result<OrderCosts> costs = startOrderCosts(Order::Best, backend, 0, err, options.quiet);
        if (!costs) {
            err << "error: " << costs.error() << "\n";
            return kExitError;
        }
        DrawList lists[kOrderCount];
        double orderMs[kOrderCount];
        for (int o = 0; o < kOrderCount; ++o) {
            const auto t0 = Clock::now();
            lists[o] = orderFrameDraws(scene, renderer.fullList(), kOrders[o], costs->costsUs());
            orderMs[o] = msSince(t0);
        }
        std::vector<double> ms[kOrderCount];
        StateChanges changes[kOrderCount];
        const auto frame = [&](int o) {
            backend.finish();
            const StateChanges before = backend.stateChanges();
            const auto t0 = Clock::now();
            renderer.renderFrame(opened->target, options.width, options.height, setup->params, setup->world,
                                 options.background, lists[o]);
            backend.finish();
            changes[o] = backend.stateChanges() - before;
            return msSince(t0);
        };
        for (int w = 0; w < warmup; ++w)
            for (int o = 0; o < kOrderCount; ++o) frame(o);
        for (int r = 0; r < runs; ++r)
            for (int k = 0; k < kOrderCount; ++k) {
                const int o = (k + r) % kOrderCount;
                ms[o].push_back(frame(o));
            }
        // Images, untimed: each order against submission order.
        frame(0);
        const Buffers submitted = backend.readBack(opened->target);
        nlohmann::json orders = nlohmann::json::array();
        for (int o = 0; o < kOrderCount; ++o) {
            frame(o);
            const Buffers image = backend.readBack(opened->target);
            const std::size_t tie = differingColorPixels(image, submitted);
            const double med = median(ms[o]);
            const auto [lo, hi] = std::minmax_element(ms[o].begin(), ms[o].end());
            const StateChanges& c = changes[o];
            orders.push_back({{"order", toString(kOrders[o])},
                              {"median_ms", med},
                              {"min_ms", *lo},
                              {"max_ms", *hi},
                              {"order_ms", orderMs[o]},
                              {"state_changes", stateChangesJson(c)},
                              {"tie_px", tie}});
            csv << backend.name() << "," << toString(kOrders[o]) << "," << med << "," << *lo << "," << *hi << ","
                << orderMs[o] << "," << c.draws << "," << c.programs << "," << c.meshes << "," << c.textures << ","
                << c.toggles << "," << c.uniforms << "," << tie << "\n";
            char line[200];
            std::snprintf(line, sizeof line,
                          "  %-7s %8.3f ms (%.3f-%.3f), order %7.3f ms, draws %5llu programs %4llu meshes %5llu "
                          "textures %4llu toggles %4llu uniforms %5llu, tie px %zu\n",
                          toString(kOrders[o]), med, *lo, *hi, orderMs[o], (unsigned long long)c.draws,
                          (unsigned long long)c.programs, (unsigned long long)c.meshes, (unsigned long long)c.textures,
                          (unsigned long long)c.toggles, (unsigned long long)c.uniforms, tie);
            out << backend.name() << line;
        }
        nlohmann::json costJson = nlohmann::json::object();
        for (std::size_t k = 0; k < kStateKinds; ++k) costJson[kStateKindNames[k]] = costs->costsUs()[k];
        backends.push_back({{"backend", backend.name()}, {"renderer", backend.renderer()}, {"state_costs_us", costJson},
                            {"runs", runs}, {"orders", orders}});
    }
    if (backends.empty()) {
        err << "error: order-bench: no backend available\n";
        return kExitNoBackend;
    }
    const nlohmann::json report = {{"command", "order-bench"}, {"scene", options.scene},
                                   {"size", {options.width, options.height}}, {"backends", backends}};
    const std::string csvText = csv.str();
    const ReportTexts texts{[&report] { return report.dump(2) + "\n"; }, [&csvText] { return csvText; },
                            [&options](const std::string& csvPath, const std::string& svgPath) {
                                return orderBenchGnuplot(csvPath, svgPath, options.scene);
                            }};
    return writeReportFiles(outputs, texts, err);
}

}  // namespace frugal
