// frugal-lab shading-bench through the command line (the real binary): every term a scene uses
// gets its row (and the ones it does not, a reason), full is the yardstick, a term taken away
// changes pixels, and the outputs are JSON, CSV and a gnuplot script.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "CliSupport.h"
#include "JsonSupport.h"
#include "TestSupport.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::runFrugal;

const std::string kClearCoat = std::string(FRUGAL_ASSIMP_GLTF2_DIR) + "/ClearCoat-glTF/ClearCoatTest.gltf";

TEST(ShadingBenchCliTest, EachTermTheSceneUsesHasItsRow) {
    const fs::path dir = test::freshDir("ShadingBenchCli");
    const CliRun run = runFrugal(dir, {"shading-bench", kClearCoat, "--size", "96x72", "--backend", "software",
                                       "--repeat", "2", "--warmup", "0", "-q", "--json", "b.json", "--csv", "b.csv"});
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json report = test::readJson(dir / "b.json");
    EXPECT_EQ(report["command"], "shading-bench");
    EXPECT_EQ(report["backend"], "software");
    std::map<std::string, nlohmann::json> rows;
    for (const nlohmann::json& r : report["rows"]) rows[r["term"].get<std::string>()] = r;
    for (const char* term : {"full", "lambert", "no environment specular", "no environment", "no textures",
                             "no normal maps", "no blending", "samples 4"})
        EXPECT_TRUE(rows.count(term)) << term << "\n" << report.dump(2);
    EXPECT_EQ(rows["full"]["over_full"], 1.0);
    EXPECT_EQ(rows["full"]["pixels_differing"], 0);
    for (const char* term : {"lambert", "no textures", "no normal maps", "no blending", "samples 4"})
        EXPECT_GT(rows[term]["pixels_differing"].get<int>(), 0) << term;
    ASSERT_EQ(report["skipped"].size(), 1u) << report["skipped"].dump();
    EXPECT_EQ(report["skipped"][0]["term"], "uniform environment");
    const std::string csv = test::readAll(dir / "b.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + long(rows.size())) << csv;
    EXPECT_EQ(test::lines(run.out).size(), rows.size()) << run.out;

    // A plain scene: the terms it lacks are skipped, each with why.
    const CliRun plain = runFrugal(dir, {"shading-bench", "builtin:cubes", "--size", "32x24", "--backend", "software",
                                         "--repeat", "1", "--warmup", "0", "-q", "--json", "c.json"});
    ASSERT_EQ(plain.status, 0) << plain.err;
    const nlohmann::json cubes = test::readJson(dir / "c.json");
    std::map<std::string, std::string> why;
    for (const nlohmann::json& s : cubes["skipped"]) why[s["term"].get<std::string>()] = s["why"].get<std::string>();
    EXPECT_EQ(why["no textures"], "no material samples a texture");
    EXPECT_EQ(why["no blending"], "no material blends");
    EXPECT_EQ(why["no normal maps"], "no material has a normal map");
}

}  // namespace
}  // namespace frugal
