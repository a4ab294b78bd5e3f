// The cull report's JSON, CSV and gnuplot script on a small hand-made report.
#include <cmath>
#include <filesystem>
#include <limits>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestSupport.h"
#include "lab/CullReport.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

MethodResult row(const std::string& method, std::size_t pvs, std::size_t misses, std::size_t pixels, double cullMs,
                 double drawMs, double ratioToOracle) {
    MethodResult m;
    m.method = method;
    m.tos = 100;
    m.pvs = pvs;
    m.rvs = 20;  // visible: `misses` of them dropped; the rest of the PVS is waste
    m.misses = misses;
    m.waste = pvs - (m.rvs - misses);
    m.pixelsDiffering = pixels;
    m.cullMs = cullMs;
    m.drawMs = drawMs;
    m.ratioToOracle = ratioToOracle;
    m.ratioToFull = ratioToOracle / 3.0;
    m.ratioToFullCullface = ratioToOracle / 2.0;
    return m;
}

// Three views; "none" and "sphere" in each (odd counts), "oracle" in views 0 and 2 only (even
// count); the other methods absent.
CullReport fakeReport() {
    CullReport r;
    r.scene = "builtin:cubes";
    r.width = 320;
    r.height = 240;
    r.backend = "software";
    r.timing = "cold";
    r.views.push_back({0, "whole", glm::vec3(0.1f, 2.0f, -3.5f), glm::vec3(0.0f), {
        row("none", 100, 0, 0, 0.0, 3.0, 3.0),
        row("sphere", 60, 0, 0, 0.25, 2.0, 2.0),
        row("oracle", 40, 0, 0, 0.0, 1.0, 1.0),
    }, std::nullopt});
    r.views.push_back({1, "partial", glm::vec3(1.0f), glm::vec3(0.0f, 0.5f, 0.0f), {
        row("none", 100, 0, 0, 0.0, 5.0, 5.0),
        row("sphere", 30, 2, 7, 0.5, 1.5, 2.5),
    }, std::nullopt});
    r.views.push_back({2, "grazing", glm::vec3(2.0f), glm::vec3(0.0f), {
        row("none", 100, 0, 0, 0.0, 4.0, 4.0),
        row("sphere", 41, 3, 1, 0.125, 1.75, 1.5),
        row("oracle", 45, 0, 0, 0.0, 2.0, 1.0),
    }, OcclusionView{2, 3, 0.75, 59, 4, 9, 3, 1.5, "m/occlusion-view-2.png"}});
    return r;
}

TEST(CullReportTest, JsonHasTheDocumentedKeys) {
    const nlohmann::json j = nlohmann::json::parse(cullReportJson(fakeReport()));
    EXPECT_EQ(j["scene"], "builtin:cubes");
    EXPECT_EQ(j["size"], nlohmann::json::array({320, 240}));
    EXPECT_EQ(j["backend"], "software");
    EXPECT_EQ(j["timing"], "cold");
    ASSERT_EQ(j["views"].size(), 3u);
    const nlohmann::json& view = j["views"][0];
    EXPECT_EQ(view["index"], 0);
    EXPECT_EQ(view["class"], "whole");
    ASSERT_EQ(view["eye"].size(), 3u);
    EXPECT_EQ(view["eye"][0].get<double>(), 0.1) << "floats written in their shortest form";
    EXPECT_EQ(view["eye"][2].get<double>(), -3.5);
    EXPECT_EQ(view["target"], nlohmann::json::array({0.0, 0.0, 0.0}));
    EXPECT_EQ(j["views"][1]["target"][1].get<double>(), 0.5);
    ASSERT_EQ(view["methods"].size(), 3u);
    const nlohmann::json& m = j["views"][1]["methods"][1];
    for (const char* key : {"method", "tos", "pvs", "rvs", "misses", "waste", "pixels_differing", "cull_ms", "draw_ms",
                            "ratio_to_oracle", "ratio_to_full", "ratio_to_full_cullface"})
        EXPECT_TRUE(m.contains(key)) << key;
    EXPECT_EQ(m.size(), 12u);
    EXPECT_EQ(m["method"], "sphere");
    EXPECT_EQ(m["tos"], 100);
    EXPECT_EQ(m["pvs"], 30);
    EXPECT_EQ(m["rvs"], 20);
    EXPECT_EQ(m["misses"], 2);
    EXPECT_EQ(m["waste"], 12);
    EXPECT_EQ(m["pixels_differing"], 7);
    EXPECT_EQ(m["cull_ms"].get<double>(), 0.5);
    EXPECT_EQ(m["draw_ms"].get<double>(), 1.5);
    EXPECT_EQ(m["ratio_to_oracle"].get<double>(), 2.5);
    EXPECT_NEAR(m["ratio_to_full"].get<double>(), 2.5 / 3.0, 1e-15);
    EXPECT_EQ(m["ratio_to_full_cullface"].get<double>(), 1.25);

    // The occlusion pass's record, on the view that has one only.
    EXPECT_FALSE(j["views"][0].contains("occlusion"));
    const nlohmann::json& o = j["views"][2]["occlusion"];
    EXPECT_EQ(o, nlohmann::json::parse(R"({"runs": 2, "frames": 3, "pass_ms": 0.75, "triangles_hidden": 59,
        "clusters_hidden": 4, "clusters_tested": 9, "draws_saved": 3, "saved_ms_estimate": 1.5, "image": "m/occlusion-view-2.png"})"));
}

TEST(CullReportTest, JsonSummaryHasMediansWorstViewAndTotals) {
    const nlohmann::json j = nlohmann::json::parse(cullReportJson(fakeReport()));
    const nlohmann::json& summary = j["summary"];
    ASSERT_EQ(summary.size(), 3u) << "only the methods present";
    EXPECT_FALSE(summary.contains("cones"));

    const nlohmann::json& none = summary["none"];  // three views: the middle value
    EXPECT_EQ(none["views"], 3);
    EXPECT_EQ(none["median_pvs"].get<double>(), 100.0);
    EXPECT_EQ(none["median_draw_ms"].get<double>(), 4.0);
    EXPECT_EQ(none["median_ratio_to_oracle"].get<double>(), 4.0);
    EXPECT_EQ(none["worst_view"]["index"], 1);
    EXPECT_EQ(none["worst_view"]["class"], "partial");
    EXPECT_EQ(none["worst_view"]["ratio_to_oracle"].get<double>(), 5.0);
    EXPECT_EQ(none["total_misses"], 0);
    EXPECT_EQ(none["views_with_misses"], 0);

    const nlohmann::json& sphere = summary["sphere"];
    EXPECT_EQ(sphere["views"], 3);
    EXPECT_EQ(sphere["median_pvs"].get<double>(), 41.0);
    EXPECT_EQ(sphere["median_cull_ms"].get<double>(), 0.25);
    EXPECT_EQ(sphere["median_draw_ms"].get<double>(), 1.75);
    EXPECT_EQ(sphere["median_ratio_to_oracle"].get<double>(), 2.0);
    EXPECT_NEAR(sphere["median_ratio_to_full"].get<double>(), 2.0 / 3.0, 1e-15);
    EXPECT_EQ(sphere["median_ratio_to_full_cullface"].get<double>(), 1.0);
    EXPECT_EQ(sphere["worst_view"]["index"], 1);
    EXPECT_EQ(sphere["total_misses"], 5);
    EXPECT_EQ(sphere["total_pixels_differing"], 8);
    EXPECT_EQ(sphere["views_with_misses"], 2);

    const nlohmann::json& oracle = summary["oracle"];  // two views: the mean of both
    EXPECT_EQ(oracle["views"], 2);
    EXPECT_EQ(oracle["median_pvs"].get<double>(), 42.5);
    EXPECT_EQ(oracle["median_draw_ms"].get<double>(), 1.5);
    EXPECT_EQ(oracle["median_ratio_to_oracle"].get<double>(), 1.0);
    EXPECT_EQ(oracle["worst_view"]["index"], 0) << "ties go to the first view";
    EXPECT_EQ(oracle["worst_view"]["class"], "whole");

    for (const auto& [method, s] : summary.items())
        for (const char* key : {"views", "median_pvs", "median_cull_ms", "median_draw_ms", "median_ratio_to_oracle",
                                "median_ratio_to_full", "median_ratio_to_full_cullface", "worst_view", "total_misses",
                                "total_pixels_differing", "views_with_misses"})
            EXPECT_TRUE(s.contains(key)) << method << ": " << key;
}

TEST(CullReportTest, JsonGivesTheCullShareAndMediansPerViewClass) {
    const nlohmann::json j = nlohmann::json::parse(cullReportJson(fakeReport()));
    // sphere: cull ÷ draw of 0.125, 0.333…, 0.0714… → the middle one.
    EXPECT_NEAR(j["summary"]["sphere"]["median_cull_over_draw"].get<double>(), 0.125, 1e-15);
    EXPECT_EQ(j["summary"]["none"]["median_cull_over_draw"].get<double>(), 0.0);

    const nlohmann::json& byClass = j["by_class"];
    ASSERT_EQ(byClass.size(), 3u);  // whole, partial, grazing
    const nlohmann::json& partialSphere = byClass["partial"]["sphere"];
    EXPECT_EQ(partialSphere["views"], 1);
    EXPECT_EQ(partialSphere["tos"], 100);
    EXPECT_EQ(partialSphere["median_pvs"].get<double>(), 30.0);
    EXPECT_NEAR(partialSphere["median_speed_up"].get<double>(), 3.0 / 2.5, 1e-15);
    EXPECT_NEAR(partialSphere["median_speed_up_over_cullface"].get<double>(), 2.0 / 2.5, 1e-15);
    EXPECT_EQ(partialSphere["total_misses"], 2);
    EXPECT_EQ(partialSphere["total_pixels_differing"], 7);
    EXPECT_FALSE(byClass["partial"].contains("oracle")) << "only the methods the class has";
    EXPECT_TRUE(byClass["grazing"].contains("oracle"));
}

TEST(CullReportTest, NonFiniteNumbersAreNullInJsonAndEmptyInCsv) {
    CullReport r = fakeReport();
    r.views[1].methods[0].ratioToOracle = std::numeric_limits<double>::infinity();
    r.views[1].methods[0].ratioToFull = std::numeric_limits<double>::quiet_NaN();
    r.views[1].eye.y = std::numeric_limits<float>::quiet_NaN();
    const nlohmann::json j = nlohmann::json::parse(cullReportJson(r));
    const nlohmann::json& m = j["views"][1]["methods"][0];
    EXPECT_TRUE(m["ratio_to_oracle"].is_null());
    EXPECT_TRUE(m["ratio_to_full"].is_null());
    EXPECT_TRUE(j["views"][1]["eye"][1].is_null());
    // The infinite ratio is the worst; NaN is left out of the median (3 and 4 remain).
    EXPECT_EQ(j["summary"]["none"]["worst_view"]["index"], 1);
    EXPECT_TRUE(j["summary"]["none"]["worst_view"]["ratio_to_oracle"].is_null());
    EXPECT_EQ(j["summary"]["none"]["median_ratio_to_full"].get<double>(), (1.0 + 4.0 / 3.0) / 2.0);

    const std::vector<std::string> rows = test::lines(cullReportCsv(r));
    ASSERT_EQ(rows.size(), 9u);
    const std::vector<std::string> fields = test::csvFields(rows[4]);  // view 1, none
    ASSERT_EQ(fields.size(), 14u) << rows[4];
    EXPECT_EQ(fields[2], "none");
    EXPECT_EQ(fields[11], "");
    EXPECT_EQ(fields[12], "");
    EXPECT_EQ(fields[13], "2.5") << "the row's own ratio_to_full_cullface";
}

TEST(CullReportTest, CsvHasTheHeaderAndOneRowPerViewAndMethod) {
    const std::vector<std::string> rows = test::lines(cullReportCsv(fakeReport()));
    ASSERT_EQ(rows.size(), 9u);
    EXPECT_EQ(rows[0],
              "view,class,method,tos,pvs,rvs,misses,waste,pixels_differing,cull_ms,draw_ms,ratio_to_oracle,"
              "ratio_to_full,ratio_to_full_cullface");
    const std::vector<std::string> fields = test::csvFields(rows[5]);  // view 1, sphere
    ASSERT_EQ(fields.size(), 14u) << rows[5];
    EXPECT_EQ(fields, (std::vector<std::string>{"1", "partial", "sphere", "100", "30", "20", "2", "12", "7", "0.5",
                                                "1.5", "2.5", "0.833333", "1.25"}));
    for (std::size_t i = 1; i < rows.size(); ++i) EXPECT_EQ(test::csvFields(rows[i]).size(), 14u) << rows[i];
}

TEST(CullReportTest, CsvQuotesFieldsWithCommasAndQuotes) {
    CullReport r = fakeReport();
    r.views[0].methods[1].method = "paper, \"tight\"";
    const std::vector<std::string> rows = test::lines(cullReportCsv(r));
    ASSERT_EQ(rows.size(), 9u);
    const std::string start = "0,whole,\"paper, \"\"tight\"\"\",100,60,20,0,";
    EXPECT_EQ(rows[2].substr(0, start.size()), start);
}

TEST(CullReportTest, GnuplotDrawsTheCsvIntoAnSvg) {
    if (!test::haveGnuplot()) FRUGAL_SKIP_IF_MISSING("gnuplot (Debian: gnuplot-nox)");
    const fs::path dir = test::freshDir("CullReportTest.Gnuplot");
    // A quote in the paths: gnuplot's single-quoted strings must double it.
    const fs::path csv = dir / "view's report.csv", svg = dir / "it's plot.svg", script = dir / "plot.gp";
    test::writeFile(csv, cullReportCsv(fakeReport()));
    test::writeFile(script, cullReportGnuplot(csv.string(), svg.string()));
    std::string messages;
    EXPECT_EQ(test::runGnuplot(script, messages), 0) << messages;
    ASSERT_TRUE(fs::exists(svg)) << messages;
    const std::string text = test::readAll(svg);
    EXPECT_NE(text.find("<svg"), std::string::npos);
    EXPECT_NE(text.find("sphere"), std::string::npos) << "a method's key entry";
}

TEST(CullReportTest, GnuplotDrawsAnEmptyReport) {
    if (!test::haveGnuplot()) FRUGAL_SKIP_IF_MISSING("gnuplot (Debian: gnuplot-nox)");
    const fs::path dir = test::freshDir("CullReportTest.GnuplotEmpty");
    CullReport empty = fakeReport();
    empty.views.clear();
    test::writeFile(dir / "report.csv", cullReportCsv(empty));
    test::writeFile(dir / "plot.gp", cullReportGnuplot((dir / "report.csv").string(), (dir / "report.svg").string()));
    std::string messages;
    EXPECT_EQ(test::runGnuplot(dir / "plot.gp", messages), 0) << messages;
    EXPECT_NE(test::readAll(dir / "report.svg").find("<svg"), std::string::npos) << messages;
}

}  // namespace
}  // namespace frugal
