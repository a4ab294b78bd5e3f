// `frugal info --state-costs` end to end: the figures are printed and written, never asserted
// (they are timings); what is asserted is that every kind is measured on each backend and that
// misuse gets one line.
#include <gtest/gtest.h>

#include <cmath>
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

TEST(StateCostsCliTest, EveryKindIsMeasuredOnEachBackend) {
    const fs::path dir = test::freshDir("StateCosts");
    for (const char* backend : {"software", "egl"}) {
        const std::string json = std::string(backend) + ".json";
        const CliRun run = runFrugal(dir, {"info", "--state-costs", "--backend", backend, "--json", json});
        if (run.status == 2) continue;  // no GL here
        ASSERT_EQ(run.status, 0) << run.err;
        EXPECT_NE(run.out.find("state costs on "), std::string::npos) << run.out;
        const nlohmann::json j = test::readJson(dir / json);
        SCOPED_TRACE(j.dump());
        for (const char* kind : {"program", "mesh", "texture", "material", "culling", "depth"}) {
            ASSERT_TRUE(j["costs"].contains(kind)) << kind;
            for (const char* key : {"us", "min_us", "max_us"}) EXPECT_TRUE(std::isfinite(j["costs"][kind][key].get<double>()));
            EXPECT_LE(j["costs"][kind]["min_us"].get<double>(), j["costs"][kind]["max_us"].get<double>());
        }
        EXPECT_GT(j["draw_us"].get<double>(), 0.0);
        EXPECT_GE(j["texture"]["upload_ms"].get<double>(), 0.0);
        EXPECT_GT(j["new_combination"]["first_ms"].get<double>(), 0.0);
        EXPECT_EQ(j["rounds"], 9);
    }
}

TEST(StateCostsCliTest, MisuseGetsOneLine) {
    const fs::path dir = test::freshDir("StateCostsErrors");
    test::expectOneErrorLine(dir, {
        {{"info", "--state-costs", "builtin:cubes"}, "error: --state-costs measures the backend, not a scene: give one or the other"},
        {{"info", "builtin:cubes", "--json", "x.json"}, "error: --backend, --threads and --json go with --state-costs"},
        {{"info"}, "error: info needs a SCENE (a file or builtin:NAME), or --state-costs"},
        {{"info", "--state-costs", "--backend", "wat"}, ""},
        {{"info", "--state-costs", "--json", ""}, "error: --json: '' is not a file name"},
    });
}

}  // namespace
}  // namespace frugal
