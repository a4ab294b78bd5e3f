// Eight-lane SIMD types for the software kernels (src/software/Kernels.inl), in two flavours with one
// interface, so that the rasterizer and shading kernels are written once:
//
// - FRUGAL_SW_SIMD_AVX2: AVX2 + FMA intrinsics. Only included from KernelsAvx2.cpp, which is compiled
//   for that target by `#pragma GCC target` and chosen at run time when the CPU has both.
// - otherwise: plain arrays of eight lanes and loops (KernelsGeneric.cpp), for any x86-64 or other
//   CPU. `FRUGAL_SW_FUSED` (0 or 1) says whether `fma` fuses (std::fma) or rounds twice.
//
// Arithmetic is IEEE binary32 in round-to-nearest-even, lane by lane, with no contraction of a·b + c
// into an FMA unless `fma` is called: every software .cpp says `#pragma GCC optimize("fp-contract=off")`,
// because GCC contracts by default in C++ whenever FMA instructions are available, and llvmpipe's
// results depend on which operations are fused and which are not (src/raster/Rasterizer.h).
//
// Integer lanes are int32 with wrap-around; comparisons give all-ones/all-zero lane masks.
//
// Included once per kernel flavour, inside that flavour's namespace (no include guard, no includes:
// the including .cpp includes <cmath>, <cstdint>, <cstring> and, for AVX2, <immintrin.h> first).

// One line per operation reads better here than clang-format's expansion.
// clang-format off
namespace simd {

inline constexpr int kLanes = 8;

#if defined(FRUGAL_SW_SIMD_AVX2)

struct F8 {
    __m256 v;
};
struct I8 {
    __m256i v;
};

inline F8 splat(float a) { return {_mm256_set1_ps(a)}; }
inline I8 splati(std::int32_t a) { return {_mm256_set1_epi32(a)}; }
inline F8 loadf(const float* p) { return {_mm256_loadu_ps(p)}; }
inline void storef(float* p, F8 a) { _mm256_storeu_ps(p, a.v); }
inline I8 loadi(const void* p) { return {_mm256_loadu_si256(static_cast<const __m256i*>(p))}; }
inline void storei(void* p, I8 a) { _mm256_storeu_si256(static_cast<__m256i*>(p), a.v); }
// Lanes 0..7 = base + 0..7.
inline I8 ramp(std::int32_t base) { return {_mm256_add_epi32(_mm256_set1_epi32(base), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7))}; }

inline F8 operator+(F8 a, F8 b) { return {_mm256_add_ps(a.v, b.v)}; }
inline F8 operator-(F8 a, F8 b) { return {_mm256_sub_ps(a.v, b.v)}; }
inline F8 operator*(F8 a, F8 b) { return {_mm256_mul_ps(a.v, b.v)}; }
inline F8 operator/(F8 a, F8 b) { return {_mm256_div_ps(a.v, b.v)}; }
inline F8 fma(F8 a, F8 b, F8 c) { return {_mm256_fmadd_ps(a.v, b.v, c.v)}; }
// min/max as x86 MINPS/MAXPS: the second operand when either is NaN (LLVM's minnum/maxnum differ
// only for NaN, which the kernels never feed them on purpose).
inline F8 min(F8 a, F8 b) { return {_mm256_min_ps(a.v, b.v)}; }
inline F8 max(F8 a, F8 b) { return {_mm256_max_ps(a.v, b.v)}; }
inline F8 sqrt(F8 a) { return {_mm256_sqrt_ps(a.v)}; }
inline F8 neg(F8 a) { return {_mm256_xor_ps(a.v, _mm256_set1_ps(-0.0f))}; }
inline F8 abs(F8 a) { return {_mm256_andnot_ps(_mm256_set1_ps(-0.0f), a.v)}; }
inline F8 floor(F8 a) { return {_mm256_round_ps(a.v, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC)}; }
inline F8 roundEven(F8 a) { return {_mm256_round_ps(a.v, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC)}; }
inline F8 tofloat(I8 a) { return {_mm256_cvtepi32_ps(a.v)}; }
// CVTPS2DQ: round to nearest even; NaN and out-of-range give INT32_MIN.
inline I8 toIntRound(F8 a) { return {_mm256_cvtps_epi32(a.v)}; }
// CVTTPS2DQ: truncation; NaN and out-of-range give INT32_MIN.
inline I8 toIntTrunc(F8 a) { return {_mm256_cvttps_epi32(a.v)}; }
inline I8 bits(F8 a) { return {_mm256_castps_si256(a.v)}; }
inline F8 fromBits(I8 a) { return {_mm256_castsi256_ps(a.v)}; }

inline I8 lt(F8 a, F8 b) { return {_mm256_castps_si256(_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ))}; }
inline F8 selectf(I8 mask, F8 a, F8 b) { return {_mm256_blendv_ps(b.v, a.v, _mm256_castsi256_ps(mask.v))}; }

inline I8 operator+(I8 a, I8 b) { return {_mm256_add_epi32(a.v, b.v)}; }
inline I8 operator-(I8 a, I8 b) { return {_mm256_sub_epi32(a.v, b.v)}; }
inline I8 operator*(I8 a, I8 b) { return {_mm256_mullo_epi32(a.v, b.v)}; }
inline I8 operator&(I8 a, I8 b) { return {_mm256_and_si256(a.v, b.v)}; }
inline I8 operator|(I8 a, I8 b) { return {_mm256_or_si256(a.v, b.v)}; }
inline I8 andnot(I8 a, I8 b) { return {_mm256_andnot_si256(a.v, b.v)}; }  // ~a & b
inline I8 sra(I8 a, int n) { return {_mm256_srai_epi32(a.v, n)}; }
inline I8 srl(I8 a, int n) { return {_mm256_srli_epi32(a.v, n)}; }
inline I8 sll(I8 a, int n) { return {_mm256_slli_epi32(a.v, n)}; }
inline I8 mini(I8 a, I8 b) { return {_mm256_min_epi32(a.v, b.v)}; }
inline I8 maxi(I8 a, I8 b) { return {_mm256_max_epi32(a.v, b.v)}; }
inline I8 gt(I8 a, I8 b) { return {_mm256_cmpgt_epi32(a.v, b.v)}; }
inline I8 eq(I8 a, I8 b) { return {_mm256_cmpeq_epi32(a.v, b.v)}; }
inline I8 selecti(I8 mask, I8 a, I8 b) { return {_mm256_blendv_epi8(b.v, a.v, mask.v)}; }
// One bit per lane, lane 0 in bit 0.
inline unsigned laneBits(I8 mask) { return unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(mask.v))); }
// Stores the lanes of `a` whose mask is set.
inline void storeMasked(void* p, I8 mask, I8 a) { _mm256_maskstore_epi32(static_cast<int*>(p), mask.v, a.v); }
inline I8 gather(const std::int32_t* base, I8 index) { return {_mm256_i32gather_epi32(base, index.v, 4)}; }

inline float fmas(float a, float b, float c) { return __builtin_fmaf(a, b, c); }
// Scalar conversions with x86 semantics: NaN and values outside int32 give INT32_MIN.
inline std::int32_t cvtRound(float f) { return _mm_cvtss_si32(_mm_set_ss(f)); }
inline std::int32_t cvtTrunc(float f) { return _mm_cvttss_si32(_mm_set_ss(f)); }

#else  // portable lanes

struct F8 {
    float v[kLanes];
};
struct I8 {
    std::int32_t v[kLanes];
};

#define FRUGAL_SW_LANES(expr)                                          \
    do {                                                               \
        for (int lane_ = 0; lane_ < kLanes; ++lane_) { expr; }         \
    } while (0)

inline F8 splat(float a) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = a); return r; }
inline I8 splati(std::int32_t a) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = a); return r; }
inline F8 loadf(const float* p) { F8 r; std::memcpy(r.v, p, sizeof r.v); return r; }
inline void storef(float* p, F8 a) { std::memcpy(p, a.v, sizeof a.v); }
inline I8 loadi(const void* p) { I8 r; std::memcpy(r.v, p, sizeof r.v); return r; }
inline void storei(void* p, I8 a) { std::memcpy(p, a.v, sizeof a.v); }
inline I8 ramp(std::int32_t base) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = base + lane_); return r; }

inline F8 operator+(F8 a, F8 b) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = a.v[lane_] + b.v[lane_]); return r; }
inline F8 operator-(F8 a, F8 b) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = a.v[lane_] - b.v[lane_]); return r; }
inline F8 operator*(F8 a, F8 b) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = a.v[lane_] * b.v[lane_]); return r; }
inline F8 operator/(F8 a, F8 b) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = a.v[lane_] / b.v[lane_]); return r; }
inline float fmas(float a, float b, float c) {
#if FRUGAL_SW_FUSED
    return std::fma(a, b, c);
#else
    return a * b + c;
#endif
}
inline F8 fma(F8 a, F8 b, F8 c) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = fmas(a.v[lane_], b.v[lane_], c.v[lane_])); return r; }
// As MINPS/MAXPS: the second operand unless a < b (resp. a > b).
inline F8 min(F8 a, F8 b) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = a.v[lane_] < b.v[lane_] ? a.v[lane_] : b.v[lane_]); return r; }
inline F8 max(F8 a, F8 b) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = a.v[lane_] > b.v[lane_] ? a.v[lane_] : b.v[lane_]); return r; }
inline F8 sqrt(F8 a) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = std::sqrt(a.v[lane_])); return r; }
inline F8 neg(F8 a) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = -a.v[lane_]); return r; }
inline F8 abs(F8 a) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = std::fabs(a.v[lane_])); return r; }
inline F8 floor(F8 a) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = std::floor(a.v[lane_])); return r; }
inline F8 roundEven(F8 a) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = std::nearbyint(a.v[lane_])); return r; }
inline F8 tofloat(I8 a) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = float(a.v[lane_])); return r; }
// x86 conversion semantics: NaN and values outside int32 give INT32_MIN.
inline std::int32_t cvtRound(float f) {
    const float r = std::nearbyint(f);
    return (r >= -2147483648.0f && r < 2147483648.0f) ? std::int32_t(r) : INT32_MIN;
}
inline std::int32_t cvtTrunc(float f) {
    return (f > -2147483649.0f && f < 2147483648.0f) ? std::int32_t(f) : INT32_MIN;
}
inline I8 toIntRound(F8 a) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = cvtRound(a.v[lane_])); return r; }
inline I8 toIntTrunc(F8 a) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = cvtTrunc(a.v[lane_])); return r; }
inline I8 bits(F8 a) { I8 r; std::memcpy(r.v, a.v, sizeof r.v); return r; }
inline F8 fromBits(I8 a) { F8 r; std::memcpy(r.v, a.v, sizeof r.v); return r; }

inline I8 lt(F8 a, F8 b) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = a.v[lane_] < b.v[lane_] ? -1 : 0); return r; }
inline F8 selectf(I8 mask, F8 a, F8 b) { F8 r; FRUGAL_SW_LANES(r.v[lane_] = mask.v[lane_] < 0 ? a.v[lane_] : b.v[lane_]); return r; }

inline I8 operator+(I8 a, I8 b) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = std::int32_t(std::uint32_t(a.v[lane_]) + std::uint32_t(b.v[lane_]))); return r; }
inline I8 operator-(I8 a, I8 b) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = std::int32_t(std::uint32_t(a.v[lane_]) - std::uint32_t(b.v[lane_]))); return r; }
inline I8 operator*(I8 a, I8 b) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = std::int32_t(std::uint32_t(a.v[lane_]) * std::uint32_t(b.v[lane_]))); return r; }
inline I8 operator&(I8 a, I8 b) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = a.v[lane_] & b.v[lane_]); return r; }
inline I8 operator|(I8 a, I8 b) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = a.v[lane_] | b.v[lane_]); return r; }
inline I8 andnot(I8 a, I8 b) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = ~a.v[lane_] & b.v[lane_]); return r; }
inline I8 sra(I8 a, int n) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = a.v[lane_] >> n); return r; }
inline I8 srl(I8 a, int n) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = std::int32_t(std::uint32_t(a.v[lane_]) >> n)); return r; }
inline I8 sll(I8 a, int n) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = std::int32_t(std::uint32_t(a.v[lane_]) << n)); return r; }
inline I8 mini(I8 a, I8 b) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = a.v[lane_] < b.v[lane_] ? a.v[lane_] : b.v[lane_]); return r; }
inline I8 maxi(I8 a, I8 b) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = a.v[lane_] > b.v[lane_] ? a.v[lane_] : b.v[lane_]); return r; }
inline I8 gt(I8 a, I8 b) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = a.v[lane_] > b.v[lane_] ? -1 : 0); return r; }
inline I8 eq(I8 a, I8 b) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = a.v[lane_] == b.v[lane_] ? -1 : 0); return r; }
inline I8 selecti(I8 mask, I8 a, I8 b) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = mask.v[lane_] < 0 ? a.v[lane_] : b.v[lane_]); return r; }
inline unsigned laneBits(I8 mask) { unsigned r = 0; FRUGAL_SW_LANES(r |= (mask.v[lane_] < 0 ? 1u : 0u) << lane_); return r; }
inline void storeMasked(void* p, I8 mask, I8 a) {
    auto* out = static_cast<std::int32_t*>(p);
    FRUGAL_SW_LANES(if (mask.v[lane_] < 0) out[lane_] = a.v[lane_]);
}
inline I8 gather(const std::int32_t* base, I8 index) { I8 r; FRUGAL_SW_LANES(r.v[lane_] = base[index.v[lane_]]); return r; }

#undef FRUGAL_SW_LANES

#endif

// ⌊f⌋ as an integer (lp_build_ifloor: round down, then convert).
inline std::int32_t cvtRoundDown(float f) { return cvtRound(std::floor(f)); }

}  // namespace simd
// clang-format on
