// The occlusion pass's quick triangle test with AVX-512 lookups (OcclusionKernels.h
// verdictsAvx512): the operations of the AVX2 kernel, eight triangles at a time, but each corner's
// attributes taken from the cluster's at most 64 vertices by two permutes of 32 and a blend, where
// the AVX2 kernel gathers them (fifteen gathers per eight triangles: a third of the pass's time on
// the AMD EPYC of docs/occlusion.md). Compiled for that target by pragma, the build being for
// baseline x86-64; Occlusion.cpp calls it only when cpuHasAvx512(). Standard headers come first.
#include <cstddef>
#include <cstdint>

#include "cull/OcclusionKernels.h"

#if defined(__x86_64__)

#include <immintrin.h>

// Every product and sum rounded on its own, as in OcclusionAvx2.cpp.
#if defined(__clang__)  // which ignores GCC's pragmas: -ffp-contract=off comes from CMakeLists.txt
#pragma clang attribute push(__attribute__((target("avx2,fma,avx512f,avx512vl"))), apply_to = function)
#else
#pragma GCC optimize("fp-contract=off")
#pragma GCC target("avx2,fma,avx512f,avx512vl")
#endif
// GCC 12's own casts between 256 and 512 bits read a deliberately undefined register and warn about
// it where they are inlined (GCC bug 105593, fixed in GCC 13).
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

namespace frugal::occlusion {

namespace {
#include "cull/OcclusionVerdicts.inl"

// Entry i (< 64) of the 64 at `t`, for eight indices: the two halves of 32 permuted, then the half
// bit 5 names. Only the low eight lanes of each 16 are used. The permutes move bits, so floats are
// looked up as their bits.
inline __m256i lookup(const std::int32_t* t, __m256i index) {
    const __m512i i = _mm512_zextsi256_si512(index);
    const __m512i low = _mm512_permutex2var_epi32(_mm512_loadu_si512(t), i, _mm512_loadu_si512(t + 16));
    const __m512i high = _mm512_permutex2var_epi32(_mm512_loadu_si512(t + 32), i, _mm512_loadu_si512(t + 48));
    return _mm512_castsi512_si256(_mm512_mask_blend_epi32(_mm512_test_epi32_mask(i, _mm512_set1_epi32(32)), low, high));
}
inline __m256 lookup(const float* t, __m256i index) {
    return _mm256_castsi256_ps(lookup(reinterpret_cast<const std::int32_t*>(t), index));
}

// The corners' attributes looked up in the window arrays' first 64 entries.
struct Permute {
    const WindowArrays& w;
    __m256i fx(__m256i i) const { return lookup(w.fx, i); }
    __m256i fy(__m256i i) const { return lookup(w.fy, i); }
    __m256 x(__m256i i) const { return lookup(w.x, i); }
    __m256 y(__m256i i) const { return lookup(w.y, i); }
    __m256 z(__m256i i) const { return lookup(w.z, i); }
};
}  // namespace

void verdictsAvx512(const WindowArrays& w, const std::uint16_t* c0, const std::uint16_t* c1, const std::uint16_t* c2,
                    std::uint32_t count, bool cullBack, const raster::Viewport& vp, int rowLo, int rowHi,
                    std::uint8_t* verdict, const SmallTriangles& out) {
    verdictsBody(Permute{w}, c0, c1, c2, count, cullBack, vp, rowLo, rowHi, verdict, out);
}

bool cpuHasAvx512() {
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("avx512f") &&
           __builtin_cpu_supports("avx512vl");
}

}  // namespace frugal::occlusion

#if defined(__clang__)
#pragma clang attribute pop
#endif

#else

namespace frugal::occlusion {
// Not an x86-64 build: the scalar loops run.
bool cpuHasAvx512() { return false; }
void verdictsAvx512(const WindowArrays&, const std::uint16_t*, const std::uint16_t*, const std::uint16_t*,
                    std::uint32_t, bool, const raster::Viewport&, int, int, std::uint8_t*, const SmallTriangles&) {}
}  // namespace frugal::occlusion

#endif
