// `frugal-lab reuse-bench` on the command line, end to end: the real binary in a child process (exit
// status, stdout, stderr, JSON, CSV, plots). The software backend at small sizes, few frames and
// rounds, so the suite stays fast; the figures themselves are never asserted, only their shape and
// the check against the full render.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "JsonSupport.h"
#include "TestSupport.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::filesIn;
using test::readAll;
using test::runFrugal;

// 804 polygons (quads) = 134 dominoes of 12 triangles, 1,608 triangles; 55.44 % static: k = 60 move
// once the fall is under way (frame f moves min(f + 1, 60)).
const char* const kDominoes = "builtin:dominoes?polygons=804&static=0.5544";

std::vector<std::string> base(const std::string& frames) {
    return {"reuse-bench", kDominoes, "--frames", frames, "--backend", "software", "--size", "96x72", "--repeat", "2"};
}

TEST(ReuseBenchCliTest, JsonHasEveryFrameAndTheSummaryAndNoErrorPixel) {
    const fs::path dir = test::freshDir("ReuseBenchJson");
    std::vector<std::string> args = base("3:8");
    args.insert(args.end(), {"--json", "bench.json", "--csv", "bench.csv"});
    const CliRun run = runFrugal(dir, args);
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"bench.csv", "bench.json"}));
    // Progress: a line per frame (the warm-up round), a line per round.
    EXPECT_NE(run.err.find("frame 3 (1/6): rebuild"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("frame 4 (2/6): reuse"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("round 2/2: full "), std::string::npos) << run.err;
    EXPECT_NE(run.err.find(" ms, whole oracle "), std::string::npos) << run.err;
    EXPECT_NE(run.out.find("reuse frames"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("whole ms"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("reuse/oracle  reuse/whole"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("cost model"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("errors 0 px"), std::string::npos) << run.out;

    const nlohmann::json j = test::readJson(dir / "bench.json");
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j["scene"], kDominoes);
    EXPECT_EQ(j["size"], nlohmann::json::array({96, 72}));
    EXPECT_EQ(j["backend"], "software");
    EXPECT_EQ(j["repeat"], 2);
    EXPECT_EQ(j["cull"], "none");
    ASSERT_EQ(j["frames"].size(), 6u);
    for (std::size_t i = 0; i < 6; ++i) {
        const nlohmann::json& f = j["frames"][i];
        SCOPED_TRACE(f.dump());
        EXPECT_EQ(f["frame"], int(3 + i));
        EXPECT_EQ(f["mode"], i == 0 ? "rebuild" : "reuse") << "the first frame has no predecessor";
        for (const char* key : {"full_ms", "reuse_ms", "oracle_ms", "oracle_whole_ms", "plan_ms", "model_ms", "overlap_ms"}) {
            ASSERT_TRUE(f[key].is_number()) << key;
            EXPECT_GE(f[key].get<double>(), 0.0) << key;
        }
        EXPECT_EQ(f["p_dd"].get<int>() + f["p_ds"].get<int>() + f["p_sd"].get<int>() + f["p_ss"].get<int>(), 1608);
        EXPECT_EQ(f["drawn_tris"], 1608);
        EXPECT_EQ(f["error_px"], 0);
        EXPECT_EQ(f["tie_px"], 0) << "dominoes never tie in depth";
        if (i > 0) {
            // Some dominoes move in every frame after the first.
            EXPECT_GT(f["p_sd"].get<int>() + f["p_dd"].get<int>(), 0);
            EXPECT_LT(f["redrawn_tris"].get<int>(), 1608);
        }
    }
    const nlohmann::json& s = j["summary"];
    EXPECT_EQ(s["frames"], 6);
    EXPECT_EQ(s["modes"]["reuse"], 5);
    EXPECT_EQ(s["modes"]["rebuild"], 1);
    EXPECT_TRUE(s["speedup"].is_number());
    EXPECT_TRUE(s["ratio_to_oracle"].is_number());
    EXPECT_TRUE(s["ratio_to_oracle_whole"].is_number());
    for (const char* set : {"reuse_frames", "all_frames"})
        for (const char* key : {"median_oracle_ms", "median_oracle_whole_ms", "ratio_to_oracle", "ratio_to_oracle_whole"})
            EXPECT_TRUE(s[set][key].is_number()) << set << " " << key;
    EXPECT_EQ(s["reuse_frames"]["ratio_to_oracle_whole"], s["ratio_to_oracle_whole"]);    EXPECT_EQ(s["total_error_px"], 0);
    EXPECT_EQ(s["total_tie_px"], 0);
    EXPECT_EQ(s["static_pair_bytes"], 96 * 72 * 12);
    EXPECT_EQ(s["model"]["fitted_frames"], 5);
    EXPECT_EQ(s["model"]["excluded_frames"], 1);
    EXPECT_FALSE(s.contains("note"));

    const std::vector<std::string> rows = test::lines(readAll(dir / "bench.csv"));
    ASSERT_EQ(rows.size(), 7u);
    EXPECT_EQ(rows[0].substr(0, 54), "frame,mode,full_ms,reuse_ms,plan_ms,oracle_ms,oracle_w");
    EXPECT_NE(rows[0].find(",oracle_whole_ms,"), std::string::npos) << rows[0];
    EXPECT_EQ(rows[1].substr(0, 10), "3,rebuild,");
    EXPECT_EQ(rows[2].substr(0, 8), "4,reuse,");
}

TEST(ReuseBenchCliTest, OneFrameIsAllowedAndTheSummarySaysNothingWasReused) {
    const fs::path dir = test::freshDir("ReuseBenchOneFrame");
    std::vector<std::string> args = base("5:5");
    args.insert(args.end(), {"--json", "one.json", "-q"});
    const CliRun run = runFrugal(dir, args);
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err, "") << "-q: nothing on stderr";
    EXPECT_NE(run.out.find("note: no frame in reuse mode"), std::string::npos) << run.out;
    const nlohmann::json j = test::readJson(dir / "one.json");
    ASSERT_EQ(j["frames"].size(), 1u);
    EXPECT_TRUE(j["summary"]["speedup"].is_null());
    EXPECT_TRUE(j["summary"]["ratio_to_oracle_whole"].is_null());
    EXPECT_TRUE(j["frames"][0]["oracle_whole_ms"].is_number());
    EXPECT_TRUE(j["summary"].contains("note"));
}

TEST(ReuseBenchCliTest, CulledListsAndReuseOptionsAreTakenAndChecked) {
    const fs::path dir = test::freshDir("ReuseBenchCull");
    std::vector<std::string> args = base("0:3");
    args.insert(args.end(), {"--cull", "backface", "--reuse-grain", "1", "--reuse-cell", "8", "--no-fallback",
                             "--json", "c.json", "-q"});
    const CliRun run = runFrugal(dir, args);
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json j = test::readJson(dir / "c.json");
    EXPECT_EQ(j["cull"], "backface");
    EXPECT_EQ(j["reuse"], (nlohmann::json{{"grain", 1}, {"cell", 8}, {"fallback", false}}));
    EXPECT_EQ(j["summary"]["total_error_px"], 0);
    for (const nlohmann::json& f : j["frames"]) EXPECT_LT(f["drawn_tris"].get<int>(), 1608) << "back faces culled";
}

TEST(ReuseBenchCliTest, PlotWritesTheSvgTheScriptAndTheCsv) {
    if (!test::haveGnuplot())
        FRUGAL_SKIP_IF_MISSING("gnuplot (Debian: gnuplot-nox)");
    const fs::path dir = test::freshDir("ReuseBenchPlot");
    std::vector<std::string> args = base("0:4");
    args.insert(args.end(), {"--plot", "bench.svg", "-q"});
    const CliRun run = runFrugal(dir, args);
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"bench.csv", "bench.gp", "bench.svg"}));
    EXPECT_NE(readAll(dir / "bench.svg").find("<svg"), std::string::npos);
    EXPECT_NE(readAll(dir / "bench.gp").find("bench.csv"), std::string::npos) << "the script reads the CSV beside it";
}

struct BadCase {
    std::vector<std::string> args;
    int status;
    std::string line;
};

TEST(ReuseBenchCliTest, BadCommandLinesGetOneLineAndNoFile) {
    const fs::path dir = test::freshDir("ReuseBenchBad");
    const BadCase cases[] = {
        {{"reuse-bench", kDominoes, "--json", "x.json"},
         2,
         "error: --frames: reuse-bench needs a frame range A:B (each frame after A may reuse the one before)"},
        {{"reuse-bench", "--frames", "0:3", "--repeat", "0"}, 2, "error: --repeat: '0' is not a whole number from 1 to 10000"},
        {{"reuse-bench", "--frames", "3:1"}, 2, "error: --frames: '3:1' is not a frame range (A:B, first and last frame: 0 <= A <= B, at most 1000000 frames)"},
        {{"reuse-bench", "--frames", "0:3", "--cull", "oracle"},
         2,
         "error: --cull oracle: the oracle is an id pass of each frame, not a plan to reuse"},
        {{"reuse-bench", "--frames", "0:3", "--plot", "x.png"}, 2, "error: --plot x.png: gnuplot writes SVG here; name it .svg"},
        {{"reuse-bench", "--frames", "0:3", "--reuse"}, 2, "error: --reuse: unknown option (see 'frugal-lab help reuse-bench')"},
        {{"reuse-bench", "--frames", "0:3", "--reuse-cell", "0"},
         2,
         "error: --reuse-cell: '0' is not a whole number from 1 to 4096"},
        {{"reuse-bench", "--frames", "0:1", "missing.glb", "--json", "x.json"}, 1, "error: missing.glb: no such file"},
    };
    for (const BadCase& c : cases) {
        std::string joined;
        for (const std::string& a : c.args) joined += a + " ";
        SCOPED_TRACE(joined);
        const CliRun run = runFrugal(dir, c.args);
        EXPECT_EQ(run.status, c.status) << run.err;
        EXPECT_EQ(run.errLines(), std::vector<std::string>{c.line});
        EXPECT_EQ(run.out, "");
        EXPECT_TRUE(filesIn(dir).empty());
    }
}

TEST(ReuseBenchCliTest, HelpListsTheOptions) {
    const fs::path dir = test::freshDir("ReuseBenchHelp");
    const CliRun run = runFrugal(dir, {"help", "reuse-bench"});
    ASSERT_EQ(run.status, 0);
    for (const char* text : {"usage: frugal-lab reuse-bench", "--repeat K", "--plot FILE.svg", "--reuse-grain N", "--frames A:B",
                             "oracle (cells)", "oracle (whole)", "reuse/whole"})
        EXPECT_NE(run.out.find(text), std::string::npos) << text;
    const CliRun usage = test::runLab(dir, {"--help"});
    EXPECT_NE(usage.out.find("frugal-lab reuse-bench"), std::string::npos);
}

}  // namespace
}  // namespace frugal
