// The reuse benchmark's report: the non-negative least squares, the cost model fitted to a
// hand-made benchmark, and its JSON, CSV and gnuplot script.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestSupport.h"
#include "lab/ReuseReport.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

// --- non-negative least squares -----------------------------------------------------------------------

TEST(ReuseReportTest, LeastSquaresRecoversExactCoefficients) {
    std::vector<std::vector<double>> rows;
    std::vector<double> y;
    for (int i = 0; i < 12; ++i) {
        const double a = 1000.0 * (i % 5) + 37.0 * i, b = 500.0 + 3.0 * i * i, c = 20000.0 - 900.0 * i;
        rows.push_back({1.0, a, b, c});
        y.push_back(0.5 + 2e-6 * a + 3e-6 * b + 1e-4 * c);
    }
    const std::vector<double> x = nonNegativeLeastSquares(rows, y);
    ASSERT_EQ(x.size(), 4u);
    EXPECT_NEAR(x[0], 0.5, 1e-9);
    EXPECT_NEAR(x[1], 2e-6, 1e-12);
    EXPECT_NEAR(x[2], 3e-6, 1e-12);
    EXPECT_NEAR(x[3], 1e-4, 1e-12);
}

TEST(ReuseReportTest, LeastSquaresKeepsEveryCoefficientNonNegative) {
    // y = 2 a − b exactly: the unconstrained fit has a negative coefficient; the constrained one
    // drops b and fits a alone: x_a = Σ a·y / Σ a².
    const std::vector<std::vector<double>> rows = {{1.0, 0.0}, {2.0, 1.0}, {3.0, 3.0}, {4.0, 2.0}};
    std::vector<double> y;
    for (const auto& r : rows) y.push_back(2.0 * r[0] - r[1]);
    const std::vector<double> x = nonNegativeLeastSquares(rows, y);
    ASSERT_EQ(x.size(), 2u);
    double ay = 0.0, aa = 0.0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        ay += rows[i][0] * y[i];
        aa += rows[i][0] * rows[i][0];
    }
    EXPECT_NEAR(x[0], ay / aa, 1e-12);
    EXPECT_EQ(x[1], 0.0);
    for (double v : x) EXPECT_GE(v, 0.0);
}

TEST(ReuseReportTest, LeastSquaresHandlesZeroAndDependentColumnsAndNoRows) {
    // Column 1 is all zero, column 2 a copy of column 0: one of the pair is enough.
    const std::vector<std::vector<double>> rows = {{1.0, 0.0, 1.0}, {2.0, 0.0, 2.0}, {3.0, 0.0, 3.0}};
    const std::vector<double> x = nonNegativeLeastSquares(rows, {3.0, 6.0, 9.0});
    ASSERT_EQ(x.size(), 3u);
    EXPECT_EQ(x[1], 0.0);
    EXPECT_NEAR(x[0] + x[2], 3.0, 1e-12);
    EXPECT_TRUE(x[0] == 0.0 || x[2] == 0.0) << "the smaller support wins a tie";
    // All negative data: nothing non-negative helps, every coefficient 0.
    EXPECT_EQ(nonNegativeLeastSquares({{1.0}, {2.0}}, {-1.0, -2.0}), std::vector<double>{0.0});
    EXPECT_TRUE(nonNegativeLeastSquares({}, {}).empty());
}

// --- the benchmark ---------------------------------------------------------------------------------

ReuseBenchFrame frameOf(int index, const std::string& mode, double fullMs, double reuseMs, double oracleMs,
                        double oracleWholeMs) {
    ReuseBenchFrame f;
    f.frame = index;
    f.mode = mode;
    f.reason = mode == "reuse" ? "camera still" : mode == "rebuild" ? "first frame" : "camera, light or background changed";
    f.fullMs = fullMs;
    f.reuseMs = reuseMs;
    f.planMs = 0.25;
    f.oracleMs = oracleMs;
    f.oracleWholeMs = oracleWholeMs;
    f.overlapMs = 0.01 * index;
    f.pDD = 12;
    f.pDS = 0;
    f.pSD = 12;
    f.pSS = 72;  // static share 72 / 96 = 0.75
    if (mode == "rebuild") {  // a first frame: everything counts as static
        f.pDD = f.pSD = 0;
        f.pSS = 96;
    }
    f.drawnTris = 96;
    f.copiedPx = mode == "reuse" ? 1000u * std::uint64_t(index) : 4800u;
    f.clearedPx = mode == "reuse" ? 300u * std::uint64_t(index % 3) : 4800u;
    f.redrawnTris = mode == "reuse" ? 24u + std::uint64_t(index % 4) * 3u : 96u;
    f.staticRedrawnTris = f.redrawnTris - 12;
    f.rects = 7;
    f.draws = 5;
    f.fullDraws = 8;
    return f;
}

// Frame 10 a rebuild, 11–15 reuse (times made by a known model), 16 a full render. The cells oracle
// takes 1 ms on every frame; the whole oracle 1 ms on the rebuild and the full render (where it copies
// what the cells oracle copies), 3.1 to 3.5 ms on the reuse frames (median 3.3; over all frames 3.2).
ReuseBench fakeBench() {
    ReuseBench b;
    b.scene = "builtin:dominoes?polygons=96";
    b.width = 80;
    b.height = 60;
    b.backend = "software";
    b.renderer = "frugal software";
    b.repeat = 3;
    b.grain = 16;
    b.cell = 16;
    b.staticPairBytes = 80 * 60 * 12;
    b.clearMs = 0.5;
    b.frames.push_back(frameOf(10, "rebuild", 4.0, 5.0, 1.0, 1.0));
    for (int i = 11; i <= 15; ++i) {
        ReuseBenchFrame f = frameOf(i, "reuse", 4.0, 0.0, 1.0, 2.0 + 0.1 * i);
        // plan + t_0 0.1 + t_c 20 ns/px + t_i 50 ns/px + t_r' 40 µs/triangle
        f.reuseMs = f.planMs + 0.1 + 20e-6 * double(f.copiedPx) + 50e-6 * double(f.clearedPx) + 0.04 * double(f.redrawnTris);
        b.frames.push_back(f);
    }
    b.frames.push_back(frameOf(16, "full", 4.0, 4.5, 1.0, 1.0));
    return b;
}

TEST(ReuseReportTest, CostModelIsFittedOnReuseFramesAndPredictsThem) {
    const ReuseBench bench = fakeBench();
    const CostModel m = fitCostModel(bench);
    EXPECT_EQ(m.twMs, 0.5);
    EXPECT_NEAR(m.trNs, 3.5 / 96.0 * 1e6, 1e-6) << "(full − t_w) / drawn triangles";
    EXPECT_EQ(m.fittedFrames, 5u);
    EXPECT_EQ(m.excludedFrames, 2u);
    EXPECT_NEAR(m.t0Ms, 0.1, 1e-9);
    EXPECT_NEAR(m.tcNs, 20.0, 1e-6);
    EXPECT_NEAR(m.tiNs, 50.0, 1e-6);
    EXPECT_NEAR(m.trReuseNs, 40000.0, 1e-3);
    EXPECT_NEAR(m.reuseR2, 1.0, 1e-12);
    EXPECT_NEAR(m.medianReuseError, 0.0, 1e-9);
    EXPECT_NEAR(m.medianFullError, 0.0, 1e-12);
    for (const ReuseBenchFrame& f : bench.frames) {
        if (f.mode == "reuse") {
            EXPECT_NEAR(modelMs(m, f), f.reuseMs, 1e-9) << f.frame;
        }
        EXPECT_NEAR(fullModelMs(m, f), 4.0, 1e-9) << f.frame;
    }
    // A rebuild: plan + a clear + every triangle + the whole target copied.
    EXPECT_NEAR(modelMs(m, bench.frames[0]), 0.25 + 0.5 + 3.5 + 20e-6 * 4800, 1e-9);
}

TEST(ReuseReportTest, JsonHasTheFramesAndTheSummary) {
    const nlohmann::json j = nlohmann::json::parse(reuseReportJson(fakeBench()));
    EXPECT_EQ(j["scene"], "builtin:dominoes?polygons=96");
    EXPECT_EQ(j["size"], nlohmann::json::array({80, 60}));
    EXPECT_EQ(j["backend"], "software");
    EXPECT_EQ(j["repeat"], 3);
    EXPECT_EQ(j["cull"], "none");
    EXPECT_EQ(j["reuse"]["grain"], 16);
    EXPECT_EQ(j["reuse"]["fallback"], true);
    ASSERT_EQ(j["frames"].size(), 7u);
    const nlohmann::json& f = j["frames"][1];
    for (const char* key : {"frame", "mode", "reason", "full_ms", "reuse_ms", "plan_ms", "oracle_ms", "oracle_whole_ms",
                            "model_ms", "full_model_ms", "speedup", "static_share", "p_dd", "p_ds", "p_sd", "p_ss",
                            "copied_px", "cleared_px", "redrawn_tris", "static_redrawn_tris", "drawn_tris", "rects",
                            "draws", "full_draws", "overlap_ms", "tie_px", "error_px"})
        EXPECT_TRUE(f.contains(key)) << key;
    EXPECT_EQ(f.size(), 27u);
    EXPECT_EQ(f["oracle_ms"].get<double>(), 1.0);
    EXPECT_NEAR(f["oracle_whole_ms"].get<double>(), 3.1, 1e-12);
    EXPECT_EQ(f["draws"], 5);
    EXPECT_EQ(f["full_draws"], 8);
    EXPECT_EQ(f["frame"], 11);
    EXPECT_EQ(f["mode"], "reuse");
    EXPECT_EQ(f["p_ss"], 72);
    EXPECT_EQ(f["copied_px"], 11000);
    EXPECT_EQ(f["static_share"].get<double>(), 0.75);
    EXPECT_NEAR(f["speedup"].get<double>(), 4.0 / f["reuse_ms"].get<double>(), 1e-12);
    EXPECT_NEAR(f["model_ms"].get<double>(), f["reuse_ms"].get<double>(), 1e-9);

    const nlohmann::json& s = j["summary"];
    EXPECT_EQ(s["frames"], 7);
    EXPECT_EQ(s["modes"], (nlohmann::json{{"full", 1}, {"rebuild", 1}, {"reuse", 5}}));
    // Reuse frames: full 4 (all), reuse the middle of five, cells oracle 1, whole oracle 3.3.
    std::vector<double> reuse;
    for (int i = 1; i <= 5; ++i) reuse.push_back(j["frames"][i]["reuse_ms"].get<double>());
    std::sort(reuse.begin(), reuse.end());
    EXPECT_NEAR(s["reuse_frames"]["median_reuse_ms"].get<double>(), reuse[2], 1e-12);
    EXPECT_NEAR(s["speedup"].get<double>(), 4.0 / reuse[2], 1e-12);
    EXPECT_NEAR(s["ratio_to_oracle"].get<double>(), reuse[2] / 1.0, 1e-12);
    EXPECT_NEAR(s["ratio_to_oracle_whole"].get<double>(), reuse[2] / 3.3, 1e-12);
    EXPECT_EQ(s["reuse_frames"]["median_oracle_ms"].get<double>(), 1.0);
    EXPECT_NEAR(s["reuse_frames"]["median_oracle_whole_ms"].get<double>(), 3.3, 1e-12);
    EXPECT_NEAR(s["reuse_frames"]["ratio_to_oracle_whole"].get<double>(), reuse[2] / 3.3, 1e-12);
    EXPECT_EQ(s["reuse_frames"]["ratio_to_oracle_whole"], s["ratio_to_oracle_whole"]);
    // All frames: the rebuild (reuse 5) and the full render (4.5) join; whole oracle 1, 1, 3.1 … 3.5.
    std::vector<double> allReuse;
    for (const nlohmann::json& frame : j["frames"]) allReuse.push_back(frame["reuse_ms"].get<double>());
    std::sort(allReuse.begin(), allReuse.end());
    EXPECT_NEAR(s["all_frames"]["median_oracle_whole_ms"].get<double>(), 3.2, 1e-12);
    EXPECT_NEAR(s["all_frames"]["ratio_to_oracle_whole"].get<double>(), allReuse[3] / 3.2, 1e-12);
    EXPECT_NEAR(s["all_frames"]["ratio_to_oracle"].get<double>(), allReuse[3] / 1.0, 1e-12);
    for (const char* set : {"reuse_frames", "all_frames"})
        for (const char* key : {"frames", "median_full_ms", "median_reuse_ms", "median_oracle_ms",
                                "median_oracle_whole_ms", "median_plan_ms", "speedup", "ratio_to_oracle",
                                "ratio_to_oracle_whole"})
            EXPECT_TRUE(s[set].contains(key)) << set << " " << key;
    EXPECT_EQ(s["reuse_frames"]["frames"], 5);
    EXPECT_EQ(s["all_frames"]["frames"], 7);
    EXPECT_EQ(s["all_frames"]["median_full_ms"].get<double>(), 4.0);
    EXPECT_EQ(s["static_share"].get<double>(), 0.75) << "over the reuse frames, not the rebuild (1.0)";
    EXPECT_EQ(s["static_pair_bytes"], 80 * 60 * 12);
    EXPECT_NEAR(s["max_overlap_ms"].get<double>(), 0.16, 1e-12);
    EXPECT_EQ(s["total_tie_px"], 0);
    EXPECT_EQ(s["total_error_px"], 0);
    EXPECT_EQ(s["frames_with_errors"], 0);
    EXPECT_TRUE(s["first_error_frame"].is_null());
    EXPECT_FALSE(s.contains("note"));
    const nlohmann::json& m = s["model"];
    for (const char* key : {"t_w_ms", "t_r_ns_per_tri", "t_0_ms", "t_c_ns_per_px", "t_i_ns_per_px",
                            "t_r_reuse_ns_per_tri", "fitted_frames", "excluded_frames", "r2", "median_reuse_error",
                            "median_full_error"})
        EXPECT_TRUE(m.contains(key)) << key;
    EXPECT_EQ(m["fitted_frames"], 5);
    EXPECT_EQ(m["excluded_frames"], 2);
    EXPECT_NEAR(m["t_c_ns_per_px"].get<double>(), 20.0, 1e-6);
}

TEST(ReuseReportTest, JsonCountsTiesAndErrorsAndSaysWhenNoFrameReused) {
    ReuseBench b = fakeBench();
    b.frames[2].tiePx = 3;
    b.frames[3].errorPx = 5;
    b.frames[5].errorPx = 1;
    b.frames[4].fullMs = std::numeric_limits<double>::quiet_NaN();
    nlohmann::json j = nlohmann::json::parse(reuseReportJson(b));
    EXPECT_EQ(j["frames"][3]["error_px"], 5);
    EXPECT_TRUE(j["frames"][4]["full_ms"].is_null());
    EXPECT_TRUE(j["frames"][4]["speedup"].is_null());
    EXPECT_EQ(j["summary"]["total_tie_px"], 3);
    EXPECT_EQ(j["summary"]["total_error_px"], 6);
    EXPECT_EQ(j["summary"]["frames_with_errors"], 2);
    EXPECT_EQ(j["summary"]["first_error_frame"], 13);

    // One frame: nothing to reuse.
    b.frames.resize(1);
    j = nlohmann::json::parse(reuseReportJson(b));
    EXPECT_TRUE(j["summary"]["speedup"].is_null());
    EXPECT_TRUE(j["summary"]["ratio_to_oracle"].is_null());
    EXPECT_TRUE(j["summary"]["ratio_to_oracle_whole"].is_null());
    EXPECT_TRUE(j["summary"]["reuse_frames"]["median_oracle_whole_ms"].is_null());
    EXPECT_EQ(j["summary"]["reuse_frames"]["frames"], 0);
    ASSERT_TRUE(j["summary"].contains("note"));
    EXPECT_NE(j["summary"]["note"].get<std::string>().find("no frame in reuse mode"), std::string::npos);
    EXPECT_EQ(j["summary"]["model"]["fitted_frames"], 0);
    EXPECT_EQ(j["summary"]["all_frames"]["speedup"].get<double>(), 4.0 / 5.0);
    EXPECT_EQ(j["summary"]["all_frames"]["ratio_to_oracle_whole"].get<double>(), 5.0 / 1.0);
    EXPECT_EQ(j["summary"]["static_share"].get<double>(), 1.0) << "no reuse frame: over all frames";
}

TEST(ReuseReportTest, CsvHasTheHeaderAndOneRowPerFrame) {
    ReuseBench b = fakeBench();
    b.frames[6].reason = "camera, light or background changed";
    const std::vector<std::string> rows = test::lines(reuseReportCsv(b));
    ASSERT_EQ(rows.size(), 8u);
    EXPECT_EQ(rows[0],
              "frame,mode,full_ms,reuse_ms,plan_ms,oracle_ms,oracle_whole_ms,model_ms,full_model_ms,speedup,static_share,"
              "p_dd,p_ds,p_sd,p_ss,copied_px,cleared_px,redrawn_tris,static_redrawn_tris,drawn_tris,rects,draws,"
              "full_draws,overlap_ms,tie_px,error_px,reason");
    const std::vector<std::string> fields = test::csvFields(rows[2]);  // frame 11
    ASSERT_EQ(fields.size(), 27u) << rows[2];
    EXPECT_EQ(fields[0], "11");
    EXPECT_EQ(fields[1], "reuse");
    EXPECT_EQ(fields[2], "4");
    EXPECT_EQ(fields[5], "1");
    EXPECT_EQ(fields[6], "3.1");
    EXPECT_EQ(fields[10], "0.75");
    EXPECT_EQ(fields[15], "11000");
    EXPECT_EQ(fields[21], "5");
    EXPECT_EQ(fields[22], "8");
    EXPECT_EQ(fields[26], "camera still");
    EXPECT_EQ(rows[7].substr(rows[7].size() - 38), ",\"camera, light or background changed\"") << "quoted";
}

TEST(ReuseReportTest, GnuplotDrawsTheCsvIntoAnSvg) {
    if (!test::haveGnuplot()) FRUGAL_SKIP_IF_MISSING("gnuplot (Debian: gnuplot-nox)");
    const fs::path dir = test::freshDir("ReuseReportTest.Gnuplot");
    const fs::path csv = dir / "bench's frames.csv", svg = dir / "it's plot.svg", script = dir / "plot.gp";
    test::writeFile(csv, reuseReportCsv(fakeBench()));
    test::writeFile(script, reuseReportGnuplot(csv.string(), svg.string()));
    std::string messages;
    EXPECT_EQ(test::runGnuplot(script, messages), 0) << messages;
    ASSERT_TRUE(fs::exists(svg)) << messages;
    const std::string text = test::readAll(svg);
    EXPECT_NE(text.find("<svg"), std::string::npos);
    EXPECT_NE(text.find("paper 000"), std::string::npos) << "the paper's points in the key";
    EXPECT_NE(text.find("oracle (cells)"), std::string::npos);
    EXPECT_NE(text.find("oracle (whole)"), std::string::npos);
}

// The script names the CSV's columns by number: each must be the column the header names.
TEST(ReuseReportTest, GnuplotColumnsAreTheCsvColumns) {
    const std::vector<std::string> header = test::csvFields(test::lines(reuseReportCsv(fakeBench()))[0]);
    const auto column = [&](const std::string& name) {
        const auto it = std::find(header.begin(), header.end(), name);
        EXPECT_NE(it, header.end()) << name;
        return std::to_string(it - header.begin() + 1);
    };
    const std::string script = reuseReportGnuplot("b.csv", "b.svg");
    EXPECT_NE(script.find("100 * $" + column("static_share") + " : NaN):(is(k) ? $" + column("speedup") + " : NaN)"),
              std::string::npos)
        << script;
    const std::vector<std::pair<std::string, std::string>> times = {{"full_ms", "'full'"},
                                                                     {"reuse_ms", "'reuse'"},
                                                                     {"oracle_ms", "'oracle (cells)'"},
                                                                     {"oracle_whole_ms", "'oracle (whole)'"},
                                                                     {"model_ms", "'model'"}};
    for (const auto& [name, title] : times) {
        const std::size_t at = script.find("title " + title);
        ASSERT_NE(at, std::string::npos) << title;
        const std::size_t use = script.rfind("using 1:", at);
        ASSERT_NE(use, std::string::npos) << title;
        EXPECT_EQ(script.substr(use + 8, script.find(' ', use + 8) - use - 8), column(name)) << title;
    }
}

TEST(ReuseReportTest, GnuplotDrawsAnEmptyBench) {
    if (!test::haveGnuplot()) FRUGAL_SKIP_IF_MISSING("gnuplot (Debian: gnuplot-nox)");
    const fs::path dir = test::freshDir("ReuseReportTest.GnuplotEmpty");
    ReuseBench empty = fakeBench();
    empty.frames.clear();
    test::writeFile(dir / "bench.csv", reuseReportCsv(empty));
    test::writeFile(dir / "plot.gp", reuseReportGnuplot((dir / "bench.csv").string(), (dir / "bench.svg").string()));
    std::string messages;
    EXPECT_EQ(test::runGnuplot(dir / "plot.gp", messages), 0) << messages;
    EXPECT_NE(test::readAll(dir / "bench.svg").find("<svg"), std::string::npos) << messages;
}

}  // namespace
}  // namespace frugal
