// Triangle setup, clipping helpers and binning (see Rasterizer.h for the rules and their sources).
#include "raster/Rasterizer.h"

#include <algorithm>
#include <cassert>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

// Every product and sum here is rounded on its own, as in llvmpipe (Rasterizer.h); GCC would
// otherwise contract a·b + c into an FMA wherever the target has one.
#if !defined(__clang__)  // Clang: -ffp-contract=off (CMakeLists.txt)
#pragma GCC optimize("fp-contract=off")
#endif

namespace frugal::raster {

bool cpuHasFma() {
#if defined(__x86_64__) || defined(__i386__)
    return __builtin_cpu_supports("fma");
#else
    return false;
#endif
}

Viewport makeViewport(int width, int height, DepthFormat format, int samples) {
    Viewport v;
    v.width = width;
    v.height = height;
    v.samples = samples;
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

void setupDepthPlane(const SetupVertex* v0, const SetupVertex* v1, const SetupVertex* v2, Triangle* out, float offset) {
    // lp_state_setup.c init_args + calc_coef4, each operation rounded to float.
    Triangle& t = *out;
    const float x0c = v0->x - offset, y0c = v0->y - offset;
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
    const float offset = pixelOffset(viewport);
    for (int i = 0; i < 3; ++i)
        if (!fixedPosition(v[i]->x, v[i]->y, &X[i], &Y[i], offset)) return false;
    const SetupOrder order = setupEdges(X, Y, cullBack, viewport, out);
    if (order == SetupOrder::Dropped) return false;
    if (order == SetupOrder::Swapped) std::swap(v[0], v[1]);
    setupDepthPlane(v[0], v[1], v[2], out, offset);
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

}  // namespace frugal::raster
