// Visible sets measured from renders, for culling-accuracy reports (paper 002's terms):
//   TOS — every triangle of every instance; PVS — what a culling method submitted (a DrawList);
//   RVS — the triangles that own at least one pixel of the full render (from its id image), and,
//         where surfaces are blended, of the render without them (what is seen through them:
//         renderer/Oracle.h).
//   misses = |RVS \ PVS| (dropped yet visible), waste = |PVS \ RVS| (submitted yet hidden).
// A triangle is named by (instance, t), t its position in the mesh's index buffer as uploaded (after
// any reordering), so sets built from draw lists and from id images compare directly. A mesh of
// segments or points (Mesh::topology) counts its primitives the same way: "triangle" here means a
// primitive, and the counts are of primitives.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <frugal/Image.h>
#include <frugal/Result.h>
#include <frugal/Scene.h>

#include "pipeline/Plan.h"

namespace frugal {

struct TriangleSet {
    // perInstance[i][t] != 0: triangle t of instance i's mesh is in the set. One entry per triangle.
    std::vector<std::vector<std::uint8_t>> perInstance;
    std::size_t count = 0;  // members over all instances
};

// The empty set shaped like `scene` (every instance, every triangle, none a member).
TriangleSet emptySet(const Scene& scene);

// The triangles `list` draws (ranges are clamped to the mesh as backends do).
TriangleSet drawnSet(const Scene& scene, const DrawList& list);

// The triangles whose id appears in `buffers.ids` (a frame drawn with ids; 0 = background). Each id
// is mapped back through Instance::firstId and Mesh::triangleSource.
// Error: "id N at pixel (x, y) belongs to no triangle of the scene" (a frame of another scene, or
// ids not written), or "the frame has no id image".
Result<TriangleSet> visibleSet(const Scene& scene, const Buffers& buffers);

struct SetCounts {
    std::size_t tos = 0, pvs = 0, rvs = 0;
    std::size_t misses = 0;  // |RVS \ PVS|
    std::size_t waste = 0;   // |PVS \ RVS|
};

// Both sets must be shaped like `scene`.
SetCounts compareSets(const Scene& scene, const TriangleSet& pvs, const TriangleSet& rvs);

// The oracle's scene: a copy of `scene` in which instance i draws a mesh of its own holding exactly
// its triangles in `set`, in their index-buffer order (same vertices, same materials, same ids via
// triangleSource and firstId). Drawn whole (fullDrawList), it is the lower bound of the draw time of
// the view `set` was measured in, and its image equals the full render's.
Scene oracleScene(const Scene& scene, const TriangleSet& set);

}  // namespace frugal
