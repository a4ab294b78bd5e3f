// Triangle setup, clipping helpers and binning (see Rasterizer.h for the rules and their sources).
#include "software/Rasterizer.h"

#include <algorithm>
#include <cassert>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

// Every product and sum here is rounded on its own, as in llvmpipe (Rasterizer.h); GCC would
// otherwise contract a·b + c into an FMA wherever the target has one.
#pragma GCC optimize("fp-contract=off")

namespace frugal::sw {

Viewport makeViewport(int width, int height, DepthFormat format) {
    Viewport v;
    v.width = width;
    v.height = height;
    // pipe_viewport_state from glViewport(0, 0, W, H) with depth range [0, 1], in float.
    v.sx = float(width) * 0.5f;
    v.tx = float(width) * 0.5f;
    v.sy = float(height) * 0.5f;
    v.ty = float(height) * 0.5f;
    if (format == DepthFormat::D32F) {  // clip_halfz: scale f − n, offset n
        v.sz = 1.0f;
        v.tz = 0.0f;
        v.halfZ = true;
    }
    return v;
}

unsigned clipMask(const glm::vec4& c, bool halfZ) {
    // Unordered comparisons: "x > w" is !(x <= w), so a NaN sets the bit.
    unsigned mask = 0;
    if (!(c.x <= c.w)) mask |= 1u;
    if (!(c.x + c.w >= 0.0f)) mask |= 2u;
    if (!(c.y <= c.w)) mask |= 4u;
    if (!(c.y + c.w >= 0.0f)) mask |= 8u;
    if (!(halfZ ? c.z >= 0.0f : c.z + c.w >= 0.0f)) mask |= 16u;
    if (!(c.z <= c.w)) mask |= 32u;
    return mask;
}

SetupVertex clippedWindowVertex(const glm::vec4& clip, const Viewport& viewport) {
    SetupVertex v{};
    const float oow = 1.0f / clip.w;
    v.x = clip.x * oow * viewport.sx + viewport.tx;
    v.y = clip.y * oow * viewport.sy + viewport.ty;
    v.z = clip.z * oow * viewport.sz + viewport.tz;
    v.oow = oow;
    return v;
}

namespace detail {

ClipNode interpolate(const ClipNode& out, float t, const ClipNode& in, const Viewport& viewport, VertexPool& pool) {
    ClipNode node;
    for (int i = 0; i < 4; ++i) node.clip[i] = out.clip[i] + t * (in.clip[i] - out.clip[i]);
    SetupVertex* v = pool.add();
    *v = clippedWindowVertex(node.clip, viewport);
    for (int i = 0; i < kAttributes; ++i) v->a[i] = out.vertex->a[i] + t * (in.vertex->a[i] - out.vertex->a[i]);
    node.vertex = v;
    return node;
}

}  // namespace detail

SetupVertex* VertexPool::add() {
    const std::size_t block = used_ / kBlock;
    if (block == blocks_.size()) blocks_.emplace_back(kBlock);
    return &blocks_[block][used_++ % kBlock];
}

namespace {

// Round to nearest even, like CVTPS2DQ in calc_fixed_position (|f| < 2^26 here). CVTSS2SI is
// baseline SSE on x86-64, where nearbyint would be a library call.
inline std::int64_t roundEven(float f) {
#if defined(__x86_64__)
    return _mm_cvtss_si32(_mm_set_ss(f));
#else
    return std::int64_t(std::nearbyint(f));
#endif
}

// Floor and ceiling of a / 256 for any sign (C++20 >> on negative values is arithmetic).
inline std::int64_t floorDiv256(std::int64_t a) { return a >> 8; }
inline std::int64_t ceilDiv256(std::int64_t a) { return -((-a) >> 8); }

}  // namespace

bool fixedPosition(float x, float y, std::int64_t* X, std::int64_t* Y) {
    constexpr float kLimit = 67108864.0f;  // 2^26: see "Where this departs" in Rasterizer.h
    // lp_setup_tri.c calc_fixed_position: (pos - pixel_offset) * FIXED_ONE, then CVTPS2DQ.
    const float fx = (x - 0.5f) * 256.0f;
    const float fy = (y - 0.5f) * 256.0f;
    if (!(std::fabs(fx) < kLimit) || !(std::fabs(fy) < kLimit)) return false;  // also NaN
    *X = roundEven(fx);
    *Y = roundEven(fy);
    return true;
}

SetupOrder setupEdges(std::int64_t X[3], std::int64_t Y[3], bool cullBack, const Viewport& viewport, Triangle* out) {
    const std::int64_t area = (X[0] - X[1]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[0] - Y[1]);
    if (area == 0) return SetupOrder::Dropped;
    const bool front = area < 0;
    if (cullBack && !front) return SetupOrder::Dropped;
    if (front) {
        // lp_setup_tri.c triangle_both/triangle_cw: do_triangle_ccw(v1, v0, v2).
        std::swap(X[0], X[1]);
        std::swap(Y[0], Y[1]);
    }

    // Pixels whose centre sample (256·px, 256·py) lies within the vertices' fixed-point bounds.
    const std::int64_t minX = std::min({X[0], X[1], X[2]}), maxX = std::max({X[0], X[1], X[2]});
    const std::int64_t minY = std::min({Y[0], Y[1], Y[2]}), maxY = std::max({Y[0], Y[1], Y[2]});
    const std::int64_t x0 = std::max<std::int64_t>(ceilDiv256(minX), 0);
    const std::int64_t x1 = std::min<std::int64_t>(floorDiv256(maxX), viewport.width - 1);
    const std::int64_t y0 = std::max<std::int64_t>(ceilDiv256(minY), 0);
    const std::int64_t y1 = std::min<std::int64_t>(floorDiv256(maxY), viewport.height - 1);
    if (x0 > x1 || y0 > y1) return SetupOrder::Dropped;

    Triangle& t = *out;
    for (int i = 0; i < 3; ++i) {
        const int j = i == 2 ? 0 : i + 1;
        const std::int64_t dcdx = Y[i] - Y[j];
        const std::int64_t dcdy = X[i] - X[j];
        std::int64_t c = dcdx * X[i] - dcdy * Y[i];
        if (dcdx < 0 || (dcdx == 0 && dcdy > 0)) c += 1;
        // c − 256·dcdx·px + 256·dcdy·py ≥ 1  ⇔  dcdx·px − dcdy·py ≤ ⌊(c − 1)/256⌋.
        t.e[i].k = floorDiv256(c - 1);
        t.e[i].dx = std::int32_t(dcdx);
        t.e[i].dy = std::int32_t(dcdy);
    }
    t.x0 = std::int32_t(x0);
    t.x1 = std::int32_t(x1);
    t.y0 = std::int32_t(y0);
    t.y1 = std::int32_t(y1);
    t.front = front ? 1u : 0u;
    return front ? SetupOrder::Swapped : SetupOrder::Given;
}

void setupDepthPlane(const SetupVertex* v0, const SetupVertex* v1, const SetupVertex* v2, Triangle* out) {
    // lp_state_setup.c init_args + calc_coef4, each operation rounded to float.
    Triangle& t = *out;
    const float x0c = v0->x - 0.5f, y0c = v0->y - 0.5f;
    const float dx01 = v0->x - v1->x, dy01 = v0->y - v1->y;
    const float dx20 = v2->x - v0->x, dy20 = v2->y - v0->y;
    const float e = dx01 * dy20, f = dy01 * dx20;
    const float ooa = 1.0f / (e - f);
    const float dx20o = dx20 * ooa, dy20o = dy20 * ooa, dx01o = dx01 * ooa, dy01o = dy01 * ooa;
    const float da01 = v0->z - v1->z, da20 = v2->z - v0->z;
    t.dzdx = da01 * dy20o - da20 * dy01o;
    t.dzdy = da20 * dx01o - da01 * dx20o;
    t.z0 = v0->z - (t.dzdx * x0c + t.dzdy * y0c);
}

bool setupTriangle(const SetupVertex* v0, const SetupVertex* v1, const SetupVertex* v2, bool cullBack,
                   const Viewport& viewport, Triangle* out) {
    const SetupVertex* v[3] = {v0, v1, v2};
    std::int64_t X[3], Y[3];
    for (int i = 0; i < 3; ++i)
        if (!fixedPosition(v[i]->x, v[i]->y, &X[i], &Y[i])) return false;
    const SetupOrder order = setupEdges(X, Y, cullBack, viewport, out);
    if (order == SetupOrder::Dropped) return false;
    if (order == SetupOrder::Swapped) std::swap(v[0], v[1]);
    setupDepthPlane(v[0], v[1], v[2], out);
    out->v[0] = v[0];
    out->v[1] = v[1];
    out->v[2] = v[2];
    return true;
}

void Segment::bin(std::uint32_t index, int tilesX) {
    const Triangle& t = triangles[index];
    const int tx0 = t.x0 >> kTileLog2, tx1 = t.x1 >> kTileLog2;
    const int ty0 = t.y0 >> kTileLog2, ty1 = t.y1 >> kTileLog2;
    for (int ty = ty0; ty <= ty1; ++ty)
        for (int tx = tx0; tx <= tx1; ++tx) {
            binTile.push_back(std::uint32_t(ty * tilesX + tx));
            binTriangle.push_back(index);
        }
}

void Segment::close(int tileCount) {
    if (closed) return;
    // Stable counting sort of the bin entries by tile.
    tileStart.assign(std::size_t(tileCount) + 1, 0);
    for (std::uint32_t tile : binTile) ++tileStart[tile + 1];
    for (int i = 0; i < tileCount; ++i) tileStart[i + 1] += tileStart[i];
    sorted.resize(binTile.size());
    std::vector<std::uint32_t> next(tileStart.begin(), tileStart.end() - 1);
    for (std::size_t i = 0; i < binTile.size(); ++i) sorted[next[binTile[i]]++] = binTriangle[i];
    closed = true;
}

}  // namespace frugal::sw
