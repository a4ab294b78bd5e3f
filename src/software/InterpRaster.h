// The slow path of the software rasterizer for SoftwareOptions::interp = Span or Dda (see
// software/SoftwareBackend.h): coverage as Kernels.h raster() gives it, depth from paper 001's span
// interpolator (span/Interp.h) instead of from the plane at every pixel. Exact never comes
// here: Pipeline::flush calls the kernels for it, so the default path is neither changed nor slowed.
//
// Per row of a triangle within a tile:
//  1. The covered run [L, R] of the whole row (not just the tile's part): the columns of the
//     triangle's bounds where all three edge functions are >= 0 (Rasterizer.h, 3.), solved per edge
//     in 64-bit integers, so the tile's part of it is exactly the pixels raster() would cover.
//  2. Its ends from the depth plane as raster() computes them (Rasterizer.h, 5.: fused or not as
//     the kernels are, clamped, rounded to 24 bits): z(L), z(R).
//  3. span::fillSpan over columns L .. (the tile's last covered column), from z(L) with slope
//     (z(R) − z(L)) / (R − L), width 24. The fill starts at L in every tile the run crosses because
//     a DDA's value at a column depends on every step before it, and the engine model anchors its
//     line at L: a tile's pixels get the values the whole run would give them.
//  4. The depth test (GL_LESS) and write with those values, then winner and ids as raster() does.
// Triangles without the depth test (DepthMode::Off) have no depth to interpolate and go through the
// kernels' raster().
#pragma once

#include <cstdint>
#include <vector>

#include "software/Kernels.h"
#include "software/SoftwareBackend.h"
#include "span/Interp.h"

namespace frugal::sw {

// One worker's output buffer and counters (no sharing between threads).
struct InterpScratch {
    std::vector<std::uint32_t> values;  // at least the target's width (a run is at most one row)
    InterpCounters stats;
};

// The covered columns of row `y` of `t`: [*left, *right] inside the triangle's bounds; false when none.
bool coveredRun(const Triangle& t, int y, int* left, int* right);

// Coverage and depth test of one triangle within the tile with span-interpolated depth (above).
// The backend passes Span or Dda; Exact gives the line through the run's two ends evaluated
// exactly, fillSpan's reference (tests measure the engine against it: the exact path's own float
// plane differs from that line by up to a further LSB). `fused`: the kernels' depth plane uses FMA
// (Pipeline::fusedViewport()).
void rasterInterp(const Triangle& t, TileState& tile, span::Interp mode, bool fused, InterpScratch& scratch);

}  // namespace frugal::sw
