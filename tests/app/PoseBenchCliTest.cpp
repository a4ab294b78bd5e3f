// frugal-lab pose-bench through the command line (the real binary): the deforming scene and its rest
// pose each get a row, the rest pose is the yardstick, a scene without skins or morph targets is
// refused with one line, and the outputs are JSON, CSV and a gnuplot script.
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

TEST(PoseBenchCliTest, TheDeformingSceneIsTimedBesideItsRestPose) {
    const fs::path dir = test::freshDir("PoseBenchCli");
    const std::string skin = std::string(FRUGAL_ASSIMP_GLTF2_DIR) + "/simple_skin/simple_skin.gltf";
    for (const std::string& scene : {std::string("tube"), skin}) {
        std::vector<std::string> args = {"pose-bench", "--size", "64x48", "--backend", "software", "--repeat", "3",
                                         "--warmup",   "0",      "-q",    "--json",    "b.json",   "--csv",    "b.csv"};
        if (scene != "tube") args.insert(args.begin() + 1, scene);
        const CliRun run = runFrugal(dir, args);
        ASSERT_EQ(run.status, 0) << run.err;
        const nlohmann::json report = test::readJson(dir / "b.json");
        EXPECT_EQ(report["command"], "pose-bench");
        EXPECT_EQ(report["runs"], 3);
        EXPECT_EQ(report["deforming_instances"], 1);
        if (scene == "tube") {
            EXPECT_EQ(report["vertices_posed"], 1251 * 40);
        }
        std::map<std::string, nlohmann::json> rows;
        for (const nlohmann::json& r : report["rows"]) rows[r["variant"].get<std::string>()] = r;
        ASSERT_EQ(rows.size(), 2u) << report.dump(2);
        EXPECT_EQ(rows["rest pose"]["over_rest"], 1.0);
        EXPECT_GT(rows["deforming"]["median_ms"].get<double>(), 0.0);
        const std::string csv = test::readAll(dir / "b.csv");
        EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3) << csv;
        EXPECT_EQ(test::lines(run.out).size(), 2u) << run.out;
    }
    const CliRun still = runFrugal(dir, {"pose-bench", "builtin:cubes", "--size", "32x24", "--backend", "software",
                                         "--repeat", "1", "--warmup", "0", "-q"});
    EXPECT_EQ(still.status, 1) << still.err;
    EXPECT_EQ(still.errLines(),
              std::vector<std::string>{"error: pose-bench: 'builtin:cubes' has no mesh that deforms (no skin, no morph "
                                       "targets)"});
}

}  // namespace
}  // namespace frugal
