// The blocks of the paper-001 engine model one at a time (span/Engine.h): number formats,
// the multipliers (III.2, Fig. 7), the midpoint tree (III.2, Fig. 8), the Edge Painting Tree (III.3),
// the LSB-first z comparator (III.3, Fig. 10), and the engine that wires them (III.1, Fig. 6).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "span/Engine.h"

namespace frugal::span {
namespace {

TEST(SpanFixedTest, FormatsStateTheirRangeAndRefuseWhatDoesNotFit) {
    const Format u8{8, 0, false}, s8{7, 1, true};
    EXPECT_EQ(u8.minRaw(), 0);
    EXPECT_EQ(u8.maxRaw(), 255);
    EXPECT_EQ(s8.totalBits(), 9);
    EXPECT_EQ(s8.minRaw(), -256);
    EXPECT_EQ(s8.maxRaw(), 255);
    EXPECT_EQ(toFixed(255.4, u8, Rounding::Nearest), 255);
    EXPECT_FALSE(toFixed(255.5, u8, Rounding::Nearest)) << "256 does not fit 8 bits: refused, not wrapped to 0";
    EXPECT_EQ(toFixed(255.9, u8, Rounding::Floor), 255);
    EXPECT_FALSE(toFixed(-0.1, u8, Rounding::Floor)) << "floor(-0.1) = -1 is not unsigned";
    EXPECT_EQ(toFixed(-0.1, u8, Rounding::Nearest), 0);
    EXPECT_EQ(toFixed(-127.75, s8, Rounding::Nearest), -255);  // −127.75·2 = −255.5, half up
    EXPECT_FALSE(toFixed(std::nan(""), s8, Rounding::Nearest));
    EXPECT_FALSE(toFixed(1e300, s8, Rounding::Nearest));
}

TEST(SpanFixedTest, RoundingIsFloorOrHalfUpForNegativeValuesToo) {
    EXPECT_EQ(shiftRound(5, 1, Rounding::Floor), 2);
    EXPECT_EQ(shiftRound(5, 1, Rounding::Nearest), 3);
    EXPECT_EQ(shiftRound(-5, 1, Rounding::Floor), -3);   // −2.5 -> −3
    EXPECT_EQ(shiftRound(-5, 1, Rounding::Nearest), -2);  // −2.5 -> −2 (half up)
    EXPECT_EQ(floorDiv(-7, 2), -4);
    EXPECT_EQ(roundDiv(-7, 2), -3);
    EXPECT_EQ(roundDiv(7, 2), 4);
    EXPECT_EQ(roundDiv(1119, 7), 160);  // z(3) of Fig. 11 on the exact line: 159.857
}

TEST(SpanMultiplierTest, EvaluatesTheLineAndRoundsAsConfigured) {
    std::uint8_t overflow = 0;
    // f(X) = 1.5·X + 2: f(3) = 6.5.
    const std::optional<ChannelLine> line = lineFromSlope(0, 2.0, 1.5, 16, overflow);
    ASSERT_TRUE(line);
    EXPECT_EQ(line->slopeRaw, 3 << 15);
    EXPECT_EQ(line->anchorRaw, 2 << 16);
    EngineConfig nearest, floor;
    floor.endRounding = Rounding::Floor;
    EXPECT_EQ(multiply(*line, 3, nearest, overflow), 7);
    EXPECT_EQ(multiply(*line, 3, floor, overflow), 6);
    // Below the anchor: f(X) = −1.5·X + 2 at X = 3 is −2.5.
    const std::optional<ChannelLine> down = lineFromSlope(0, 2.0, -1.5, 16, overflow);
    ASSERT_TRUE(down);
    EXPECT_EQ(multiply(*down, 3, nearest, overflow), -2);
    EXPECT_EQ(multiply(*down, 3, floor, overflow), -3);
    EXPECT_EQ(overflow, kOverflowNone);
    EXPECT_EQ(multiplierCycles(24), 35);  // (11 + n)·T_c, 3.5 µs at 10 MHz (III.2)
    EXPECT_EQ(multiplierCycles(16), 27);  // 2.7 µs
}

TEST(SpanMultiplierTest, OverflowIsReportedNeverWrapped) {
    std::uint8_t overflow = 0;
    // |A| must stay below 2^width: 256 LSB/pixel at 8 bits is refused.
    EXPECT_FALSE(lineFromSlope(0, 0.0, 256.0, 8, overflow));
    EXPECT_EQ(overflow, kOverflowSlope);
    overflow = 0;
    EXPECT_FALSE(lineFromSlope(0, 0.0, std::nan(""), 8, overflow));
    EXPECT_EQ(overflow, kOverflowSlope);
    overflow = 0;
    EXPECT_FALSE(lineFromSlope(0, 1e30, 1.0, 8, overflow));
    EXPECT_EQ(overflow, kOverflowAnchor);
    // A legal slope evaluated far from its anchor: 255·200 = 51000 > 2^15 − 1, the endpoint format
    // of an 8-bit channel (8 + 7 integer bits).
    overflow = 0;
    const std::optional<ChannelLine> steep = lineFromSlope(0, 0.0, 255.0, 8, overflow);
    ASSERT_TRUE(steep);
    EXPECT_EQ(multiply(*steep, 128, EngineConfig{}, overflow), 32640);
    EXPECT_EQ(overflow, kOverflowNone);
    EXPECT_FALSE(multiply(*steep, 200, EngineConfig{}, overflow));
    EXPECT_EQ(overflow, kOverflowEndpoint);
    EXPECT_EQ(describeOverflow(kOverflowSlope | kOverflowOutput), "slope, output");
}

TEST(SpanInterpolatorTest, NinePixelExampleOfSectionIII2) {
    // f(0) = 0, f(8) = 7: level 1 f(4) = 3.5, level 2 f(2) = 1.75, f(6) = 5.25, level 3 the odd ones.
    std::array<std::int64_t, 9> exact{}, trunc{}, round{};
    subdivide(0, 7, 3, Midpoint::Exact, exact);
    for (int k = 0; k <= 8; ++k) EXPECT_EQ(exact[std::size_t(k)], 7 * k) << "k/8 of 7 with 3 fraction bits, k = " << k;
    // PIPE's add-and-shift: f(4) = 3, f(2) = 1, f(6) = 5, f(1) = 0, f(3) = 2, f(5) = 4, f(7) = 6.
    subdivide(0, 7, 3, Midpoint::TruncateEachLevel, trunc);
    const std::array<std::int64_t, 9> wantTrunc{0, 0, 1, 2, 3, 4, 5, 6, 7};
    for (int k = 0; k <= 8; ++k) EXPECT_EQ(trunc[std::size_t(k)], 8 * wantTrunc[std::size_t(k)]) << k;
    // Rounding each level: f(4) = 4, f(2) = 2, f(6) = 6, f(1) = 1, f(3) = 3, f(5) = 5, f(7) = 7.
    subdivide(0, 7, 3, Midpoint::RoundEachLevel, round);
    for (int k = 1; k <= 7; ++k) EXPECT_EQ(round[std::size_t(k)], 8 * k) << k;
}

TEST(SpanInterpolatorTest, ExactTreeEqualsTheLineThroughItsEnds) {
    std::mt19937_64 rng(7);
    std::array<std::int64_t, kEnginePixels + 1> tree{};
    for (int trial = 0; trial < 1000; ++trial) {
        const std::int64_t left = std::int64_t(rng() % (1u << 31)) - (1 << 30);
        const std::int64_t right = std::int64_t(rng() % (1u << 31)) - (1 << 30);
        subdivide(left, right, kTreeLevels, Midpoint::Exact, tree);
        for (int k = 0; k <= kEnginePixels; ++k)
            ASSERT_EQ(tree[std::size_t(k)], left * 64 + (right - left) * k) << left << " " << right << " k " << k;
    }
}

TEST(SpanEdgePaintingTreeTest, PaintsExactlyThePixelsInsideTheSpan) {
    for (int ml = -3; ml <= 67; ++ml)
        for (int mr = -3; mr <= 67; ++mr) {
            std::uint64_t want = 0;
            for (int k = 0; k < 64; ++k)
                if (k >= ml && k <= mr) want |= std::uint64_t(1) << k;
            ASSERT_EQ(edgePaintingTree(ml, mr), want) << ml << ".." << mr;
        }
    EXPECT_EQ(edgePaintingTree(2, 9), 0x3FCu);  // Fig. 11
    EXPECT_EQ(edgePaintingTree(0, 63), ~std::uint64_t(0));
}

TEST(SpanComparatorTest, LsbFirstGivesNewLessThanOldForEveryPair) {
    for (std::uint32_t a = 0; a < 128; ++a)
        for (std::uint32_t b = 0; b < 128; ++b) ASSERT_EQ(lessLsbFirst(a, b, 7), a < b) << a << " " << b;
    EXPECT_TRUE(lessLsbFirst(0x7FFFFE, 0x7FFFFF, 24));
    EXPECT_FALSE(lessLsbFirst(0xFFFFFF, 0xFFFFFF, 24)) << "equal z is not nearer: the old pixel stays";
}

TEST(SpanComparatorTest, TheTextsLiteralRuleWouldBeWrong) {
    // Section III.3 read literally: the flag is set when NZ_i < OZ_i and kept otherwise. Then new 2
    // (10b) against old 1 (01b) sets the flag at bit 0 and keeps it at bit 1: "2 < 1". The model
    // clears the flag when NZ_i > OZ_i, the only rule that makes the MSB decide.
    const auto literal = [](std::uint32_t nz, std::uint32_t oz, int width) {
        bool flag = false;
        for (int bit = 0; bit < width; ++bit)
            if (!((nz >> bit) & 1u) && ((oz >> bit) & 1u)) flag = true;
        return flag;
    };
    EXPECT_TRUE(literal(2, 1, 2));
    EXPECT_FALSE(lessLsbFirst(2, 1, 2));
}

SpanCommand rampCommand(int xl, int xr, double z0, double z1) {
    SpanCommand c;
    c.xl = xl;
    c.xr = xr;
    std::uint8_t overflow = 0;
    c.z = *lineThrough(xl, z0, xr, z1, 24, 0, overflow);
    c.r = *lineThrough(xl, 0, xr, 100, 16, 0, overflow);
    c.g = *lineThrough(xl, 65535, xr, 65535, 16, 0, overflow);
    c.b = *lineThrough(xl, 1000, xr, 0, 16, 0, overflow);
    EXPECT_EQ(overflow, kOverflowNone);
    return c;
}

TEST(SpanEngineTest, WriteEnableIsMaskAndNearer) {
    // Engine 1 (columns 64..127), span 70..90, z from 1000 to 3000 (100 per pixel).
    const SpanCommand c = rampCommand(70, 90, 1000, 3000);
    std::array<std::uint32_t, kEnginePixels> oldZ;
    oldZ.fill(2000);  // nearer than the new z from column 80 on (z(80) = 2000 is a tie: not written)
    const EngineOutput out = runEngine(1, c, oldZ);
    EXPECT_EQ(out.overflow, kOverflowNone);
    for (int k = 0; k < 64; ++k) {
        const int x = 64 + k;
        const bool inside = x >= 70 && x <= 90;
        SCOPED_TRACE(x);
        EXPECT_EQ((out.mask >> k) & 1u, inside ? 1u : 0u);
        if (inside) {
            EXPECT_EQ(out.z[std::size_t(k)], std::uint32_t(1000 + 100 * (x - 70)));
            EXPECT_EQ(out.g[std::size_t(k)], 65535u);
        }
        EXPECT_EQ((out.writeEnable >> k) & 1u, (inside && x < 80) ? 1u : 0u);
    }
    EXPECT_EQ(out.writeEnable, out.mask & out.zLess);
}

TEST(SpanEngineTest, OutputOverflowInsideTheMaskIsFlaggedAndClamped) {
    std::array<std::uint32_t, kEnginePixels> oldZ;
    oldZ.fill(0xFFFFFF);
    // Blue 1000 -> 0 over 10..20 runs below 0 right of column 20: outside the mask, not an overflow.
    SpanCommand c = rampCommand(10, 20, 5, 500);
    EXPECT_EQ(runEngine(0, c, oldZ).overflow, kOverflowNone);
    EXPECT_EQ(runEngine(0, c, oldZ).b[30], 0u) << "clamped outside the span, silently: never written";
    // A command whose blue line reaches −100 at column 20, inside the span: flagged, clamped to 0.
    std::uint8_t overflow = 0;
    c.b = *lineThrough(10, 900, 20, -100, 16, 0, overflow);
    const EngineOutput out = runEngine(0, c, oldZ);
    EXPECT_EQ(out.overflow, kOverflowOutput);
    EXPECT_EQ(out.b[20], 0u);
    EXPECT_EQ(out.b[19], 0u);  // 0
    EXPECT_EQ(out.b[18], 100u);
}

}  // namespace
}  // namespace frugal::span
