// Linear colour in the software reference (software/Shading.h): the sRGB decode table, the display
// encoding's table against the power it stands for, and the values a frame shows. The GL side of
// each is checked by the *GLTest suites, which compare whole frames with llvmpipe's.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "software/Shading.h"

namespace frugal::sw {
namespace {

TEST(ColorTest, EncodingTableEqualsThePowerAtEveryThresholdAndOnRandomFloats) {
    // Around each step of the table (where it could be off by one) and on floats of every exponent.
    for (int b = 1; b < 256; ++b) {
        std::uint32_t lo = 0, hi = 0x3F800000u;
        while (hi - lo > 1) {
            const std::uint32_t mid = lo + (hi - lo) / 2;
            (ColorEncoding::exact(std::bit_cast<float>(mid)) >= b ? hi : lo) = mid;
        }
        for (std::uint32_t bits = hi - 2; bits <= hi + 2; ++bits) {
            const float v = std::bit_cast<float>(bits);
            ASSERT_EQ(ColorEncoding::encode(v), ColorEncoding::exact(v)) << "byte " << b << ", v " << v;
        }
    }
    std::mt19937 random(20261205);
    std::uniform_int_distribution<std::uint32_t> bits(0, 0x3F900000u);  // +0 to just above 1
    for (int i = 0; i < 1000000; ++i) {
        const float v = std::bit_cast<float>(bits(random));
        ASSERT_EQ(ColorEncoding::encode(v), ColorEncoding::exact(v)) << v;
    }
}

TEST(ColorTest, EncodingIsTheKhronosRenderersPowerAndClamps) {
    EXPECT_EQ(ColorEncoding::encode(0.0f), 0);
    EXPECT_EQ(ColorEncoding::encode(-1.0f), 0);
    EXPECT_EQ(ColorEncoding::encode(std::nanf("")), 0);
    EXPECT_EQ(ColorEncoding::encode(1.0f), 255);
    EXPECT_EQ(ColorEncoding::encode(7.5f), 255);
    // The default light (pipeline/Backend.h): white facing the light 1.0, at right angles 0.3.
    EXPECT_EQ(ColorEncoding::encode(0.3f), 148);  // 255 · 0.3^(1/2.2) = 147.7
    EXPECT_EQ(ColorEncoding::encode(0.5f), 186);  // 186.0 (exact sRGB would give 188)
    EXPECT_EQ(ColorEncoding::encode(0.01f), 31);  // 31.4 (exact sRGB: 25)
}

TEST(ColorTest, SrgbDecodeIsGallivmsPolynomialWithinAThirdOfAStepOfTheCurve) {
    for (const bool fused : {false, true}) {
        const DecodeTable& table = srgbDecode(fused);
        EXPECT_EQ(table[0], 0.0f);
        EXPECT_EQ(table[15], 15.0f * float(1.0 / (12.6 * 255.0)));  // the linear segment's end
        for (int i = 1; i < 256; ++i) {
            EXPECT_GT(table[std::size_t(i)], table[std::size_t(i) - 1]) << i;  // monotonic
            // Back through the exact curve, each value lands within 0.35 of its byte (gallivm's
            // stated error; the d3d10 rule is 0.5).
            const double l = table[std::size_t(i)];
            const double s = l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
            EXPECT_NEAR(s * 255.0, double(i), 0.35) << i << (fused ? " fused" : "");
        }
        EXPECT_NEAR(table[255], 1.0f, 2e-4f);
    }
    // Values read back from llvmpipe (an RGBA32F target, GL_NEAREST) on an FMA host.
    EXPECT_EQ(srgbDecode(true)[1], 0x1.465aacp-12f);
    EXPECT_EQ(srgbDecode(true)[99], 0x1.014492p-3f);
    EXPECT_EQ(srgbDecode(true)[100], 0x1.06be54p-3f);
    EXPECT_EQ(srgbDecode(true)[101], 0x1.0c48fep-3f);
    EXPECT_EQ(unormDecode()[255], 1.0f);
}

}  // namespace
}  // namespace frugal::sw
