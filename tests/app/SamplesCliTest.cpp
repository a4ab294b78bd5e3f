// --samples through the command line (the real binary): 4 samples smooth the edges (pixels between
// a surface and the background that neither has alone) and leave the inside of surfaces as one
// sample draws it; 2 draws as 4 on llvmpipe and on the software reference; GL and the software
// reference agree (frugal diff: coverage, ids and depth exact); reuse, the adaptive z-buffer and the
// exact culling methods keep their images byte for byte when multisampled; what cannot be is one line.
#include <filesystem>
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

const auto render = test::renderedPixels;

TEST(SamplesCliTest, FourSamplesSmoothTheEdgesOnly) {
    const fs::path dir = test::freshDir("SamplesCli");
    const std::vector<std::string> scene = {"render", "builtin:cubes", "--size", "200x150", "--background", "0,0,0"};
    const auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = scene;
        args.insert(args.end(), extra.begin(), extra.end());
        return args;
    };
    const std::vector<std::uint8_t> one = render(dir, "one", scene);
    render(dir, "one-given", with({"--samples", "1"}));
    EXPECT_EQ(readAll(dir / "one.png"), readAll(dir / "one-given.png"));
    for (const char* backend : {"auto", "software"}) {
        SCOPED_TRACE(backend);
        const std::vector<std::uint8_t> four =
            render(dir, std::string("four-") + backend, with({"--samples", "4", "--backend", backend}));
        render(dir, std::string("two-") + backend, with({"--samples", "2", "--backend", backend}));
        EXPECT_EQ(readAll(dir / (std::string("four-") + backend + ".png")),
                  readAll(dir / (std::string("two-") + backend + ".png")))
            << "2 samples are drawn as llvmpipe's 4";
        ASSERT_EQ(four.size(), one.size());
        // Edge pixels: background in one image, partly covered (neither black nor the surface's
        // colour) in the other. The inside of a surface is the same colour either way.
        std::size_t blended = 0, same = 0, covered = 0;
        for (std::size_t i = 0; i < one.size(); i += 4) {
            const bool black1 = one[i] == 0 && one[i + 1] == 0 && one[i + 2] == 0;
            const bool black4 = four[i] == 0 && four[i + 1] == 0 && four[i + 2] == 0;
            covered += !black1;
            same += !black1 && one[i] == four[i] && one[i + 1] == four[i + 1] && one[i + 2] == four[i + 2];
            blended += black1 != black4 || (!black1 && (one[i] != four[i] || one[i + 1] != four[i + 1]));
        }
        EXPECT_GT(blended, 200u);
        EXPECT_GT(same, covered * 8 / 10) << "most covered pixels are inside a surface";
        EXPECT_LT(blended, covered / 4);
    }
    const CliRun diff = runFrugal(
        dir, {"diff", "builtin:cubes", "--size", "200x150", "--samples", "4", "--tolerance", "1", "--out", "diff"});
    EXPECT_EQ(diff.status, 0) << diff.out << diff.err;
    EXPECT_NE(diff.out.find("coverage mismatches (from ids): 0"), std::string::npos) << diff.out;
    EXPECT_NE(diff.out.find("triangle-id mismatches: 0"), std::string::npos) << diff.out;
    EXPECT_NE(diff.out.find("largest difference 0 LSB"), std::string::npos) << diff.out;
}

// The methods that promise the plain render's image keep it, multisampled, on both backends.
TEST(SamplesCliTest, ExactMethodsKeepTheirImages) {
    const fs::path dir = test::freshDir("SamplesCliMethods");
    const std::string bunny = FRUGAL_BUNNY_OBJ;
    for (const char* backend : {"auto", "software"}) {
        SCOPED_TRACE(backend);
        const std::vector<std::string> common = {"--samples", "4", "--backend", backend, "--size", "160x120"};
        const auto args = [&](std::vector<std::string> a) {
            a.insert(a.end(), common.begin(), common.end());
            return a;
        };
        const std::string b = backend;
        render(dir, "plain-bunny-" + b, args({"render", bunny}));
        for (const char* cull : {"sphere", "backface", "cones", "conservative"}) {
            render(dir, std::string("cull-") + cull + "-" + b, args({"render", bunny, "--cull", cull}));
            EXPECT_EQ(readAll(dir / ("plain-bunny-" + b + ".png")),
                      readAll(dir / (std::string("cull-") + cull + "-" + b + ".png")))
                << cull;
        }
        render(dir, "plain-cubes-" + b, args({"render", "builtin:cubes"}));
        render(dir, "adaptive-" + b, args({"render", "builtin:cubes", "--hsr", "adaptive"}));
        EXPECT_EQ(readAll(dir / ("plain-cubes-" + b + ".png")), readAll(dir / ("adaptive-" + b + ".png")));
        for (const char* mode : {"plain", "reuse"}) {
            std::vector<std::string> a = args(
                {"render", "builtin:dominoes", "--frames", "0:4", "-o", std::string(mode) + "-" + b + "-%d.png", "-q"});
            if (std::string(mode) == "reuse") a.push_back("--reuse");
            const CliRun run = runFrugal(dir, a);
            EXPECT_EQ(run.status, 0) << run.err;
        }
        for (int frame = 0; frame <= 4; ++frame) {
            const std::string n = b + "-" + std::to_string(frame) + ".png";
            EXPECT_EQ(readAll(dir / ("plain-" + n)), readAll(dir / ("reuse-" + n))) << "frame " << frame;
        }
    }
}

TEST(SamplesCliTest, WhatCannotBeIsOneLine) {
    test::expectOneErrorLine(
        test::freshDir("SamplesCliBad"),
        {{{"render", "--samples", "3"}, "error: --samples: '3' is not 1, 2, 4 or 8"},
         {{"render", "--samples", "16"}, "error: --samples: '16' is not 1, 2, 4 or 8"},
         {{"render", "--samples", "8", "--backend", "software"},
          "error: --samples 8: software has at most 4 samples a pixel",
          1},
         {{"render", "--samples", "4", "--cull", "occlusion"},
          "error: --samples 4 with --cull occlusion: they find what is visible at pixel centres, and a "
          "multisampled pixel is seen at 4 samples"},
         {{"render", "--samples", "4", "--backend", "software", "--interp", "span"},
          "error: --samples 4 with --interp span: the span engine models one sample a pixel"}});
}

}  // namespace
}  // namespace frugal
