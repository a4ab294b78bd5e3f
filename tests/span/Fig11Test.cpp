// Fig. 11 of paper 001 (section IV), reproduced by the engine model, and the schemes that do not
// reproduce it (span/Fig11.h).
#include <gtest/gtest.h>

#include "lab/Fig11.h"

namespace frugal::span {
namespace {

TEST(SpanFig11Test, TheEngineModelPrintsEveryValueOfTheFigure) {
    const std::vector<Fig11Scheme> schemes = fig11Schemes();
    ASSERT_FALSE(schemes.empty());
    const Fig11Result r = runFig11(schemes.front());
    EXPECT_EQ(r.mismatches, 0);
    EXPECT_EQ(r.overflow, kOverflowNone);
    EXPECT_EQ(fig11Hex(r.channels[0]), "010 0A0 12F 1BF 24F 2DF 36F 3FF");
    EXPECT_EQ(fig11Hex(r.channels[1]), "0 1 2 3 4 5 6 7");
    EXPECT_EQ(fig11Hex(r.channels[2]), "7 6 5 4 3 2 1 0");
    EXPECT_EQ(fig11Hex(r.channels[3]), "3 3 2 2 1 1 1 0");
    // The text's red "0, 2, 2": the model (and every other scheme) has 1 at X = 3.
    EXPECT_EQ(r.doubtfulMismatches, 1);
    EXPECT_EQ(r.mask, 0x3FCu) << "pixels 2..9";
    EXPECT_EQ(r.writeEnable, 0x3FCu) << "a cleared z-buffer: every pixel of the span is written";
}

TEST(SpanFig11Test, FiveFractionBitsInTheSlopeSufficeFourDoNot) {
    const std::vector<Fig11Scheme> schemes = fig11Schemes();
    ASSERT_GE(schemes.size(), 3u);
    EXPECT_EQ(runFig11(schemes[1]).mismatches, 0) << schemes[1].name;
    EXPECT_GT(runFig11(schemes[2]).mismatches, 0) << schemes[2].name;
}

TEST(SpanFig11Test, TheExactLineGivesEither0A0Or12FNeverBoth) {
    Fig11Scheme rounded{"exact line, rounded", true, Rounding::Nearest, {}};
    Fig11Scheme truncated{"exact line, truncated", true, Rounding::Floor, {}};
    const Fig11Result a = runFig11(rounded), b = runFig11(truncated);
    EXPECT_EQ(a.channels[0].values[1], 0xA0);
    EXPECT_EQ(a.channels[0].values[2], 0x130) << "303.71 rounds to 304, the figure prints 12F";
    EXPECT_EQ(b.channels[0].values[1], 0x9F) << "159.86 truncates to 159, the figure prints 0A0";
    EXPECT_EQ(b.channels[0].values[2], 0x12F);
    EXPECT_GT(a.mismatches, 0);
    EXPECT_GT(b.mismatches, 0);
}

TEST(SpanFig11Test, EveryOtherNaturalSchemeMissesAPrintedValue) {
    const std::vector<Fig11Scheme> schemes = fig11Schemes();
    int matching = 0;
    for (const Fig11Scheme& scheme : schemes) {
        const Fig11Result r = runFig11(scheme);
        SCOPED_TRACE(scheme.name + ": z " + fig11Hex(r.channels[0]) + ", blue " + fig11Hex(r.channels[3]));
        if (r.mismatches == 0) ++matching;
        // No scheme prints the text's red 2 at X = 3 for a slope-1 ramp.
        EXPECT_EQ(r.channels[1].values[1], 1);
    }
    EXPECT_EQ(matching, 2) << "the engine at 16 and at 5 fraction bits of A and B, and nothing else";
}

}  // namespace
}  // namespace frugal::span
