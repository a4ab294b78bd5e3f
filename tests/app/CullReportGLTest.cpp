// `frugal cull-report` end to end against the issue's accuracy goal: the conservative methods
// (conservative, backface, cones, sphere) drop no triangle that owns a pixel (0 misses) and change no
// pixel (0 differing), on every view of every report, on the default GL backend and on the software
// reference; the oracle submits exactly the really visible set; none submits everything. Scenes: the
// bunny (double- and single-sided), three bunnies, builtin:default, glTF 2.0 models of Debian's
// assimp-testmodels, and a camera path written here. The real binary runs in a child process.
//
// Kept small so the file runs in well under 3 minutes in Release on 2 cores (and in a few minutes
// under ASan+UBSan in Debug): 160x120, 6 views, 1 timed round. Without a GL backend (status 3 from
// a probe render) the software reference is still checked and the test is then reported skipped.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "TestSupport.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::filesIn;
using test::readAll;
using test::runFrugal;  // the frugal binary in a child process

const std::vector<std::string> kMethods = {"none",         "sphere",    "backface",        "cones", "paper",
                                           "conservative", "occlusion", "occlusion-ahead", "oracle"};
// Methods that never drop a triangle owning a pixel (src/cull/Culling.h).
const std::set<std::string> kConservative = {"sphere", "backface", "cones", "conservative", "occlusion", "occlusion-ahead"};
const std::vector<std::string> kMethodKeys = {"method",
                                              "tos",
                                              "pvs",
                                              "rvs",
                                              "misses",
                                              "waste",
                                              "pixels_differing",
                                              "cull_ms",
                                              "draw_ms",
                                              "ratio_to_oracle",
                                              "ratio_to_full",
                                              "ratio_to_full_cullface"};
const std::vector<std::string> kSummaryKeys = {"views",
                                               "median_pvs",
                                               "median_cull_ms",
                                               "median_draw_ms",
                                               "median_ratio_to_oracle",
                                               "median_ratio_to_full",
                                               "median_ratio_to_full_cullface",
                                               "worst_view",
                                               "total_misses",
                                               "total_pixels_differing",
                                               "views_with_misses"};
const std::set<std::string> kViewClasses = {"whole", "partial", "grazing", "inside", "pole", "camera", "path"};

// Whether the default (GL) backend opens here; status 3 means it does not.
bool glAvailable() {
    static const bool available = [] {
        // A folder of the test's own: ctest runs the tests of this file in parallel processes.
        const fs::path dir = test::freshDir(std::string("CullReportGLProbe.") +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        const CliRun run = runFrugal(dir, {"render", "--size", "8x8", "-q", "-o", "probe.png"});
        EXPECT_TRUE(run.status == 0 || run.status == 3) << run.err;
        return run.status != 3;
    }();
    return available;
}

// The backends to judge: "" is the default (a GL one), then the software reference.
std::vector<std::string> backends() {
    std::vector<std::string> list;
    if (glAvailable()) list.push_back("");
    list.push_back("software");
    return list;
}

struct Report {
    CliRun run;
    nlohmann::json json;  // discarded (is_discarded()) when the run wrote none
};

// `frugal cull-report SCENE_ARGS --size 160x120 [--views 6] --repeat 1 --json report.json -q
// [--backend B] EXTRA` in `dir`, its JSON parsed.
Report cullReport(const fs::path& dir, const std::vector<std::string>& sceneArgs, const std::string& backend,
                  const std::vector<std::string>& extra = {"--views", "6"}) {
    std::vector<std::string> args = {"cull-report"};
    args.insert(args.end(), sceneArgs.begin(), sceneArgs.end());
    args.insert(args.end(), {"--size", "160x120", "--repeat", "1", "--json", "report.json", "-q"});
    if (!backend.empty()) args.insert(args.end(), {"--backend", backend});
    args.insert(args.end(), extra.begin(), extra.end());
    Report report;
    report.run = runFrugal(dir, args);
    EXPECT_EQ(report.run.status, 0) << "frugal " << test::joined(args) << "\n" << report.run.err;
    if (report.run.status == 0) {
        for (const std::string& line : report.run.errLines())
            EXPECT_EQ(line.rfind("warning: ", 0), 0u)
                << "frugal " << test::joined(args) << ": -q prints warnings only: " << line;
    }
    report.json = nlohmann::json::parse(readAll(dir / "report.json"), nullptr, false);
    EXPECT_FALSE(report.json.is_discarded()) << "frugal " << test::joined(args) << ": no JSON report";
    fs::remove(dir / "report.json");
    return report;
}

bool isNumberOrNull(const nlohmann::json& j) { return j.is_number() || j.is_null(); }

// The report's shape (research/lab/CullReport.h and CullReportCommand.cpp): every key, every view,
// every method in the default order, the summary consistent with the views.
void expectReportStructure(const nlohmann::json& j, const std::string& scene, const std::string& backend,
                           std::size_t views, const std::string& timing) {
    ASSERT_TRUE(j.is_object());
    for (const char* key :
         {"scene", "size", "backend", "timing", "views", "summary", "preprocess", "repeat", "renderer"})
        ASSERT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["scene"], scene);
    EXPECT_EQ(j["size"], nlohmann::json::array({160, 120}));
    if (backend.empty()) {
        EXPECT_NE(j["backend"], "software") << "the default backend is a GL one";
    } else {
        EXPECT_EQ(j["backend"], backend);
    }
    EXPECT_EQ(j["timing"], timing);
    EXPECT_EQ(j["repeat"], 1);
    EXPECT_TRUE(j["renderer"].is_string());
    ASSERT_TRUE(j["preprocess"].is_object());
    EXPECT_EQ(j["preprocess"]["bins"], nlohmann::json::array({16, 32}));
    ASSERT_TRUE(j["preprocess"]["meshes"].is_array());
    EXPECT_FALSE(j["preprocess"]["meshes"].empty());
    for (const nlohmann::json& mesh : j["preprocess"]["meshes"])
        for (const char* key : {"mesh", "triangles", "total_ms", "map_bytes", "clusters", "hull_kind"})
            EXPECT_TRUE(mesh.contains(key)) << key;

    ASSERT_TRUE(j["views"].is_array());
    ASSERT_EQ(j["views"].size(), views);
    std::map<std::string, std::size_t> misses, pixels, withMisses;
    for (std::size_t v = 0; v < views; ++v) {
        const nlohmann::json& view = j["views"][v];
        SCOPED_TRACE("view " + std::to_string(v));
        for (const char* key : {"index", "class", "eye", "target", "methods"}) ASSERT_TRUE(view.contains(key)) << key;
        EXPECT_EQ(view["index"], v);
        EXPECT_EQ(kViewClasses.count(view["class"].get<std::string>()), 1u) << view["class"];
        for (const char* key : {"eye", "target"}) {
            ASSERT_TRUE(view[key].is_array() && view[key].size() == 3) << key;
            for (const nlohmann::json& x : view[key]) EXPECT_TRUE(x.is_number()) << key;
        }
        ASSERT_EQ(view["methods"].size(), kMethods.size());
        for (std::size_t m = 0; m < kMethods.size(); ++m) {
            const nlohmann::json& result = view["methods"][m];
            EXPECT_EQ(result["method"], kMethods[m]);
            for (const std::string& key : kMethodKeys) ASSERT_TRUE(result.contains(key)) << kMethods[m] << " " << key;
            for (const char* key : {"tos", "pvs", "rvs", "misses", "waste", "pixels_differing"})
                EXPECT_TRUE(result[key].is_number_unsigned()) << kMethods[m] << " " << key;
            for (const char* key : {"cull_ms", "draw_ms", "ratio_to_oracle", "ratio_to_full", "ratio_to_full_cullface"})
                EXPECT_TRUE(isNumberOrNull(result[key])) << kMethods[m] << " " << key;
            misses[kMethods[m]] += result["misses"].get<std::size_t>();
            pixels[kMethods[m]] += result["pixels_differing"].get<std::size_t>();
            withMisses[kMethods[m]] += result["misses"].get<std::size_t>() > 0;
        }
    }
    ASSERT_TRUE(j["summary"].is_object());
    EXPECT_EQ(j["summary"].size(), kMethods.size());
    for (const std::string& method : kMethods) {
        SCOPED_TRACE("summary of " + method);
        ASSERT_TRUE(j["summary"].contains(method));
        const nlohmann::json& s = j["summary"][method];
        for (const std::string& key : kSummaryKeys) ASSERT_TRUE(s.contains(key)) << key;
        EXPECT_EQ(s["views"], views);
        EXPECT_EQ(s["total_misses"], misses[method]);
        EXPECT_EQ(s["total_pixels_differing"], pixels[method]);
        EXPECT_EQ(s["views_with_misses"], withMisses[method]);
        for (const char* key : {"index", "class", "ratio_to_oracle"}) EXPECT_TRUE(s["worst_view"].contains(key)) << key;
        if (views > 0) {
            EXPECT_LT(s["worst_view"]["index"].get<int>(), int(views));
        }
    }
}

// The accuracy goal, view by view. Returns the conservative method's submitted and total triangles
// summed over the views (to show that it culls something where it can).
std::pair<std::size_t, std::size_t> expectAccurate(const nlohmann::json& j) {
    std::size_t pvs = 0, tos = 0, visible = 0;
    if (!j.is_object() || !j.contains("views")) {
        ADD_FAILURE() << "no report";
        return {0, 0};
    }
    for (const nlohmann::json& view : j["views"]) {
        SCOPED_TRACE("view " + view["index"].dump() + " (" + view["class"].get<std::string>() + ") eye " +
                     view["eye"].dump() + " target " + view["target"].dump());
        const nlohmann::json& first = view["methods"][0];
        const std::size_t viewTos = first["tos"], viewRvs = first["rvs"];
        visible += viewRvs;
        for (const nlohmann::json& result : view["methods"]) {
            const std::string method = result["method"];
            SCOPED_TRACE(method);
            const std::size_t t = result["tos"], p = result["pvs"], r = result["rvs"], miss = result["misses"],
                              waste = result["waste"], px = result["pixels_differing"];
            EXPECT_EQ(t, viewTos) << "every method sees the same scene";
            EXPECT_EQ(r, viewRvs) << "every method is judged against the same visible set";
            EXPECT_LE(p, t);
            EXPECT_LE(r, t);
            EXPECT_LE(miss, r);
            EXPECT_LE(waste, p);
            EXPECT_EQ(p - waste, r - miss) << "submitted and visible = pvs - waste = rvs - misses";
            if (kConservative.count(method)) {
                EXPECT_EQ(miss, 0u) << "a conservative method dropped a visible triangle";
                EXPECT_EQ(px, 0u) << "a conservative method changed pixels";
            } else if (method == "none") {
                EXPECT_EQ(p, t);
                EXPECT_EQ(miss, 0u);
                EXPECT_EQ(px, 0u) << "the full draw differs from itself";
            } else if (method == "oracle") {
                EXPECT_EQ(p, r);
                EXPECT_EQ(miss, 0u);
                EXPECT_EQ(waste, 0u);
            }
            if (method == "conservative") {
                pvs += p;
                tos += t;
            }
        }
    }
    EXPECT_GT(visible, 0u) << "no view sees the scene: the report judges nothing";
    return {pvs, tos};
}

// Reports of `sceneArgs` (SCENE first) on every backend: structure and accuracy. Returns the
// conservative pvs and tos summed over views and backends.
std::pair<std::size_t, std::size_t> judge(const std::string& name, const std::vector<std::string>& sceneArgs,
                                          std::size_t views = 6,
                                          const std::vector<std::string>& extra = {"--views", "6"},
                                          const std::string& timing = "cold") {
    std::pair<std::size_t, std::size_t> totals{0, 0};
    for (const std::string& backend : backends()) {
        SCOPED_TRACE(test::joined(sceneArgs) + " on " + (backend.empty() ? "the default backend" : backend));
        const fs::path dir = test::freshDir("CullReportGL" + name + (backend.empty() ? "Default" : "Software"));
        const Report report = cullReport(dir, sceneArgs, backend, extra);
        if (report.run.status != 0 || report.json.is_discarded()) continue;
        expectReportStructure(report.json, sceneArgs[0], backend, views, timing);
        const auto [pvs, tos] = expectAccurate(report.json);
        totals.first += pvs;
        totals.second += tos;
    }
    return totals;
}

void skipWithoutGl() {
    if (!glAvailable()) FRUGAL_SKIP_IF_NO_GL("status 3: judged on the software reference only");
}

// --- the scenes ---------------------------------------------------------------------------------

TEST(CullReportGLTest, BunnyIsConservativeOnBothBackends) {
    ASSERT_TRUE(fs::exists(FRUGAL_BUNNY_OBJ)) << FRUGAL_BUNNY_OBJ << " missing (Debian glmark2-data)";
    judge("Bunny", {FRUGAL_BUNNY_OBJ});
    // Single-sided: facing tests may drop the back half, and the methods must still miss nothing.
    const auto [pvs, tos] = judge("BunnySingleSided", {FRUGAL_BUNNY_OBJ, "--cull-backfaces"});
    EXPECT_LT(pvs, tos * 3 / 4) << "conservative culling of the single-sided bunny drops little: is it culling?";
    skipWithoutGl();
}

TEST(CullReportGLTest, ThreeBunniesAreConservativeOnBothBackends) {
    ASSERT_TRUE(fs::exists(FRUGAL_BUNNY_OBJ)) << FRUGAL_BUNNY_OBJ << " missing (Debian glmark2-data)";
    judge("Copies", {std::string("builtin:copies?count=3&of=") + FRUGAL_BUNNY_OBJ});
    skipWithoutGl();
}

TEST(CullReportGLTest, DefaultSceneIsConservativeOnBothBackends) {
    judge("Default", {"builtin:default"});
    skipWithoutGl();
}

// Every glTF 2.0 model of assimp-testmodels that frugal loads with some triangles. Many files repeat
// another's geometry (the BoxTextured variants differ only in how the texture is stored, the
// Mesh_PrimitiveMode files all draw the same unit square) and add nothing to a test of culling,
// while each report costs up to seconds (several times that under the sanitizers). So the models
// are taken in path order, the first of each geometry (triangle count, bounds, single/double-sided
// materials, as `frugal info` prints them) is kept, and of those at most 12, evenly spaced: a fixed,
// deterministic choice that keeps the test bounded in time whatever the package holds.
TEST(CullReportGLTest, AssimpGltfModelsAreConservativeOnBothBackends) {
    const fs::path root = FRUGAL_ASSIMP_GLTF2_DIR;
    ASSERT_TRUE(fs::is_directory(root)) << root << " missing: install assimp-testmodels (scripts/install-deps --tests)";
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        const std::string ext = entry.path().extension().string();
        if (entry.is_regular_file() && (ext == ".gltf" || ext == ".glb")) files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    ASSERT_FALSE(files.empty());

    const fs::path infoDir = test::freshDir("CullReportGLInfo");
    std::vector<fs::path> kinds;
    std::set<std::string> seen;
    for (const fs::path& file : files) {
        const CliRun info = runFrugal(infoDir, {"info", file.string()});
        if (info.status != 0) continue;  // does not load: not frugal's to cull
        std::string signature;
        std::stringstream lines(info.out);
        for (std::string line; std::getline(lines, line);) {
            if (line.rfind("triangles: ", 0) == 0 || line.rfind("bounds: ", 0) == 0) signature += line + "\n";
            if (line.find("single-sided") != std::string::npos) signature += "single\n";
            if (line.find("double-sided") != std::string::npos) signature += "double\n";
        }
        if (signature.rfind("triangles: 0 ", 0) == 0 || signature.empty()) continue;  // nothing to view
        if (seen.insert(signature).second) kinds.push_back(file);
    }
    ASSERT_GE(kinds.size(), 5u) << "fewer glTF models load than expected";
    std::vector<fs::path> chosen;
    const std::size_t kMax = 12;
    const std::size_t count = std::min(kinds.size(), kMax);
    for (std::size_t i = 0; i < count; ++i) chosen.push_back(kinds[i * kinds.size() / count]);

    for (std::size_t i = 0; i < chosen.size(); ++i) {
        SCOPED_TRACE(chosen[i].string());
        judge("Gltf" + std::to_string(i), {chosen[i].string()});
    }
    std::cout << "judged " << chosen.size() << " glTF models of " << files.size() << " files\n";
    skipWithoutGl();
}

// A camera path: views given one by one, timed in order, each with its own up and field of view.
TEST(CullReportGLTest, CameraPathIsConservativeOnBothBackends) {
    ASSERT_TRUE(fs::exists(FRUGAL_BUNNY_OBJ)) << FRUGAL_BUNNY_OBJ << " missing (Debian glmark2-data)";
    // The bunny spans about -1..1 × -1..1 × -0.78..0.78 (radius 1.6).
    const nlohmann::json views = nlohmann::json::parse(R"([
        {"eye": [0, 0, 5], "target": [0, 0, 0]},
        {"eye": [0.4, 0.3, 1.2], "target": [0, 0, 0], "fov": 60},
        {"eye": [0, 0, 0], "target": [1, 0, 0], "up": [0, 0, 1]},
        {"eye": [3, 0.05, 0], "target": [0, 0.05, -0.2], "up": [0, 1, 0], "fov": 20},
        {"eye": [0, 4, 0.01], "target": [0, 0, 0], "up": [0, 0, -1]},
        {"eye": [-2, -1, -3], "target": [-0.5, 0.2, 0], "fov": 100},
        {"eye": [1.2, -0.2, 0.9], "target": [-1, 0.5, -0.4], "fov": 35}
    ])");
    const fs::path pathDir = test::freshDir("CullReportGLPath");
    // Both forms the command reads: a list, and an object holding the list as "views".
    test::writeFile(pathDir / "path.json", views.dump(2));
    test::writeFile(pathDir / "path-object.json", nlohmann::json{{"views", views}}.dump(2));
    for (const char* file : {"path.json", "path-object.json"}) {
        SCOPED_TRACE(file);
        const std::vector<std::string> scene = {FRUGAL_BUNNY_OBJ, "--cull-backfaces"};
        for (const std::string& backend : backends()) {
            SCOPED_TRACE(backend.empty() ? "the default backend" : backend);
            const fs::path dir = test::freshDir("CullReportGLPathRun");
            const Report report = cullReport(dir, scene, backend, {"--camera-path", (pathDir / file).string()});
            if (report.run.status != 0 || report.json.is_discarded()) continue;
            expectReportStructure(report.json, FRUGAL_BUNNY_OBJ, backend, views.size(), "path");
            expectAccurate(report.json);
            for (std::size_t v = 0; v < views.size(); ++v) {
                const nlohmann::json& view = report.json["views"][v];
                EXPECT_EQ(view["class"], "path");
                for (std::size_t k = 0; k < 3; ++k) {
                    EXPECT_NEAR(view["eye"][k].get<double>(), views[v]["eye"][k].get<double>(), 1e-6) << v;
                    EXPECT_NEAR(view["target"][k].get<double>(), views[v]["target"][k].get<double>(), 1e-6) << v;
                }
            }
            if (std::string(file) == "path-object.json") break;  // the object form once is enough
        }
    }
    skipWithoutGl();
}

// --- the other outputs --------------------------------------------------------------------------

std::vector<std::string> splitFields(const std::string& line) {
    std::vector<std::string> fields;
    std::stringstream in(line);
    for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
    return fields;
}

// --csv has a header and a row per view and method, agreeing with the JSON; --plot writes the SVG and
// the gnuplot script beside it (and the CSV beside it unless --csv names one).
TEST(CullReportGLTest, CsvAndPlotFollowTheReport) {
    const fs::path dir = test::freshDir("CullReportGLCsv");
    const Report report = cullReport(dir, {"builtin:default"}, "", {"--views", "6", "--csv", "r.csv"});
    ASSERT_EQ(report.run.status, 0) << report.run.err;
    const nlohmann::json& j = report.json;
    ASSERT_FALSE(j.is_discarded());
    ASSERT_EQ(j["views"].size(), 6u);
    const std::vector<std::string> lines = test::lines(readAll(dir / "r.csv"));
    ASSERT_EQ(lines.size(), 1 + 6 * kMethods.size());
    EXPECT_EQ(lines[0],
              "view,class,method,tos,pvs,rvs,misses,waste,pixels_differing,cull_ms,draw_ms,ratio_to_oracle,"
              "ratio_to_full,ratio_to_full_cullface");
    std::size_t row = 1;
    for (const nlohmann::json& view : j["views"])
        for (const nlohmann::json& result : view["methods"]) {
            SCOPED_TRACE(lines[row]);
            const std::vector<std::string> fields = splitFields(lines[row++]);
            ASSERT_EQ(fields.size(), 14u);
            EXPECT_EQ(fields[0], view["index"].dump());
            EXPECT_EQ(fields[1], view["class"].get<std::string>());
            EXPECT_EQ(fields[2], result["method"].get<std::string>());
            EXPECT_EQ(fields[3], result["tos"].dump());
            EXPECT_EQ(fields[4], result["pvs"].dump());
            EXPECT_EQ(fields[5], result["rvs"].dump());
            EXPECT_EQ(fields[6], result["misses"].dump());
            EXPECT_EQ(fields[7], result["waste"].dump());
            EXPECT_EQ(fields[8], result["pixels_differing"].dump());
        }

    if (!test::haveGnuplot())
        FRUGAL_SKIP_IF_MISSING("gnuplot (Debian: gnuplot-nox): plots not checked");
    // --plot alone: the CSV goes beside the plot.
    const fs::path plotDir = test::freshDir("CullReportGLPlot");
    Report plotted = cullReport(plotDir, {"builtin:default"}, "", {"--views", "2", "--plot", "p.svg"});
    ASSERT_EQ(plotted.run.status, 0) << plotted.run.err;
    EXPECT_EQ(filesIn(plotDir), (std::vector<std::string>{"p.csv", "p.gp", "p.svg"}));
    EXPECT_NE(readAll(plotDir / "p.svg").find("<svg"), std::string::npos);
    EXPECT_NE(readAll(plotDir / "p.gp").find("p.csv"), std::string::npos) << "the script reads the CSV beside it";
    EXPECT_EQ(test::lines(readAll(plotDir / "p.csv")).size(), 1 + 2 * kMethods.size());
    // With --csv, the script reads that one and no CSV is written beside the plot.
    const fs::path bothDir = test::freshDir("CullReportGLPlotCsv");
    plotted = cullReport(bothDir, {"builtin:default"}, "", {"--views", "2", "--plot", "p.svg", "--csv", "r.csv"});
    ASSERT_EQ(plotted.run.status, 0) << plotted.run.err;
    EXPECT_EQ(filesIn(bothDir), (std::vector<std::string>{"p.gp", "p.svg", "r.csv"}));
    EXPECT_NE(readAll(bothDir / "p.gp").find("r.csv"), std::string::npos);
    EXPECT_NE(readAll(bothDir / "p.svg").find("<svg"), std::string::npos);
}

}  // namespace
}  // namespace frugal
