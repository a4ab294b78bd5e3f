// windowDepth's D24 quotient in float is the same as dividing in double and rounding to float
// (double rounding is harmless for a quotient when the wider format has at least 2p + 2 bits):
// checked for every 24-bit value.
#include <gtest/gtest.h>

#include <frugal/Image.h>

namespace frugal {
namespace {

TEST(WindowDepthTest, D24IsTheCorrectlyRoundedQuotientForEveryValue) {
    std::uint32_t differing = 0, first = 0;
    for (std::uint32_t v = 0; v <= kDepthMax; ++v)
        if (windowDepth(DepthFormat::D24, v) != float(double(v) / double(kDepthMax)) && differing++ == 0) first = v;
    EXPECT_EQ(differing, 0u) << "first at " << first;
    EXPECT_EQ(windowDepth(DepthFormat::D24, 0), 0.0f);
    EXPECT_EQ(windowDepth(DepthFormat::D24, kDepthMax), 1.0f);
}

}  // namespace
}  // namespace frugal
