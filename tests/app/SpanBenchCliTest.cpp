// `frugal-lab span-bench` on the command line, end to end: the real binary in a child process. The
// error figures are deterministic for a seed and asserted as bounds (the model's <= 1 LSB); the
// speeds are printed, never asserted.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
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

TEST(SpanBenchCliTest, PrintsFig11AndTheErrorTableAndWritesJsonAndCsv) {
    const fs::path dir = test::freshDir("SpanBenchJson");
    const CliRun run = runFrugal(dir, {"span-bench", "--lengths", "8,64,2048", "--widths", "16,24", "--spans", "200",
                                       "--speed-ms", "5", "--json", "span.json", "--csv", "span.csv"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err, "");
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"span.csv", "span.json"}));
    for (const char* text : {"Fig. 11", "010  0A0  12F  1BF  24F  2DF  36F  3FF", "printed: 010 0A0 12F 3FF", "EPT mask 0x3FC",
                             "worst     mean", "paper, hardware (one span per 17 us, 10 MHz)", "engine model"})
        EXPECT_NE(run.out.find(text), std::string::npos) << text << "\n" << run.out;

    const nlohmann::json j = test::readJson(dir / "span.json");
    ASSERT_TRUE(j.is_object());
    const nlohmann::json& fig = j["fig11"];
    EXPECT_EQ(fig["mismatches"], 0);
    EXPECT_EQ(fig["channels"]["z"]["hex"], "010 0A0 12F 1BF 24F 2DF 36F 3FF");
    EXPECT_EQ(fig["channels"]["green"]["hex"], "7 6 5 4 3 2 1 0");
    EXPECT_EQ(fig["channels"]["red"]["hex"], "0 1 2 3 4 5 6 7");
    EXPECT_EQ(fig["channels"]["blue"]["hex"], "3 3 2 2 1 1 1 0");
    EXPECT_GE(fig["schemes"].size(), 10u);

    const nlohmann::json& errors = j["errors"];
    ASSERT_EQ(errors.size(), 2u * 3u * 4u);  // widths × lengths × methods
    for (const nlohmann::json& e : errors) {
        SCOPED_TRACE(e.dump());
        EXPECT_EQ(e["spans"], 200);
        EXPECT_EQ(e["pixels"], 200 * e["length"].get<int>());
        if (e["method"] == "span") {
            EXPECT_LE(e["worst_lsb"].get<int>(), 1);
        }
        if (e["method"] == "dda" && e["width"] == 24 && e["length"] == 2048) {
            EXPECT_GT(e["worst_lsb"].get<int>(), 1);
        }
    }
    const nlohmann::json& speed = j["spans_per_second"];
    EXPECT_NEAR(speed["paper"].get<double>(), 58823.5, 1.0);
    EXPECT_TRUE(speed["engine_model"].is_number());
    EXPECT_EQ(speed["fill_span"].size(), 3u * 4u);

    const std::vector<std::string> csv = test::lines(test::readAll(dir / "span.csv"));
    ASSERT_EQ(csv.size(), 1u + 24u);
    EXPECT_EQ(csv[0], "width,length,method,worst_lsb,mean_lsb,spans,pixels,overflow_spans");
    EXPECT_EQ(test::csvFields(csv[1]).size(), 8u);
}

TEST(SpanBenchCliTest, TheSameSeedPrintsTheSameTable) {
    const fs::path dir = test::freshDir("SpanBenchSeed");
    const std::vector<std::string> args{"span-bench", "--lengths", "64", "--spans", "50", "--seed", "9", "--speed-ms", "0"};
    const CliRun a = runFrugal(dir, args), b = runFrugal(dir, args);
    ASSERT_EQ(a.status, 0) << a.err;
    EXPECT_EQ(a.out, b.out) << "no speed measured: the output is deterministic";
    EXPECT_NE(a.out.find("not measured: --speed-ms 0"), std::string::npos);
}

TEST(SpanBenchCliTest, PlotWritesTheScriptBesideTheSvg) {
    if (!test::haveGnuplot()) FRUGAL_SKIP_IF_MISSING("gnuplot (Debian: gnuplot-nox)");
    const fs::path dir = test::freshDir("SpanBenchPlot");
    const CliRun run = runFrugal(dir, {"span-bench", "--lengths", "8,512", "--spans", "20", "--speed-ms", "0", "--plot", "e.svg"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"e.csv", "e.gp", "e.svg"}));
    EXPECT_NE(test::readAll(dir / "e.svg").find("<svg"), std::string::npos);
}

// --scene: the software backend's --interp modes on a whole scene. Exact departs from itself
// nowhere; span is within 2 LSB of the exact render (1 from the line through each run's ends, 1 more
// from the exact path's float plane) and changes no colour on cubes; both slow paths ran.
TEST(SpanBenchCliTest, SceneReportsTheInterpModesAgainstExact) {
    const fs::path dir = test::freshDir("SpanBenchScene");
    const CliRun run = runFrugal(dir, {"span-bench", "--scene", "builtin:cubes", "--render-size", "240x320", "--lengths", "8",
                                       "--spans", "10", "--speed-ms", "0", "--json", "s.json"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err, "");
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"s.json"});
    for (const char* text : {"software backend, --interp", "builtin:cubes 240x320", "spans/frame"})
        EXPECT_NE(run.out.find(text), std::string::npos) << text << "\n" << run.out;

    const nlohmann::json j = test::readJson(dir / "s.json");
    ASSERT_TRUE(j.is_object());
    const nlohmann::json& render = j["render"];
    ASSERT_EQ(render.size(), 3u);
    std::vector<std::string> modes;
    for (const nlohmann::json& row : render) {
        SCOPED_TRACE(row.dump());
        modes.push_back(row["mode"].get<std::string>());
        EXPECT_EQ(row["scene"], "builtin:cubes");
        EXPECT_EQ(row["size"], nlohmann::json::array({240, 320}));
        EXPECT_EQ(row["overflow"], 0);
        EXPECT_GT(row["frame_ms"].get<double>(), 0.0);
        EXPECT_EQ(row["exact_frame_ms"], render[0]["frame_ms"]);
        for (const char* key : {"colour_px", "id_px", "worst_lsb", "mean_lsb", "depth_changed_px", "spans", "spans_per_second"})
            EXPECT_TRUE(row.contains(key)) << key;
        if (row["mode"] == "exact") {
            for (const char* key : {"colour_px", "id_px", "worst_lsb", "depth_changed_px", "spans"}) EXPECT_EQ(row[key], 0) << key;
            EXPECT_EQ(row["mean_lsb"].get<double>(), 0.0);
        } else {
            EXPECT_GT(row["spans"].get<long long>(), 0);
            EXPECT_GT(row["spans_per_second"].get<double>(), 0.0);
        }
        if (row["mode"] == "span") {
            EXPECT_LE(row["worst_lsb"].get<int>(), 2);
            EXPECT_EQ(row["colour_px"], 0);
            EXPECT_GT(row["depth_changed_px"].get<long long>(), 0) << "the span path rounds some pixel differently";
        }
    }
    EXPECT_EQ(modes, (std::vector<std::string>{"exact", "span", "dda"}));
}

TEST(SpanBenchCliTest, ABadSceneIsOneLineAndNoFile) {
    const fs::path dir = test::freshDir("SpanBenchBadScene");
    const CliRun run = runFrugal(dir, {"span-bench", "--speed-ms", "0", "--scene", "builtin:cubes", "--scene", "missing.obj",
                                       "--json", "x.json", "--csv", "x.csv"});
    EXPECT_EQ(run.status, 1) << run.err;
    EXPECT_EQ(run.errLines(), std::vector<std::string>{"error: missing.obj: no such file"});
    EXPECT_EQ(run.out, "");
    EXPECT_TRUE(filesIn(dir).empty());
}

TEST(SpanBenchCliTest, BadCommandLinesGetOneLineStatus2AndNoFile) {
    const fs::path dir = test::freshDir("SpanBenchBad");
    const std::vector<test::FailingRun> cases = {
        {{"span-bench", "--lengths", "8,1", "--json", "x.json"}, "error: --lengths: '8,1' is not a list of whole numbers from 2 to 61440"},
        {{"span-bench", "--lengths", "8,x"}, "error: --lengths: '8,x' is not a list of whole numbers from 2 to 61440"},
        {{"span-bench", "--lengths", "8,"}, "error: --lengths: '8,' is not a list of whole numbers from 2 to 61440"},
        {{"span-bench", "--widths", "16,30"}, "error: --widths: '16,30' is not a list of whole numbers from 1 to 28"},
        {{"span-bench", "--spans", "0"}, "error: --spans: '0' is not a whole number from 1 to 1000000"},
        {{"span-bench", "--dda-bits", "24"},
         "error: --dda-bits 24: the DDA register must be wider than every width (24 bits) to hold a fraction"},
        {{"span-bench", "--plot", "x.png"}, "error: --plot x.png: gnuplot writes SVG here; name it .svg"},
        {{"span-bench", "--render-size", "240", "--json", "x.json"},
         "error: --render-size: '240' is not a size (WxH, each 1 to 16384)"},
        {{"span-bench", "--render-size", "0x320"}, "error: --render-size: '0x320' is not a size (WxH, each 1 to 16384)"},
        {{"span-bench", "--wat"}, "error: --wat: unknown option (see 'frugal-lab help span-bench')"},
        {{"span-bench", "extra"}, "error: unexpected argument 'extra'"},
    };
    test::expectOneErrorLine(dir, cases);
}

TEST(SpanBenchCliTest, HelpExplainsEveryOption) {
    const fs::path dir = test::freshDir("SpanBenchHelp");
    const CliRun run = runFrugal(dir, {"help", "span-bench"});
    ASSERT_EQ(run.status, 0);
    for (const char* text : {"usage: frugal-lab span-bench", "--lengths", "--widths", "--spans N", "--seed S", "--dda-bits N",
                             "--speed-ms N", "--scene SCENE", "--render-size WxH", "--json FILE", "--csv FILE", "--plot FILE.svg", "span_trunc"})
        EXPECT_NE(run.out.find(text), std::string::npos) << text;
    const CliRun usage = test::runLab(dir, {"--help"});
    EXPECT_NE(usage.out.find("frugal-lab span-bench"), std::string::npos);
}

}  // namespace
}  // namespace frugal
