// Draw orders by measured state-change costs on real frames: each draw's render-state set (RSS) as
// the backends set it, the kinds' costs from the backend's own measurement (gl/StateCosts.h), and
// paper 004's sort, greedy nearest neighbour and the best order (src/order/Order.h) applied to a
// frame's draw list.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <frugal/Scene.h>
#include <frugal/Stats.h>

#include "gl/StateCosts.h"
#include "order/Order.h"
#include "pipeline/Plan.h"

namespace frugal {

// The state kinds of an RSS, in the order of StateCostReport::costs: program (shader variant:
// texture, vertex colours), mesh, texture (0 = none), material, culling (single or double-sided),
// depth (Test or Off). A draw's transform changes with every instance whatever the order, so it is
// not a kind here.
std::vector<order::Rss> drawStates(const Scene& scene, const DrawList& list, bool cullAllBackFaces = false);

// `list` in `order`: submit and key as orderDraws; paper, greedy and best computed on the list's
// distinct RSSs (copies drawn together, in submission order, which keeps batches whole) with
// `costs` under order::CostRule::SetNotHeld; paper's high-cost set has 3 kinds.
DrawList orderFrameDraws(const Scene& scene, const DrawList& list, Order order, const std::vector<double>& costs);

// The costs `order` needs on `backend` (paper, greedy, best; none for submit and key): measured at
// start, 5 rounds of 200 draws a kind (gl/StateCosts.h), then refined while frames render: every
// `refineEvery` frames (0: never) one more round of 100 draws between two frames, folded into the
// running average of the last 32 rounds.
class OrderCosts {
public:
    // Error: the measurement's (the backend refused the probe's target, mesh or texture).
    static Result<OrderCosts> start(Order order, Backend& backend, int refineEvery);

    const std::vector<double>& costsUs() const { return costs_; }
    // Call between frames, with `framesDone` frames finished: one more round when one is due (never
    // inside a frame: the probe draws into a target of its own). True when the costs were refined.
    bool refine(int framesDone);
    // What was measured (frugal/Stats.h); nothing for submit and key.
    std::optional<StateCosts> report() const;

private:
    std::unique_ptr<StateCostProbe> probe_;
    RunningStateCosts running_;
    std::vector<double> start_, costs_;
    int refineEvery_ = 0;
};


}  // namespace frugal
