// Settings files: the library reads every setting by its command-line name, writes them back the
// same, and refuses a bad key or value with one line; `render --settings` starts from a file and
// the flags given beside it win; the same frame as the flags alone, byte for byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <frugal/Settings.h>

#include "CliSupport.h"
#include "JsonSupport.h"
#include "TestSupport.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::readAll;
using test::runFrugal;

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

TEST(SettingsFileTest, EverySettingReadsBackAsItWasWritten) {
    Settings s;
    s.width = 321;
    s.height = 123;
    s.backend = BackendKind::Software;
    s.threads = 3;
    s.interp = DepthInterp::Span;
    s.cull = Cull::Conservative;
    s.cullBinsTheta = 8;
    s.cullBinsPhi = 12;
    s.order = Order::Greedy;
    s.refineCosts = 4;
    s.reuse = true;
    s.reuseSettings = {5, 32, false, true};
    s.hsr = Hsr::Adaptive;
    s.depthFormat = DepthFormat::D32F;
    s.background = {0.1f, 0.2f, 0.3f, 0.5f};
    s.ids = true;
    Result<SettingsFile> read = parseSettingsJson(settingsJson(s), "x");
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(settingsJson(read->settings), settingsJson(s));
    EXPECT_EQ(read->settings.background, s.background);
    std::vector<std::string> names;
    for (const SettingInfo& info : settingInfos()) names.push_back(info.name);
    std::sort(names.begin(), names.end());
    EXPECT_EQ(read->keys, names) << "every setting is written, under the names the reader takes";
}

TEST(SettingsFileTest, OnlyTheKeysGivenChangeTheBase) {
    Settings base;
    base.order = Order::Key;
    Result<SettingsFile> read = parseSettingsJson(R"({"cull": "paper", "size": "64x48", "cull-bins": [4, 8]})", "f", base);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(read->settings.cull, Cull::Paper);
    EXPECT_EQ(read->settings.order, Order::Key);
    EXPECT_EQ(read->settings.width, 64);
    EXPECT_EQ(read->settings.cullBinsPhi, 8);
    EXPECT_EQ(read->keys, (std::vector<std::string>{"cull", "cull-bins", "size"}));
}

TEST(SettingsFileTest, BadFilesAreOneLineNamingTheKey) {
    const auto error = [](const std::string& text) { return parseSettingsJson(text, "s.json").error().message; };
    EXPECT_EQ(error(R"({"cull": "x"})"),
              "settings s.json: key 'cull': \"x\" is not a method (" + namesOf(kCulls) + ")");
    EXPECT_EQ(error(R"({"reuse": 1})"), "settings s.json: key 'reuse': 1 is not true or false");
    EXPECT_EQ(error(R"({"threads": 2.5})"), "settings s.json: key 'threads': 2.5 is not a whole number from 0 to 256");
    EXPECT_EQ(error(R"({"size": "80x"})"), "settings s.json: key 'size': \"80x\" is not a size (WxH, each 1 to 65536)");
    EXPECT_EQ(error(R"({"background": [1, 2, 3]})"),
              "settings s.json: key 'background': [1,2,3] is not a colour (r,g,b or r,g,b,a, each 0 to 1)");
    EXPECT_EQ(error("[1]"), "settings s.json: expected a JSON object of settings, got array");
    EXPECT_TRUE(error("{").starts_with("settings s.json: not JSON ("));
    EXPECT_TRUE(error(R"({"culll": "none"})").starts_with("settings s.json: 'culll' is not a setting (size, backend,"));
    Result<SettingsFile> missing = readSettingsFile("/nonexistent/s.json");
    EXPECT_EQ(missing.error().message, "settings /nonexistent/s.json: cannot read the file");
    EXPECT_EQ(missing.error().kind, ErrorKind::Io);
}

TEST(SettingsFileCliTest, RenderStartsFromTheFileAndFlagsWin) {
    const fs::path dir = test::freshDir("SettingsFileCli");
    write(dir / "s.json", R"({"cull": "conservative", "size": [96, 72], "order": "key", "background": [1, 1, 1]})");
    const std::string scene = "builtin:cubes?count=6";
    CliRun run = runFrugal(dir, {"render", scene, "--settings", "s.json", "-q", "-o", "a.png", "--json", "a.json"});
    ASSERT_EQ(run.status, 0) << run.err;
    run = runFrugal(dir, {"render", scene, "--cull", "conservative", "--size", "96x72", "--order", "key",
                          "--background", "1,1,1", "-q", "-o", "b.png"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(readAll(dir / "a.png"), readAll(dir / "b.png"));
    EXPECT_EQ(test::readJson(dir / "a.json")["cull"], "conservative");

    // A flag before or after --settings wins over the file.
    run = runFrugal(dir, {"render", scene, "--size", "32x24", "--settings", "s.json", "--cull", "none", "-q", "-o",
                          "c.png", "--json", "c.json"});
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json c = test::readJson(dir / "c.json");
    EXPECT_EQ(c["size"], nlohmann::json::array({32, 24}));
    EXPECT_EQ(c["cull"], "none");
    EXPECT_EQ(c["draw_order"], "key");
}

TEST(SettingsFileCliTest, ABadFileIsOneLineAndNoOutput) {
    const fs::path dir = test::freshDir("SettingsFileCliBad");
    write(dir / "bad.json", R"({"hsr": "fast"})");
    CliRun run = runFrugal(dir, {"render", "--settings", "bad.json", "-q", "-o", "x.png"});
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.err, "error: --settings bad.json: key 'hsr': \"fast\" is not a mode (zbuffer, depthsort, adaptive, "
                       "adaptive-convex)\n");
    EXPECT_EQ(run.out, "");
    run = runFrugal(dir, {"render", "--settings", "none.json", "-q", "-o", "x.png"});
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.err, "error: --settings none.json: cannot read the file\n");
    EXPECT_EQ(test::filesIn(dir), std::vector<std::string>{"bad.json"});
}

}  // namespace
}  // namespace frugal
