#include "lab/OrderBench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "lab/SceneInfo.h"
#include "lab/ImageCompare.h"
#include "lab/RenderRecord.h"
#include "renderer/Research.h"
#include "lab/ReportText.h"

namespace frugal {

namespace {
constexpr int kOrderCount = 5;
}  // namespace

std::string orderBenchGnuplot(const std::string& csvPath, const std::string& svgPath, const std::string& scene) {
    using reporttext::gnuplotQuoted;
    return "# frugal-lab order-bench: frame time and draws per backend and draw order.\n"
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

Result<OrderBenchResult> measureOrders(const Scene& scene, const FrameSetup& setup, const OrderBenchSettings& settings,
                                       const std::function<void(const std::string&)>& progress) {
    const Settings& r = settings.render;
    std::vector<BackendKind> choices;
    if (r.backend != BackendKind::Auto)
        choices = {r.backend};
    else
        choices = {BackendKind::Auto, BackendKind::Software};

    using Clock = std::chrono::steady_clock;
    const auto msSince = [](Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); };
    nlohmann::json backends = nlohmann::json::array();
    std::ostringstream csv, text;
    csv << "backend,order,median_ms,min_ms,max_ms,order_ms,draws,programs,meshes,textures,toggles,uniforms,tie_px\n";
    for (const BackendKind choice : choices) {
        Settings stageSettings = r;
        stageSettings.backend = choice;
        std::string unavailable;
        Result<std::optional<Stage>> opened = Stage::openIfAvailable(stageSettings, unavailable);
        if (!opened) return opened.error();
        if (!*opened) {
            progress(std::string("skipped ") + toString(choice) + ": " + unavailable);
            continue;
        }
        Stage& stage = **opened;
        if (Result<bool> uploaded = stage.upload(scene); !uploaded) return uploaded.error();
        Backend& backend = stage.backend();
        SceneRenderer& renderer = stage.renderer();
        Result<OrderCosts> costs = OrderCosts::start(Order::Best, backend, 0);
        if (!costs) return costs.error();
        if (const std::optional<StateCosts> measured = costs->report())
            progress(stateCostsLine(Order::Best, backend.name(), *measured));
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
            renderer.renderFrame(stage.target(), r.width, r.height, setup.params, setup.world, r.background,
                                 lists[o]);
            backend.finish();
            changes[o] = backend.stateChanges() - before;
            return msSince(t0);
        };
        for (int w = 0; w < settings.warmup; ++w)
            for (int o = 0; o < kOrderCount; ++o) frame(o);
        for (int round = 0; round < settings.repeat; ++round)
            for (int k = 0; k < kOrderCount; ++k) {
                const int o = (k + round) % kOrderCount;
                ms[o].push_back(frame(o));
            }
        // Images, untimed: each order against submission order.
        frame(0);
        const Buffers submitted = backend.readBack(stage.target());
        nlohmann::json orders = nlohmann::json::array();
        for (int o = 0; o < kOrderCount; ++o) {
            frame(o);
            const Buffers image = backend.readBack(stage.target());
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
            text << backend.name() << line;
        }
        nlohmann::json costJson = nlohmann::json::object();
        for (std::size_t k = 0; k < kStateKinds; ++k) costJson[kStateKindNames[k]] = costs->costsUs()[k];
        backends.push_back({{"backend", backend.name()}, {"renderer", backend.renderer()}, {"state_costs_us", costJson},
                            {"runs", settings.repeat}, {"orders", orders}});
    }
    if (backends.empty()) return Error{"order-bench: no backend available", ErrorKind::BackendUnavailable};
    const nlohmann::json report = {{"command", "order-bench"}, {"scene", settings.scene},
                                   {"size", {r.width, r.height}}, {"backends", backends}};
    return OrderBenchResult{report.dump(2) + "\n", csv.str(), text.str()};
}

}  // namespace frugal
