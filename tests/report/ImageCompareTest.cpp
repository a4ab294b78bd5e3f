// Image comparison metrics on small constructed images whose answers are known by hand.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestSupport.h"
#include "lab/ImageCompare.h"

namespace frugal {
namespace {

// A width×height image filled with one colour; ids and depth only when asked for.
Buffers solid(int width, int height, std::array<std::uint8_t, 4> rgba, bool withIds = false, bool withDepth = false) {
    Buffers b;
    b.width = width;
    b.height = height;
    for (std::size_t i = 0; i < b.pixelCount(); ++i) b.rgba.insert(b.rgba.end(), rgba.begin(), rgba.end());
    if (withIds) b.ids.assign(b.pixelCount(), 0);
    if (withDepth) b.depth.assign(b.pixelCount(), kDepthMax);
    return b;
}

// Buffers rows are bottom-up: window (x, y) → index.
std::size_t at(const Buffers& b, int x, int windowY) { return std::size_t(windowY) * b.width + x; }

std::array<std::uint8_t, 4> pixel(const Buffers& b, std::size_t i) {
    return {b.rgba[4 * i], b.rgba[4 * i + 1], b.rgba[4 * i + 2], b.rgba[4 * i + 3]};
}

ImageComparison compare(const Buffers& a, const Buffers& r, int tolerance = 0,
                        std::optional<std::array<std::uint8_t, 4>> background = std::nullopt) {
    Result<ImageComparison> c = compareBuffers(a, r, CompareOptions{tolerance, background});
    EXPECT_TRUE(c) << c.error().message;
    return c ? *c : ImageComparison{};
}

TEST(ImageCompareTest, IdenticalImagesHaveNoDifferenceAndInfinitePsnr) {
    const Buffers a = solid(8, 4, {10, 20, 30, 255}, true, true);
    const ImageComparison c = compare(a, a);
    EXPECT_TRUE(c.passed());
    EXPECT_TRUE(c.identical());
    EXPECT_EQ(c.failingPixels, 0u);
    EXPECT_EQ(c.maxChannelDifference, 0);
    EXPECT_FALSE(c.worstPixel);
    EXPECT_TRUE(std::isinf(c.psnr) && c.psnr > 0);
    EXPECT_EQ(formatPsnr(c.psnr), "inf");
    EXPECT_EQ(c.coverageSource, ImageComparison::CoverageSource::Ids);
    EXPECT_EQ(c.coverageMismatches(), 0u);
    ASSERT_TRUE(c.idMismatches);
    EXPECT_EQ(*c.idMismatches, 0u);
    ASSERT_TRUE(c.depth);
    EXPECT_EQ(c.depth->maxDifference, 0u);
    const nlohmann::json j = nlohmann::json::parse(comparisonJson(c));
    EXPECT_TRUE(j["psnr_db"].is_null());
    EXPECT_TRUE(j["identical"].get<bool>());
    EXPECT_EQ(j["failing_pixels"], 0);
}

TEST(ImageCompareTest, OnePixelOffByThreeFailsAtToleranceTwoAndPassesAtThree) {
    const Buffers reference = solid(4, 4, {100, 100, 100, 255});
    Buffers actual = reference;
    actual.rgba[4 * at(actual, 1, 3) + 1] = 103;  // window (1, 3) = top row of a 4-high image

    const ImageComparison strict = compare(actual, reference, 2);
    EXPECT_FALSE(strict.passed());
    EXPECT_EQ(strict.failingPixels, 1u);
    EXPECT_EQ(strict.maxChannelDifference, 3);
    ASSERT_TRUE(strict.worstPixel);
    EXPECT_EQ(strict.worstPixel->x, 1);
    EXPECT_EQ(strict.worstPixel->y, 0) << "reported in file coordinates, top row 0";
    // MSE = 9 / (16 pixels × 4 channels).
    EXPECT_NEAR(strict.psnr, 10.0 * std::log10(255.0 * 255.0 / (9.0 / 64.0)), 1e-9);

    const ImageComparison loose = compare(actual, reference, 3);
    EXPECT_TRUE(loose.passed());
    EXPECT_EQ(loose.failingPixels, 0u);
    EXPECT_EQ(loose.maxChannelDifference, 3);
    EXPECT_FALSE(loose.identical());
}

TEST(ImageCompareTest, AlphaCountsLikeAnyChannel) {
    const Buffers reference = solid(2, 2, {0, 0, 0, 255});
    Buffers actual = reference;
    actual.rgba[3] = 250;
    EXPECT_EQ(compare(actual, reference, 4).failingPixels, 1u);
    EXPECT_EQ(compare(actual, reference, 5).failingPixels, 0u);
}

TEST(ImageCompareTest, CoverageAndIdMismatchesFromIds) {
    Buffers reference = solid(4, 2, {50, 50, 50, 255}, true, true);
    Buffers actual = reference;
    // Pixel 0: geometry in actual only. Pixel 1: geometry in reference only. Pixel 2: both, other
    // triangle. Pixel 3: both, same triangle, depth off by 7 LSB. Pixels 4..7: background in both.
    actual.ids[0] = 5;
    reference.ids[1] = 6;
    actual.ids[2] = 7, reference.ids[2] = 8;
    actual.ids[3] = reference.ids[3] = 9;
    actual.depth[0] = 100;                  // covered on one side only: not a depth comparison
    actual.depth[2] = reference.depth[2] = 1000;
    actual.depth[3] = 2007, reference.depth[3] = 2000;
    const ImageComparison c = compare(actual, reference);
    EXPECT_TRUE(c.passed()) << "ids and depth do not decide the verdict";
    EXPECT_EQ(c.coverageSource, ImageComparison::CoverageSource::Ids);
    EXPECT_EQ(c.coveredOnlyInActual, 1u);
    EXPECT_EQ(c.coveredOnlyInReference, 1u);
    EXPECT_EQ(c.coverageMismatches(), 2u);
    ASSERT_TRUE(c.idMismatches);
    EXPECT_EQ(*c.idMismatches, 1u);
    ASSERT_TRUE(c.depth);
    EXPECT_EQ(c.depth->comparedPixels, 2u);
    EXPECT_EQ(c.depth->differingPixels, 1u);
    EXPECT_EQ(c.depth->maxDifference, 7u);
    ASSERT_TRUE(c.depth->worstPixel);
    EXPECT_EQ(c.depth->worstPixel->x, 3);
    EXPECT_EQ(c.depth->worstPixel->y, 1);  // window row 0 of a 2-high image is the file's row 1

    const nlohmann::json j = nlohmann::json::parse(comparisonJson(c));
    EXPECT_EQ(j["coverage"]["source"], "ids");
    EXPECT_EQ(j["coverage"]["mismatches"], 2);
    EXPECT_EQ(j["id_mismatches"], 1);
    EXPECT_EQ(j["depth"]["max_difference_lsb"], 7);
}

TEST(ImageCompareTest, IdsOnOneSideOnlyFallBackToTheBackgroundColour) {
    const std::array<std::uint8_t, 4> bg = {31, 33, 38, 255};
    Buffers reference = solid(3, 1, bg, true);
    Buffers actual = solid(3, 1, bg);
    actual.rgba[0] = 200;  // geometry in actual only
    actual.rgba[4] = 33;   // 2 steps off the background: background at tolerance 2, geometry at 1
    const ImageComparison loose = compare(actual, reference, 2, bg);
    EXPECT_EQ(loose.coverageSource, ImageComparison::CoverageSource::BackgroundColor);
    EXPECT_FALSE(loose.idMismatches);
    EXPECT_EQ(loose.coveredOnlyInActual, 1u);
    EXPECT_EQ(loose.coveredOnlyInReference, 0u);
    EXPECT_EQ(compare(actual, reference, 1, bg).coveredOnlyInActual, 2u);
    // Neither ids on both sides nor a background colour: coverage is not measured.
    const ImageComparison none = compare(actual, reference, 2);
    EXPECT_EQ(none.coverageSource, ImageComparison::CoverageSource::None);
    EXPECT_TRUE(nlohmann::json::parse(comparisonJson(none))["coverage"].is_null());
}

TEST(ImageCompareTest, MaskIsRedWhereAPixelFailsAndTheReferenceInGreyElsewhere) {
    Buffers reference = solid(2, 2, {255, 255, 255, 255});
    reference.rgba[4 * 1 + 0] = 200, reference.rgba[4 * 1 + 1] = 100, reference.rgba[4 * 1 + 2] = 50;
    reference.rgba[4 * 2 + 0] = 0, reference.rgba[4 * 2 + 1] = 0, reference.rgba[4 * 2 + 2] = 0;
    Buffers actual = reference;
    actual.rgba[4 * 3 + 2] = 0;  // pixel 3 fails
    const ImageComparison c = compare(actual, reference, 10);
    ASSERT_EQ(c.mask.width, 2);
    ASSERT_EQ(c.mask.height, 2);
    EXPECT_EQ(pixel(c.mask, 0), (std::array<std::uint8_t, 4>{255, 255, 255, 255}));
    // (77·200 + 150·100 + 29·50 + 128) >> 8 = 31978 >> 8 = 124
    EXPECT_EQ(pixel(c.mask, 1), (std::array<std::uint8_t, 4>{124, 124, 124, 255}));
    EXPECT_EQ(pixel(c.mask, 2), (std::array<std::uint8_t, 4>{0, 0, 0, 255}));
    EXPECT_EQ(pixel(c.mask, 3), (std::array<std::uint8_t, 4>{255, 0, 0, 255}));
}

TEST(ImageCompareTest, BadInputsAreErrorsWithTheNumbers) {
    const Buffers a = solid(4, 3, {0, 0, 0, 255});
    Result<ImageComparison> size = compareBuffers(a, solid(3, 4, {0, 0, 0, 255}));
    ASSERT_FALSE(size);
    EXPECT_EQ(size.error().message, "size differs: actual 4x3, reference 3x4");
    Result<ImageComparison> tolerance = compareBuffers(a, a, {256, std::nullopt});
    ASSERT_FALSE(tolerance);
    EXPECT_EQ(tolerance.error().message, "tolerance 256 is outside 0..255 (8-bit steps)");
    Buffers shortIds = a;
    shortIds.ids.assign(5, 1);
    Result<ImageComparison> ids = compareBuffers(a, shortIds);
    ASSERT_FALSE(ids);
    EXPECT_EQ(ids.error().message, "reference: 5 ids for 12 pixels");
}

TEST(ImageCompareTest, PngsRoundTripIntoBuffers) {
    Buffers render = solid(3, 2, {1, 2, 3, 4}, true);
    render.rgba[0] = 99;             // window (0, 0): the file's bottom-left
    render.ids[5] = 0x04030201u;     // window (2, 1): the file's top-right
    const std::filesystem::path dir = test::freshDir("ImageComparePng");
    const std::string color = (dir / "c.png").string(), ids = (dir / "i.png").string();
    ASSERT_TRUE(writeFileAtomic(color, encodeColorPng(render)));
    ASSERT_TRUE(writeFileAtomic(ids, encodeIdPng(render)));
    Result<Buffers> back = readRenderPngs(color, ids);
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(back->rgba, render.rgba);
    EXPECT_EQ(back->ids, render.ids);

    // An RGB PNG gets alpha 255; a grey one is copied to all three colour channels.
    const std::uint8_t rgb[3] = {7, 8, 9}, grey[1] = {42};
    ASSERT_TRUE(writeFileAtomic((dir / "rgb.png").string(), encodePng(1, 1, 3, 8, rgb)));
    ASSERT_TRUE(writeFileAtomic((dir / "grey.png").string(), encodePng(1, 1, 1, 8, grey)));
    EXPECT_EQ(readRenderPngs((dir / "rgb.png").string())->rgba, (std::vector<std::uint8_t>{7, 8, 9, 255}));
    EXPECT_EQ(readRenderPngs((dir / "grey.png").string())->rgba, (std::vector<std::uint8_t>{42, 42, 42, 255}));

    // Errors name the file.
    const std::uint16_t deep[1] = {1000};
    ASSERT_TRUE(writeFileAtomic((dir / "deep.png").string(), encodePng(1, 1, 1, 16, deep)));
    Result<Buffers> sixteen = readRenderPngs((dir / "deep.png").string());
    ASSERT_FALSE(sixteen);
    EXPECT_EQ(sixteen.error().message, (dir / "deep.png").string() + ": 16-bit PNG; colour images are compared as 8-bit");
    Result<Buffers> wrongIds = readRenderPngs(color, (dir / "rgb.png").string());
    ASSERT_FALSE(wrongIds);
    EXPECT_EQ(wrongIds.error().message, (dir / "rgb.png").string() +
                                    ": not a triangle-id image: 8-bit with 3 channels, expected 8-bit RGBA");
    Result<Buffers> missing = readRenderPngs((dir / "none.png").string());
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().message, (dir / "none.png").string() + ": cannot open");
}

TEST(ImageCompareTest, SummaryNamesTheSides) {
    Buffers reference = solid(2, 1, {0, 0, 0, 255}, true);
    Buffers actual = reference;
    actual.ids[0] = 3;
    actual.rgba[0] = 9;
    const std::string text = comparisonSummary(compare(actual, reference, 2), "gl", "software");
    EXPECT_EQ(text,
              "  pixels beyond tolerance 2: 1 of 2 (50.00%)\n"
              "  largest channel difference: 9 at (0, 0); PSNR " + formatPsnr(compare(actual, reference).psnr) + "\n"
              "  coverage mismatches (from ids): 1 (geometry only in gl: 1, only in software: 0)\n"
              "  triangle-id mismatches: 0\n");
}

}  // namespace
}  // namespace frugal
