// `frugal-lab soak` (issue 11) on a few frames and cycles, end to end with the real binary, and the
// checks it judges by (report/SoakReport.h), each shown to fail on what it must catch. The real
// soak (100,000 frames, 1,000 cycles) is the CTest test Soak.* (label soak, -DFRUGAL_SOAK_TESTS=ON).
// The runs here allow any memory growth (--max-growth 1000): a few frames are no measure of it, and
// under AddressSanitizer freed memory stays in quarantine; SoakChecksTest shows the limit biting.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "CliSupport.h"
#include "JsonSupport.h"
#include "TestSupport.h"
#include "lab/SoakReport.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::filesIn;
using test::runFrugal;

Buffers image(int width, int height, std::uint8_t value) {
    Buffers b;
    b.width = width;
    b.height = height;
    b.rgba.assign(b.pixelCount() * 4, value);
    b.depth.assign(b.pixelCount(), kDepthMax);
    b.ids.assign(b.pixelCount(), 0u);
    return b;
}

// --frames is a range, as in every command: frames 4..11 at period 4 are 8 frames, the last 4
// compared with the first 4 (frame f at time (f mod 4) / fps).
TEST(SoakCliTest, FramesAreARange) {
    const fs::path dir = test::freshDir("SoakRange");
    const CliRun run = runFrugal(dir, {"soak", "--backend", "software", "--frames", "4:11", "--period", "4",
                                       "--warmup", "4", "--cycles", "0", "-q", "--max-growth", "1000", "--json", "s.json"});
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    const nlohmann::json j = test::readJson(dir / "s.json");
    ASSERT_EQ(j["frames"].size(), 1u);
    EXPECT_EQ(j["frames"][0]["frames"], 8);
    EXPECT_EQ(j["frames"][0]["compared_frames"], 4);
    EXPECT_EQ(j["frames"][0]["mismatched_frames"], 0);
    EXPECT_TRUE(j["cycles"].empty());
}

TEST(SoakCliTest, SoftwareRunReportsMemoryImagesAndCycles) {
    const fs::path dir = test::freshDir("Soak");
    // 24 frames looped every 6: frames 6..23 are compared with frames 0..5.
    const CliRun run =
        runFrugal(dir, {"soak", "--backend", "software", "--frames", "0:23", "--period", "6", "--warmup", "6", "--cycles",
                        "3", "-q", "--max-growth", "1000", "--json", "s.json", "--csv", "s.csv"});
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    EXPECT_EQ(run.err, "");
    EXPECT_NE(run.out.find("soak builtin:cubes, 64x48, period 6 frames"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("soak: passed"), std::string::npos) << run.out;
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"s.csv", "s.json"}));

    const nlohmann::json j = test::readJson(dir / "s.json");
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j["command"], "soak");
    EXPECT_EQ(j["size"], nlohmann::json({64, 48}));
    EXPECT_EQ(j["period"], 6);
    EXPECT_EQ(j["max_growth_pct"], 1000);
    EXPECT_EQ(j["passed"], true);
    ASSERT_EQ(j["frames"].size(), 1u);
    const nlohmann::json& frames = j["frames"][0];
    EXPECT_EQ(frames["backend"], "software");
    EXPECT_EQ(frames["frames"], 24);
    EXPECT_EQ(frames["warmup"], 6);
    for (const char* key : {"rss_start_kb", "rss_warm_kb", "rss_end_kb", "rss_low_kb", "rss_peak_kb", "hwm_kb"})
        EXPECT_GT(frames[key].get<double>(), 0.0) << key;
    for (const char* key : {"growth_pct", "peak_growth_pct", "ms_per_frame"})
        EXPECT_TRUE(frames[key].is_number()) << key;
    EXPECT_GE(frames["peak_growth_pct"].get<double>(), frames["growth_pct"].get<double>());
    EXPECT_EQ(frames["compared_frames"], 18);
    EXPECT_EQ(frames["mismatched_frames"], 0);
    EXPECT_TRUE(frames["first_mismatch"].is_null());
    EXPECT_EQ(frames["blank_frames"], 0);
    EXPECT_EQ(frames["passed"], true);

    ASSERT_EQ(j["cycles"].size(), 3u);
    const char* kinds[] = {"backend", "target", "scene"};
    for (std::size_t k = 0; k < 3; ++k) {
        const nlohmann::json& cycles = j["cycles"][k];
        SCOPED_TRACE(cycles.dump());
        EXPECT_EQ(cycles["backend"], "software");
        EXPECT_EQ(cycles["kind"], kinds[k]);
        EXPECT_EQ(cycles["cycles"], 3);
        EXPECT_EQ(cycles["failures"], 0);
        EXPECT_TRUE(cycles["first_failure"].is_null());
        EXPECT_EQ(cycles["warmup"], 1);
        EXPECT_GT(cycles["rss_warm_kb"].get<double>(), 0.0);
        EXPECT_TRUE(cycles["growth_pct"].is_number());
        EXPECT_EQ(cycles["passed"], true);
    }
    EXPECT_EQ(j["skipped"].size(), 0u);

    // A sample after every frame (24 / 1000 rounds up to 1) and after every cycle.
    const std::vector<std::string> csv = test::lines(test::readAll(dir / "s.csv"));
    ASSERT_EQ(csv.size(), 1u + 25u + 3u * 3u);
    EXPECT_EQ(csv[0], "run,backend,index,rss_kb,hwm_kb,ms_each");
    EXPECT_EQ(test::csvFields(csv[1])[0], "frames");
    EXPECT_EQ(test::csvFields(csv[25])[2], "24");
    EXPECT_EQ(test::csvFields(csv[26])[0], "backend");
    EXPECT_EQ(test::csvFields(csv.back())[0], "scene");
}

TEST(SoakCliTest, GlBackendSurvivesCyclesWhenNamesAreReused) {
    // Mesa hands out fresh GL names unless told to reuse freed ones, as other drivers do; the scene
    // cycles then upload textures into the names just deleted. GlBackend's state cache still held a
    // deleted texture as bound when its name came back, skipped binding the new texture for its
    // upload, and later draws sampled an empty texture: on this scene every scene cycle failed
    // before a deletion reset the cached binding (whether the stale name comes back first depends
    // on which texture the last draw bound, so not every scene shows it).
    const fs::path dir = test::freshDir("SoakGl");
    const CliRun run = runFrugal(dir,
                                 {"soak", "builtin:materials?draws=20", "--backend", "egl-surfaceless", "--frames", "0:2",
                                  "--cycles", "3", "-q", "--max-growth", "1000", "--json", "s.json"},
                                 "force_gl_names_reuse=true");
    if (run.status == 3) FRUGAL_SKIP_IF_NO_GL(run.err);
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    const nlohmann::json j = test::readJson(dir / "s.json");
    EXPECT_EQ(j["period"], 1);  // a still scene: every frame is compared with the first
    EXPECT_EQ(j["frames"][0]["backend"], "egl-surfaceless");
    EXPECT_EQ(j["frames"][0]["compared_frames"], 2);
    EXPECT_EQ(j["frames"][0]["mismatched_frames"], 0);
    ASSERT_EQ(j["cycles"].size(), 3u);
    for (const nlohmann::json& cycles : j["cycles"]) EXPECT_EQ(cycles["failures"], 0) << cycles.dump();
}

TEST(SoakCliTest, MinimalDrawsTheFramesWithTheMinimalGlProgram) {
    // What Mesa alone does with memory over the same frames: the yardstick beside frugal's rows.
    const fs::path dir = test::freshDir("SoakMinimal");
    const CliRun run = runFrugal(dir, {"soak", "--minimal", "--backend", "egl-surfaceless", "--frames", "0:7", "--period",
                                       "4", "-q", "--max-growth", "1000", "--json", "s.json"});
    if (run.status == 3) FRUGAL_SKIP_IF_NO_GL(run.err);
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    const nlohmann::json j = test::readJson(dir / "s.json");
    ASSERT_EQ(j["frames"].size(), 1u);
    EXPECT_EQ(j["frames"][0]["backend"], "egl-surfaceless (minimal)");
    EXPECT_EQ(j["frames"][0]["compared_frames"], 4);
    EXPECT_EQ(j["frames"][0]["mismatched_frames"], 0);
    EXPECT_EQ(j["frames"][0]["blank_frames"], 0);
    EXPECT_EQ(j["cycles"].size(), 0u);  // the cycles are frugal's own
}

TEST(SoakCliTest, PlotIsDrawnFromTheCsv) {
    if (!test::haveGnuplot()) FRUGAL_SKIP_IF_MISSING("gnuplot (Debian: gnuplot-nox)");
    const fs::path dir = test::freshDir("SoakPlot");
    for (const char* plot : {"s.svg", "s.png"}) {
        const CliRun run = runFrugal(dir, {"soak", "--backend", "software", "--frames", "0:3", "--period", "2",
                                           "--cycles", "2", "-q", "--max-growth", "1000", "--plot", plot});
        ASSERT_EQ(run.status, 0) << run.err;
    }
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"s.csv", "s.gp", "s.png", "s.svg"}));
    EXPECT_NE(test::readAll(dir / "s.svg").find("<svg"), std::string::npos);
    EXPECT_EQ(test::readAll(dir / "s.png").substr(1, 3), "PNG");
}

TEST(SoakCliTest, ImpossibleOptionsGetOneLine) {
    const fs::path dir = test::freshDir("SoakErrors");
    test::expectOneErrorLine(
        dir,
        {
            {{"soak", "--frames", "-1"}, "error: --frames: '-1' is not a frame range (A:B, 0 <= A <= B <= 1000000000) or none"},
            {{"soak", "--frames", "9:0"}, "error: --frames: '9:0' is not a frame range (A:B, 0 <= A <= B <= 1000000000) or none"},
            {{"soak", "--frames", "100"}, "error: --frames: '100' is not a frame range (A:B, 0 <= A <= B <= 1000000000) or none"},
            {{"soak", "--frames", "none", "--cycles", "0"}, "error: --frames none with --cycles 0: nothing to do"},
            {{"soak", "--frames", "5:14", "--warmup", "10"}, "error: --warmup 10: must be less than the 10 frames of --frames"},
            {{"soak", "--period", "0"}, "error: --period: '0' is not a whole number from 1 to 1000000000"},
            {{"soak", "--plot", "x.pdf"}, "error: --plot x.pdf: gnuplot writes SVG or PNG here; name it .svg or .png"},
            {{"soak", "--minimal", "--ids"}, "error: --minimal with --ids: the minimal GL program draws no ids"},
            {{"soak", "--minimal", "--frames", "none"},
             "error: --minimal with --frames none: the minimal GL program only draws frames"},
            {{"soak", "--minimal", "--backend", "software"},
             "error: --minimal with --backend software: the minimal program is a GL program; pick a GL backend"},
            {{"soak", "--backend", "wat"}, "", 2},
            {{"soak", "builtin:nope"}, "", 1},
        });
}

TEST(SoakChecksTest, ImagesAtEqualTimesMustBeIdentical) {
    EqualTimeImages images(3);
    for (std::int64_t f = 0; f < 9; ++f) images.add(f, std::uint64_t(100 + f % 3), false);
    EXPECT_EQ(images.compared, 6);
    EXPECT_EQ(images.mismatched, 0);

    images.add(9, 101, false);  // time 0 drew time 1's image
    images.add(10, 101, true);  // right, but blank
    EXPECT_EQ(images.compared, 8);
    EXPECT_EQ(images.mismatched, 1);
    EXPECT_EQ(images.firstMismatch, 9);
    EXPECT_EQ(images.blank, 1);
    EXPECT_EQ(images.firstBlank, 10);
}

TEST(SoakChecksTest, HashAndBlankSeeOneChangedValue) {
    const std::array<std::uint8_t, 4> background{7, 7, 7, 7};
    Buffers a = image(4, 3, 7);
    EXPECT_TRUE(isBlank(a, background));
    const std::uint64_t hash = imageHash(a);
    EXPECT_EQ(imageHash(image(4, 3, 7)), hash);
    a.rgba[45] = 8;
    EXPECT_FALSE(isBlank(a, background));
    EXPECT_NE(imageHash(a), hash);
    Buffers b = image(4, 3, 7);
    b.depth[11] -= 1;
    EXPECT_NE(imageHash(b), hash);
    Buffers c = image(4, 3, 7);
    c.ids[0] = 1;
    EXPECT_NE(imageHash(c), hash);
    EXPECT_NE(imageHash(image(3, 4, 7)), hash);  // same bytes, another shape
}

TEST(SoakChecksTest, GrowthIsMeasuredFromTheEndOfWarmUp) {
    SoakFrames run;
    run.frames = 300;
    run.warmup = 100;
    for (std::int64_t i = 0; i <= 300; i += 50) {
        // Memory rises during the warm-up (0 → 100) and then by 4 %, with a peak of 6 % on the way.
        const std::uint64_t kb = i < 100 ? 500 + 5 * std::uint64_t(i) : i == 200 ? 1060 : i == 300 ? 1040 : 1000;
        run.samples.push_back({i, {kb, 1060}, 1.0});
    }
    const GrowthSummary g = summarizeGrowth(run);
    EXPECT_EQ(g.baseline.rssKb, 1000u);
    EXPECT_EQ(g.end.rssKb, 1040u);
    EXPECT_EQ(g.lowRssKb, 1000u);  // not the warm-up's 500
    EXPECT_EQ(g.peakRssKb, 1060u);
    EXPECT_DOUBLE_EQ(g.growthPct, 4.0);
    EXPECT_DOUBLE_EQ(g.peakGrowthPct, 6.0);
    EXPECT_TRUE(passed(run, 5.0));
    EXPECT_FALSE(passed(run, 3.0));

    SoakReport report;
    report.maxGrowthPct = 5.0;
    report.frames.push_back(run);
    EXPECT_TRUE(passed(report));
    report.frames[0].images.add(0, 1, false);
    report.frames[0].images.add(1, 2, false);  // period 1: frame 1 must equal frame 0
    EXPECT_FALSE(passed(report.frames[0], 5.0));
    EXPECT_FALSE(passed(report));
    const nlohmann::json j = nlohmann::json::parse(soakReportJson(report));
    EXPECT_EQ(j["passed"], false);
    EXPECT_EQ(j["frames"][0]["growth_pct"], 4.0);
    EXPECT_EQ(j["frames"][0]["mismatched_frames"], 1);
    EXPECT_EQ(j["frames"][0]["first_mismatch"], 1);
}

TEST(SoakChecksTest, CyclesFailOnAFailureOrGrowth) {
    SoakCycles run;
    run.kind = "target";
    run.cycles = 3;
    run.samples = {{1, {1000, 1000}, 1.0}, {2, {1010, 1010}, 1.0}, {3, {1020, 1020}, 1.0}};
    EXPECT_DOUBLE_EQ(summarizeGrowth(run).growthPct, 2.0);
    EXPECT_TRUE(passed(run, 5.0));
    EXPECT_FALSE(passed(run, 1.0));
    run.failures = 1;
    EXPECT_FALSE(passed(run, 5.0));
    // No memory figure at all is no proof of a flat one.
    SoakCycles none;
    EXPECT_TRUE(std::isnan(summarizeGrowth(none).growthPct));
    EXPECT_FALSE(passed(none, 5.0));
}

}  // namespace
}  // namespace frugal
