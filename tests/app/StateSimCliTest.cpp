// `frugal-lab state-sim` on the command line, end to end: the real binary in a child process. The figures
// are means over random instances, so the tests assert orderings and ranges that hold on average (best
// <= paper <= submit, the bound below best), never the paper's numbers.
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

const char* const kMethodNames[] = {"submit", "paper", "key", "greedy", "lookahead", "best"};

void expectCells(const nlohmann::json& cells, const char* axis, const std::vector<int>& values) {
    ASSERT_TRUE(cells.is_array());
    ASSERT_EQ(cells.size(), values.size());
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const nlohmann::json& c = cells[i];
        SCOPED_TRACE(c.dump());
        EXPECT_EQ(c.size(), 5u) << "rss_count, states, paper_sorted, paper_unsorted, methods";
        EXPECT_EQ(c[axis], values[i]);
        EXPECT_GT(c["paper_sorted"].get<double>(), 0.0);
        EXPECT_GT(c["paper_unsorted"].get<double>(), c["paper_sorted"].get<double>());
        const nlohmann::json& m = c["methods"];
        ASSERT_EQ(m.size(), 6u);
        for (const char* name : kMethodNames) {
            ASSERT_TRUE(m.contains(name)) << name;
            EXPECT_GT(m[name]["mean"].get<double>(), 0.0) << name;
            EXPECT_GE(m[name]["ci95"].get<double>(), 0.0) << name;
        }
        const double best = m["best"]["mean"].get<double>();
        for (const char* name : kMethodNames) {
            EXPECT_LE(best, m[name]["mean"].get<double>() + 1e-9) << name;
        }
        EXPECT_LT(m["paper"]["mean"].get<double>(), m["submit"]["mean"].get<double>());
        EXPECT_LE(m["greedy"]["mean"].get<double>(), m["submit"]["mean"].get<double>());
        // Our unsorted figure is the paper's within a wide margin even over 5 instances.
        EXPECT_NEAR(m["submit"]["mean"].get<double>() / c["paper_unsorted"].get<double>(), 1.0, 0.35);
    }
}

TEST(StateSimCliTest, WritesTheTablesAsJsonAndCsv) {
    const fs::path dir = test::freshDir("StateSimJson");
    const CliRun run = runFrugal(dir, {"state-sim", "--seeds", "5", "--json", "s.json", "--csv", "s.csv"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err, "");
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"s.csv", "s.json"}));
    for (const char* text : {"Table 6", "Table 7", "set-not-held", "every-set", "symmetric-difference", "Held-Karp", "ratios"})
        EXPECT_NE(run.out.find(text), std::string::npos) << text << "\n" << run.out;

    const nlohmann::json j = test::readJson(dir / "s.json");
    ASSERT_TRUE(j.is_object());
    expectCells(j["table6"], "rss_count", {40, 80, 120, 160, 200});
    expectCells(j["table7"], "states", {5, 10, 15, 20, 25});
    for (const nlohmann::json& c : j["table6"]) EXPECT_EQ(c["states"], 5);
    for (const nlohmann::json& c : j["table7"]) EXPECT_EQ(c["rss_count"], 50);
    EXPECT_EQ(j["table6"][0]["paper_sorted"], 334);
    EXPECT_EQ(j["table6"][0]["paper_unsorted"], 921);
    EXPECT_EQ(j["seeds"], 5);
    EXPECT_EQ(j["cost_rule"], "set-not-held");
    for (const char* table : {"table6", "table7"}) {
        const nlohmann::json& bounds = j["lower_bound"][table];
        ASSERT_EQ(bounds.size(), 5u);
        for (std::size_t i = 0; i < 5; ++i) {
            EXPECT_LE(bounds[i]["mean"].get<double>(), j[table][i]["methods"]["best"]["mean"].get<double>() + 1e-9);
        }
    }
    // Paying for every state set makes every order cost the same.
    for (const nlohmann::json& c : j["alternatives"]["every-set"]["table6"]) {
        EXPECT_DOUBLE_EQ(c["methods"]["best"]["mean"].get<double>(), c["methods"]["submit"]["mean"].get<double>());
    }
    EXPECT_EQ(j["alternatives"]["symmetric-difference"]["table7"].size(), 5u);
    const nlohmann::json& checks = j["optimum_check"];
    ASSERT_EQ(checks.size(), 2u);
    for (const nlohmann::json& c : checks) {
        EXPECT_EQ(c["rss_count"], 16);
        EXPECT_EQ(c["instances"], 5);
        EXPECT_LE(c["optimum"]["mean"].get<double>(), c["search"]["mean"].get<double>() + 1e-9);
        EXPECT_LE(c["lower_bound"]["mean"].get<double>(), c["optimum"]["mean"].get<double>() + 1e-9);
        EXPECT_GE(c["mean_gap"].get<double>(), 0.0);
    }

    const std::vector<std::string> csv = test::lines(test::readAll(dir / "s.csv"));
    ASSERT_EQ(csv.size(), 1u + 3u * 2u * 5u * 7u);  // rules × tables × cells × (methods + bound)
    EXPECT_EQ(csv[0], "rule,table,rss_count,states,method,mean,ci95,paper_sorted,paper_unsorted");
    EXPECT_EQ(test::csvFields(csv[1]).size(), 9u);
}

TEST(StateSimCliTest, TheSameSeedsPrintTheSameTables) {
    const fs::path dir = test::freshDir("StateSimSeeds");
    const CliRun a = runFrugal(dir, {"state-sim", "--seeds", "2"}), b = runFrugal(dir, {"state-sim", "--seeds", "2"});
    ASSERT_EQ(a.status, 0) << a.err;
    EXPECT_EQ(a.out, b.out);
}

TEST(StateSimCliTest, PlotWritesTheScriptBesideTheSvg) {
    if (!test::haveGnuplot()) FRUGAL_SKIP_IF_MISSING("gnuplot (Debian: gnuplot-nox)");
    const fs::path dir = test::freshDir("StateSimPlot");
    const CliRun run = runFrugal(dir, {"state-sim", "--seeds", "2", "--plot", "s.svg"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"s.csv", "s.gp", "s.svg"}));
    EXPECT_NE(test::readAll(dir / "s.svg").find("<svg"), std::string::npos);
}

// Without gnuplot the data files stay (they are what the plot is drawn from) and one line says what
// to install. (PATH names a folder without gnuplot; frugal is run by its full path.)
TEST(StateSimCliTest, PlotWithoutGnuplotIsOneLineAndKeepsTheData) {
    const fs::path dir = test::freshDir("StateSimNoGnuplot");
    const fs::path noGnuplot = test::freshDir("StateSimNoGnuplotBin");
    const CliRun run = runFrugal(dir, {"state-sim", "--seeds", "1", "--plot", "s.svg"}, "PATH=" + noGnuplot.string());
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.errLines(),
              std::vector<std::string>{"error: --plot s.svg: gnuplot not found (Debian: apt-get install gnuplot-nox)"});
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"s.csv", "s.gp"}));
}

TEST(StateSimCliTest, BadCommandLinesGetOneLineStatus2AndNoFile) {
    const fs::path dir = test::freshDir("StateSimBad");
    const std::vector<test::FailingRun> cases = {
        {{"state-sim", "--seeds", "0", "--json", "x.json"}, "error: --seeds: '0' is not a whole number from 1 to 100000"},
        {{"state-sim", "--seeds", "x"}, "error: --seeds: 'x' is not a whole number from 1 to 100000"},
        {{"state-sim", "--json", "", "--seeds", "1"}, "error: --json: '' is not a file name"},
        {{"state-sim", "--seeds", "1", "--plot", "x.png"}, "error: --plot x.png: gnuplot writes SVG here; name it .svg"},
        {{"state-sim", "--wat"}, "error: --wat: unknown option (see 'frugal-lab help state-sim')"},
        {{"state-sim", "extra"}, "error: unexpected argument 'extra'"},
    };
    test::expectOneErrorLine(dir, cases);
}

TEST(StateSimCliTest, AnUnwritableFileIsOneLineAndNoFile) {
    const fs::path dir = test::freshDir("StateSimUnwritable");
    const CliRun run = runFrugal(dir, {"state-sim", "--seeds", "1", "--csv", "s.csv", "--json", "missing/s.json"});
    EXPECT_EQ(run.status, 1) << run.err;
    ASSERT_EQ(run.errLines().size(), 1u);
    EXPECT_EQ(run.errLines()[0].rfind("error: ", 0), 0u) << run.err;
    EXPECT_TRUE(filesIn(dir).empty());
}

TEST(StateSimCliTest, HelpExplainsEveryOption) {
    const fs::path dir = test::freshDir("StateSimHelp");
    const CliRun run = runFrugal(dir, {"help", "state-sim"});
    ASSERT_EQ(run.status, 0);
    for (const char* text : {"usage: frugal-lab state-sim", "--seeds N", "--json FILE", "--csv FILE", "--plot FILE.svg", "set-not-held",
                             "lookahead", "Held-Karp"})
        EXPECT_NE(run.out.find(text), std::string::npos) << text;
    const CliRun usage = test::runLab(dir, {"--help"});
    EXPECT_NE(usage.out.find("frugal-lab state-sim"), std::string::npos);
}

}  // namespace
}  // namespace frugal
