// Plans: what a frame draws, as data. cull/ and reuse/ produce these without touching GL; either
// backend executes them (SceneRenderer).
#pragma once

#include <vector>

#include <frugal/Settings.h>

#include "pipeline/Backend.h"

namespace frugal {

// One instance's index ranges. A full draw is one range over the whole mesh. `depth`: how the draw
// uses the depth buffer (pipeline/Backend.h); plans other than the hidden-surface modes' leave Test.
struct DrawCommand {
    int instance = -1;
    std::vector<IndexRange> ranges;
    DepthMode depth = DepthMode::Test;
};

// In draw order: the order is part of the result (depth ties resolve to the first drawn).
using DrawList = std::vector<DrawCommand>;

// Every instance of the scene, whole, in instance order.
DrawList fullDrawList(const Scene& scene);

// Whether instance `instance` draws a blended material (AlphaMode::Blend): such commands are drawn
// after all the others of a list (SceneRenderer::draw), and never hide anything from a method.
bool blendedInstance(const Scene& scene, int instance);
// Whether any material of the scene is blended (when none is, blendedInstance is always false).
bool anyBlended(const Scene& scene);

// Draw orders (issue 10). submit: the list as it is. key: a stable sort by a state key as bgfx
// sorts, costliest-first by convention rather than by measurement: the texture, then the program
// variant (vertex colours or not), then the mesh. Consecutive draws of one mesh then become one
// instanced draw (SceneRenderer). Opaque geometry renders the same in every order except where two
// fragments tie exactly in depth: the first drawn keeps the pixel (Backend.h), so a reordered list
// may give such a pixel to the other one; the commands report those pixels (tie_px).
// paper, greedy and best order by measured state-change costs (src/order/, app/OrderSupport.h);
// orderDraws leaves the list as it is for them.
DrawList orderDraws(const Scene& scene, DrawList list, Order order);

// The two targets a frame plan names: the one the frame is rendered into, and the static pair of
// temporal reuse (src/reuse/), which holds what the static instances alone render to.
enum class PlanTarget : std::uint8_t { Render, Static };

// One step of a frame plan, executed in order:
//   Clear: `rects` of `to` to the background colour, far depth and id 0;
//   Copy:  `rects` from `from` to `to`: colour, depth, and ids when the frame writes them;
//   Draw:  `draws` into `to` (in list order, each with its depth mode, with the frame's camera and light).
struct PlanStep {
    enum class Op : std::uint8_t { Clear, Copy, Draw };
    Op op = Op::Draw;
    PlanTarget from = PlanTarget::Render;
    PlanTarget to = PlanTarget::Render;
    std::vector<Rect> rects;
    DrawList draws;
    // Draw: this list instead of `draws` when set (not owned: it must outlive the plan's execution).
    const DrawList* list = nullptr;
};

using FramePlan = std::vector<PlanStep>;

}  // namespace frugal
