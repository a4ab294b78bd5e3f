// The occlusion pass's per-vertex and per-triangle loops, eight at a time in AVX2
// (OcclusionAvx2.cpp), for CPUs with AVX2 and FMA. Occlusion.cpp holds the scalar code they equal
// bit for bit and decision for decision; OcclusionTest checks the two give the same plan.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "raster/Rasterizer.h"

namespace frugal::occlusion {

// A fixed-point coordinate that setup cannot use: the vertex is clipped by the draw (its clip mask
// is not 0), or its window position is not representable (raster::fixedPosition is false). A triangle
// with such a corner is kept and hides nothing. Real coordinates are within ±2^26.
inline constexpr std::int32_t kUnfixed = std::numeric_limits<std::int32_t>::min();

// A cluster's vertices as the pass reads them, structure of arrays: window position, and setup's
// fixed-point position (Rasterizer.h 3.) or kUnfixed.
struct WindowArrays {
    float *x, *y, *z;
    std::int32_t *fx, *fy;
};

// What the quick test says of a triangle.
enum Verdict : std::uint8_t {
    kDrop = 0,  // owns no pixel centre in the rows looked at (or is degenerate, or a culled back face)
    kTest = 1,  // may own one: the full test decides (Occlusion.cpp triangleMaySeen)
    kKeep = 2,  // a corner is kUnfixed, or its depth plane is too steep to bound: kept, hides nothing
    kSmall = 3,  // owns the pixel centres in SmallTriangles::covered, with the depth bounds given there
    kMedium = 4,  // at most 8 pixel centres wide: rasterized by narrowAvx2 from SmallTriangles' edges and plane
};

// What the quick test gives of a kSmall triangle t (one of at most 2 × 2 pixel centres), structure
// of arrays: its first pixel (x0, y0), the pixels it covers (bit a + 2b: pixel (x0 + a, y0 + b)),
// whether it occludes (Occlusion.cpp: not a sliver the draw module may drop), and at each covered
// pixel k = a + 2b the bounds lo[k·stride + t] ≤ the far-ness the GL draw writes ≤ hi[k·stride + t]
// (depthBounds).
// A kMedium triangle t (within kQuickExtent, more than 2 × 2 and at most 8 pixel centres wide, a
// depth plane not too steep) gets instead its pixel bounds x0 … x1, y0 … y1 (setup's, on the rows
// looked at), whether it occludes, its three edges at pixel (x0, y0) and their steps in
// narrowAvx2's form (edge[k·stride + t], edge[(3 + k)·stride + t] = dx, edge[(6 + k)·stride + t] =
// dy for edge k), and its plane: plane[t] = z0, plane[stride + t] = dzdx, plane[2·stride + t] = dzdy,
// plane[3·stride + t] = depthSlack.
struct SmallTriangles {
    std::int32_t *x0, *y0;
    std::uint8_t *covered, *occludes;
    float *lo, *hi;
    std::uint32_t stride;
    std::int32_t *x1 = nullptr, *y1 = nullptr, *edge = nullptr;
    float* plane = nullptr;
};

// The rounding bound of the depth plane z0 + dzdx·px + dzdy·py on a target of `width` × `height`
// pixels: both llvmpipe's z (fma(dzdy, py, fma(dzdx, px, z0))) and the pass's ((z0 + dzdy·py) +
// dzdx·px, rounded as it goes) are within 3 units of roundoff of the sizes of the terms from the
// exact plane, so 8 units of them bound the distance between the two; 2 more units and the
// 1 + 10^-6 cover the rounding of this sum itself. Not finite, or 1 or more: the plane says nothing.
inline float depthSlack(float z0, float dzdx, float dzdy, float width, float height) {
    constexpr float kUnit = 1.0f / 16777216.0f;  // 2^-24
    const float size = (std::fabs(z0) + std::fabs(dzdx) * width) + std::fabs(dzdy) * height;
    return ((8.0f * kUnit) * size + 2.0f * kUnit) * (1.0f + 1e-6f);
}

// Triangles whose fixed-point extent is below this (in 1/256 pixel) in x and in y are decided in
// 32-bit arithmetic when they span at most 2 × 2 pixel centres (kSmall), or set up for narrowAvx2
// when they span at most 8 columns (kMedium, when the caller asks for it); the others get kTest.
inline constexpr std::int32_t kQuickExtent = 1 << 12;

// ⌊a / b⌋ for b > 0.
inline std::int64_t floorDiv(std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Where one edge of a triangle (raster::Edge: a pixel is inside when k − dx·px + dy·py ≥ 0) bounds the
// covered pixels of successive rows, with no division a row: inside is dx·px ≤ r = k + dy·py, so
// px ≤ ⌊r / dx⌋ for dx > 0, px ≥ −⌊r / −dx⌋ for dx < 0, and every pixel or none (r ≥ 0) for
// dx = 0. The quotient is stepped exactly from row to row: r grows by dy, the quotient by
// ⌊dy / d⌋ and the remainder by the rest, carrying one when it reaches d.
struct EdgeRows {
    std::int64_t r = 0, dy = 0;       // k + dy·py at the current row, and its step
    std::int64_t d = 0, q = 0, rem = 0, dq = 0, dr = 0;  // |dx|; ⌊r / d⌋ = q, r − q·d = rem; the steps
    int sign = 0;                     // +1: px ≤ q; −1: px ≥ −q; 0: dx = 0

    EdgeRows(const raster::Edge& e, std::int64_t py)
        : r(e.k + std::int64_t(e.dy) * py), dy(e.dy), sign(e.dx > 0 ? 1 : e.dx < 0 ? -1 : 0) {
        if (sign == 0) return;
        d = e.dx > 0 ? std::int64_t(e.dx) : -std::int64_t(e.dx);
        q = floorDiv(r, d), rem = r - q * d;
        dq = floorDiv(dy, d), dr = dy - dq * d;
    }
    // The row's covered pixels within [xa, xb] (xa > xb: none).
    void bound(std::int64_t& xa, std::int64_t& xb) const {
        if (sign > 0)
            xb = xb < q ? xb : q;
        else if (sign < 0)
            xa = xa > -q ? xa : -q;
        else if (r < 0)
            xb = xa - 1;
    }
    void nextRow() {
        r += dy;
        if (sign == 0) return;
        q += dq, rem += dr;
        if (rem >= d) ++q, rem -= d;
    }
};

// Whether the CPU runs the AVX2 kernels below (AVX2 and FMA: the viewport is then fused, as
// llvmpipe fuses it on such a CPU).
bool cpuHasAvx2();

// The software backend's vertex stage for positions only (Rasterizer.h 1. and 3.), vertices
// [0, count) rounded up to a multiple of 8: `px`, `py`, `pz` and every array of `out` must hold
// that many. `m` is column-major.
void transformAvx2(const float* m, const float* px, const float* py, const float* pz, std::uint32_t count,
                   const raster::Viewport& viewport, const WindowArrays& out);

// The verdict of triangles [0, count) (rounded up to a multiple of 8; `c0`, `c1`, `c2` hold their
// corners' indices into `window`, every one valid) on pixel rows [rowLo, rowHi] of `viewport`, and
// what `small` needs of the kSmall ones (its arrays hold `count` rounded up).
void verdictsAvx2(const WindowArrays& window, const std::uint16_t* c0, const std::uint16_t* c1, const std::uint16_t* c2,
                  std::uint32_t count, bool cullBack, const raster::Viewport& viewport, int rowLo, int rowHi,
                  std::uint8_t* verdict, const SmallTriangles& small);

// verdictsAvx2's verdicts and outputs, bit for bit, with each corner's attributes looked up by
// AVX-512 permutes instead of gathered: every index in `c0`, `c1`, `c2` is below kLookupVertices, and
// every array of `window` holds at least kLookupVertices values (those past the cluster's vertices
// are read and never used). Called only when cpuHasAvx512().
inline constexpr std::uint32_t kLookupVertices = 64;
bool cpuHasAvx512();
void verdictsAvx512(const WindowArrays& window, const std::uint16_t* c0, const std::uint16_t* c1,
                    const std::uint16_t* c2, std::uint32_t count, bool cullBack, const raster::Viewport& viewport,
                    int rowLo, int rowHi, std::uint8_t* verdict, const SmallTriangles& small);

// One row of a triangle's covered pixels [xa, xb] (xa ≤ xb) against the buffer `row` (far-ness;
// Occlusion.cpp triangleMaySeen): whether some pixel may be seen, and, when `occludes`, each pixel
// lowered to the triangle's upper bound there. zRow + dzdx·px is the plane, `slack` its rounding
// bound, `up` the 24-bit step. Eight pixels at a time; the last few with masked loads and stores,
// which touch nothing past xb.
bool spanAvx2(float* row, int xa, int xb, float zRow, float dzdx, float slack, float up, bool halfZ, bool occludes);

// A triangle at most eight pixels wide (x1 − x0 < 8) on rows [y0, y1] of the buffer `depth` (rows of
// `width`; Occlusion.cpp triangleMaySeen): pixel (px, py) of the rectangle is covered when the three
// edges e[i] − dx[i]·(px − x0) + dy[i]·(py − y0) are ≥ 0 (raster::Edge at (x0, y0)); every such value,
// at the corners of columns x0 … x0 + 7 and rows y0 … y1 (and so between them), lies within ±2^30.
// Each covered row is spanAvx2 of its covered pixels, the plane at row py being z0 + dzdy·py:
// whether some pixel may be seen, and, when `occludes`, each lowered. `columns`: bit i when some row
// covers column x0 + i. Nothing outside the covered pixels changes; columns x0 … x0 + 7 that lie
// within the row are read and written back (the caller's thread must own the rows), those past its
// end are not touched.
bool narrowAvx2(float* depth, int width, int x0, int x1, int y0, int y1, const std::int32_t e[3],
                const std::int32_t dx[3], const std::int32_t dy[3], float z0, float dzdx, float dzdy, float slack,
                float up, bool halfZ, bool occludes, std::uint32_t* columns);
}  // namespace frugal::occlusion
