// The occlusion pass's quick test (cull/OcclusionKernels.h: AVX2 with gathers, and with AVX-512
// lookups where the CPU has them) against setup's own scalar steps (raster/Rasterizer.h), lane by
// lane, on random triangles of a few pixels: the verdict, the pixels covered, whether the triangle
// occludes, and the depth bounds at each pixel, bit for bit.
// The plans the two give are compared in tests/cullrender/OcclusionTest.cpp; this test also
// reaches what a plan does not show (a bound a little too near that no scene happens to reveal).
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cull/OcclusionKernels.h"

namespace frugal::occlusion {
namespace {

using Kernel = void (*)(const WindowArrays&, const std::uint16_t*, const std::uint16_t*, const std::uint16_t*,
                        std::uint32_t, bool, const raster::Viewport&, int, int, std::uint8_t*, const SmallTriangles&);
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
    // kMedium: the last pixel, the plane (z0, dzdx, dzdy, slack) and setup's edges.
    std::int64_t x1 = 0, y1 = 0;
    float plane[4] = {};
    raster::Triangle edges{};
};

// The pass's scalar rules for one triangle whose corners are all representable (Occlusion.cpp
// triangleMaySeen), on rows [rowLo, rowHi] of the target.
Expected reference(const float (*v)[3], bool cullBack, const raster::Viewport& vp, int rowLo, int rowHi) {
    Expected e;
    std::int64_t X[3], Y[3];
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(raster::fixedPosition(v[i][0], v[i][1], &X[i], &Y[i]));
    const std::int64_t minX = std::min({X[0], X[1], X[2]}), maxX = std::max({X[0], X[1], X[2]});
    const std::int64_t minY = std::min({Y[0], Y[1], Y[2]}), maxY = std::max({Y[0], Y[1], Y[2]});
    // Setup's bounds first (no pixel centre: dropped), then the size the quick test decides.
    const std::int64_t bx0 = std::max<std::int64_t>(-((-minX) >> 8), 0),
                       bx1 = std::min<std::int64_t>(maxX >> 8, vp.width - 1);
    const std::int64_t by0 = std::max<std::int64_t>(-((-minY) >> 8), rowLo),
                       by1 = std::min<std::int64_t>(maxY >> 8, rowHi);
    if (bx0 > bx1 || by0 > by1) return e;
    if (maxX - minX >= kQuickExtent || maxY - minY >= kQuickExtent || bx1 - bx0 > 7) {
        e.verdict = kTest;
        return e;
    }
    raster::Triangle t{};
    const raster::SetupOrder order = raster::setupEdges(X, Y, cullBack, vp, &t);
    if (order == raster::SetupOrder::Dropped) return e;
    if (bx1 - bx0 > 1 || by1 - by0 > 1) {  // medium: the plane, unless too steep (then kTest)
        EXPECT_EQ(t.x0, bx0);
        EXPECT_EQ(t.x1, bx1);
        raster::SetupVertex s[3]{};
        for (int i = 0; i < 3; ++i) s[i].x = v[i][0], s[i].y = v[i][1], s[i].z = v[i][2], s[i].oow = 1.0f;
        e.occludes = !cullBack || raster::drawModuleKeepsFront(&s[0], &s[1], &s[2]);
        if (order == raster::SetupOrder::Swapped) std::swap(s[0], s[1]);
        raster::setupDepthPlane(&s[0], &s[1], &s[2], &t);
        const float slack = depthSlack(t.z0, t.dzdx, t.dzdy, float(vp.width), float(vp.height));
        e.verdict = slack < 1.0f ? kMedium : kTest;
        e.x0 = bx0, e.y0 = by0, e.x1 = bx1, e.y1 = by1;
        e.plane[0] = t.z0, e.plane[1] = t.dzdx, e.plane[2] = t.dzdy, e.plane[3] = slack;
        e.edges = t;
        return e;
    }
    for (unsigned k = 0; k < 4; ++k) {
        const std::int64_t px = bx0 + (k & 1u), py = by0 + (k >> 1);
        if (px > bx1 || py > by1) continue;
        std::int64_t m = 0;
        for (const raster::Edge& edge : t.e) m |= edge.k - std::int64_t(edge.dx) * px + std::int64_t(edge.dy) * py;
        if (m >= 0) e.covered |= 1u << k;
    }
    if (e.covered == 0) return e;
    e.x0 = bx0, e.y0 = by0;
    raster::SetupVertex s[3]{};
    for (int i = 0; i < 3; ++i) s[i].x = v[i][0], s[i].y = v[i][1], s[i].z = v[i][2], s[i].oow = 1.0f;
    e.occludes = !cullBack || raster::drawModuleKeepsFront(&s[0], &s[1], &s[2]);
    if (order == raster::SetupOrder::Swapped) std::swap(s[0], s[1]);
    raster::setupDepthPlane(&s[0], &s[1], &s[2], &t);
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
        std::size_t small = 0, dropped = 0, tested = 0, kept = 0, medium = 0;
        for (const DepthFormat format : {DepthFormat::D24, DepthFormat::D32F}) {
            const raster::Viewport vp = raster::makeViewport(64, 48, format);
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
                const int sizeClass = (batch / 2) % 4;
                const float size = sizeClass == 0 ? 0.6f : sizeClass == 1 ? 2.5f : sizeClass == 2 ? 4.5f : 14.0f;
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
                        ASSERT_TRUE(raster::fixedPosition(x[i], y[i], &X, &Y));
                        fx[i] = std::int32_t(X), fy[i] = std::int32_t(Y);
                    }
                }
                for (int i = 24; i < 64; ++i) {  // the rest: copies of the vertices of other triangles
                    const int from = place[std::size_t(i) % 24];
                    x[place[i]] = x[from] + 0.25f, y[place[i]] = y[from] - 0.5f, z[place[i]] = 1.0f - z[from];
                    std::int64_t X = 0, Y = 0;
                    ASSERT_TRUE(raster::fixedPosition(x[place[i]], y[place[i]], &X, &Y));
                    fx[place[i]] = std::int32_t(X), fy[place[i]] = std::int32_t(Y);
                }
                std::uint16_t c0[8], c1[8], c2[8];
                for (int t = 0; t < 8; ++t) c0[t] = place[3 * t], c1[t] = place[3 * t + 1], c2[t] = place[3 * t + 2];
                const bool cullBack = batch % 2 == 0;
                // Every fourth batch on a band of rows only, as a thread of the pass sees it.
                const int rowLo = batch % 4 == 3 ? 20 : 0, rowHi = batch % 4 == 3 ? 27 : vp.height - 1;
                std::uint8_t verdict[8], covered[8], occludes[8];
                std::int32_t x0[8], y0[8], x1[8], y1[8], edge[72];
                float lo[32], hi[32], plane[32];
                const SmallTriangles out{x0, y0, covered, occludes, lo, hi, 8, x1, y1, edge, plane};
                named.kernel({x, y, z, fx, fy}, c0, c1, c2, 8, cullBack, vp, rowLo, rowHi, verdict, out);
                for (int t = 0; t < 8; ++t) {
                    const float v[3][3] = {
                        {x[c0[t]], y[c0[t]], z[c0[t]]}, {x[c1[t]], y[c1[t]], z[c1[t]]}, {x[c2[t]], y[c2[t]], z[c2[t]]}};
                    const Expected e = reference(v, cullBack, vp, rowLo, rowHi);
                    const std::string where = "batch " + std::to_string(batch) + ", lane " + std::to_string(t);
                    ASSERT_EQ(int(verdict[t]), int(e.verdict)) << where;
                    small += e.verdict == kSmall, dropped += e.verdict == kDrop, tested += e.verdict == kTest;
                    kept += e.verdict == kKeep, medium += e.verdict == kMedium;
                    if (e.verdict == kMedium) {
                        ASSERT_EQ(x0[t], e.x0) << where;
                        ASSERT_EQ(y0[t], e.y0) << where;
                        ASSERT_EQ(x1[t], e.x1) << where;
                        ASSERT_EQ(y1[t], e.y1) << where;
                        ASSERT_EQ(occludes[t] != 0, e.occludes) << where;
                        for (int k = 0; k < 4; ++k)
                            ASSERT_EQ(std::memcmp(&plane[k * 8 + t], &e.plane[k], 4), 0) << where << ", plane " << k;
                        // Each edge's sign at every pixel of the box, as narrowAvx2 evaluates it.
                        for (std::int64_t py = e.y0; py <= e.y1; ++py)
                            for (std::int64_t px = e.x0; px <= e.x1; ++px)
                                for (int k = 0; k < 3; ++k) {
                                    const raster::Edge& edgeK = e.edges.e[k];
                                    const bool inside = edgeK.k - std::int64_t(edgeK.dx) * px + std::int64_t(edgeK.dy) * py >= 0;
                                    const std::int64_t got = std::int64_t(edge[k * 8 + t]) -
                                                             std::int64_t(edge[(3 + k) * 8 + t]) * (px - e.x0) +
                                                             std::int64_t(edge[(6 + k) * 8 + t]) * (py - e.y0);
                                    ASSERT_EQ(got >= 0, inside) << where << ", edge " << k << " at " << px << ", " << py;
                                }
                        continue;
                    }
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
        EXPECT_GT(tested, 1000u);
        EXPECT_GT(medium, 5000u);
        RecordProperty(std::string("kept, ") + named.name, int(kept));
    }
}

TEST(OcclusionKernelsTest, ACornerThePassCannotUseKeepsTheTriangle) {
    if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2 and FMA: only the scalar loops run";
    const raster::Viewport vp = raster::makeViewport(64, 48, DepthFormat::D24);
    float x[64] = {}, y[64] = {}, z[64] = {};
    std::int32_t fx[64] = {}, fy[64] = {};
    for (int i = 0; i < 24; ++i) {
        x[i] = 10.0f + float(i % 3), y[i] = 10.0f + float(i % 3 == 1), z[i] = 0.5f;
        std::int64_t X = 0, Y = 0;
        ASSERT_TRUE(raster::fixedPosition(x[i], y[i], &X, &Y));
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

// EdgeRows steps each row's bound of an edge without dividing: the same bounds as dividing on every
// row, for edges of every slope and sign (vertical and horizontal ones too), over a few hundred
// rows from anywhere, with the values setup's fixed point can reach.
TEST(OcclusionKernelsTest, EdgeRowsStepsTheBoundsThatDividingGives) {
    std::mt19937_64 rng(5);
    const auto pick = [&rng](std::int64_t lo, std::int64_t hi) {
        return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng);
    };
    std::size_t upper = 0, lower = 0, flat = 0;
    for (int n = 0; n < 20000; ++n) {
        raster::Edge e{};
        const std::int64_t span = n % 3 == 0 ? 300 : n % 3 == 1 ? 70000 : (std::int64_t(1) << 26);
        e.dx = std::int32_t(n % 11 == 0 ? 0 : pick(-span, span));
        e.dy = std::int32_t(n % 13 == 0 ? 0 : pick(-span, span));
        e.k = pick(-(std::int64_t(1) << 40), std::int64_t(1) << 40);
        const std::int64_t py0 = pick(-100, 5000);
        occlusion::EdgeRows rows(e, py0);
        for (std::int64_t py = py0; py < py0 + 300; ++py) {
            // What dividing gives, in a row of pixels [−1000, 1000].
            std::int64_t xa = -1000, xb = 1000;
            const std::int64_t r = e.k + std::int64_t(e.dy) * py;
            if (e.dx > 0)
                xb = std::min(xb, floorDiv(r, e.dx)), ++upper;
            else if (e.dx < 0)
                xa = std::max(xa, -floorDiv(r, -std::int64_t(e.dx))), ++lower;
            else if (r < 0)
                xb = xa - 1, ++flat;
            std::int64_t ga = -1000, gb = 1000;
            rows.bound(ga, gb);
            rows.nextRow();
            ASSERT_EQ(ga, xa) << "edge " << n << ", row " << py;
            ASSERT_EQ(gb, xb) << "edge " << n << ", row " << py;
            // And each bound is the last (or first) pixel inside the edge.
            if (e.dx > 0) {
                ASSERT_GE(r - std::int64_t(e.dx) * floorDiv(r, e.dx), 0);
                ASSERT_LT(r - std::int64_t(e.dx) * (floorDiv(r, e.dx) + 1), 0);
            }
        }
    }
    EXPECT_GT(upper, 100000u);
    EXPECT_GT(lower, 100000u);
    EXPECT_GT(flat, 1000u);
}

// narrowAvx2 against the pass's scalar rasterization of a triangle (Occlusion.cpp triangleMaySeen
// without SIMD): its covered pixels by setup's edges one at a time, the depth bounds of each, the
// buffer lowered pixel by pixel. On random triangles up to 8 pixels wide, some reaching past the
// target's right edge (whose columns the kernel must not touch), on buffers holding random far-ness:
// the buffers bit for bit, whether some pixel may be seen, and the columns covered.
TEST(OcclusionKernelsTest, TheNarrowRasterizerEqualsThePixelByPixelOne) {
    if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2 and FMA: only the scalar loops run";
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    constexpr int kWidth = 37, kHeight = 29;  // not a multiple of 8: the last columns end a row
    std::size_t seenCount = 0, hiddenCount = 0, empty = 0;
    for (const DepthFormat format : {DepthFormat::D24, DepthFormat::D32F}) {
        const raster::Viewport vp = raster::makeViewport(kWidth, kHeight, format);
        const bool halfZ = format == DepthFormat::D32F;
        for (int n = 0; n < 20000; ++n) {
            // A corner anywhere (past the right edge too), two more within 8 pixels across and
            // up to 20 up or down.
            float v[3][3];
            const float cx = -2.0f + (kWidth + 6.0f) * unit(rng), cy = (kHeight - 1.0f) * unit(rng), cz = unit(rng);
            for (int c = 0; c < 3; ++c) {
                v[c][0] = cx + (c == 0 ? 0.0f : 7.9f * unit(rng));
                v[c][1] = cy + (c == 0 ? 0.0f : 20.0f * (unit(rng) - 0.5f));
                v[c][2] = n % 5 == 0 ? unit(rng) : cz + 1e-3f * unit(rng);
            }
            std::int64_t X[3], Y[3];
            for (int c = 0; c < 3; ++c) ASSERT_TRUE(raster::fixedPosition(v[c][0], v[c][1], &X[c], &Y[c]));
            raster::Triangle t{};
            const bool cullBack = n % 2 == 0;
            const raster::SetupOrder order = raster::setupEdges(X, Y, cullBack, vp, &t);
            if (order == raster::SetupOrder::Dropped || t.x1 - t.x0 >= 8 || t.x0 > t.x1) continue;
            raster::SetupVertex s[3]{};
            for (int c = 0; c < 3; ++c) s[c].x = v[c][0], s[c].y = v[c][1], s[c].z = v[c][2], s[c].oow = 1.0f;
            if (order == raster::SetupOrder::Swapped) std::swap(s[0], s[1]);
            raster::setupDepthPlane(&s[0], &s[1], &s[2], &t);
            const float slack = depthSlack(t.z0, t.dzdx, t.dzdy, float(kWidth), float(kHeight));
            if (!(slack < 1.0f)) continue;
            const float up = 2.0f / 16777216.0f;
            // Sometimes a band of rows only, as a thread of the pass sees it.
            const int y0 = n % 4 == 3 ? std::max(t.y0, 10) : t.y0, y1 = n % 4 == 3 ? std::min(t.y1, 17) : t.y1;
            if (y0 > y1) continue;
            std::int32_t e[3], dx[3], dy[3];
            for (int i = 0; i < 3; ++i) {
                const std::int64_t at = t.e[i].k - std::int64_t(t.e[i].dx) * t.x0 + std::int64_t(t.e[i].dy) * y0;
                ASSERT_LT(std::abs(at), std::int64_t(1) << 30);
                e[i] = std::int32_t(at), dx[i] = t.e[i].dx, dy[i] = t.e[i].dy;
            }
            // Far-ness that hides some pixels and not others.
            std::vector<float> buffer(std::size_t(kWidth) * kHeight);
            for (float& f : buffer) f = n % 3 == 0 ? std::numeric_limits<float>::infinity() : (halfZ ? -unit(rng) : unit(rng));
            std::vector<float> expected = buffer;
            const bool occludes = n % 7 != 6;
            bool seen = false;
            std::uint32_t columns = 0;
            for (int py = y0; py <= y1; ++py) {
                const float zRow = t.z0 + t.dzdy * float(py);
                for (int px = t.x0; px <= t.x1; ++px) {
                    std::int64_t m = 0;
                    for (const raster::Edge& edge : t.e) m |= edge.k - std::int64_t(edge.dx) * px + std::int64_t(edge.dy) * py;
                    if (m < 0) continue;
                    columns |= 1u << (px - t.x0);
                    const float z = zRow + t.dzdx * float(px);
                    const float lo = halfZ ? -std::clamp(z + slack, 0.0f, 1.0f) : std::clamp(z - slack, 0.0f, 1.0f);
                    const float hi = halfZ ? -std::clamp(z - slack, 0.0f, 1.0f) + up : std::min(z + slack, 1.0f) + up;
                    float& stored = expected[std::size_t(py) * kWidth + std::size_t(px)];
                    seen = seen || !(stored < lo);
                    if (occludes) stored = std::min(stored, hi);
                }
            }
            std::uint32_t gotColumns = 0;
            const bool got = narrowAvx2(buffer.data(), kWidth, t.x0, t.x1, y0, y1, e, dx, dy, t.z0, t.dzdx, t.dzdy,
                                        slack, up, halfZ, occludes, &gotColumns);
            const std::string where = "triangle " + std::to_string(n);
            ASSERT_EQ(got, seen) << where;
            ASSERT_EQ(gotColumns, columns) << where;
            ASSERT_EQ(std::memcmp(buffer.data(), expected.data(), buffer.size() * sizeof(float)), 0) << where;
            seenCount += columns != 0 && seen, hiddenCount += columns != 0 && !seen, empty += columns == 0;
        }
    }
    // Seen, hidden and empty triangles are all reached often.
    EXPECT_GT(seenCount, 2000u);
    EXPECT_GT(hiddenCount, 1000u);
    EXPECT_GT(empty, 100u);
}

}  // namespace
}  // namespace frugal::occlusion
