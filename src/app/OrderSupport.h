// Draw orders by measured state-change costs on real frames (issue 10): each draw's render-state set
// (RSS) as the backends set it, the kinds' costs from `info --state-costs`'s measurement
// (gl/StateCosts.h), and paper 004's sort, greedy nearest neighbour and the best order
// (src/order/Order.h) applied to a frame's draw list.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "gl/StateCosts.h"
#include "order/Order.h"
#include "render/Plan.h"
#include "scene/Scene.h"

namespace frugal {

// The state kinds of an RSS, in the order of StateCostReport::costs: program (shader variant:
// texture, vertex colours), mesh, texture (0 = none), material, culling (single or double-sided),
// depth (Test or Off). A draw's transform changes with every instance whatever the order, so it is
// not a kind here.
std::vector<order::Rss> drawStates(const Scene& scene, const DrawList& list, bool cullAllBackFaces = false);

// The kinds' costs in microseconds from a measurement; a cost measured at or below 0 (noise around a
// free change) counts as 0.01 us, so that every kind still has an order to prefer.
std::vector<double> stateCostsUs(const StateCostReport& report);

// `list` in `order`: submit and key as orderDraws; paper, greedy and best computed on the list's
// distinct RSSs (copies drawn together, in submission order, which keeps batches whole) with
// `costs` under order::CostRule::SetNotHeld; paper's high-cost set has 3 kinds.
DrawList orderFrameDraws(const Scene& scene, const DrawList& list, DrawOrder order, const std::vector<double>& costs);

// {"draws","programs","meshes","textures","toggles","uniforms"}: the render and order-bench JSON.
nlohmann::json stateChangesJson(const StateChanges& changes);

// The costs `order` needs, measured on `backend` (paper, greedy, best; nothing for submit and key),
// with one line on `err` unless quiet: "order best: state costs on egl-surfaceless (us): program
// 8.3, mesh 0.1, ...". Error: the measurement's.
Result<std::vector<double>> costsForOrder(DrawOrder order, Backend& backend, std::ostream& err, bool quiet);

}  // namespace frugal
