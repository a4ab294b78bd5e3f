// `frugal report`: every trade on one scene in one run, judged against the plain render; the
// recommendation is exact (or within the budget) and its settings.json renders what the plain
// render does; the pick is never a no-op (a method whose draws are the plain render's) and always a
// row whose paired interval lies below 0.97, and every interval is what its timings in report.json
// give again. No test here depends on which method is fastest: timings decide that.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <frugal/Settings.h>

#include "CliSupport.h"
#include "JsonSupport.h"
#include "TestSupport.h"
#include "io/ImageIO.h"
#include "lab/TradePage.h"
#include "lab/Trades.h"
#include "lab/Views.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::readAll;
using test::runFrugal;

std::size_t occurrences(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

const nlohmann::json& row(const nlohmann::json& report, const std::string& name) {
    for (const nlohmann::json& r : report["rows"])
        if (r["name"] == name) return r;
    static const nlohmann::json none;
    ADD_FAILURE() << "no row " << name;
    return none;
}

// Every row's paired ratio and interval in report.json is what its own timings ("shot_ms", against
// the plain row's) give again; what pays is what the rule says; the picks pay.
void checkIntervals(const nlohmann::json& report, std::size_t pairs) {
    const auto timings = [](const nlohmann::json& r) { return r["shot_ms"].get<std::vector<std::vector<double>>>(); };
    const std::vector<std::vector<double>> plain = timings(report["rows"][0]);
    EXPECT_EQ(report["interval"]["resamples"], kBootstrapResamples);
    EXPECT_EQ(report["interval"]["seed"], kBootstrapSeed);
    for (const nlohmann::json& r : report["rows"]) {
        const PairedRatio p = pairedRatio(timings(r), plain);
        EXPECT_EQ(r["pairs"], pairs) << r["name"];
        EXPECT_EQ(r["x_plain_paired"].get<double>(), p.estimate) << r["name"];
        EXPECT_EQ(r["x_plain_low"].get<double>(), p.low) << r["name"];
        EXPECT_EQ(r["x_plain_high"].get<double>(), p.high) << r["name"];
        EXPECT_LE(p.low, p.estimate) << r["name"];
        EXPECT_GE(p.high, p.estimate) << r["name"];
        const bool pays = r["name"] != "plain" && !r["floor"].get<bool>() && r["same_draws_as"].is_null() && p.high < kPays;
        EXPECT_EQ(r["no_op"].get<bool>(), r["same_draws_as"] == "plain") << r["name"];
        EXPECT_EQ(r["pays"].get<bool>(), pays) << r["name"];
    }
    for (const char* pick : {"exact", "within_budget"}) {
        const std::string name = report["recommended"][pick];
        if (name == "plain") continue;
        const nlohmann::json& picked = row(report, name);
        EXPECT_TRUE(picked["pays"].get<bool>()) << name;
        EXPECT_FALSE(picked["no_op"].get<bool>()) << name;
        EXPECT_LT(picked["x_plain_high"].get<double>(), kPays) << name;
    }
}

TEST(ReportCliTest, ViewsGiveEveryMethodJudgedAndAnExactRecommendation) {
    const fs::path dir = test::freshDir("ReportViews");
    const CliRun run = runFrugal(dir, {"report", "builtin:cubes?count=12", "--views", "4", "--size", "96x72",
                                       "--repeat", "2", "--budget-px", "50", "-o", "out"});
    ASSERT_EQ(run.status, 0) << run.err;
    ASSERT_EQ(run.out.substr(0, 15), "fastest exact: ") << run.out;
    EXPECT_EQ(occurrences(run.out, "% interval ["), 2u) << "each line gives its pick's interval, or the nearest miss's\n"
                                                         << run.out;
    EXPECT_NE(run.out.find("\nfastest within 50 px a frame: "), std::string::npos) << run.out;
    EXPECT_NE(run.err.find("report: 16 candidates on "), std::string::npos) << run.err;

    const nlohmann::json report = test::readJson(dir / "out" / "report.json");
    checkIntervals(report, 4 * 2);
    EXPECT_EQ(report["shots"], 4);
    EXPECT_EQ(report["rows"][0]["name"], "plain");
    EXPECT_EQ(report["rows"].size(), 16u);
    for (const nlohmann::json& r : report["rows"]) {
        EXPECT_EQ(r["exact"], r["differing_px"] == 0 && r["worst_depth"] == 0) << r["name"];
        EXPECT_LE(r["worst_frame_px"].get<std::uint64_t>(), r["differing_px"].get<std::uint64_t>()) << r["name"];
    }
    EXPECT_TRUE(row(report, "cull oracle")["floor"].get<bool>());
    EXPECT_EQ(row(report, "cull conservative")["differing_px"], 0) << "conservative culling never misses";
    EXPECT_EQ(row(report, "cull conservative")["misses"], 0);
    EXPECT_GT(row(report, "cull paper")["differing_px"].get<int>(), 0) << "paper 002's method misses on these views";
    EXPECT_GT(row(report, "cull paper")["misses"].get<int>(), 0);
    EXPECT_EQ(row(report, "plain")["misses"], 0);
    // The Lambert approximation: the same triangles, other colours.
    EXPECT_EQ(row(report, "shading lambert")["family"], "shading");
    EXPECT_GT(row(report, "shading lambert")["differing_px"].get<int>(), 0);
    EXPECT_EQ(row(report, "shading lambert")["misses"], 0);
    EXPECT_EQ(row(report, "no environment specular")["family"], "shading");
    EXPECT_GT(row(report, "no environment specular")["differing_px"].get<int>(), 0);
    EXPECT_EQ(row(report, "no environment specular")["misses"], 0);

    // The same views in cull-report, which finds the misses from the oracle's visible set and the
    // submitted list instead of two images: the same triangles missed, the same pixels differing.
    const CliRun cull = runFrugal(dir, {"cull-report", "builtin:cubes?count=12", "--views", "4", "--size", "96x72",
                                        "--methods", "paper", "--repeat", "1", "-q", "--json", "cull.json"});
    ASSERT_EQ(cull.status, 0) << cull.err;
    const nlohmann::json paper = test::readJson(dir / "cull.json")["summary"]["paper"];
    EXPECT_EQ(row(report, "cull paper")["misses"], paper["total_misses"]);
    EXPECT_EQ(row(report, "cull paper")["differing_px"], paper["total_pixels_differing"]);

    const std::string exact = report["recommended"]["exact"], budget = report["recommended"]["within_budget"];
    EXPECT_NE(exact, "cull oracle");
    if (exact != "plain") {
        EXPECT_TRUE(row(report, exact)["exact"].get<bool>());
    }
    if (budget != "plain") {
        EXPECT_LE(row(report, budget)["worst_frame_px"].get<int>(), 50);
    }

    // settings.json is the exact pick's settings, which the library reads back.
    Result<SettingsFile> settings = readSettingsFile((dir / "out" / "settings.json").string());
    ASSERT_TRUE(settings) << settings.error().message;
    EXPECT_EQ(settingsJson(settings->settings) + "", readAll(dir / "out" / "settings.json"));
    EXPECT_EQ(nlohmann::json::parse(readAll(dir / "out" / "settings.json")),
              exact == "plain" ? report["rows"][0]["settings"] : row(report, exact)["settings"]);
    const std::string csv = readAll(dir / "out" / "report.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 17) << "a header and a line a row";
    EXPECT_NE(csv.find(",misses,x_plain_paired,x_plain_low,x_plain_high,pairs,no_op,pays,same_draws_as\n"), std::string::npos)
        << "the paired columns after the ones pareto.gp reads";

    // The page: this run's figures, a mask for each inexact method (inline, and full size beside it).
    const std::string html = readAll(dir / "out" / "index.html");
    EXPECT_LE(html.size(), 2u << 20) << "at most 2 MB";
    std::size_t inexact = 0;
    for (const nlohmann::json& r : report["rows"]) {
        char median[64];
        std::snprintf(median, sizeof median, "<td>%.3f</td>", r["median_ms"].get<double>());
        EXPECT_NE(html.find("<td>" + r["name"].get<std::string>() + "</td>"), std::string::npos) << r["name"];
        EXPECT_NE(html.find(median), std::string::npos) << r["name"] << ": " << median;
        if (r["differing_px"] == 0) continue;
        ++inexact;
        const fs::path maskFile = dir / "out" / "masks" / (methodSlug(r["name"].get<std::string>()) + ".png");
        Result<DecodedImage> m = readPng(maskFile.string());
        ASSERT_TRUE(m) << m.error().message;
        EXPECT_EQ(m->width, 96);
        EXPECT_EQ(m->height, 72);
    }
    EXPECT_GE(inexact, 1u) << "paper culling";
    EXPECT_EQ(occurrences(html, "<img class=\"mask\""), inexact);
    EXPECT_EQ(test::filesIn(dir / "out" / "masks").size(), inexact);
    const std::vector<std::string> papers = test::lines(readAll(dir / "out" / "papers.csv"));
    EXPECT_EQ(papers.size(), 1u + 2 + 2 + 1) << "002 twice, 003 twice, 004 once; no reuse in a set of views";
    if (!test::haveGnuplot()) FRUGAL_SKIP_IF_MISSING("gnuplot (Debian: gnuplot-nox): pareto.gp not checked");
    ASSERT_EQ(std::system(("cd '" + (dir / "out").string() + "' && gnuplot pareto.gp").c_str()), 0);
    EXPECT_NE(readAll(dir / "out" / "pareto.svg").find("<svg"), std::string::npos);
}

// A single mesh: an order of its one draw changes nothing, and a cull that keeps all of it neither;
// the report calls them no-ops, says so on the page, and never picks one, whatever their times; a
// combination whose order changed nothing is not picked either.
TEST(ReportCliTest, ASingleMeshSceneNeverGetsAnOrderOrANoOpPick) {
    const fs::path dir = test::freshDir("ReportSingleMesh");
    const CliRun run = runFrugal(dir, {"report", "builtin:cubes?count=1", "--views", "6", "--size", "64x48",
                                       "--repeat", "2", "--budget-px", "1000000", "-q", "-o", "out"});
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json report = test::readJson(dir / "out" / "report.json");
    checkIntervals(report, 6 * 2);
    EXPECT_TRUE(row(report, "order key")["no_op"].get<bool>());
    EXPECT_TRUE(row(report, "order greedy")["no_op"].get<bool>());
    EXPECT_FALSE(row(report, "plain")["no_op"].get<bool>());
    EXPECT_FALSE(row(report, "cull oracle")["no_op"].get<bool>()) << "the floor draws its own scene";
    EXPECT_FALSE(row(report, "hsr depthsort")["no_op"].get<bool>()) << "it draws polygons of its own";
    // Ordering one culled draw adds nothing to the cull: the combination repeats it (or the plain
    // render, where the cull kept everything) and never pays. Occlusion culling skips its pass by
    // its own timing, so two renderers that use it need not draw alike: the order is seen to do
    // nothing against the combination's own culled list.
    for (const std::string cull : {"cull conservative", "cull occlusion"}) {
        const nlohmann::json& combination = row(report, cull + " + order key");
        EXPECT_TRUE(combination["same_draws_as"] == cull || combination["same_draws_as"] == "plain")
            << cull << ": " << combination["same_draws_as"];
        EXPECT_FALSE(combination["pays"].get<bool>()) << cull;
    }
    std::size_t noOps = 0;
    for (const nlohmann::json& r : report["rows"]) {
        noOps += r["no_op"].get<bool>();
        if (r["no_op"].get<bool>()) {
            EXPECT_FALSE(r["pays"].get<bool>()) << r["name"];
        }
    }
    for (const char* pick : {"exact", "within_budget"}) {
        const std::string name = report["recommended"][pick];
        EXPECT_NE(name.substr(0, 6), "order ") << pick;
        if (name != "plain") {
            EXPECT_FALSE(row(report, name)["no_op"].get<bool>()) << name;
        }
    }
    const std::string html = readAll(dir / "out" / "index.html");
    EXPECT_EQ(occurrences(html, "no-op: draws the plain render's draws"), noOps);
    const std::string csv = readAll(dir / "out" / "report.csv");
    EXPECT_NE(csv.find("\norder greedy,order,"), std::string::npos);
    for (const std::string& line : test::lines(csv))
        if (line.rfind("order ", 0) == 0) {
            EXPECT_TRUE(line.ends_with(",1,0,plain")) << "no_op 1, pays 0, the plain render's draws: " << line;
        }
}

TEST(ReportCliTest, ASequenceWeighsReuseAndItsSettingsRenderThePlainImages) {
    const fs::path dir = test::freshDir("ReportSequence");
    const std::string scene = "builtin:dominoes?polygons=204";
    CliRun run = runFrugal(dir, {"report", scene, "--frames", "0:5", "--size", "96x72", "-q", "-o", "out"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err, "");
    const nlohmann::json report = test::readJson(dir / "out" / "report.json");
    EXPECT_TRUE(report["sequence"].get<bool>());
    EXPECT_GT(row(report, "reuse")["extra_bytes"].get<int>(), 0) << "the static pair";
    EXPECT_EQ(row(report, "reuse")["differing_px"], 0);

    run = runFrugal(dir, {"render", scene, "--frames", "0:5", "--size", "96x72", "-q", "-o", "a.png",
                          "--settings", "out/settings.json"});
    ASSERT_EQ(run.status, 0) << run.err;
    run = runFrugal(dir, {"render", scene, "--frames", "0:5", "--size", "96x72", "-q", "-o", "b.png"});
    ASSERT_EQ(run.status, 0) << run.err;
    for (int f = 0; f <= 5; ++f) {
        const std::string n = "_000" + std::to_string(f) + ".png";
        EXPECT_EQ(readAll(dir / ("a" + n)), readAll(dir / ("b" + n))) << "frame " << f;
    }
}

TEST(ReportCliTest, ACameraPathGivesItsViewsAndOneCameraOneView) {
    const fs::path dir = test::freshDir("ReportPath");
    test::writeFile(dir / "path.json", R"([{"eye":[0,0.5,3],"target":[0,0,0]},{"eye":[2,0.5,2],"target":[0,0,0],"fov":50}])");
    CliRun run = runFrugal(dir, {"report", "builtin:cubes?count=3", "--camera-path", "path.json", "--size", "48x36",
                                 "--repeat", "1", "-q", "-o", "path"});
    ASSERT_EQ(run.status, 0) << run.err;
    nlohmann::json report = test::readJson(dir / "path" / "report.json");
    EXPECT_EQ(report["shots"], 2);
    EXPECT_FALSE(report["sequence"].get<bool>());
    run = runFrugal(dir, {"report", "builtin:cubes?count=3", "--eye", "0,1,4", "--size", "48x36", "--repeat", "1",
                          "-q", "-o", "one"});
    ASSERT_EQ(run.status, 0) << run.err;
    report = test::readJson(dir / "one" / "report.json");
    EXPECT_EQ(report["shots"], 1);
    run = runFrugal(dir, {"report", "--views", "3", "--eye", "1,1,1", "-o", "x"});
    EXPECT_EQ(run.status, 2);
    EXPECT_EQ(run.err, "error: --views: give either --views N, --frames A:B, --camera-path or one camera\n");
    run = runFrugal(dir, {"report", "--camera-path", "path.json", "--camera", "0", "-o", "x"});
    EXPECT_EQ(run.status, 2);
    EXPECT_EQ(run.err, "error: --camera-path: give either a camera path or one camera (--camera, --eye, ...)\n");
}

TEST(ReportCliTest, BadInputIsOneLineAndNoFiles) {
    const fs::path dir = test::freshDir("ReportBad");
    CliRun run = runFrugal(dir, {"report", "--views", "0", "-o", "out"});
    EXPECT_EQ(run.status, 2);
    EXPECT_EQ(run.err, "error: --views: '0' is not a whole number from 1 to 10000\n");
    run = runFrugal(dir, {"report", "missing.obj", "-o", "out"});
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.errLines().size(), 1u) << run.err;
    test::writeFile(dir / "file", "x");
    run = runFrugal(dir, {"report", "builtin:cubes?count=2", "--views", "1", "--size", "32x24", "-q", "-o", "file"});
    EXPECT_EQ(run.status, 2) << "refused before any work";
    EXPECT_EQ(run.err, "error: -o file: a file, not a folder\n");
    EXPECT_EQ(test::filesIn(dir), std::vector<std::string>{"file"});
}

}  // namespace
}  // namespace frugal

namespace frugal {
namespace {

// With --samples 4 the report weighs one sample a pixel as a shading trade, and leaves out the
// methods that see pixel centres only (occlusion culling and the oracle are refused with it).
TEST(ReportCliTest, AMultisampledBaseWeighsOneSampleAndLeavesOutCentreMethods) {
    const fs::path dir = test::freshDir("ReportSamples");
    const CliRun run = runFrugal(dir, {"report", "builtin:cubes?count=6", "--views", "2", "--size", "96x72", "--repeat",
                                       "1", "--samples", "4", "-o", "out", "-q"});
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json report = test::readJson(dir / "out" / "report.json");
    std::set<std::string> names;
    for (const nlohmann::json& r : report["rows"]) names.insert(r["name"].get<std::string>());
    EXPECT_TRUE(names.count("samples 1")) << report["rows"].dump();
    EXPECT_TRUE(names.count("shading lambert"));
    EXPECT_TRUE(names.count("cull conservative"));
    for (const char* refused : {"cull occlusion", "cull oracle", "cull occlusion + order key"})
        EXPECT_FALSE(names.count(refused)) << refused;
    EXPECT_GT(row(report, "samples 1")["differing_px"].get<int>(), 0) << "edges lose their blend";
}

}  // namespace
}  // namespace frugal
