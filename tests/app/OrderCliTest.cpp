// Draw order and batching on the command line (issue 10): --order on render, diff and bench, the
// batches the GL backend draws as one instanced draw, and bench's unbatched and premerged rows.
// Timings are printed, never asserted.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "CliSupport.h"
#include "JsonSupport.h"
#include "TestSupport.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::runFrugal;

constexpr const char* kDominoes = "builtin:dominoes?polygons=6000";  // 1,000 dominoes of 6 meshes

TEST(OrderCliTest, KeyOrderBatchesEachMeshIntoOneDrawAndMatchesTheReference) {
    const fs::path dir = test::freshDir("OrderRender");
    for (const char* backend : {"software", "egl"}) {
        const std::string json = std::string(backend) + ".json";
        const CliRun run = runFrugal(dir, {"render", kDominoes, "--size", "160x120", "--backend", backend, "--order",
                                           "key", "-q", "-o", std::string(backend) + ".png", "--json", json});
        if (run.status == 2) continue;  // no GL here
        ASSERT_EQ(run.status, 0) << run.err;
        const nlohmann::json meta = test::readJson(dir / json);
        EXPECT_EQ(meta["draw_order"], "key");
        const nlohmann::json& changes = meta["frames"][0]["state_changes"];
        // GL: one instanced draw per mesh; the software backend executes the batches draw by draw.
        EXPECT_EQ(changes["draws"], std::string(backend) == "egl" ? 6 : 1000) << changes.dump();
    }
    // GL's batches against the software reference, bit for bit, over a few frames.
    const CliRun diff = runFrugal(dir, {"diff", kDominoes, "--size", "160x120", "--frames", "0:2", "--order", "key",
                                        "--tolerance", "0", "-q", "--out", "d"});
    if (diff.status != 2) {
        EXPECT_EQ(diff.status, 0) << diff.out << diff.err;
    }
}

TEST(OrderCliTest, CostOrdersMeasureTheBackendAndGroupEachStateSet) {
    // paper, greedy and best order the distinct state sets by costs measured at start; the default
    // scene's 135 draws (6 domino meshes and a textured floor) become 7 runs, the dominoes' runs
    // batched. The image equals the software reference's drawing the same list.
    const fs::path dir = test::freshDir("OrderCosts");
    for (const char* order : {"paper", "greedy", "best"}) {
        const std::string json = std::string(order) + ".json";
        const CliRun run = runFrugal(dir, {"render", "--size", "160x120", "--backend", "egl", "--order", order, "-o",
                                           std::string(order) + ".png", "--json", json});
        if (run.status == 3) FRUGAL_SKIP_IF_NO_GL(run.err);
        ASSERT_EQ(run.status, 0) << run.err;
        EXPECT_NE(run.err.find(std::string("order ") + order + ": state costs on egl-surfaceless (us): program "),
                  std::string::npos) << run.err;
        const nlohmann::json meta = test::readJson(dir / json);
        EXPECT_EQ(meta["draw_order"], order);
        EXPECT_EQ(meta["state_costs"]["us"].size(), 6u);
        EXPECT_EQ(meta["frames"][0]["state_changes"]["draws"], 7) << meta["frames"][0].dump();
    }
    const CliRun diff = runFrugal(dir, {"diff", "--size", "160x120", "--order", "best", "--tolerance", "0", "-q",
                                        "--out", "d"});
    EXPECT_EQ(diff.status, 0) << diff.out << diff.err;
}

TEST(OrderCliTest, CostsAreRefinedBetweenFramesOfASequence) {
    // 5 frames, a round after every 2nd: after frames 1 and 3 (never after the last), 5 start-up
    // rounds + 2. The images equal the software reference's drawing the same lists.
    const fs::path dir = test::freshDir("OrderRefine");
    const CliRun run = runFrugal(dir, {"render", "builtin:materials?draws=200", "--size", "96x72", "--frames", "0:4",
                                       "--backend", "software", "--order", "greedy", "--refine-costs", "2", "-q", "-o",
                                       "f_%d.png", "--json", "r.json"});
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json meta = test::readJson(dir / "r.json");
    const nlohmann::json& costs = meta["state_costs"];
    EXPECT_EQ(costs["rounds"], 7);
    EXPECT_EQ(costs["refine_every"], 2);
    EXPECT_EQ(costs["kinds"].size(), 6u);
    for (int f = 0; f < 5; ++f) {
        EXPECT_EQ(meta["frames"][f].contains("refined_state_costs_us"), f == 1 || f == 3) << f;
        EXPECT_EQ(meta["frames"][f].contains("refine_ms"), f == 1 || f == 3) << f;
    }
    EXPECT_EQ(meta["frames"][3]["refined_state_costs_us"], costs["us"]);

    const CliRun never = runFrugal(dir, {"render", "--size", "32x24", "--frames", "0:2", "--backend", "software",
                                         "--order", "best", "--refine-costs", "0", "-q", "-o", "n_%d.png", "--json",
                                         "n.json"});
    ASSERT_EQ(never.status, 0) << never.err;
    const nlohmann::json neverMeta = test::readJson(dir / "n.json");
    EXPECT_EQ(neverMeta["state_costs"]["rounds"], 5);
    EXPECT_EQ(neverMeta["state_costs"]["us"], neverMeta["state_costs"]["start_us"]);

    // Orders that measure nothing have no costs.
    const CliRun key = runFrugal(dir, {"render", "--size", "32x24", "--backend", "software", "--order", "key", "-q",
                                       "-o", "k.png", "--json", "k.json"});
    ASSERT_EQ(key.status, 0) << key.err;
    EXPECT_TRUE(test::readJson(dir / "k.json")["state_costs"].is_null());

    test::expectOneErrorLine(
        test::freshDir("OrderRefineErrors"),
        {{{"render", "--order", "best", "--refine-costs", "-1", "-o", "x.png"},
          "error: --refine-costs: '-1' is not a whole number from 0 to 1000000"},
         {{"render", "--order", "best", "--refine-costs", "often", "-o", "x.png"},
          "error: --refine-costs: 'often' is not a whole number from 0 to 1000000"}});
}

TEST(OrderCliTest, BenchTimesBatchedUnbatchedAndPremerged) {
    const fs::path dir = test::freshDir("OrderBench");
    const CliRun run = runFrugal(dir, {"bench", "render", kDominoes, "--size", "64x48", "--backend", "software", "--repeat",
                                       "2", "--warmup", "0", "--order", "key", "-q"});
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json j = nlohmann::json::parse(run.out, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << run.out;
    EXPECT_EQ(j["draw_order"], "key");
    bool unbatched = false, premerged = false;
    for (const nlohmann::json& row : j["results"]) {
        if (row["variant"] == "unbatched") {
            unbatched = true;
            EXPECT_EQ(row["pixels_differing"], 0);  // batching never changes a pixel
        }
        if (row["variant"] == "premerged") premerged = true;
        if (row["variant"] == "frugal" && row["order"] == "optimized") {
            EXPECT_TRUE(row["pixels_differing"].is_number());
        }
    }
    EXPECT_TRUE(unbatched && premerged) << run.out;
    EXPECT_TRUE(j["ratios"]["over_premerged"]["software"].is_number());
    EXPECT_TRUE(j["ratios"]["unbatched_over_batched"]["software"].is_number());
}

TEST(OrderCliTest, OrderBenchTimesEveryOrderWithItsStateChanges) {
    const fs::path dir = test::freshDir("OrderBenchCommand");
    const CliRun run = runFrugal(dir, {"order-bench", "builtin:materials?draws=200", "--size", "64x48", "--backend",
                                       "egl", "--repeat", "2", "--warmup", "0", "-q", "--json", "o.json", "--csv", "o.csv",
                                       "--plot", "o.svg"});
    if (run.status == 3) FRUGAL_SKIP_IF_NO_GL(run.err);
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json j = test::readJson(dir / "o.json");
    ASSERT_EQ(j["backends"].size(), 1u);
    const nlohmann::json& orders = j["backends"][0]["orders"];
    ASSERT_EQ(orders.size(), 5u);
    EXPECT_EQ(orders[0]["order"], "submit");
    EXPECT_EQ(j["backends"][0]["state_costs_us"].size(), 6u);
    for (const nlohmann::json& o : orders) {
        SCOPED_TRACE(o.dump());
        EXPECT_EQ(o["tie_px"], 0);  // boxes apart: no exact depth ties to change
        EXPECT_TRUE(o["median_ms"].is_number());
        if (o["order"] != "submit") {
            // Every other order keeps each mesh's draws together: one instanced draw a mesh (40).
            EXPECT_EQ(o["state_changes"]["draws"], 40);
            EXPECT_LT(o["state_changes"]["programs"].get<int>(), orders[0]["state_changes"]["programs"].get<int>());
        }
    }
    EXPECT_EQ(test::lines(test::readAll(dir / "o.csv")).size(), 6u);
    EXPECT_NE(test::readAll(dir / "o.svg").find("<svg"), std::string::npos);  // gnuplot drew it from the CSV
    EXPECT_NE(test::readAll(dir / "o.gp").find("'o.csv'"), std::string::npos);
}

TEST(OrderCliTest, AnUnknownOrderIsOneLine) {
    const fs::path dir = test::freshDir("OrderErrors");
    const std::string line = "error: --order: 'random' is not an order (submit, key, paper, greedy, best)";
    test::expectOneErrorLine(dir, {{{"render", "--order", "random"}, line},
                                   {{"bench", "render", "--order", "random"}, line},
                                   {{"diff", "--order", "random"}, line},
                                   {{"info", "builtin:materials?textures=30&materials=4"},
                                    "error: builtin:materials?textures=30&materials=4: textures=30 exceeds materials=4 "
                                    "(one texture a material at most)",
                                    1},
                                   {{"order-bench", "--repeat", "0"},
                                    "error: --repeat: '0' is not a whole number from 1 to 100000"},
                                   {{"order-bench", "--plot", "o.png"},
                                    "error: --plot o.png: gnuplot writes SVG here; name it .svg"}});
}

}  // namespace
}  // namespace frugal
