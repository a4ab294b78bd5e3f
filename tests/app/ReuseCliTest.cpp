// `frugal render --reuse` end to end (the real binary in a child process): the same bytes as a
// render without it (colour PNG, id PNG, float depth PFM) on the software backend and on the
// default GL backend; per-frame "reuse" objects in the JSON; one `error:` line and a non-zero
// exit for bad options; a camera path that moves and then stops gives full, rebuild, reuse.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "JsonSupport.h"
#include "TestSupport.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::filesIn;
using test::readAll;
using test::runFrugal;

const char* const kSize = "96x72";

// Renders frames 0..9 of `scene` into `dir` (colour, ids, depth as PFM, JSON) with `extra` flags.
CliRun renderInto(const fs::path& dir, const std::string& scene, const std::vector<std::string>& extra,
                  const std::string& frames = "0:9") {
    std::vector<std::string> args = {"render", scene,    "--frames", frames,  "--size", kSize,   "-o",
                                     "c.png",  "--ids",  "i.png",    "--depth", "d.pfm", "--json", "m.json", "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    return runFrugal(dir, args);
}

// Every image of `a` equals, byte for byte, the file of the same name in `b`.
void expectSameImages(const fs::path& a, const fs::path& b, std::size_t expectedFiles, const std::string& label) {
    SCOPED_TRACE(label);
    std::vector<std::string> names = filesIn(a), other = filesIn(b);
    EXPECT_EQ(names, other);
    std::size_t compared = 0;
    for (const std::string& name : names) {
        if (fs::path(name).extension() == ".json") continue;
        const std::string x = readAll(a / name), y = readAll(b / name);
        EXPECT_FALSE(x.empty()) << name;
        EXPECT_TRUE(x == y) << name << " differs between the full render and reuse";
        ++compared;
    }
    EXPECT_EQ(compared, expectedFiles);
}

// The same scene and flags with and without --reuse (and its options): identical files.
// `tag` names the test's folders (ctest runs tests in parallel).
void expectReuseChangesNoByte(const std::string& tag, const std::string& scene, const std::vector<std::string>& common,
                              const std::vector<std::vector<std::string>>& variants, const std::string& label) {
    const fs::path full = test::freshDir(tag + "Full");
    const CliRun plain = renderInto(full, scene, common);
    ASSERT_EQ(plain.status, 0) << label << ": " << plain.err;
    for (const std::vector<std::string>& variant : variants) {
        std::vector<std::string> flags = common;
        flags.push_back("--reuse");
        flags.insert(flags.end(), variant.begin(), variant.end());
        const fs::path dir = test::freshDir(tag + "Reused");
        const CliRun run = renderInto(dir, scene, flags);
        ASSERT_EQ(run.status, 0) << label << " " << test::joined(flags) << ": " << run.err;
        EXPECT_EQ(run.err, "") << "-q: nothing on stderr";
        expectSameImages(full, dir, 30, label + " " + test::joined(flags));
        const nlohmann::json j = test::readJson(dir / "m.json");
        ASSERT_TRUE(j.is_object());
        ASSERT_EQ(j["frames"].size(), 10u);
        // The frames of a still camera after the first are reuse frames or planned fallbacks.
        std::size_t reused = 0;
        for (const nlohmann::json& frame : j["frames"]) reused += frame["reuse"]["mode"] == "reuse" ? 1 : 0;
        EXPECT_EQ(j["frames"][0]["reuse"]["mode"], "rebuild");
        if (scene.find("cubes") == std::string::npos) {
            EXPECT_EQ(reused, 9u) << label << " " << test::joined(flags);
        }
    }
}

const std::vector<std::vector<std::string>> kVariants = {
    {}, {"--reuse-grain", "1", "--reuse-cell", "8", "--exact-static"}, {"--reuse-grain", "0", "--reuse-cell", "64", "--no-fallback"}};

TEST(ReuseCliTest, SoftwareRendersTheSameBytesWithReuse) {
    for (const char* scene : {"builtin:default", "builtin:dominoes?polygons=804&static=0.5544", "builtin:cubes"}) {
        expectReuseChangesNoByte("ReuseCliSoftware", scene, {"--backend", "software"}, kVariants, std::string(scene) + " software");
    }
    // A culled draw list, reused.
    expectReuseChangesNoByte("ReuseCliSoftware", "builtin:default", {"--backend", "software", "--cull", "conservative"}, {{}},
                             "default software conservative");
}

TEST(ReuseCliTest, DefaultGlBackendRendersTheSameBytesWithReuse) {
    const fs::path probe = test::freshDir("ReuseCliProbe");
    const CliRun run = runFrugal(probe, {"render", "builtin:cubes", "--size", kSize, "-o", "p.png", "-q"});
    if (run.status == 3) FRUGAL_SKIP_IF_NO_GL(run.err);
    ASSERT_EQ(run.status, 0) << run.err;
    for (const char* scene : {"builtin:default", "builtin:cubes"}) {
        expectReuseChangesNoByte("ReuseCliGl", scene, {}, kVariants, std::string(scene) + " default backend");
    }
    expectReuseChangesNoByte("ReuseCliGl", "builtin:default", {"--cull", "sphere"}, {{}}, "default backend sphere");
}

TEST(ReuseCliTest, JsonHasTheReuseFiguresOfEveryFrame) {
    const fs::path dir = test::freshDir("ReuseCliJson");
    const CliRun run = renderInto(dir, "builtin:dominoes?polygons=804&static=0.5544", {"--backend", "software", "--reuse"});
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json j = test::readJson(dir / "m.json");
    ASSERT_TRUE(j.is_object());
    ASSERT_TRUE(j["reuse"].is_object());
    EXPECT_EQ(j["reuse"]["grain"], 16);
    EXPECT_EQ(j["reuse"]["cell"], 16);
    EXPECT_EQ(j["reuse"]["fallback"], true);
    EXPECT_EQ(j["frames"][0]["reuse"]["reason"], "first frame");
    EXPECT_EQ(j["reuse"]["static_pair_bytes"], 96 * 72 * 12);
    const std::uint64_t triangles = j["counts"]["triangles"].get<std::uint64_t>();
    ASSERT_EQ(j["frames"].size(), 10u);
    for (std::size_t i = 0; i < 10; ++i) {
        const nlohmann::json& frame = j["frames"][i];
        SCOPED_TRACE("frame " + std::to_string(i));
        ASSERT_TRUE(frame.contains("reuse"));
        const nlohmann::json& r = frame["reuse"];
        for (const char* key : {"mode", "reason", "p_dd", "p_ds", "p_sd", "p_ss", "copied_px", "cleared_px", "redrawn_tris",
                                "static_redrawn_tris", "rects", "instances"})
            ASSERT_TRUE(r.contains(key)) << key;
        EXPECT_EQ(r["mode"], i == 0 ? "rebuild" : "reuse");
        EXPECT_FALSE(r["reason"].get<std::string>().empty());
        const std::uint64_t sum = r["p_dd"].get<std::uint64_t>() + r["p_ds"].get<std::uint64_t>() +
                                  r["p_sd"].get<std::uint64_t>() + r["p_ss"].get<std::uint64_t>();
        EXPECT_EQ(sum, triangles) << "the four states cover every triangle";
        const std::uint64_t instances = r["instances"]["p_dd"].get<std::uint64_t>() + r["instances"]["p_ds"].get<std::uint64_t>() +
                                        r["instances"]["p_sd"].get<std::uint64_t>() + r["instances"]["p_ss"].get<std::uint64_t>();
        EXPECT_EQ(instances, j["counts"]["instances"].get<std::uint64_t>());
        EXPECT_LE(r["redrawn_tris"].get<std::uint64_t>(), triangles);
        if (i == 0) {
            EXPECT_EQ(r["copied_px"], 96 * 72);
            EXPECT_EQ(r["cleared_px"], 96 * 72);
            EXPECT_EQ(r["redrawn_tris"].get<std::uint64_t>(), triangles);
            EXPECT_EQ(r["p_ss"].get<std::uint64_t>(), triangles);
        } else {
            EXPECT_LT(r["redrawn_tris"].get<std::uint64_t>(), triangles) << "reuse redraws less";
            EXPECT_GT(r["p_sd"].get<std::uint64_t>() + r["p_dd"].get<std::uint64_t>(), 0u) << "dominoes fall";
        }
    }
    // Without --reuse, no reuse figures.
    const CliRun plain = renderInto(dir, "builtin:dominoes?polygons=804&static=0.5544", {"--backend", "software"}, "0:1");
    ASSERT_EQ(plain.status, 0) << plain.err;
    const nlohmann::json p = test::readJson(dir / "m.json");
    EXPECT_TRUE(p["reuse"].is_null());
    for (const nlohmann::json& frame : p["frames"]) EXPECT_FALSE(frame.contains("reuse"));
}

TEST(ReuseCliTest, BadOptionsGiveOneErrorLine) {
    const fs::path dir = test::freshDir("ReuseCliBad");
    test::writeFile(dir / "notjson.json", "this is not JSON {");
    test::writeFile(dir / "wrong.json", R"([{"eye":[0,5,10],"target":[0,0,0]},{"eye":[1,2],"target":[0,0,0]}])");
    test::writeFile(dir / "noeye.json", R"([{"target":[0,0,0]}])");
    test::writeFile(dir / "empty.json", "[]");
    struct Case {
        std::vector<std::string> flags;
        std::string says;  // part of the error line
    };
    const std::vector<Case> cases = {
        {{"--reuse", "--reuse-grain", "-1"}, "--reuse-grain"},
        {{"--reuse", "--reuse-grain", "x"}, "--reuse-grain"},
        {{"--reuse", "--reuse-cell", "0"}, "--reuse-cell"},
        {{"--reuse", "--reuse-cell", "100000"}, "--reuse-cell"},
        {{"--reuse", "--cull", "oracle"}, "oracle"},
        {{"--cull", "oracle", "--reuse"}, "oracle"},
        {{"--reuse", "--camera-path", "missing.json"}, "missing.json"},
        {{"--reuse", "--camera-path", "notjson.json"}, "not JSON"},
        {{"--reuse", "--camera-path", "wrong.json"}, "entry 1: eye: expected 3 numbers"},
        {{"--reuse", "--camera-path", "noeye.json"}, "entry 0: eye: missing"},
        {{"--reuse", "--camera-path", "empty.json"}, "non-empty list"},
    };
    for (const Case& c : cases) {
        std::vector<std::string> args = {"render", "builtin:cubes", "--size", kSize, "--backend", "software", "-o", "x.png"};
        args.insert(args.end(), c.flags.begin(), c.flags.end());
        const CliRun run = runFrugal(dir, args);
        SCOPED_TRACE(test::joined(c.flags));
        EXPECT_NE(run.status, 0);
        const std::vector<std::string> lines = run.errLines();
        ASSERT_EQ(lines.size(), 1u) << run.err;
        EXPECT_EQ(lines[0].rfind("error: ", 0), 0u) << lines[0];
        EXPECT_NE(lines[0].find(c.says), std::string::npos) << lines[0];
        EXPECT_FALSE(fs::exists(dir / "x.png")) << "nothing written";
    }
}

TEST(ReuseCliTest, CameraPathMovingThenStillGivesFullRebuildReuse) {
    const fs::path dir = test::freshDir("ReuseCliPath");
    // Entries 0, 1, 2 differ (moving); the last holds for the frames after it (still).
    test::writeFile(dir / "path.json", R"({"views": [{"eye":[0,20,30],"target":[0,0,0]},
                                                     {"eye":[2,20,30],"target":[0,0,0],"up":[0,1,0]},
                                                     {"eye":[4,20,30],"target":[0,0,0],"fov":40}]})");
    std::vector<std::string> reuseFlags = {"--backend", "software", "--reuse", "--camera-path", "path.json"};
    const CliRun run = renderInto(dir, "builtin:dominoes?polygons=1404&static=0.9866", reuseFlags, "0:7");
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json j = test::readJson(dir / "m.json");
    ASSERT_EQ(j["frames"].size(), 8u);
    const std::vector<std::string> expected = {"rebuild", "full", "full", "rebuild", "reuse", "reuse", "reuse", "reuse"};
    for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(j["frames"][i]["reuse"]["mode"], expected[i]) << "frame " << i << ": " << j["frames"][i]["reuse"]["reason"];
    }
    EXPECT_EQ(j["frames"][1]["reuse"]["reason"], "camera, light or background changed");
    EXPECT_EQ(j["frames"][3]["reuse"]["reason"], "first still frame");
    // And the images are those of the same path without reuse.
    const fs::path plainDir = test::freshDir("ReuseCliPathPlain");
    fs::copy_file(dir / "path.json", plainDir / "path.json");
    const CliRun plain = renderInto(plainDir, "builtin:dominoes?polygons=1404&static=0.9866",
                                    {"--backend", "software", "--camera-path", "path.json"}, "0:7");
    ASSERT_EQ(plain.status, 0) << plain.err;
    expectSameImages(plainDir, dir, 24, "camera path");
}

}  // namespace
}  // namespace frugal
