// The AVX2 + FMA flavour of the kernels (Kernels.h). Compiled for that target by pragma, because the
// build compiles for baseline x86-64; selectKernels() only hands it out when the CPU has both.
// Standard headers come first so that nothing they define is compiled for AVX2 (an inline function
// emitted here must never be the copy the rest of the program links to).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "software/Kernels.h"

#if defined(__x86_64__)

#include <immintrin.h>

#if defined(__clang__)  // which ignores GCC's pragmas: -ffp-contract=off comes from CMakeLists.txt
#pragma clang attribute push(__attribute__((target("avx2,fma"))), apply_to = function)
#else
#pragma GCC optimize("fp-contract=off")
#pragma GCC target("avx2,fma")
#endif

namespace frugal::sw::avx2 {
#define FRUGAL_SW_SIMD_AVX2 1
// Simd.h defines what Kernels.inl uses: the order matters.
// clang-format off
#include "software/Simd.h"
#include "software/Kernels.inl"
// clang-format on
#undef FRUGAL_SW_SIMD_AVX2

const Kernels kKernels = kernelTable("avx2");
}  // namespace frugal::sw::avx2

#if defined(__clang__)
#pragma clang attribute pop
#endif

#else

namespace frugal::sw::avx2 {
// Not an x86-64 build: never selected; the portable kernels stand in.
const Kernels kKernels = generic::kUnfused;
}  // namespace frugal::sw::avx2

#endif
