// Files written while the next frame renders, end to end: `frugal render --png-level` (every
// level gives the same pixels, the render JSON's write timings) and `frugal-lab write-bench` (its
// table and sequence, pixels equal at every level and filter). Timings are printed, never asserted.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "CliSupport.h"
#include "JsonSupport.h"
#include "TestSupport.h"
#include "io/ImageIO.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::filesIn;
using test::runFrugal;

TEST(WriteCliTest, EveryPngLevelGivesTheSamePixels) {
    const fs::path dir = test::freshDir("WriteCliLevels");
    std::vector<DecodedImage> first;
    for (const std::string level : {"auto", "0", "1", "2", "6", "12"}) {
        SCOPED_TRACE(level);
        const CliRun run =
            runFrugal(dir, {"render", "builtin:cubes", "--backend", "software", "--size", "96x64", "--frames", "0:2",
                            "-o", "c" + level + "_%d.png", "--depth", "d" + level + "_%d.png", "--ids",
                            "i" + level + "_%d.png", "--png-level", level, "--json", "r" + level + ".json", "-q"});
        ASSERT_EQ(run.status, 0) << run.err;
        const nlohmann::json j = test::readJson(dir / ("r" + level + ".json"));
        ASSERT_EQ(j["frames"].size(), 3u);
        for (const nlohmann::json& frame : j["frames"]) {
            EXPECT_GE(frame["write_ms"].get<double>(), frame["encode_ms"].get<double>());
            EXPECT_GT(frame["encode_ms"].get<double>(), 0.0);
        }
        std::vector<DecodedImage> images;
        for (int f = 0; f < 3; ++f)
            for (const char* kind : {"c", "d", "i"}) {
                Result<DecodedImage> image =
                    readPng((dir / (kind + level + "_" + std::to_string(f) + ".png")).string());
                ASSERT_TRUE(image) << image.error().message;
                images.push_back(*image);
            }
        if (first.empty()) {
            first = images;
            continue;
        }
        for (std::size_t k = 0; k < images.size(); ++k) {
            EXPECT_EQ(images[k].pixels8, first[k].pixels8) << k;
            EXPECT_EQ(images[k].pixels16, first[k].pixels16) << k;
        }
    }
}

TEST(WriteCliTest, AnImpossibleLevelIsOneLine) {
    const fs::path dir = test::freshDir("WriteCliBadLevel");
    for (const std::string level : {"13", "-1", "x", ""}) {
        const CliRun run = runFrugal(dir, {"render", "--png-level", level, "-o", "x.png"});
        EXPECT_EQ(run.status, 2) << level;
        EXPECT_EQ(run.err, "error: --png-level: '" + level + "' must be 0 to 12 or auto\n");
    }
    EXPECT_TRUE(filesIn(dir).empty());
}

TEST(WriteCliTest, WriteBenchMeasuresEveryLevelAndTheSequence) {
    const fs::path dir = test::freshDir("WriteBench");
    const CliRun run = runFrugal(dir, {"write-bench",
                                       "--scene",
                                       "builtin:cubes",
                                       "--scene",
                                       "builtin:default",
                                       "--backend",
                                       "software",
                                       "--size",
                                       "64x48",
                                       "--levels",
                                       "1,2,6",
                                       "--repeat",
                                       "1",
                                       "--frames",
                                       "2",
                                       "--rounds",
                                       "1",
                                       "--json",
                                       "w.json",
                                       "--csv",
                                       "w.csv"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"w.csv", "w.json"})) << "the sequence's files are removed";
    const nlohmann::json j = test::readJson(dir / "w.json");
    // Per scene and image: the baseline and 3 levels x 4 filters.
    ASSERT_EQ(j["encodes"].size(), 2u * 3u * (1u + 3u * 4u));
    for (const nlohmann::json& row : j["encodes"]) {
        SCOPED_TRACE(row.dump());
        EXPECT_TRUE(row["pixels_equal"].get<bool>());
        EXPECT_GT(row["bytes"].get<int>(), 0);
        EXPECT_EQ(row["encoder"], row["level"] == 1              ? "run-length"
                                  : row["encoder"] == "baseline" ? "baseline"
                                                                 : "libdeflate");
    }
    ASSERT_EQ(j["choices"].size(), 3u);
    ASSERT_EQ(j["sequence"]["results"].size(), 2u * 6u);  // two sets of images, six variants
    for (const nlohmann::json& row : j["sequence"]["results"]) {
        EXPECT_GT(row["median_ms_per_frame"].get<double>(), 0.0);
        EXPECT_GT(row["cpu_ms_per_frame"].get<double>(), 0.0);
    }
    EXPECT_NE(run.err.find("the fastest level and filter within 1.1x"), std::string::npos) << run.err;
    EXPECT_EQ(j["readback"]["skipped"], "the software backend reads no GL framebuffer");
}

TEST(WriteCliTest, WriteBenchReadsBackFourWaysOnGl) {
    const fs::path dir = test::freshDir("WriteBenchReadBack");
    const CliRun run = runFrugal(dir, {"write-bench", "--scene", "builtin:cubes", "--size", "64x48", "--levels", "2",
                                       "--repeat", "1", "--frames", "0", "--readback-frames", "3", "--rounds", "2",
                                       "--json", "w.json"});
    if (run.status == 3) GTEST_SKIP() << run.err;  // no GL here
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json j = test::readJson(dir / "w.json");
    EXPECT_FALSE(j.contains("sequence")) << "--frames 0 skips part two";
    ASSERT_EQ(j["readback"]["results"].size(), 2u * 4u) << j["readback"].dump();
    for (const nlohmann::json& row : j["readback"]["results"]) {
        SCOPED_TRACE(row.dump());
        EXPECT_EQ(row["ms_per_frame"].size(), 2u);
        EXPECT_GT(row["median_ms_per_frame"].get<double>(), 0.0);
        if (row["variant"] == "draw")
            EXPECT_FALSE(row.contains("pixels_equal"));
        else
            EXPECT_TRUE(row["pixels_equal"].get<bool>());
    }
    // A scene the minimal frame does not draw skips part three with the reason.
    const CliRun textured = runFrugal(dir, {"write-bench", "--size", "64x48", "--levels", "2", "--repeat", "1",
                                            "--frames", "0", "--json", "t.json"});
    ASSERT_EQ(textured.status, 0) << textured.err;
    const std::string skipped = test::readJson(dir / "t.json")["readback"]["skipped"];
    EXPECT_EQ(skipped.rfind("builtin:default: material ", 0), 0u) << skipped;
}

}  // namespace
}  // namespace frugal
