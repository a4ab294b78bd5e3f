// Screen data of a frame for hidden-surface modes that sort instead of (or before) z-buffering
// (paper 003, the adaptive z-buffer): per drawn triangle its window-space extents and its average
// depth, and the depth-sort order. Plans only: computed on the CPU from the same float
// model-view-projection the backends use (projection × view × world[node], glm), no backend here.
//
// The extents, exactly (the paper's x, y and z ranges of a polygon's vertices, made safe for our
// rasterizers):
// - x, y: the inclusive integer pixel box [x0, x1] × [y0, y1] (window coordinates, origin
//   bottom-left, clipped to the target) that contains every pixel the triangle can cover. A pixel is
//   covered only if its centre lies inside the triangle (src/raster/Rasterizer.h, llvmpipe), so
//   inside the box of the projected vertices; one pixel more on each side plus 1e-5 of the
//   coordinate's magnitude absorbs snapping and the float differences of a vertex shader, as in
//   src/reuse/Extents.h. Why pixels and not the paper's vertex coordinates: the paper's test
//   (Fig. 7, lines 20–22: union length < sum of lengths − 1) calls two integer vertex ranges
//   overlapping only when they share at least two integer values, which is right for a fixed-point
//   rasterizer that leaves out a triangle's right and top edge (ranges [0, 5] and [5, 9] then cover
//   no common pixel column). Stated on the pixels a triangle covers, the same rule is "they share
//   one pixel": so our boxes are pixel sets and the test (hsr/Flags.h) is inclusive.
// - z: the closed range [z0, z1] of the vertices' window z (depth range [0, 1], smaller is nearer;
//   D32F's reversed window z is taken as 1 − z so that this holds in both formats),
//   widened by kZMargin on each side and clamped to [0, 1]. Window z is affine over the triangle in
//   window space, so every covered pixel's depth lies between the vertices'; clipping against the
//   near and far planes only adds points on edges, whose z lies between the ends'. The margin covers
//   the float error of the backends' depth plane and the 24-bit rounding, so that two triangles
//   whose ranges are apart never tie or swap in the depth buffer.
// - Triangles crossing the eye plane (a vertex at w ≤ 0, where the near plane's clipping makes the
//   projection unbounded) and triangles with a non-finite vertex are treated conservatively: box
//   = the whole target, z = [0, 1]. Such a triangle overlaps every other one, so a frame that has one
//   is flagged whole (the z-buffer everywhere): always correct, never faster. Clipping such a
//   triangle to the near plane first would give a tight box (left for a later increment).
//
// What is listed: the triangles a z-buffered draw of the list can show, in draw order (draw
// commands in list order, ranges in order, triangles in index-buffer order: the order in which depth
// ties resolve, pipeline/Backend.h). Left out, because they draw nothing in any mode: triangles whose
// three vertices lie outside one clip plane, boxes that miss the target, and back faces of
// single-sided materials that are clearly back-facing (signed window area below −1e-5 of the product
// of two edge lengths, computed in double: a sign the backends' float arithmetic cannot flip).
// Nearly edge-on back faces stay listed: drawn or not, listing them only adds flags.
//
// Average depth: the mean of the three window z, each clamped to [0, 1] (a vertex at w ≤ 0 counts as
// 0, the near plane, where clipping puts it), as the paper sorts (Fig. 7, line 2; its Fig. 3 finds
// the mean the best of min, max and mean).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Scene.h>

#include "pipeline/Backend.h"
#include "pipeline/Plan.h"

namespace frugal::hsr {

// Two 24-bit depth steps on each side of a triangle's z range (window z units, see above).
inline constexpr float kZMargin = 2.0f / 16777215.0f;
// The same for D32F, whose window z (reversed, then taken as 1 − z here so that 0 is near in both
// formats) is a float in [0, 1]: eight of its largest steps, 2⁻²⁴ each below 1, cover the depth
// plane's float error there and below.
inline constexpr float kZMarginF32 = 8.0f / 16777216.0f;

// A triangle's extents: pixels [x0, x1] × [y0, y1], both ends included, and depth [z0, z1], closed.
// Never empty: x0 ≤ x1, y0 ≤ y1, z0 ≤ z1.
struct Extent {
    std::int32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    float z0 = 0.0f, z1 = 0.0f;
    bool operator==(const Extent&) const = default;
};

// Which triangle: an instance of the scene and a triangle of its mesh's index buffer.
struct TriangleRef {
    int instance = -1;
    std::uint32_t triangle = 0;
    bool operator==(const TriangleRef&) const = default;
};

// The listed triangles of a frame, in draw order; the three vectors are parallel.
struct ScreenTriangles {
    std::vector<TriangleRef> refs;
    std::vector<Extent> extents;
    std::vector<float> depth;  // average window z, in [0, 1]
    // 1 when clearly front-facing (signed window area above +1e-5 of the product of two edge
    // lengths, the mirror of the back-face test above): every backend draws it as a front face.
    std::vector<std::uint8_t> front;
    std::size_t size() const { return refs.size(); }
};

// The triangles of `list` as the frame `frame` on a width × height target shows them; `world` holds
// every node's matrix (Scene::worldTransforms). Ranges beyond a mesh's triangles are clipped to it.
ScreenTriangles screenTriangles(const Scene& scene, const FrameParams& frame, const std::vector<glm::mat4>& world,
                                const DrawList& list, int width, int height);

// Indices into `depth`: back to front (largest average depth first), equal depths in index order
// (draw order), so that the order is a function of the input alone. `depth` holds no NaN.
std::vector<std::uint32_t> backToFront(std::span<const float> depth);

}  // namespace frugal::hsr
