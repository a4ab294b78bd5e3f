// The occlusion pass's quick test (cull/OcclusionKernels.h: AVX2 with gathers, and with AVX-512
// lookups where the CPU has them) against setup's own scalar steps (software/Rasterizer.h), lane by
// lane, on random triangles of a few pixels: the verdict, the pixels covered, whether the triangle
// occludes, and the depth bounds at each pixel, bit for bit.
// The plans the two give are compared in tests/cullrender/OcclusionTest.cpp; this test also
// reaches what a plan does not show (a bound a little too near that no scene happens to reveal).
#include <algorithm>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cull/OcclusionKernels.h"

namespace frugal::occlusion {
namespace {

using Kernel = void (*)(const WindowArrays&, const std::uint16_t*, const std::uint16_t*, const std::uint16_t*,
                        std::uint32_t, bool, const sw::Viewport&, int, int, std::uint8_t*, const SmallTriangles&);
struct NamedKernel {
    const char* name;
    Kernel kernel;
};
// The quick tests this CPU runs.
std::vector<NamedKernel> kernels() {
    std::vector<NamedKernel> k;
    if (cpuHasAvx2()) k.push_back({"AVX2 gathers", verdictsAvx2});
    if (cpuHasAvx512()) k.push_back({"AVX-512 lookups", verdictsAvx512});
    return k;
}

struct Expected {
    Verdict verdict = kDrop;
    std::int64_t x0 = 0, y0 = 0;  // the first pixel
    unsigned covered = 0;
    bool occludes = false;
    float lo[4] = {}, hi[4] = {};
};

// The pass's scalar rules for one triangle whose corners are all representable (Occlusion.cpp
// triangleMaySeen), on rows [rowLo, rowHi] of the target.
Expected reference(const float (*v)[3], bool cullBack, const sw::Viewport& vp, int rowLo, int rowHi) {
    Expected e;
    std::int64_t X[3], Y[3];
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(sw::fixedPosition(v[i][0], v[i][1], &X[i], &Y[i]));
    const std::int64_t minX = std::min({X[0], X[1], X[2]}), maxX = std::max({X[0], X[1], X[2]});
    const std::int64_t minY = std::min({Y[0], Y[1], Y[2]}), maxY = std::max({Y[0], Y[1], Y[2]});
    // Setup's bounds first (no pixel centre: dropped), then the size the quick test decides.
    const std::int64_t bx0 = std::max<std::int64_t>(-((-minX) >> 8), 0),
                       bx1 = std::min<std::int64_t>(maxX >> 8, vp.width - 1);
    const std::int64_t by0 = std::max<std::int64_t>(-((-minY) >> 8), rowLo),
                       by1 = std::min<std::int64_t>(maxY >> 8, rowHi);
    if (bx0 > bx1 || by0 > by1) return e;
    if (maxX - minX >= kQuickExtent || maxY - minY >= kQuickExtent || bx1 - bx0 > 1 || by1 - by0 > 1) {
        e.verdict = kTest;
        return e;
    }
    sw::Triangle t{};
    const sw::SetupOrder order = sw::setupEdges(X, Y, cullBack, vp, &t);
    if (order == sw::SetupOrder::Dropped) return e;
    for (unsigned k = 0; k < 4; ++k) {
        const std::int64_t px = bx0 + (k & 1u), py = by0 + (k >> 1);
        if (px > bx1 || py > by1) continue;
        std::int64_t m = 0;
        for (const sw::Edge& edge : t.e) m |= edge.k - std::int64_t(edge.dx) * px + std::int64_t(edge.dy) * py;
        if (m >= 0) e.covered |= 1u << k;
    }
    if (e.covered == 0) return e;
    e.x0 = bx0, e.y0 = by0;
    sw::SetupVertex s[3]{};
    for (int i = 0; i < 3; ++i) s[i].x = v[i][0], s[i].y = v[i][1], s[i].z = v[i][2], s[i].oow = 1.0f;
    e.occludes = !cullBack || sw::drawModuleKeepsFront(&s[0], &s[1], &s[2]);
    if (order == sw::SetupOrder::Swapped) std::swap(s[0], s[1]);
    sw::setupDepthPlane(&s[0], &s[1], &s[2], &t);
    const float slack = depthSlack(t.z0, t.dzdx, t.dzdy, float(vp.width), float(vp.height));
    if (!(slack < 1.0f)) {
        e.verdict = kKeep;
        return e;
    }
    e.verdict = kSmall;
    const float up = 2.0f / 16777216.0f;
    for (unsigned k = 0; k < 4; ++k) {
        if (!(e.covered & (1u << k))) continue;
        const float zRow = t.z0 + t.dzdy * float(by0 + int(k >> 1));
        const float z = zRow + t.dzdx * float(bx0 + int(k & 1u));
        if (!vp.halfZ) {
            e.lo[k] = std::clamp(z - slack, 0.0f, 1.0f), e.hi[k] = std::min(z + slack, 1.0f) + up;
        } else {
            e.lo[k] = -std::clamp(z + slack, 0.0f, 1.0f), e.hi[k] = -std::clamp(z - slack, 0.0f, 1.0f) + up;
        }
    }
    return e;
}

TEST(OcclusionKernelsTest, TheQuickTestAgreesWithSetupLaneByLane) {
    if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2 and FMA: only the scalar loops run";
    for (const NamedKernel& named : kernels()) {
        SCOPED_TRACE(named.name);
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        std::size_t small = 0, dropped = 0, tested = 0, kept = 0;
        for (const DepthFormat format : {DepthFormat::D24, DepthFormat::D32F}) {
            const sw::Viewport vp = sw::makeViewport(64, 48, format);
            for (int batch = 0; batch < 4000; ++batch) {
                // Eight triangles, three vertices each: a corner and two more within `size` pixels,
                // sometimes snapped to the pixel grid or its centres, depths close together or steep.
                // They are 24 of a cluster's 64 vertices, at random places among the others (which
                // hold other triangles' values): a lookup that takes the wrong one shows.
                float x[64], y[64], z[64];
                std::int32_t fx[64], fy[64];
                std::uint16_t place[64];
                for (int i = 0; i < 64; ++i) place[i] = std::uint16_t(i);
                std::shuffle(place, place + 64, rng);
                const float size = batch % 3 == 0 ? 0.6f : batch % 3 == 1 ? 2.5f : 4.5f;
                for (int t = 0; t < 8; ++t) {
                    const float cx = 1.0f + 61.0f * unit(rng), cy = 1.0f + 45.0f * unit(rng), cz = unit(rng);
                    for (int c = 0; c < 3; ++c) {
                        const int i = place[3 * t + c];
                        x[i] = cx + (c == 0 ? 0.0f : size * (unit(rng) - 0.5f));
                        y[i] = cy + (c == 0 ? 0.0f : size * (unit(rng) - 0.5f));
                        if (batch % 5 == 1)
                            x[i] = std::round(x[i] * 2.0f) * 0.5f, y[i] = std::round(y[i] * 2.0f) * 0.5f;
                        z[i] = batch % 7 == 2 ? unit(rng) : cz + 1e-3f * unit(rng);
                        std::int64_t X = 0, Y = 0;
                        ASSERT_TRUE(sw::fixedPosition(x[i], y[i], &X, &Y));
                        fx[i] = std::int32_t(X), fy[i] = std::int32_t(Y);
                    }
                }
                for (int i = 24; i < 64; ++i) {  // the rest: copies of the vertices of other triangles
                    const int from = place[std::size_t(i) % 24];
                    x[place[i]] = x[from] + 0.25f, y[place[i]] = y[from] - 0.5f, z[place[i]] = 1.0f - z[from];
                    std::int64_t X = 0, Y = 0;
                    ASSERT_TRUE(sw::fixedPosition(x[place[i]], y[place[i]], &X, &Y));
                    fx[place[i]] = std::int32_t(X), fy[place[i]] = std::int32_t(Y);
                }
                std::uint16_t c0[8], c1[8], c2[8];
                for (int t = 0; t < 8; ++t) c0[t] = place[3 * t], c1[t] = place[3 * t + 1], c2[t] = place[3 * t + 2];
                const bool cullBack = batch % 2 == 0;
                // Every fourth batch on a band of rows only, as a thread of the pass sees it.
                const int rowLo = batch % 4 == 3 ? 20 : 0, rowHi = batch % 4 == 3 ? 27 : vp.height - 1;
                std::uint8_t verdict[8], covered[8], occludes[8];
                std::int32_t x0[8], y0[8];
                float lo[32], hi[32];
                const SmallTriangles out{x0, y0, covered, occludes, lo, hi, 8};
                named.kernel({x, y, z, fx, fy}, c0, c1, c2, 8, cullBack, vp, rowLo, rowHi, verdict, out);
                for (int t = 0; t < 8; ++t) {
                    const float v[3][3] = {
                        {x[c0[t]], y[c0[t]], z[c0[t]]}, {x[c1[t]], y[c1[t]], z[c1[t]]}, {x[c2[t]], y[c2[t]], z[c2[t]]}};
                    const Expected e = reference(v, cullBack, vp, rowLo, rowHi);
                    const std::string where = "batch " + std::to_string(batch) + ", lane " + std::to_string(t);
                    ASSERT_EQ(int(verdict[t]), int(e.verdict)) << where;
                    small += e.verdict == kSmall, dropped += e.verdict == kDrop, tested += e.verdict == kTest;
                    kept += e.verdict == kKeep;
                    if (e.verdict != kSmall) continue;
                    ASSERT_EQ(unsigned(covered[t]), e.covered) << where;
                    ASSERT_EQ(x0[t], e.x0) << where;
                    ASSERT_EQ(y0[t], e.y0) << where;
                    ASSERT_EQ(occludes[t] != 0, e.occludes) << where;
                    for (unsigned k = 0; k < 4; ++k) {
                        if (!(e.covered & (1u << k))) continue;
                        // Bit for bit: the same float operations in the same order.
                        ASSERT_EQ(std::memcmp(&lo[k * 8 + unsigned(t)], &e.lo[k], 4), 0) << where << ", pixel " << k;
                        ASSERT_EQ(std::memcmp(&hi[k * 8 + unsigned(t)], &e.hi[k], 4), 0) << where << ", pixel " << k;
                    }
                }
            }
        }
        // Every verdict but kKeep (steep planes need depths far apart in a pixel) is reached often.
        EXPECT_GT(small, 5000u);
        EXPECT_GT(dropped, 5000u);
        EXPECT_GT(tested, 5000u);
        RecordProperty(std::string("kept, ") + named.name, int(kept));
    }
}

TEST(OcclusionKernelsTest, ACornerThePassCannotUseKeepsTheTriangle) {
    if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2 and FMA: only the scalar loops run";
    const sw::Viewport vp = sw::makeViewport(64, 48, DepthFormat::D24);
    float x[64] = {}, y[64] = {}, z[64] = {};
    std::int32_t fx[64] = {}, fy[64] = {};
    for (int i = 0; i < 24; ++i) {
        x[i] = 10.0f + float(i % 3), y[i] = 10.0f + float(i % 3 == 1), z[i] = 0.5f;
        std::int64_t X = 0, Y = 0;
        ASSERT_TRUE(sw::fixedPosition(x[i], y[i], &X, &Y));
        fx[i] = std::int32_t(X), fy[i] = std::int32_t(Y);
    }
    for (int t = 0; t < 8; ++t) (t % 2 ? fx : fy)[3 * t + t % 3] = kUnfixed;  // one corner of each
    std::uint16_t c0[8], c1[8], c2[8];
    for (int t = 0; t < 8; ++t)
        c0[t] = std::uint16_t(3 * t), c1[t] = std::uint16_t(3 * t + 1), c2[t] = std::uint16_t(3 * t + 2);
    std::uint8_t verdict[8], covered[8], occludes[8];
    std::int32_t x0[8], y0[8];
    float lo[32], hi[32];
    for (const NamedKernel& named : kernels()) {
        named.kernel({x, y, z, fx, fy}, c0, c1, c2, 8, false, vp, 0, vp.height - 1, verdict,
                     {x0, y0, covered, occludes, lo, hi, 8});
        for (int t = 0; t < 8; ++t) EXPECT_EQ(int(verdict[t]), int(kKeep)) << named.name << ", lane " << t;
    }
}

}  // namespace
}  // namespace frugal::occlusion
