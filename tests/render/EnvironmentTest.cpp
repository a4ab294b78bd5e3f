// The environment map (pipeline/Environment.h): the Radiance reader, the direction-to-map lookup
// the shaders share, and what prefiltering must give (a uniform map stays uniform; the diffuse
// light follows the bright side; rougher levels are smoother).
#include <cmath>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "pipeline/Environment.h"

namespace frugal {
namespace {

std::span<const std::uint8_t> bytesOf(const std::string& text) {
    return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

// Values RGBE holds exactly (8-bit mantissas under one shared exponent).
std::vector<float> exactPixels(int width, int height) {
    std::vector<float> rgb(std::size_t(width) * std::size_t(height) * 3);
    for (std::size_t i = 0; i < rgb.size(); i += 3) {
        const float scale = std::ldexp(1.0f, int(i / 3 % 7) - 3);
        rgb[i] = 200.0f / 256.0f * scale;
        rgb[i + 1] = float(i % 5) * 32.0f / 256.0f * scale;
        rgb[i + 2] = (i / 3) % 11 == 0 ? 0.0f : 64.0f / 256.0f * scale;
    }
    return rgb;
}

TEST(EnvironmentTest, ReadsFlatAndRunLengthEncodedScanLines) {
    for (const bool rle : {false, true}) {
        const int width = 40, height = 3;
        const std::vector<float> rgb = exactPixels(width, height);
        const Result<HdrImage> image = decodeRadianceHdr(bytesOf(test::radianceFile(width, height, rgb, rle)), "t.hdr");
        ASSERT_TRUE(image) << image.error().message;
        EXPECT_EQ(image->width, width);
        EXPECT_EQ(image->height, height);
        EXPECT_EQ(image->rgb, rgb) << (rle ? "run-length encoded" : "flat");
    }
    // A run-length encoded file of runs: a uniform image.
    const Result<HdrImage> uniform =
        decodeRadianceHdr(bytesOf(test::radianceFile(64, 2, std::vector<float>(64 * 2 * 3, 0.25f))), "u.hdr");
    ASSERT_TRUE(uniform) << uniform.error().message;
    for (const float v : uniform->rgb) ASSERT_EQ(v, 0.25f);
}

// The fuzzer's files (scripts/fuzz): its seeds, a flat and a run-length encoded image, are read;
// its findings are refused on one line that names the file (a header line with a carriage return,
// a size beyond 64 bits).
TEST(EnvironmentTest, TheFuzzFilesAreReadOrRefusedOnOneLine) {
    const std::filesystem::path dir = std::filesystem::path(FRUGAL_TEST_DATA_DIR) / "fuzz" / "hdr";
    for (const char* name : {"flat.hdr", "rle.hdr"}) {
        const Result<HdrImage> image = decodeRadianceHdr(bytesOf(test::readAll(dir / name)), name);
        ASSERT_TRUE(image) << image.error().message;
        EXPECT_EQ(image->height, 2) << name;
    }
    for (const char* name : {"resolution-with-carriage-return.hdr", "size-beyond-64-bits.hdr"}) {
        const Result<HdrImage> image = decodeRadianceHdr(bytesOf(test::readAll(dir / name)), name);
        ASSERT_FALSE(image) << name;
        EXPECT_EQ(image.error().message.rfind(std::string(name) + ": ", 0), 0u) << image.error().message;
        EXPECT_EQ(image.error().message.find_first_of("\r\n"), std::string::npos) << image.error().message;
    }
}

TEST(EnvironmentTest, RefusesBrokenFilesWithOneReason) {
    const std::string good = test::radianceFile(16, 2, exactPixels(16, 2));
    const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"", "t.hdr: not a Radiance file (no #? signature)"},
        {"P6\n1 1\n255\n", "t.hdr: not a Radiance file (no #? signature)"},
        {"#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n",
         "t.hdr: format '32-bit_rle_xyze' is not 32-bit_rle_rgbe (XYZE is not read)"},
        {"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n", "t.hdr: the header ends before the image's size"},
        {header + "+Y 2 +X 2\n",
         "t.hdr: resolution '+Y 2 +X 2': only top-to-bottom, left-to-right images (-Y H +X W) are read"},
        {header + "-Y two +X 2\n", "t.hdr: resolution '-Y two +X 2' is not '-Y H +X W'"},
        {header + "-Y 0 +X 2\n", "t.hdr: size 2x0 is not 1 to 67108864 pixels"},
        {header + "-Y 100000 +X 100000\n", "t.hdr: size 100000x100000 is not 1 to 67108864 pixels"},
        {header + "-Y 2 +X 2\nabcd", "t.hdr: the data ends in scan line 0"},
        {good.substr(0, good.size() - 3), "t.hdr: the data ends in scan line 1"},
        {header + "-Y 1 +X 8\n" + std::string("\x02\x02\x00\x09", 4),
         "t.hdr: scan line 0 says it is 9 pixels wide, not 8"},
        {header + "-Y 1 +X 8\n" + std::string("\x02\x02\x00\x08\x89\x01", 6),
         "t.hdr: scan line 0 runs past its 8 pixels"},
        {header + "-Y 1 +X 8\n" + std::string("\x02\x02\x00\x08\x00", 5), "t.hdr: scan line 0 runs past its 8 pixels"},
        {header + "-Y 1 +X 2\n" + std::string("\x01\x01\x01\x05\x10\x10\x10\x80", 8),
         "t.hdr: scan line 0 uses the old run-length encoding, which is not read"},
    };
    for (const auto& [bytes, message] : cases) {
        const Result<HdrImage> image = decodeRadianceHdr(bytesOf(bytes), "t.hdr");
        ASSERT_FALSE(image) << message;
        EXPECT_EQ(image.error().message, message);
    }
}

TEST(EnvironmentTest, TheLookupIsTheMapsAngles) {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
    for (int i = 0; i < 10000; ++i) {
        glm::vec3 d(coordinate(random), coordinate(random), coordinate(random));
        if (glm::length(d) < 1e-3f) continue;
        d = glm::normalize(d);
        const glm::vec2 uv = equirectUv(d);
        const double u = 0.5 + std::atan2(double(d.z), double(d.x)) / (2.0 * M_PI);
        const double v = std::acos(std::clamp(double(d.y), -1.0, 1.0)) / M_PI;
        ASSERT_NEAR(uv.x, u, 5e-6) << d.x << " " << d.y << " " << d.z;
        ASSERT_NEAR(uv.y, v, 3e-5) << d.x << " " << d.y << " " << d.z;
    }
    EXPECT_NEAR(equirectUv({0, 1, 0}).y, 0.0f, 1e-6f) << "+Y is the top row";
    EXPECT_NEAR(equirectUv({0, -1, 0}).y, 1.0f, 1e-6f);
    EXPECT_NEAR(equirectUv({1, 0, 0}).x, 0.5f, 1e-6f) << "+X the middle column";
    EXPECT_NEAR(equirectUv({0, 0, -1}).x, 0.25f, 1e-5f);
}

TEST(EnvironmentTest, AUniformMapPrefiltersToItsRadiance) {
    HdrImage image{96, 48, std::vector<float>(96 * 48 * 3, 0.25f)};
    const std::shared_ptr<const EnvironmentMap> map = prefilterEnvironment(image, "uniform", 2);
    EXPECT_NEAR(map->sh[0].r, 0.25f, 1e-4f);
    for (int i = 1; i < 9; ++i) EXPECT_NEAR(glm::length(map->sh[std::size_t(i)]), 0.0f, 1e-4f) << i;
    for (const EnvironmentMap::Level& level : map->specular)
        for (std::size_t i = 0; i < level.rgba.size(); i += 4) {
            ASSERT_NEAR(level.rgba[i], 0.25f, 1e-5f) << level.width;
            ASSERT_EQ(level.rgba[i + 3], 1.0f);
        }
    EXPECT_EQ(map->specular[0].width, EnvironmentMap::kWidth);
    EXPECT_EQ(map->specular[4].width, EnvironmentMap::kWidth >> 4);
}

TEST(EnvironmentTest, PrefilteringFollowsTheLightAndSmoothsWithRoughness) {
    const int width = 256, height = 128;
    HdrImage image{width, height, test::testSky(width, height)};
    const std::shared_ptr<const EnvironmentMap> map = prefilterEnvironment(image, "sky", 2);
    const auto diffuse = [&map](glm::vec3 n) {
        const float b[9] = {
            1, n.y, n.z, n.x, n.x * n.y, n.y * n.z, 3 * n.z * n.z - 1, n.x * n.z, n.x * n.x - n.y * n.y};
        glm::vec3 e(0.0f);
        for (int i = 0; i < 9; ++i) e += map->sh[std::size_t(i)] * b[i];
        return e;
    };
    // Against E(n)/π summed over the image's pixels: three bands of harmonics keep the cosine lobe
    // within 0.03 here (a sun 40 times the sky rings the most).
    const auto exact = [&image](glm::vec3 n) {
        glm::dvec3 e(0.0);
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                const double theta = (y + 0.5) / image.height * M_PI, phi = ((x + 0.5) / image.width - 0.5) * 2 * M_PI;
                const glm::dvec3 d(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
                const double c = glm::dot(d, glm::dvec3(n));
                const float* p = &image.rgb[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3];
                if (c > 0)
                    e += glm::dvec3(p[0], p[1], p[2]) *
                         (c * std::sin(theta) * (2 * M_PI / image.width) * (M_PI / image.height));
            }
        return glm::vec3(e / M_PI);
    };
    const glm::vec3 sun = glm::normalize(glm::vec3(0.5f, 0.7f, 0.3f));
    for (const glm::vec3 n :
         {sun, -sun, glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(1, 0, 0), glm::vec3(0, 0, -1)})
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(diffuse(n)[c], exact(n)[c], 0.03f) << n.x << " " << n.y << " " << n.z;
    EXPECT_GT(diffuse(sun).r, diffuse(-sun).r * 2.0f) << "the sun's side is lit";
    EXPECT_GT(diffuse({0, 1, 0}).b, diffuse({0, -1, 0}).b) << "the sky is above";
    // Each rougher level varies less from texel to texel (the sun spreads out).
    double previous = 1e30;
    for (const EnvironmentMap::Level& level : map->specular) {
        double peak = 0.0;
        for (std::size_t i = 0; i < level.rgba.size(); i += 4) peak = std::max(peak, double(level.rgba[i]));
        EXPECT_LT(peak, previous) << level.width;
        previous = peak;
    }
}

// The largest RGBE values (1.7e38), infinities, NaNs and negative values prefilter to finite
// levels and coefficients.
TEST(EnvironmentTest, ExtremeValuesPrefilterToFiniteLight) {
    HdrImage image{16, 8, std::vector<float>(16 * 8 * 3, 1.7e38f)};
    image.rgb[0] = std::numeric_limits<float>::infinity();
    image.rgb[4] = std::numeric_limits<float>::quiet_NaN();
    image.rgb[8] = -5.0f;
    const std::shared_ptr<const EnvironmentMap> map = prefilterEnvironment(image, "extreme", 1);
    for (const glm::vec3& c : map->sh)
        for (int k = 0; k < 3; ++k) ASSERT_TRUE(std::isfinite(c[k]));
    for (const EnvironmentMap::Level& level : map->specular)
        for (const float v : level.rgba) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << level.width;
}

TEST(EnvironmentTest, LoadsOnceAndSaysWhyNot) {
    const std::filesystem::path dir = test::freshDir("EnvironmentLoad");
    const std::string path = (dir / "sky.hdr").string();
    test::writeFile(path, test::radianceFile(64, 32, test::testSky(64, 32)));
    const Result<std::shared_ptr<const EnvironmentMap>> first = loadEnvironmentMap(path);
    ASSERT_TRUE(first) << first.error().message;
    EXPECT_EQ((*first)->sourceWidth, 64);
    EXPECT_GT((*first)->prefilterMs, 0.0);
    const Result<std::shared_ptr<const EnvironmentMap>> again = loadEnvironmentMap(path);
    ASSERT_TRUE(again);
    EXPECT_EQ(again->get(), first->get()) << "read once a process";

    const std::string missing = (dir / "none.hdr").string();
    const Result<std::shared_ptr<const EnvironmentMap>> none = loadEnvironmentMap(missing);
    ASSERT_FALSE(none);
    EXPECT_EQ(none.error().message, "environment-map " + missing + ": cannot open it (No such file or directory)");
    test::writeFile(dir / "text.hdr", "hello");
    const Result<std::shared_ptr<const EnvironmentMap>> text = loadEnvironmentMap((dir / "text.hdr").string());
    ASSERT_FALSE(text);
    EXPECT_EQ(text.error().message,
              "environment-map " + (dir / "text.hdr").string() + ": not a Radiance file (no #? signature)");
}

}  // namespace
}  // namespace frugal
