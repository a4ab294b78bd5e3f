// Portable flavours of the kernels (Kernels.h), and the run-time choice between them and AVX2.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "software/Kernels.h"

#if !defined(__clang__)  // Clang: -ffp-contract=off (CMakeLists.txt)
#pragma GCC optimize("fp-contract=off")
#endif

namespace frugal::sw {

namespace generic::fused {
#define FRUGAL_SW_FUSED 1
// Simd.h defines what Kernels.inl uses: the order matters.
// clang-format off
#include "software/Simd.h"
#include "software/Kernels.inl"
// clang-format on
#undef FRUGAL_SW_FUSED
}  // namespace generic::fused

namespace generic::unfused {
#define FRUGAL_SW_FUSED 0
// Simd.h defines what Kernels.inl uses: the order matters.
// clang-format off
#include "software/Simd.h"
#include "software/Kernels.inl"
// clang-format on
#undef FRUGAL_SW_FUSED
}  // namespace generic::unfused

namespace generic {
const Kernels kFused = fused::kernelTable("generic-fma");
const Kernels kUnfused = unfused::kernelTable("generic");
}  // namespace generic

const Kernels& selectKernels(bool allowSimd) {
#if defined(__x86_64__)
    if (allowSimd && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return avx2::kKernels;
#endif
    return cpuHasFma() ? generic::kFused : generic::kUnfused;
}

}  // namespace frugal::sw
