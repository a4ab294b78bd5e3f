// The per-span API (span/Interp.h) and the error tables (span/ErrorTable.h): the
// paper's claim (III.2) that midpoint subdivision avoids the error add-and-shift accumulates, as
// bounds on the error against the exact line, and overflow reported instead of wrapped.
#include <array>
#include <vector>

#include <gtest/gtest.h>

#include "lab/ErrorTable.h"
#include "span/Interp.h"

namespace frugal::span {
namespace {

TEST(SpanInterpTest, EveryModeFillsAnExactRampExactly) {
    for (Interp mode : {Interp::Exact, Interp::Span, Interp::Dda}) {
        std::vector<std::uint32_t> out(300, 0xDEAD);
        const FillResult r = fillSpan(mode, {50, 350, 1000.0, 3.0, 16}, out);
        SCOPED_TRACE(toString(mode));
        EXPECT_TRUE(r.ok()) << describeOverflow(r.overflow);
        for (int k = 0; k < 300; ++k) ASSERT_EQ(out[std::size_t(k)], std::uint32_t(1000 + 3 * k)) << k;
    }
}

TEST(SpanInterpTest, EmptySpanWritesNothing) {
    std::array<std::uint32_t, 1> out{42};
    for (Interp mode : {Interp::Exact, Interp::Span, Interp::Dda})
        EXPECT_TRUE(fillSpan(mode, {10, 10, 5.0, 1.0, 16}, std::span<std::uint32_t>(out.data(), 0)).ok());
    EXPECT_EQ(out[0], 42u);
}

TEST(SpanInterpTest, OutOfRangeValuesAreFlaggedAndClampedNotWrapped) {
    // 0.. 65535 + 10: columns 100.. run past the top of 16 bits.
    for (Interp mode : {Interp::Exact, Interp::Span, Interp::Dda}) {
        SCOPED_TRACE(toString(mode));
        std::vector<std::uint32_t> out(120);
        const FillResult r = fillSpan(mode, {0, 120, 65000.0, 6.0, 16}, out);  // 65000 + 6·90 = 65540 at column 90
        EXPECT_EQ(r.overflow, kOverflowOutput);
        EXPECT_EQ(r.firstOverflowColumn, 90);  // 65000 + 6·89 = 65534 fits, 65540 does not
        EXPECT_EQ(out[89], 65534u);
        EXPECT_EQ(out[90], 65535u) << "clamped to the top, not wrapped to 4";
        EXPECT_EQ(out[119], 65535u);
        // Below zero.
        const FillResult down = fillSpan(mode, {0, 10, 3.0, -1.0, 16}, out);
        EXPECT_EQ(down.firstOverflowColumn, 4);
        EXPECT_EQ(out[4], 0u);
    }
}

TEST(SpanInterpTest, ASlopeTheFormatCannotHoldIsReported) {
    std::vector<std::uint32_t> out(4, 7);
    const FillResult span = fillSpan(Interp::Span, {0, 4, 0.0, 70000.0, 16}, out);
    EXPECT_EQ(span.overflow, kOverflowSlope);
    EXPECT_EQ(out[0], 0u) << "nothing computed: zeros, flagged";
    const FillResult dda = fillSpan(Interp::Dda, {0, 4, 0.0, 70000.0, 16}, out);
    EXPECT_EQ(dda.overflow, kOverflowSlope);
    const FillResult nan = fillSpan(Interp::Span, {0, 4, 0.0, std::nan(""), 16}, out);
    EXPECT_EQ(nan.overflow, kOverflowSlope);
    const FillResult exactNan = fillSpan(Interp::Exact, {0, 4, std::nan(""), 0.0, 16}, out);
    EXPECT_EQ(exactNan.overflow, kOverflowOutput);
}

TEST(SpanInterpTest, SpanModeMatchesTheEngineBlocksAcrossEngineBoundaries) {
    // A span over engines 0..2: every pixel equals what runEngine's channel gives for its engine.
    std::uint8_t overflow = 0;
    const std::optional<ChannelLine> line = lineFromSlope(40, 12345.0, 97.3, 24, overflow);
    ASSERT_TRUE(line);
    std::vector<std::uint32_t> out(120);
    ASSERT_TRUE(fillSpan(Interp::Span, {40, 160, 12345.0, 97.3, 24}, out).ok());
    for (int engine = 0; engine <= 2; ++engine) {
        std::array<std::int64_t, kEnginePixels> values{};
        ASSERT_TRUE(interpolateEngine(engine, *line, EngineConfig{}, values, overflow));
        for (int k = 0; k < 64; ++k) {
            const int x = 64 * engine + k;
            if (x >= 40 && x < 160) {
                ASSERT_EQ(out[std::size_t(x - 40)], std::uint64_t(values[std::size_t(k)])) << x;
            }
        }
    }
}

TEST(SpanInterpTest, SpanEndingAtTheTopCanExceedItByOneLsb) {
    // 0 -> 2^24 − 1 over columns 32..96 (65 pixels, slope 262143.98). Engine 0's ends are
    // f(0) = −8388607.5 and f(64) = 8388607.5, both ties, both rounded up: the tree's f(32) is 0.5,
    // which rounds to 1. Engine 1 likewise ends the span at 2^24: one LSB over the top. Hardware
    // with a 24-bit output would wrap it to 0 (the nearest z there is); the model flags and clamps.
    const double top = double((1 << 24) - 1);
    std::vector<std::uint32_t> out(65);
    const FillResult r = fillSpan(Interp::Span, {32, 97, 0.0, top / 64.0, 24}, out);
    EXPECT_EQ(r.overflow, kOverflowOutput);
    EXPECT_EQ(r.firstOverflowColumn, 96);
    EXPECT_EQ(out[0], 1u);
    EXPECT_EQ(out[64], std::uint32_t(top));
    // The exact evaluation stays inside.
    EXPECT_TRUE(fillSpan(Interp::Exact, {32, 97, 0.0, top / 64.0, 24}, out).ok());
}

// The rows of one table by method.
const ErrorRow& rowOf(const std::vector<ErrorRow>& rows, int width, int length, Method method) {
    for (const ErrorRow& r : rows)
        if (r.width == width && r.length == length && r.method == method) return r;
    static const ErrorRow none;
    ADD_FAILURE() << "no row " << width << " " << length << " " << methodName(method);
    return none;
}

TEST(SpanErrorTableTest, MidpointSubdivisionStaysWithinOneLsbAtEveryLengthAndWidth) {
    ErrorTableSettings settings;
    settings.lengths = {2, 8, 64, 65, 512, 8192};
    settings.widths = {8, 12, 16, 24, 28};
    settings.spans = 60;
    settings.methods = {Method::Span};
    for (const ErrorRow& r : errorTable(settings)) {
        SCOPED_TRACE("width " + std::to_string(r.width) + ", length " + std::to_string(r.length));
        EXPECT_LE(r.worstLsb, 1);
        EXPECT_LT(r.meanLsb, 0.5);
        // Ramps that end at 0 or at the top may leave the range by 1 LSB (flagged, clamped: see
        // SpanEndingAtTheTopCanExceedItByOneLsb), so overflowSpans is not asserted here.
        EXPECT_EQ(r.pixels, std::int64_t(r.length) * 60);
    }
}

TEST(SpanErrorTableTest, DdaErrorGrowsWithTheSpanLength) {
    ErrorTableSettings settings;
    settings.lengths = {8, 64, 512, 8192};
    settings.widths = {24};
    settings.spans = 100;
    settings.methods = {Method::Dda, Method::Span};
    const std::vector<ErrorRow> rows = errorTable(settings);
    // A 32-bit register leaves 8 fraction bits at 24 bits: the rounded step is off by up to 2^-9 LSB
    // a pixel, 16 LSB after 8192 pixels.
    const ErrorRow& short8 = rowOf(rows, 24, 8, Method::Dda);
    const ErrorRow& long8192 = rowOf(rows, 24, 8192, Method::Dda);
    EXPECT_LE(short8.worstLsb, 1);
    EXPECT_GT(long8192.worstLsb, 4);
    EXPECT_LE(long8192.worstLsb, 17);
    EXPECT_GT(long8192.worstLsb, rowOf(rows, 24, 512, Method::Dda).worstLsb);
    EXPECT_GT(rowOf(rows, 24, 512, Method::Dda).meanLsb, rowOf(rows, 24, 64, Method::Dda).meanLsb);
    EXPECT_GT(long8192.meanLsb, rowOf(rows, 24, 512, Method::Dda).meanLsb);
    EXPECT_GT(long8192.meanLsb, 10 * rowOf(rows, 24, 8192, Method::Span).meanLsb);
    EXPECT_LE(rowOf(rows, 24, 8192, Method::Span).worstLsb, 1);
}

TEST(SpanErrorTableTest, WiderAccumulatorOrNarrowerChannelKeepsDdaClose) {
    // At 16 bits a 32-bit register has 16 fraction bits: 8192·2^-17 = 1/16 LSB of drift.
    ErrorTableSettings settings;
    settings.lengths = {8192};
    settings.widths = {16};
    settings.spans = 50;
    settings.methods = {Method::Dda};
    EXPECT_LE(errorTable(settings).front().worstLsb, 1);
}

TEST(SpanErrorTableTest, TruncatingEachLevelAsAddAndShiftDoesIsWorse) {
    ErrorTableSettings settings;
    settings.lengths = {64, 8192};
    settings.widths = {16};
    settings.spans = 100;
    settings.methods = {Method::SpanTruncating, Method::Span};
    const std::vector<ErrorRow> rows = errorTable(settings);
    for (int length : {64, 8192}) {
        EXPECT_GE(rowOf(rows, 16, length, Method::SpanTruncating).worstLsb, 2) << length;
        EXPECT_GT(rowOf(rows, 16, length, Method::SpanTruncating).meanLsb, rowOf(rows, 16, length, Method::Span).meanLsb);
    }
}

TEST(SpanErrorTableTest, DoubleEvaluationAgreesWithTheExactLine) {
    ErrorTableSettings settings;
    settings.spans = 100;
    settings.methods = {Method::Exact};
    for (const ErrorRow& r : errorTable(settings)) EXPECT_LE(r.worstLsb, 1) << r.width << " " << r.length;
}

TEST(SpanErrorTableTest, TheSameSeedGivesTheSameTable) {
    ErrorTableSettings settings;
    settings.lengths = {64};
    settings.spans = 20;
    const std::vector<ErrorRow> a = errorTable(settings), b = errorTable(settings);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].worstLsb, b[i].worstLsb);
        EXPECT_EQ(a[i].meanLsb, b[i].meanLsb);
    }
}

}  // namespace
}  // namespace frugal::span
