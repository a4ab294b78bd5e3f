#include "software/InterpRaster.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <span>

#if !defined(__clang__)  // Clang: -ffp-contract=off (CMakeLists.txt)
#pragma GCC optimize("fp-contract=off")
#endif

namespace frugal::sw {

namespace {

constexpr int kDepthBits = 24;  // Rasterizer.h: depth is stored as 24-bit unsigned integers

// ⌊a / b⌋ for b ≠ 0.
inline std::int64_t floorDiv(std::int64_t a, std::int64_t b) {
    const std::int64_t q = a / b;
    return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}

// The 24-bit depth raster() stores at (px, py) (Rasterizer.h, 5.), one lane of it: the same
// operations, fused when the kernels fuse, clamped as MAXPS/MINPS clamp (a NaN gives 0), rounded to
// nearest even as CVTPS2DQ rounds.
inline std::uint32_t planeDepth(const Triangle& t, int px, int py, bool fused) {
    return storedDepth(fused ? std::fma(t.dzdy, float(py), std::fma(t.dzdx, float(px), t.z0))
                             : t.dzdy * float(py) + (t.dzdx * float(px) + t.z0),
                       DepthFormat::D24);
}

}  // namespace

bool coveredRun(const Triangle& t, int y, int* left, int* right) {
    std::int64_t lo = t.x0, hi = t.x1;
    for (const Edge& e : t.e) {
        // Inside when k − dx·px + dy·y ≥ 0, i.e. dx·px ≤ c.
        const std::int64_t c = e.k + std::int64_t(e.dy) * y;
        if (e.dx > 0) hi = std::min(hi, floorDiv(c, e.dx));
        else if (e.dx < 0) lo = std::max(lo, -floorDiv(c, -std::int64_t(e.dx)));  // px ≥ ⌈c / dx⌉
        else if (c < 0) return false;
    }
    if (lo > hi) return false;
    *left = int(lo);
    *right = int(hi);
    return true;
}

void rasterInterp(const Triangle& t, TileState& tile, span::Interp mode, bool fused, InterpScratch& scratch) {
    assert(t.depthTest);
    const int y0 = std::max(t.y0, tile.y0), y1 = std::min(t.y1, tile.y1 - 1);
    const std::size_t stride = std::size_t(tile.target.stride);
    std::uint32_t myIndex = kNoWinner;
    for (int y = y0; y <= y1; ++y) {
        int left = 0, right = 0;
        if (!coveredRun(t, y, &left, &right)) continue;
        const int from = std::max(left, tile.x0), to = std::min(right, tile.x1 - 1);  // the tile's part
        if (from > to) continue;

        const std::uint32_t zl = planeDepth(t, left, y, fused), zr = planeDepth(t, right, y, fused);
        span::SpanInput input;
        input.xBegin = left;
        input.xEnd = to + 1;
        input.value = double(zl);
        input.slope = right > left ? (double(zr) - double(zl)) / double(right - left) : 0.0;
        input.width = kDepthBits;
        assert(std::size_t(input.xEnd - input.xBegin) <= scratch.values.size());
        const span::FillResult filled = span::fillSpan(mode, input, std::span<std::uint32_t>(scratch.values));
        ++scratch.stats.spans;
        scratch.stats.pixels += std::uint64_t(to - from + 1);
        if (!filled.ok()) {
            ++scratch.stats.overflow;
            scratch.stats.overflowBits |= filled.overflow;
        }

        std::uint32_t* depthRow = tile.target.depth + std::size_t(y) * stride;
        std::uint32_t* idRow = tile.target.ids + std::size_t(y) * stride;
        std::uint32_t* winnerRow = tile.winner + (y - tile.y0) * kTileSize;
        for (int x = from; x <= to; ++x) {
            const std::uint32_t z = scratch.values[std::size_t(x - left)];
            if (!(depthRow[x] > z)) continue;
            depthRow[x] = z;
            if (myIndex == kNoWinner) {
                myIndex = std::uint32_t(tile.won.size());
                tile.won.push_back(&t);
            }
            winnerRow[x - tile.x0] = myIndex;
            if (t.writesId) idRow[x] = t.id;  // at the depth test, as raster() writes them
        }
    }
}

}  // namespace frugal::sw
