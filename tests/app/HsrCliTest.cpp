// The hidden-surface modes on the command line (`--hsr` on render, diff and bench, and
// `frugal-lab hsr-bench`), end to end with the real binary. Speeds are printed, never asserted; the
// pixel counts are asserted where src/hsr/Plan.h says adaptive is exact.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "CliSupport.h"
#include "JsonSupport.h"
#include "TestSupport.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::filesIn;
using test::runFrugal;

TEST(HsrCliTest, HsrBenchReportsEveryModeAgainstTheZBuffer) {
    const fs::path dir = test::freshDir("HsrBench");
    const CliRun run = runFrugal(dir, {"hsr-bench", "--backend", "software", "--frames", "0:5", "-q", "--json",
                                       "hsr.json", "--csv", "hsr.csv", "--masks", "masks"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err, "");
    EXPECT_NE(run.out.find("hsr-bench builtin:cubes, 240x320, software"), std::string::npos) << run.out;
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"hsr.csv", "hsr.json", "masks"}));
    EXPECT_EQ(filesIn(dir / "masks"),
              (std::vector<std::string>{"adaptive-convex.png", "adaptive-convex_mask.png", "adaptive.png",
                                        "adaptive_mask.png", "depthsort.png", "depthsort_mask.png", "zbuffer.png"}));

    const nlohmann::json j = test::readJson(dir / "hsr.json");
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j["scene"], "builtin:cubes");
    EXPECT_EQ(j["size"], nlohmann::json({240, 320}));
    EXPECT_EQ(j["backend"], "software");
    EXPECT_EQ(j["polygons"], 168);
    ASSERT_EQ(j["modes"].size(), 5u);
    const char* names[] = {"zbuffer", "depthsort", "adaptive", "adaptive-convex", "sorted-zbuffer"};
    for (int m = 0; m < 5; ++m) {
        const nlohmann::json& mode = j["modes"][std::size_t(m)];
        SCOPED_TRACE(mode.dump());
        EXPECT_EQ(mode["mode"], names[m]);
        for (const char* key : {"fps", "median_ms", "plan_ms", "speedup", "flagged_share"})
            EXPECT_TRUE(mode[key].is_number()) << key;
        EXPECT_EQ(mode["paper_speedup"].is_number(), m < 3);  // the last two are ours, not the paper's
        EXPECT_EQ(mode["per_frame"]["ms"].size(), 6u);
        EXPECT_EQ(mode["per_frame"]["differing_px"].size(), 6u);
    }
    EXPECT_EQ(j["modes"][0]["differing_px"], 0);
    EXPECT_EQ(j["modes"][0]["flagged_share"], 1.0);
    EXPECT_EQ(j["modes"][1]["flagged_share"], 0.0);
    EXPECT_GT(j["modes"][1]["differing_px"].get<int>(), 0);  // the painter's errors on interpenetrating cubes
    EXPECT_EQ(j["modes"][2]["differing_px"], 0);             // Plan.h: exact on the paper's scene
    EXPECT_EQ(j["modes"][3]["differing_px"], 0);
    EXPECT_LT(j["modes"][3]["flagged_share"].get<double>(), j["modes"][2]["flagged_share"].get<double>());
    EXPECT_NEAR(j["modes"][2]["paper_speedup"].get<double>(), 27.83 / 14.20, 1e-9);

    const std::vector<std::string> csv = test::lines(test::readAll(dir / "hsr.csv"));
    ASSERT_EQ(csv.size(), 6u);
    EXPECT_EQ(test::csvFields(csv[0])[4], "mode");
    EXPECT_EQ(test::csvFields(csv[3])[4], "adaptive");
    EXPECT_EQ(test::csvFields(csv[5])[4], "sorted-zbuffer");
}

TEST(HsrCliTest, HsrBenchPlotIsDrawnFromTheCsv) {
    if (!test::haveGnuplot()) FRUGAL_SKIP_IF_MISSING("gnuplot (Debian: gnuplot-nox)");
    const fs::path dir = test::freshDir("HsrBenchPlot");
    const CliRun run = runFrugal(dir, {"hsr-bench", "--backend", "software", "--frames", "0:1", "-q", "--plot", "hsr.svg"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"hsr.csv", "hsr.gp", "hsr.svg"}));
    EXPECT_NE(test::readAll(dir / "hsr.svg").find("<svg"), std::string::npos);
}

TEST(HsrCliTest, RenderDiffAndBenchTakeTheMode) {
    const fs::path dir = test::freshDir("HsrRender");
    CliRun run = runFrugal(dir, {"render", "builtin:cubes", "--size", "64x48", "--backend", "software", "--hsr", "adaptive",
                                 "-o", "a.png", "--json", "a.json"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.err.find("(adaptive: "), std::string::npos) << run.err;
    const nlohmann::json meta = test::readJson(dir / "a.json");
    EXPECT_EQ(meta["hsr"], "adaptive");
    EXPECT_EQ(meta["frames"][0]["hsr"]["mode"], "adaptive");
    EXPECT_TRUE(meta["frames"][0]["hsr"]["polygons"].is_number());
    // At least one draw per cube: exactly that when every polygon is flagged (one run, in submission order).
    EXPECT_GE(meta["frames"][0]["state_changes"]["draws"].get<int>(), 28);

    // The adaptive image is the z-buffer image (compare exits 0 on identical images).
    run = runFrugal(dir, {"render", "builtin:cubes", "--size", "64x48", "--backend", "software", "-o", "z.png", "-q"});
    ASSERT_EQ(run.status, 0) << run.err;
    run = runFrugal(dir, {"compare", "a.png", "z.png", "--tolerance", "0"});
    EXPECT_EQ(run.status, 0) << run.out << run.err;

    run = runFrugal(dir, {"diff", "builtin:cubes", "--size", "64x48", "--hsr", "depthsort", "-q", "--out", "d", "--json", "d.json"});
    if (run.status != 2) {  // 2: no GL backend here
        EXPECT_EQ(run.status, 0) << run.out << run.err;
        EXPECT_EQ(test::readJson(dir / "d.json")["hsr"], "depthsort");
    }
    run = runFrugal(dir, {"bench", "render", "builtin:cubes", "--size", "32x24", "--backend", "software", "--repeat", "2",
                          "--warmup", "0", "--hsr", "depthsort", "-q"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("\"hsr\": \"depthsort\""), std::string::npos) << run.out;
}

TEST(HsrCliTest, CullReportDrawsEveryRowInTheMode) {
    // Against the z-buffered full render: adaptive adds no differing pixel, depthsort adds some.
    const fs::path dir = test::freshDir("HsrCullReport");
    for (const char* mode : {"adaptive", "depthsort"}) {
        const std::string json = std::string(mode) + ".json";
        const CliRun run = runFrugal(dir, {"cull-report", "builtin:cubes", "--size", "120x160", "--views", "3", "--repeat", "1",
                                           "--methods", "none,sphere,oracle", "--backend", "software", "--hsr", mode, "-q",
                                           "--json", json});
        ASSERT_EQ(run.status, 0) << run.err;
        const nlohmann::json j = test::readJson(dir / json);
        EXPECT_EQ(j["hsr"], mode);
        std::size_t differing = 0;
        for (const nlohmann::json& view : j["views"])
            for (const nlohmann::json& method : view["methods"]) differing += method["pixels_differing"].get<std::size_t>();
        if (std::string(mode) == "adaptive") {
            EXPECT_EQ(differing, 0u);
        } else {
            EXPECT_GT(differing, 0u);
        }
    }
}

TEST(HsrCliTest, ImpossibleOptionsGetOneLine) {
    const fs::path dir = test::freshDir("HsrErrors");
    test::expectOneErrorLine(dir, {
        {{"render", "--hsr", "wat"}, "error: --hsr: 'wat' is not a mode (zbuffer, depthsort, adaptive, adaptive-convex)"},
        {{"render", "--hsr"}, "error: --hsr: missing value"},
        {{"render", "--hsr", "adaptive", "--reuse"},
         "error: --hsr adaptive with --reuse: reuse redraws what moved with the z-buffer over the static image"},
        {{"render", "--hsr", "depthsort", "--cull", "oracle"},
         "error: --hsr depthsort with --cull oracle: the oracle draws its own scene"},
        {{"hsr-bench", "--repeat", "0"}, "error: --repeat: '0' is not a whole number from 1 to 10000"},
        {{"hsr-bench", "--masks", ""}, "error: --masks: '' is not a folder name"},
        {{"hsr-bench", "--plot", "x.png"}, "error: --plot x.png: gnuplot writes SVG here; name it .svg"},
        {{"hsr-bench", "builtin:nope"}, "", 1},
    });
}

}  // namespace
}  // namespace frugal
