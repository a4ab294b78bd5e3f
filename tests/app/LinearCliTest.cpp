// render --linear FILE through the command line (the real binary): a PFM of the frame's linear
// colour (rgb float32, rows bottom-up) or a 16-bit PNG; the -o image beside it is that colour's
// display encoding (on the software reference, byte for byte the image without --linear); a
// sequence names each frame's file like the others; a wrong name is one error line.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "CliSupport.h"
#include "TestSupport.h"
#include "io/ImageIO.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::readAll;
using test::runFrugal;

// A PFM "PF" file's size and floats (rgb, bottom row first); nothing when it is not one.
struct Pfm {
    int width = 0, height = 0;
    std::vector<float> rgb;
};
std::optional<Pfm> readPfm(const fs::path& path) {
    const std::string bytes = readAll(path);
    Pfm pfm;
    char scale[16] = {};
    int consumed = 0;
    if (std::sscanf(bytes.c_str(), "PF\n%d %d\n%15s\n%n", &pfm.width, &pfm.height, scale, &consumed) != 3) return {};
    if (std::string(scale) != "-1.0" || consumed == 0) return {};
    const std::size_t values = std::size_t(pfm.width) * std::size_t(pfm.height) * 3;
    if (bytes.size() != std::size_t(consumed) + values * 4) return {};
    pfm.rgb.resize(values);
    std::memcpy(pfm.rgb.data(), bytes.data() + consumed, values * 4);
    return pfm;
}

TEST(LinearCliTest, PfmAndPngOfTheLinearColour) {
    const fs::path dir = test::freshDir("LinearCli");
    const std::vector<std::string> scene = {"render",  "builtin:materials", "--size",
                                            "160x120", "--backend",         "software"};
    const std::vector<std::uint8_t> plain = test::renderedPixels(dir, "plain", scene);
    std::vector<std::string> args = scene;
    args.insert(args.end(), {"--linear", "linear.pfm"});
    const std::vector<std::uint8_t> encoded = test::renderedPixels(dir, "encoded", args);
    EXPECT_EQ(encoded, plain) << "the display encoding of the linear colour: the 8-bit render's bytes";

    const std::optional<Pfm> pfm = readPfm(dir / "linear.pfm");
    ASSERT_TRUE(pfm) << "not a PF file of 160x120";
    EXPECT_EQ(pfm->width, 160);
    EXPECT_EQ(pfm->height, 120);
    // Row 0 of the PFM is the bottom row, the PNG's last: each value encodes to the PNG's byte.
    std::size_t lit = 0;
    for (int y = 0; y < 120; ++y)
        for (int x = 0; x < 160; ++x)
            for (int c = 0; c < 3; ++c) {
                const float value = pfm->rgb[(std::size_t(y) * 160 + std::size_t(x)) * 3 + std::size_t(c)];
                const std::uint8_t byte = plain[(std::size_t(119 - y) * 160 + std::size_t(x)) * 4 + std::size_t(c)];
                ASSERT_EQ(displayLevel(value), byte) << x << "," << y << " channel " << c;
                lit += value > 0.2f;
            }
    EXPECT_GT(lit, 1000u);

    args = scene;
    args.insert(args.end(), {"--linear", "linear.png", "-o", "again.png", "-q"});
    const CliRun run = runFrugal(dir, args);
    ASSERT_EQ(run.status, 0) << run.err;
    Result<DecodedImage> png = readPng((dir / "linear.png").string());
    ASSERT_TRUE(png) << png.error().message;
    EXPECT_EQ(png->bitDepth, 16);
    EXPECT_EQ(png->channels, 4);
    // The PNG's top-left pixel is the PFM's first value of its last row, in 65535 steps.
    const float topLeft = pfm->rgb[std::size_t(119) * 160 * 3];
    EXPECT_EQ(png->pixels16[0], std::uint16_t(std::nearbyint(std::fmin(topLeft, 1.0f) * 65535.0)));
}

TEST(LinearCliTest, ASequenceNamesEachFrame) {
    const fs::path dir = test::freshDir("LinearCliFrames");
    const CliRun run = runFrugal(dir, {"render", "builtin:default", "--size", "64x48", "--frames", "0:1", "-o",
                                       "f_%02d.png", "--linear", "l_%02d.pfm", "-q"});
    ASSERT_EQ(run.status, 0) << run.err;
    for (const char* name : {"l_00.pfm", "l_01.pfm", "f_00.png", "f_01.png"})
        EXPECT_TRUE(fs::exists(dir / name)) << name;
}

TEST(LinearCliTest, AWrongNameIsOneLine) {
    test::expectOneErrorLine(
        test::freshDir("LinearCliBad"),
        {{{"render", "--linear", "out.exr"}, "error: --linear out.exr: name it .pfm (float32) or .png (16-bit)"},
         {{"render", "--frames", "0:1", "--linear", "a%d%d.pfm"},
          "error: --linear a%d%d.pfm: at most one %d (or %0Nd) and no other % in a file name"}});
}

}  // namespace
}  // namespace frugal
