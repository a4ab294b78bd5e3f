// Plans: what a frame draws, as data. cull/ and reuse/ produce these without touching GL; either
// backend executes them (SceneRenderer).
#pragma once

#include <vector>

#include "render/Backend.h"

namespace frugal {

// One instance's index ranges. A full draw is one range over the whole mesh.
struct DrawCommand {
    int instance = -1;
    std::vector<IndexRange> ranges;
};

// In draw order: the order is part of the result (depth ties resolve to the first drawn).
using DrawList = std::vector<DrawCommand>;

// Every instance of the scene, whole, in instance order.
DrawList fullDrawList(const Scene& scene);

}  // namespace frugal
