// Mipmaps made on the CPU (pipeline/Mipmaps.h): level sizes as GL's, box averages of the area each
// texel covers, sRGB colour averaged in linear light.
#include <gtest/gtest.h>

#include "pipeline/Mipmaps.h"

namespace frugal {
namespace {

Texture texture(int w, int h, std::vector<std::uint8_t> rgba, bool srgb) {
    Texture t;
    t.width = w;
    t.height = h;
    t.rgba = std::move(rgba);
    t.srgb = srgb;
    t.mipmaps = MipFilter::Linear;
    return t;
}

// A row of grey texels of the given values (alpha = value).
Texture row(std::vector<std::uint8_t> values, bool srgb) {
    std::vector<std::uint8_t> rgba;
    for (std::uint8_t v : values) rgba.insert(rgba.end(), {v, v, v, v});
    return texture(int(values.size()), 1, std::move(rgba), srgb);
}

TEST(MipmapsTest, LevelsHalveRoundingDownToOneTexel) {
    EXPECT_EQ(mipLevelCount(1, 1), 1);
    EXPECT_EQ(mipLevelCount(64, 64), 7);
    EXPECT_EQ(mipLevelCount(5, 3), 3);
    EXPECT_EQ(mipLevelCount(1, 16), 5);
    EXPECT_EQ(mipLevelCount(37, 23), 6);
    const std::vector<MipLevel> levels = mipLevels(texture(5, 3, std::vector<std::uint8_t>(5 * 3 * 4, 9), false));
    ASSERT_EQ(levels.size(), 2u);
    EXPECT_EQ(levels[0].width, 2);
    EXPECT_EQ(levels[0].height, 1);
    EXPECT_EQ(levels[1].width, 1);
    EXPECT_EQ(levels[1].height, 1);
    for (const MipLevel& level : levels) {
        ASSERT_EQ(level.rgba.size(), std::size_t(level.width * level.height * 4));
        for (std::uint8_t v : level.rgba) EXPECT_EQ(v, 9);  // a uniform texture stays uniform
    }
    EXPECT_TRUE(mipLevels(texture(1, 1, {1, 2, 3, 4}, true)).empty());
    const std::vector<MipLevel> column = mipLevels(texture(1, 4, std::vector<std::uint8_t>(16, 0), false));
    ASSERT_EQ(column.size(), 2u);
    EXPECT_EQ(column[0].width, 1);
    EXPECT_EQ(column[0].height, 2);
}

TEST(MipmapsTest, EvenSizesAverageTwoByTwoRoundingToNearest) {
    // rgba texels (0, 10, 0, 255), (1, 20, 0, 255), (2, 30, 1, 0), (4, 41, 0, 0): linear data.
    const Texture t = texture(2, 2, {0, 10, 0, 255, 1, 20, 0, 255, 2, 30, 1, 0, 4, 41, 0, 0}, false);
    const std::vector<MipLevel> levels = mipLevels(t);
    ASSERT_EQ(levels.size(), 1u);
    // 7/4 = 1.75 → 2; 101/4 = 25.25 → 25; 1/4 → 0; 510/4 = 127.5 → 128
    EXPECT_EQ(levels[0].rgba, (std::vector<std::uint8_t>{2, 25, 0, 128}));
}

TEST(MipmapsTest, OddSizesWeighTheTexelsByTheAreaCovered) {
    // 3 → 1: a third each.
    EXPECT_EQ(mipLevels(row({0, 30, 90}, false))[0].rgba, (std::vector<std::uint8_t>{40, 40, 40, 40}));
    // 5 → 2: texel 0 covers [0, 2.5) (weights 0.4, 0.4, 0.2), texel 1 covers [2.5, 5).
    const std::vector<MipLevel> levels = mipLevels(row({10, 20, 30, 40, 50}, false));
    ASSERT_EQ(levels[0].width, 2);
    EXPECT_EQ(levels[0].rgba, (std::vector<std::uint8_t>{18, 18, 18, 18, 42, 42, 42, 42}));
}

TEST(MipmapsTest, SrgbColourIsAveragedInLinearLightAndAlphaAsItIs) {
    // Black and white average to linear 0.5, which is sRGB 0.7354 (188); alpha 127.5 → 128.
    EXPECT_EQ(mipLevels(row({0, 255}, true))[0].rgba, (std::vector<std::uint8_t>{188, 188, 188, 128}));
    EXPECT_EQ(mipLevels(row({0, 255}, false))[0].rgba, (std::vector<std::uint8_t>{128, 128, 128, 128}));
    // Every byte survives the sRGB curve both ways.
    for (int v = 0; v < 256; ++v) {
        const std::vector<MipLevel> levels = mipLevels(row({std::uint8_t(v), std::uint8_t(v)}, true));
        ASSERT_EQ(levels[0].rgba[0], v);
    }
}

}  // namespace
}  // namespace frugal
