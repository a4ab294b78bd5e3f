// The occlusion pass's loops in AVX2 (OcclusionKernels.h). Compiled for that target by pragma, the
// build being for baseline x86-64; Occlusion.cpp calls them only when cpuHasAvx2(). Standard headers
// come first, so that nothing they define is compiled for AVX2.
#include <cstddef>
#include <cstdint>

#include "cull/OcclusionKernels.h"

#if defined(__x86_64__)

#include <immintrin.h>

// Every product and sum rounded on its own (Rasterizer.h 1.): GCC would otherwise fuse _mm256_mul_ps
// and _mm256_add_ps into an FMA.
#if defined(__clang__)  // which ignores GCC's pragmas: -ffp-contract=off comes from CMakeLists.txt
#pragma clang attribute push(__attribute__((target("avx2,fma"))), apply_to = function)
#else
#pragma GCC optimize("fp-contract=off")
#pragma GCC target("avx2,fma")
#endif

namespace frugal::occlusion {

void transformAvx2(const float* m, const float* px, const float* py, const float* pz, std::uint32_t count,
                   const raster::Viewport& vp, const WindowArrays& out) {
    __m256 col[4][4];
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) col[c][r] = _mm256_set1_ps(m[4 * c + r]);
    const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f), half = _mm256_set1_ps(0.5f);
    const __m256 sx = _mm256_set1_ps(vp.sx), tx = _mm256_set1_ps(vp.tx), sy = _mm256_set1_ps(vp.sy),
                 ty = _mm256_set1_ps(vp.ty), sz = _mm256_set1_ps(vp.sz), tz = _mm256_set1_ps(vp.tz);
    const __m256 fixedOne = _mm256_set1_ps(256.0f), limit = _mm256_set1_ps(67108864.0f);  // 2^26
    const __m256 absMask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
    const __m256i unfixed = _mm256_set1_epi32(kUnfixed);
    for (std::uint32_t i = 0; i < count; i += 8) {
        const __m256 x = _mm256_loadu_ps(px + i), y = _mm256_loadu_ps(py + i), z = _mm256_loadu_ps(pz + i);
        __m256 c[4];
        for (int r = 0; r < 4; ++r)  // ((m0·x + m1·y) + m2·z) + m3, every step rounded
            c[r] = _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(col[0][r], x), _mm256_mul_ps(col[1][r], y)),
                                               _mm256_mul_ps(col[2][r], z)),
                                 col[3][r]);
        // The clip mask is not 0 (raster::clipMask; unordered: a NaN sets a bit).
        __m256 clipped = _mm256_or_ps(_mm256_cmp_ps(c[0], c[3], _CMP_NLE_UQ),
                                      _mm256_cmp_ps(_mm256_add_ps(c[0], c[3]), zero, _CMP_NGE_UQ));
        clipped = _mm256_or_ps(clipped, _mm256_cmp_ps(c[1], c[3], _CMP_NLE_UQ));
        clipped = _mm256_or_ps(clipped, _mm256_cmp_ps(_mm256_add_ps(c[1], c[3]), zero, _CMP_NGE_UQ));
        clipped = _mm256_or_ps(clipped, vp.halfZ ? _mm256_cmp_ps(c[2], zero, _CMP_NGE_UQ)
                                                 : _mm256_cmp_ps(_mm256_add_ps(c[2], c[3]), zero, _CMP_NGE_UQ));
        clipped = _mm256_or_ps(clipped, _mm256_cmp_ps(c[2], c[3], _CMP_NLE_UQ));
        // Viewport: oow = 1 / w, then fma(x·oow, scale, translate).
        const __m256 oow = _mm256_div_ps(one, c[3]);
        const __m256 wx = _mm256_fmadd_ps(_mm256_mul_ps(c[0], oow), sx, tx);
        const __m256 wy = _mm256_fmadd_ps(_mm256_mul_ps(c[1], oow), sy, ty);
        const __m256 wz = _mm256_fmadd_ps(_mm256_mul_ps(c[2], oow), sz, tz);
        _mm256_storeu_ps(out.x + i, wx);
        _mm256_storeu_ps(out.y + i, wy);
        _mm256_storeu_ps(out.z + i, wz);
        // raster::fixedPosition: round_even((x − 0.5)·256), representable when |…| < 2^26 (false for NaN).
        const __m256 fx = _mm256_mul_ps(_mm256_sub_ps(wx, half), fixedOne);
        const __m256 fy = _mm256_mul_ps(_mm256_sub_ps(wy, half), fixedOne);
        const __m256 fits = _mm256_and_ps(_mm256_cmp_ps(_mm256_and_ps(fx, absMask), limit, _CMP_LT_OQ),
                                          _mm256_cmp_ps(_mm256_and_ps(fy, absMask), limit, _CMP_LT_OQ));
        const __m256i usable = _mm256_castps_si256(_mm256_andnot_ps(clipped, fits));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.fx + i),
                            _mm256_blendv_epi8(unfixed, _mm256_cvtps_epi32(fx), usable));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.fy + i),
                            _mm256_blendv_epi8(unfixed, _mm256_cvtps_epi32(fy), usable));
    }
}

namespace {
#include "cull/OcclusionVerdicts.inl"

// The corners' attributes gathered from the window arrays.
struct Gather {
    const WindowArrays& w;
    __m256i fx(__m256i i) const { return _mm256_i32gather_epi32(w.fx, i, 4); }
    __m256i fy(__m256i i) const { return _mm256_i32gather_epi32(w.fy, i, 4); }
    __m256 x(__m256i i) const { return _mm256_i32gather_ps(w.x, i, 4); }
    __m256 y(__m256i i) const { return _mm256_i32gather_ps(w.y, i, 4); }
    __m256 z(__m256i i) const { return _mm256_i32gather_ps(w.z, i, 4); }
};
}  // namespace

void verdictsAvx2(const WindowArrays& w, const std::uint16_t* c0, const std::uint16_t* c1, const std::uint16_t* c2,
                  std::uint32_t count, bool cullBack, const raster::Viewport& vp, int rowLo, int rowHi, std::uint8_t* verdict,
                  const SmallTriangles& out) {
    verdictsBody(Gather{w}, c0, c1, c2, count, cullBack, vp, rowLo, rowHi, verdict, out);
}

bool spanAvx2(float* row, int xa, int xb, float zRow, float dzdx, float slack, float up, bool halfZ, bool occludes) {
    const __m256 vz = _mm256_set1_ps(zRow), vdz = _mm256_set1_ps(dzdx), vs = _mm256_set1_ps(slack), vup = _mm256_set1_ps(up);
    const __m256 zero = _mm256_setzero_ps();
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    // Far-ness bounds at pixels px … px + 7: z = zRow + dzdx·px, rounded twice.
    const auto bounds = [&](int px, __m256& lo, __m256& hi) {
        const __m256 z = _mm256_add_ps(vz, _mm256_mul_ps(vdz, _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(px), lane))));
        depthBounds(z, vs, vup, halfZ, lo, hi);
    };
    // Seen where !(stored < lo); stored lowered to hi where hi < stored (std::min(stored, hi) is
    // _mm256_min_ps(hi, stored)).
    __m256 seen = zero;
    int px = xa;
    for (; px + 7 <= xb; px += 8) {
        __m256 lo, hi;
        bounds(px, lo, hi);
        const __m256 stored = _mm256_loadu_ps(row + px);
        seen = _mm256_or_ps(seen, _mm256_cmp_ps(stored, lo, _CMP_NLT_UQ));
        if (occludes) _mm256_storeu_ps(row + px, _mm256_min_ps(hi, stored));
    }
    if (px <= xb) {  // the last 1 to 7 pixels, with loads and stores masked to them
        const __m256i mask = _mm256_cmpgt_epi32(_mm256_set1_epi32(xb - px + 1), lane);
        __m256 lo, hi;
        bounds(px, lo, hi);
        const __m256 stored = _mm256_maskload_ps(row + px, mask);
        seen = _mm256_or_ps(seen, _mm256_and_ps(_mm256_cmp_ps(stored, lo, _CMP_NLT_UQ), _mm256_castsi256_ps(mask)));
        if (occludes) _mm256_maskstore_ps(row + px, mask, _mm256_min_ps(hi, stored));
    }
    return _mm256_movemask_ps(seen) != 0;
}

bool narrowAvx2(float* depth, int width, int x0, int x1, int y0, int y1, const std::int32_t e[3],
                const std::int32_t dx[3], const std::int32_t dy[3], float z0, float dzdx, float dzdy, float slack,
                float up, bool halfZ, bool occludes, std::uint32_t* columns) {
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    // The edges at pixels x0 … x0 + 7 of row y0 (k − dx·px + dy·py), a row up each step; every value
    // lies between the rectangle's corners', which the caller made sure fit.
    __m256i edge[3], step[3];
    for (int i = 0; i < 3; ++i) {
        edge[i] = _mm256_sub_epi32(_mm256_set1_epi32(e[i]), _mm256_mullo_epi32(_mm256_set1_epi32(dx[i]), lane));
        step[i] = _mm256_set1_epi32(dy[i]);
    }
    const __m256i inBox = _mm256_cmpgt_epi32(_mm256_set1_epi32(x1 - x0 + 1), lane);
    const bool inRow = x0 + 8 <= width;
    // spanAvx2's bounds: z = zRow + dzdx·px, the product the same on every row.
    const __m256 slope = _mm256_mul_ps(_mm256_set1_ps(dzdx), _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(x0), lane)));
    const __m256 vs = _mm256_set1_ps(slack), vup = _mm256_set1_ps(up);
    // What was seen, and the columns covered, as bits in general registers: sixteen vector registers
    // hold the edges, their steps and the constants, and two more accumulators spilled to the stack
    // on every row.
    int seen = 0, any = 0;
    for (int py = y0; py <= y1; ++py) {
        // Covered: every edge ≥ 0, i.e. the sign bit of their OR clear.
        const __m256i cover =
            _mm256_andnot_si256(_mm256_srai_epi32(_mm256_or_si256(_mm256_or_si256(edge[0], edge[1]), edge[2]), 31), inBox);
        for (int i = 0; i < 3; ++i) edge[i] = _mm256_add_epi32(edge[i], step[i]);
        // A row with no pixel covered goes through the same steps (it writes back what it read): a
        // branch on it is one the CPU mispredicts, at the corners of the triangle.
        const int coverBits = _mm256_movemask_ps(_mm256_castsi256_ps(cover));
        any |= coverBits;
        const float zRow = z0 + dzdy * float(py);
        __m256 lo, hi;
        depthBounds(_mm256_add_ps(_mm256_set1_ps(zRow), slope), vs, vup, halfZ, lo, hi);
        float* row = depth + std::ptrdiff_t(py) * width + x0;
        const __m256 mask = _mm256_castsi256_ps(cover);
        if (inRow) {
            // The 8 columns are within the row: a plain load, and a store of the same values where
            // the triangle is not (the row is this thread's alone). Masked moves cost a few times
            // as much on some CPUs (AMD's Zen).
            const __m256 stored = _mm256_loadu_ps(row);
            seen |= _mm256_movemask_ps(_mm256_cmp_ps(stored, lo, _CMP_NLT_UQ)) & coverBits;
            if (occludes) _mm256_storeu_ps(row, _mm256_blendv_ps(stored, _mm256_min_ps(hi, stored), mask));
        } else {
            const __m256 stored = _mm256_maskload_ps(row, cover);
            seen |= _mm256_movemask_ps(_mm256_cmp_ps(stored, lo, _CMP_NLT_UQ)) & coverBits;
            if (occludes) _mm256_maskstore_ps(row, cover, _mm256_min_ps(hi, stored));
        }
    }
    *columns = std::uint32_t(any);
    return seen != 0;
}

bool cpuHasAvx2() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }

}  // namespace frugal::occlusion

#if defined(__clang__)
#pragma clang attribute pop
#endif

#else

namespace frugal::occlusion {
// Not an x86-64 build: the scalar loops run.
bool cpuHasAvx2() { return false; }
void transformAvx2(const float*, const float*, const float*, const float*, std::uint32_t, const raster::Viewport&,
                   const WindowArrays&) {}
void verdictsAvx2(const WindowArrays&, const std::uint16_t*, const std::uint16_t*, const std::uint16_t*, std::uint32_t,
                  bool, const raster::Viewport&, int, int, std::uint8_t*, const SmallTriangles&) {}
bool spanAvx2(float*, int, int, float, float, float, float, bool, bool) { return true; }
bool narrowAvx2(float*, int, int, int, int, int, const std::int32_t*, const std::int32_t*, const std::int32_t*, float,
                float, float, float, float, bool, bool, std::uint32_t* columns) {
    *columns = 0xff;
    return true;
}
}  // namespace frugal::occlusion

#endif
