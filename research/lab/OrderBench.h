// `frugal-lab order-bench`'s measurement: what draw order buys on a real frame (paper 004). On each
// backend (a GL one and the software reference, or one kind), the state-change costs are measured
// once, the frame's draw list is put in every order, and the orders' frames are timed interleaved
// (the first order rotating from run to run), each with the state changes the backend issued, by
// kind, and the pixels where its image differs from submission order's (exact depth ties: opaque
// geometry renders the same in every order otherwise).
#pragma once

#include <functional>
#include <string>

#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>

#include "lab/ReportText.h"
#include "renderer/Research.h"

namespace frugal {

struct OrderBenchSettings {
    std::string scene;  // the scene's name in the report
    // The stage (size, threads, interp, depth format, background); backend: one kind, or Auto for
    // the GL backend Auto opens and the software reference.
    Settings render;
    int repeat = 20;  // timed frames per order
    int warmup = 3;   // untimed frames per order first
};

// json: {"command","scene","size","backends":[{"backend","renderer","state_costs_us","runs","orders"}]};
// csv: one row per backend and order; text: one line per backend and order, as the command prints it.
using OrderBenchResult = BenchTexts;

// Measures `setup`'s frame of `scene` in every order on every backend that opens. `progress`
// receives "skipped KIND: why" for a backend that does not open and each backend's state-cost line.
// Errors: "order-bench: no backend available" (BackendUnavailable), the upload's, the cost
// measurement's.
Result<OrderBenchResult> measureOrders(const Scene& scene, const FrameSetup& setup, const OrderBenchSettings& settings,
                                       const std::function<void(const std::string&)>& progress);

// The gnuplot script that draws the CSV at `csvPath` into `svgPath`: frame time and draws per
// backend and order.
std::string orderBenchGnuplot(const std::string& csvPath, const std::string& svgPath, const std::string& scene);

}  // namespace frugal
