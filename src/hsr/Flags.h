// The adaptive z-buffer's overlap flags (paper 003, Fig. 7, lines 6–27): a triangle is flagged when
// its x, y and z extents (hsr/Order.h) all overlap those of at least one other triangle. Unflagged
// triangles cannot change order with any other one, so the depth sort draws them right without a
// depth test; flagged ones are z-buffered among themselves.
//
// Overlap, exactly: pixels inclusive (boxes [x0, x1] and [x0', x1'] overlap when x0 ≤ x1' and
// x0' ≤ x1, likewise y: they share a pixel), depth closed (z0 ≤ z1' and z0' ≤ z1: touching counts).
// Order.h says why this is the paper's "share two integer values" test restated on pixels.
//
// Two implementations that return the same flags (one byte a triangle, 0 or 1, in input order):
// - flagOverlapsAllPairs: the paper's, every pair once, O(n²). The reference for the other.
// - flagOverlaps: a uniform screen grid with an x sweep inside each cell, O(n log n + k).
//   Why a grid and not one global x sweep: on a frame, a triangle's x range meets those of a whole
//   vertical strip of the screen (with 100k small triangles on 1920×1080, hundreds at a time), while
//   its box meets a few; the grid confines the candidates to a cell, and sorting the cell by x0
//   (one global sort, then a stable bucketing) stops each scan at the first candidate whose x0 lies
//   right of the triangle's x1. Any two boxes that share a pixel share the cell holding the pixel
//   (max x0, max y0), so no pair is missed; a pair that shares several cells is tested in each,
//   which only repeats a result. The cell side is a power of two from the mean box side, doubled
//   until the grid has at most 2n cells and at most 8n (cell, triangle) entries, so time and
//   memory stay O(n) besides the sort and the tests even for whole-screen boxes.
//   k = the pairs tested: pairs in a common cell whose x ranges overlap, once per common cell. It is
//   at least the number of overlapping box pairs and, when boxes are about the cell's size, a small
//   multiple of it; boxes far larger than the mean (a near-plane triangle's whole screen) put many
//   triangles in their cells. A pair whose triangles are both flagged already is skipped untested.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "hsr/Order.h"

namespace frugal::hsr {

inline bool overlaps(const Extent& a, const Extent& b) {
    return a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1 && a.z0 <= b.z1 && b.z0 <= a.z1;
}

// Extents must be non-empty (x0 ≤ x1, y0 ≤ y1, z0 ≤ z1) with no NaN z. `groups`, when not empty,
// holds one number per extent: two extents of one group (a number ≥ 0) are never flagged against
// each other (polygons that cannot share a pixel, hsr/Plan.h's adaptive-convex); −1 is no group.
std::vector<std::uint8_t> flagOverlapsAllPairs(std::span<const Extent> extents, std::span<const std::int32_t> groups = {});
std::vector<std::uint8_t> flagOverlaps(std::span<const Extent> extents, std::span<const std::int32_t> groups = {});

}  // namespace frugal::hsr
