// The split-sum table of the environment's specular term, as a formula: the Khronos glTF Sample
// Renderer's look-up table (its lut_ggx: GGX, height-correlated Smith visibility), whose two
// channels weigh f0 and f90 in the image-based Fresnel (Backend.h, `Lighting`), fitted by
// research/shading/dfg_fit.py. A formula instead of a texture: a texture fetch per pixel costs
// llvmpipe more than these 43 multiply-adds, and the software backend computes the same numbers.
//
// With x = n·v, r = perceptual roughness, alpha = r², u = x · (1 / sqrt(max(x² + 4·alpha², 1e-30))) (the
// grazing layer, at n·v ≈ alpha) and f5 = (1 − x)⁵, each of A and B is
//   P = ((c0 + r(c1 + r(c2 + r(c3 + r(c4 + r·c5))))) + x((c6 + r(c7 + r·c8)) + x·c9))
//       + u(((c10 + r(c11 + r(c12 + r·c13))) + x·c14) + u·c15) + f5(c16 + r·c17),
// clamped to [0, 1], evaluated in this order (mesh.frag's dfg() is written from kDfgA and kDfgB by
// the GL backend, GlPrograms.cpp). Against the exact integral: A within 0.020, B within 0.013, A + B
// within 0.027 anywhere (0.009 and 0.007 r.m.s.); the Khronos renderer's own 128² table, sampled
// bilinearly, is within 0.006 and 0.018 of it inside its texel centres.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace frugal::brdf {

inline constexpr std::array<float, 18> kDfgA = {
    0.822543621f,   0.664519608f, 2.58137655f,  -9.60213661f, 8.94883442f, -2.7754333f,
    -1.17064095f,   0.613827705f, -0.866843641f, -0.369361728f, -0.0724142343f, -1.3563838f,
    0.365230918f,   2.61944628f,  1.67190576f,  0.0989411175f, -0.842350066f, 1.13513947f};
inline constexpr std::array<float, 18> kDfgB = {
    0.096355617f,  -0.813487828f, -5.20299435f, 16.0580616f,  -15.4138317f, 5.02842951f,
    2.79810667f,   -0.632939994f, 1.78408194f,  0.202189386f, -0.427496165f, 1.4651773f,
    1.84651101f,   -8.76186943f,  -3.05961776f, 0.403327495f, 0.91682446f,  -0.628975391f};

template <class T>
struct Dfg {
    T a, b;
};

// A and B at (x, r) in float or double, in the order above. (The software backend's SIMD kernels
// evaluate the same order on their own vector type: src/software/Kernels.inl.)
template <class T>
Dfg<T> dfg(T x, T r) {
    const auto polynomial = [&](const std::array<float, 18>& c, T u, T f5) {
        const auto k = [&c](int i) { return T(c[std::size_t(i)]); };
        const T inR = k(0) + r * (k(1) + r * (k(2) + r * (k(3) + r * (k(4) + r * k(5)))));
        const T inX = x * ((k(6) + r * (k(7) + r * k(8))) + x * k(9));
        const T inU = u * (((k(10) + r * (k(11) + r * (k(12) + r * k(13)))) + x * k(14)) + u * k(15));
        const T inF = f5 * (k(16) + r * k(17));
        return std::clamp(((inR + inX) + inU) + inF, T(0), T(1));
    };
    const T alpha = r * r;
    const T u = x * (T(1) / std::sqrt(std::max(x * x + T(4) * (alpha * alpha), T(1.0e-30f))));
    const T y = T(1) - x;
    const T y2 = y * y;
    const T f5 = (y2 * y2) * y;
    return {polynomial(kDfgA, u, f5), polynomial(kDfgB, u, f5)};
}

}  // namespace frugal::brdf
