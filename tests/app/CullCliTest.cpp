// `frugal render --cull METHOD` and `frugal cull-report` on the command line, end to end: the real
// binary in a child process (exit status, stdout, stderr, JSON, files left behind). Renders use the
// software backend at small sizes, so the suite stays fast; the accuracy of the methods over many
// views and both backends is CullReportGLTest's.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include <frugal/Settings.h>

#include "JsonSupport.h"
#include "TestSupport.h"
#include "io/ImageIO.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::filesIn;
using test::readAll;
using test::runFrugal;  // the frugal binary in a child process

// Every method, as refusals list them (the order is pinned in tests/cullrender/MethodsTest.cpp).
const std::string kMethodList = namesOf(kCulls);

// The number of distinct triangle ids (background 0 excluded) in frugal's id PNG.
std::size_t distinctIds(const fs::path& path) {
    Result<DecodedImage> image = readPng(path.string());
    EXPECT_TRUE(image) << path << ": " << (image ? "" : image.error().message);
    if (!image) return 0;
    EXPECT_EQ(image->channels, 4);
    EXPECT_EQ(image->bitDepth, 8);
    std::set<std::uint32_t> ids;
    const std::vector<std::uint8_t>& p = image->pixels8;
    for (std::size_t i = 0; i + 3 < p.size(); i += 4) {
        const std::uint32_t id = std::uint32_t(p[i]) | std::uint32_t(p[i + 1]) << 8 | std::uint32_t(p[i + 2]) << 16 |
                                 std::uint32_t(p[i + 3]) << 24;
        if (id != 0) ids.insert(id);
    }
    return ids.size();
}

// --- render --cull ----------------------------------------------------------------------------------

TEST(CullCliTest, RenderConservativeWritesThePngAndCullFiguresOfEveryFrame) {
    const fs::path dir = test::freshDir("CullCliConservative");
    const CliRun run = runFrugal(dir, {"render", "builtin:cubes", "--cull", "conservative", "--frames", "0:2", "--size",
                                       "64x48", "--backend", "software", "-o", "c.png", "--json", "m.json"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"c_0000.png", "c_0001.png", "c_0002.png", "m.json"}));
    // Progress names the method and the preparation.
    EXPECT_NE(run.err.find("cull: 28 meshes, 336 triangles prepared in "), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("(conservative: "), std::string::npos) << run.err;
    for (const char* png : {"c_0000.png", "c_0001.png", "c_0002.png"}) {
        Result<DecodedImage> image = readPng((dir / png).string());
        ASSERT_TRUE(image) << png << ": " << image.error().message;
        EXPECT_EQ(image->width, 64);
        EXPECT_EQ(image->height, 48);
    }
    const nlohmann::json j = test::readJson(dir / "m.json");
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j["cull"], "conservative");
    EXPECT_EQ(j["backend"], "software");
    const std::size_t tos = j["counts"]["triangles"].get<std::size_t>();
    EXPECT_EQ(tos, 336u);
    ASSERT_EQ(j["frames"].size(), 3u);
    for (const nlohmann::json& frame : j["frames"]) {
        SCOPED_TRACE(frame.dump());
        for (const char* key : {"tos", "pvs", "cull_ms", "ranges"}) ASSERT_TRUE(frame.contains(key)) << key;
        EXPECT_EQ(frame["tos"].get<std::size_t>(), tos);
        EXPECT_GT(frame["pvs"].get<std::size_t>(), 0u) << "the cubes are in view";
        EXPECT_LE(frame["pvs"].get<std::size_t>(), tos);
        EXPECT_GE(frame["ranges"].get<std::size_t>(), 1u);
        EXPECT_GE(frame["cull_ms"].get<double>(), 0.0);
    }
}

TEST(CullCliTest, EveryMethodReportsItsFiguresAndNoneAddsNoKeys) {
    const fs::path dir = test::freshDir("CullCliMethods");
    const std::vector<std::string> base = {"render", "builtin:cubes", "--frames", "0:1", "--size",
                                           "64x48",  "--backend",     "software", "-o",  "c.png",
                                           "--json", "m.json",        "-q"};
    for (const char* name : {"", "none", "sphere", "backface", "cones", "paper", "conservative", "oracle"}) {
        const std::string method = name;
        SCOPED_TRACE("--cull " + method);
        std::vector<std::string> args = base;
        if (!method.empty()) args.insert(args.end(), {"--cull", method});
        const CliRun run = runFrugal(dir, args);
        ASSERT_EQ(run.status, 0) << run.err;
        EXPECT_EQ(run.err, "") << "-q: nothing on stderr";
        const nlohmann::json j = test::readJson(dir / "m.json");
        ASSERT_TRUE(j.is_object());
        EXPECT_EQ(j["cull"], method.empty() ? "none" : method);
        ASSERT_EQ(j["frames"].size(), 2u);
        for (const nlohmann::json& frame : j["frames"]) {
            if (method.empty() || method == "none") {
                for (const char* key : {"tos", "pvs", "cull_ms", "ranges"}) EXPECT_FALSE(frame.contains(key)) << key;
                continue;
            }
            for (const char* key : {"tos", "pvs", "cull_ms"}) ASSERT_TRUE(frame.contains(key)) << key;
            // The oracle is no plan of index ranges: it draws its own index buffers.
            if (method != "oracle") {
                EXPECT_TRUE(frame.contains("ranges"));
            }
            EXPECT_EQ(frame["tos"], 336);
            EXPECT_LE(frame["pvs"].get<std::size_t>(), 336u);
        }
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
}

// The oracle submits exactly the frame's really visible set: as many triangles as the id image of
// the same frame, rendered whole with --ids, has distinct ids.
TEST(CullCliTest, OraclePvsIsTheCountOfDistinctIdsOfTheFrame) {
    const fs::path dir = test::freshDir("CullCliOracle");
    struct Case {
        std::vector<std::string> scene;  // scene and frame options
        int frames;
    };
    const Case cases[] = {
        {{"builtin:default"}, 1},
        {{"builtin:cubes", "--frames", "0:2"}, 3},
        {{FRUGAL_BUNNY_OBJ, "--cull-backfaces"}, 1},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(test::joined(c.scene));
        std::vector<std::string> common = {"render"};
        common.insert(common.end(), c.scene.begin(), c.scene.end());
        common.insert(common.end(), {"--size", "64x48", "--backend", "software", "-q"});
        std::vector<std::string> oracle = common, ids = common;
        oracle.insert(oracle.end(), {"--cull", "oracle", "-o", "o.png", "--json", "o.json"});
        ids.insert(ids.end(), {"-o", "f.png", "--ids", "i.png"});
        CliRun run = runFrugal(dir, oracle);
        ASSERT_EQ(run.status, 0) << run.err;
        run = runFrugal(dir, ids);
        ASSERT_EQ(run.status, 0) << run.err;
        const nlohmann::json j = test::readJson(dir / "o.json");
        ASSERT_TRUE(j.is_object());
        ASSERT_EQ(j["frames"].size(), std::size_t(c.frames));
        for (int f = 0; f < c.frames; ++f) {
            SCOPED_TRACE("frame " + std::to_string(f));
            const std::string idFile = c.frames == 1 ? "i.png" : "i_000" + std::to_string(f) + ".png";
            const std::size_t visible = distinctIds(dir / idFile);
            EXPECT_GT(visible, 0u);
            EXPECT_EQ(j["frames"][std::size_t(f)]["pvs"].get<std::size_t>(), visible);
            EXPECT_EQ(j["frames"][std::size_t(f)]["tos"], j["counts"]["triangles"]);
            // The oracle's image is the full render's: it leaves out hidden triangles only.
            const std::string suffix = c.frames == 1 ? ".png" : "_000" + std::to_string(f) + ".png";
            Result<DecodedImage> full = readPng((dir / ("f" + suffix)).string());
            Result<DecodedImage> drawn = readPng((dir / ("o" + suffix)).string());
            ASSERT_TRUE(full && drawn);
            EXPECT_TRUE(full->pixels8 == drawn->pixels8) << "the oracle's colour image differs from the full render";
        }
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
}

// Conservative methods only leave out triangles that own no pixel: the colour PNG is the one of
// --cull none, byte for byte (the file, and the decoded pixels).
TEST(CullCliTest, ConservativeMethodsLeaveTheImageUnchanged) {
    const fs::path dir = test::freshDir("CullCliSameImage");
    // (The bunny's preparation takes seconds under the sanitizers: two views of it, single-sided so
    // that facing matters, and no --cull-bins variants; the double-sided bunny is CullReportGLTest's.)
    const std::vector<std::vector<std::string>> scenes = {
        {"builtin:default"},
        {"builtin:cubes", "--frames", "0:2"},
        {FRUGAL_BUNNY_OBJ, "--cull-backfaces"},
        {FRUGAL_BUNNY_OBJ, "--cull-backfaces", "--eye", "0.3,0.2,0.9", "--target", "0,0,0"},  // close: partly in view
    };
    const std::vector<std::vector<std::string>> methods = {
        {"--cull", "conservative"},
        {"--cull", "backface"},
        {"--cull", "cones"},
        {"--cull", "sphere"},
        {"--cull", "conservative", "--cull-bins", "1x1"},
        {"--cull", "conservative", "--cull-bins", "64x128"},
    };
    for (const std::vector<std::string>& scene : scenes) {
        SCOPED_TRACE(test::joined(scene));
        const bool sequence = scene.size() > 1 && scene[1] == "--frames";
        std::vector<std::string> common = {"render"};
        common.insert(common.end(), scene.begin(), scene.end());
        common.insert(common.end(), {"--size", "64x48", "--backend", "software", "-q"});
        std::vector<std::string> none = common;
        none.insert(none.end(), {"--cull", "none", "-o", "none.png"});
        CliRun run = runFrugal(dir, none);
        ASSERT_EQ(run.status, 0) << run.err;
        for (const std::vector<std::string>& method : methods) {
            SCOPED_TRACE(test::joined(method));
            if (scene[0] == FRUGAL_BUNNY_OBJ && method.size() > 2) continue;
            std::vector<std::string> args = common;
            args.insert(args.end(), method.begin(), method.end());
            args.insert(args.end(), {"-o", "culled.png"});
            run = runFrugal(dir, args);
            ASSERT_EQ(run.status, 0) << run.err;
            const std::vector<std::string> suffixes =
                sequence ? std::vector<std::string>{"_0000.png", "_0001.png", "_0002.png"}
                         : std::vector<std::string>{".png"};
            for (const std::string& suffix : suffixes) {
                SCOPED_TRACE(suffix);
                Result<DecodedImage> reference = readPng((dir / ("none" + suffix)).string());
                Result<DecodedImage> culled = readPng((dir / ("culled" + suffix)).string());
                ASSERT_TRUE(reference) << reference.error().message;
                ASSERT_TRUE(culled) << culled.error().message;
                EXPECT_EQ(culled->width, reference->width);
                EXPECT_EQ(culled->height, reference->height);
                std::size_t differing = 0;
                for (std::size_t i = 0; i + 3 < reference->pixels8.size() && i + 3 < culled->pixels8.size(); i += 4)
                    differing += reference->pixels8[i] != culled->pixels8[i] ||
                                 reference->pixels8[i + 1] != culled->pixels8[i + 1] ||
                                 reference->pixels8[i + 2] != culled->pixels8[i + 2] ||
                                 reference->pixels8[i + 3] != culled->pixels8[i + 3];
                EXPECT_EQ(differing, 0u) << "pixels differing from --cull none";
                EXPECT_TRUE(readAll(dir / ("culled" + suffix)) == readAll(dir / ("none" + suffix)))
                    << "the PNG files differ";
            }
        }
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
}

TEST(CullCliTest, OcclusionAheadRendersASequenceAsNoneDoes) {
    // Each frame's plan made while the frame before draws: the same colour, depth and id files as a
    // plain render, and the JSON tells which frames took a plan made ahead (all but the first).
    const fs::path dir = test::freshDir("CullCliAhead");
    test::writeFile(dir / "path.json", R"([{"eye": [0, 2, 11.5], "target": [0, 0, 0]},
                                           {"eye": [2, 2, 11.3], "target": [0, 0, 0]},
                                           {"eye": [4, 2, 10.8], "target": [0, 0, 0]}])");
    const std::string scene = std::string("builtin:copies?count=3&of=") + FRUGAL_BUNNY_OBJ;
    for (const char* method : {"none", "occlusion-ahead"}) {
        const std::string m = method;
        const CliRun run = runFrugal(dir, {"render", scene, "--camera-path", "path.json", "--frames", "0:2", "--size",
                                           "96x72", "--backend", "software", "--cull-backfaces", "--cull", m, "-o",
                                           m + "-%d.png", "--depth", m + "-%d.pfm", "--ids", m + "-ids-%d.png",
                                           "--json", m + ".json", "-q"});
        ASSERT_EQ(run.status, 0) << run.err;
    }
    for (int i = 0; i < 3; ++i) {
        const std::string n = std::to_string(i);
        for (const std::string& file : {"%-" + n + ".png", "%-" + n + ".pfm", "%-ids-" + n + ".png"}) {
            std::string none = file, ahead = file;
            none.replace(0, 1, "none");
            ahead.replace(0, 1, "occlusion-ahead");
            ASSERT_TRUE(fs::exists(dir / ahead)) << ahead;
            EXPECT_TRUE(readAll(dir / none) == readAll(dir / ahead)) << ahead << " differs from " << none;
        }
    }
    const nlohmann::json report = test::readJson(dir / "occlusion-ahead.json");
    ASSERT_EQ(report["frames"].size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        const nlohmann::json& frame = report["frames"][i];
        ASSERT_TRUE(frame.contains("occlusion")) << frame.dump();
        EXPECT_EQ(frame["occlusion"]["ahead"], i > 0) << frame.dump();
        EXPECT_TRUE(frame["occlusion"]["ahead_wait_ms"].is_number()) << frame.dump();
        EXPECT_LT(frame["pvs"].get<std::size_t>(), frame["tos"].get<std::size_t>()) << frame.dump();
    }
    EXPECT_FALSE(test::readJson(dir / "none.json")["frames"][0].contains("occlusion"));
}

// --- errors ---------------------------------------------------------------------------------------

struct BadCase {
    std::vector<std::string> args;
    int status;
    std::string message;  // the whole of stderr, one line; a prefix when it ends in "..."
};

TEST(CullCliTest, BadCullOptionsGetOneLineAndNoFile) {
    const fs::path dir = test::freshDir("CullCliBad");
    test::writeFile(dir / "in" / "text.json", "not json at all\n");
    test::writeFile(dir / "in" / "empty.json", "[]\n");
    test::writeFile(dir / "in" / "emptyviews.json", "{\"views\": []}\n");
    test::writeFile(dir / "in" / "object.json", "{\"eye\": [0, 0, 5], \"target\": [0, 0, 0]}\n");
    test::writeFile(dir / "in" / "noeye.json", "[{\"target\": [0, 0, 0]}]\n");
    test::writeFile(dir / "in" / "notarget.json", "[{\"eye\": [0, 0, 5]}]\n");
    test::writeFile(dir / "in" / "shorteye.json", "[{\"eye\": [0, 5], \"target\": [0, 0, 0]}]\n");
    test::writeFile(dir / "in" / "wordeye.json", "[{\"eye\": [0, \"x\", 5], \"target\": [0, 0, 0]}]\n");
    test::writeFile(dir / "in" / "fov180.json", "[{\"eye\": [0, 0, 5], \"target\": [0, 0, 0], \"fov\": 180}]\n");
    test::writeFile(
        dir / "in" / "fov0.json",
        "[{\"eye\": [0, 0, 5], \"target\": [0, 0, 0]}, {\"eye\": [0, 0, 5], \"target\": [0, 0, 0], \"fov\": 0}]\n");
    test::writeFile(dir / "in" / "fovword.json", "[{\"eye\": [0, 0, 5], \"target\": [0, 0, 0], \"fov\": \"wide\"}]\n");
    // 1e300 is a finite double but no finite float; 1e999 is no JSON number nlohmann accepts.
    test::writeFile(dir / "in" / "hugeeye.json", "[{\"eye\": [1e300, 0, 0], \"target\": [0, 0, 0]}]\n");
    test::writeFile(dir / "in" / "infeye.json", "[{\"eye\": [1e999, 0, 0], \"target\": [0, 0, 0]}]\n");
    test::writeFile(dir / "in" / "hugeup.json",
                    "[{\"eye\": [0, 0, 5], \"target\": [0, 0, 0], \"up\": [0, -1e300, 0]}]\n");
    test::writeFile(dir / "in" / "sameeye.json",
                    "[{\"eye\": [0, 0, 5], \"target\": [0, 0, 1]}, {\"eye\": [0, 0, 5], \"target\": [0, 0, 5]}]\n");
    test::writeFile(dir / "in" / "fareye.json", "[{\"eye\": [3e38, 0, 0], \"target\": [-3e38, 0, 0]}]\n");
    test::writeFile(dir / "in" / "parallelup.json", "[{\"eye\": [0, 4, 0], \"target\": [0, 0, 0]}]\n");
    const std::string methods = std::string("(") + kMethodList + ")";
    const std::string bins = "' is not a bin grid (TxP, each 1 to 1024)";
    const BadCase cases[] = {
        // render
        {{"render", "--cull", "bogus"}, 2, "error: --cull: 'bogus' is not a method " + methods},
        {{"render", "--cull", "Conservative"}, 2, "error: --cull: 'Conservative' is not a method " + methods},
        {{"render", "--cull"}, 2, "error: --cull: missing value"},
        {{"render", "--cull-bins", "0x4"}, 2, "error: --cull-bins: '0x4" + bins},
        {{"render", "--cull-bins", "4x0"}, 2, "error: --cull-bins: '4x0" + bins},
        {{"render", "--cull-bins", "16"}, 2, "error: --cull-bins: '16" + bins},
        {{"render", "--cull-bins", "16x"}, 2, "error: --cull-bins: '16x" + bins},
        {{"render", "--cull-bins", "x16"}, 2, "error: --cull-bins: 'x16" + bins},
        {{"render", "--cull-bins", "2000x3"}, 2, "error: --cull-bins: '2000x3" + bins},
        {{"render", "--cull-bins", "16x32x2"}, 2, "error: --cull-bins: '16x32x2" + bins},
        {{"render", "--cull-bins", "-4x4"}, 2, "error: --cull-bins: '-4x4" + bins},
        // cull-report: the command line
        {{"cull-report", "--cull", "conservative"}, 2, "error: --cull: unknown option (see 'frugal help cull-report')"},
        {{"cull-report", "--methods", "a,b"}, 2, "error: --methods: 'a,b' names 'a', not a method " + methods},
        {{"cull-report", "--methods", "none,bogus"},
         2,
         "error: --methods: 'none,bogus' names 'bogus', not a method " + methods},
        {{"cull-report", "--methods", ","}, 2, "error: --methods: ',' names '', not a method " + methods},
        {{"cull-report", "--methods", ""}, 2, "error: --methods: '' is not a list of methods " + methods},
        {{"cull-report", "--views", "0"}, 2, "error: --views: '0' is not a whole number from 1 to 10000"},
        {{"cull-report", "--methods", "conservative", "--masks", "m"},
         2,
         "error: --masks: the occlusion buffers come from the occlusion method; add it to --methods"},
        {{"cull-report", "--views", "3x"}, 2, "error: --views: '3x' is not a whole number from 1 to 10000"},
        {{"cull-report", "--repeat", "0"}, 2, "error: --repeat: '0' is not a whole number from 1 to 10000"},
        {{"cull-report", "--cull-bins", "16"}, 2, "error: --cull-bins: '16" + bins},
        {{"cull-report", "--plot", "out.png"}, 2, "error: --plot out.png: gnuplot writes SVG here; name it .svg"},
        {{"cull-report", "--plot", "it's.svg"},
         2,
         "error: --plot it's.svg: a path with a single quote cannot be passed to gnuplot"},
        {{"cull-report", "--camera-path", "in/object.json", "--views", "3"},
         2,
         "error: --camera-path: give either a camera path, --views N, or one camera"},
        {{"cull-report", "--views", "3", "--camera-path", "in/object.json"},
         2,
         "error: --camera-path: give either a camera path, --views N, or one camera"},
        {{"cull-report", "--camera-path", "in/object.json", "--eye", "1,2,3"},
         2,
         "error: --camera-path: give either a camera path, --views N, or one camera"},
        {{"cull-report", "--views", "3", "--eye", "1,2,3"},
         2,
         "error: --views: give either --views N or one camera (--camera/--eye/--target)"},
        {{"cull-report", "--frames", "0:2"}, 2, "error: --frames: cull-report measures views at one time; use --time"},
        {{"cull-report", "builtin:default", "builtin:cubes"},
         2,
         "error: unexpected argument 'builtin:cubes' (one SCENE only)"},
        // cull-report: the camera path file (bad input: status 1)
        {{"cull-report", "--camera-path", "in/missing.json"},
         1,
         "error: --camera-path in/missing.json: cannot read the file"},
        {{"cull-report", "--camera-path", "in/text.json"}, 1, "error: --camera-path in/text.json: not JSON (..."},
        {{"cull-report", "--camera-path", "in/infeye.json"}, 1, "error: --camera-path in/infeye.json: not JSON (..."},
        {{"cull-report", "--camera-path", "in/empty.json"},
         1,
         "error: --camera-path in/empty.json: expected a non-empty list of {\"eye\",\"target\",\"up\",\"fov\"}"},
        {{"cull-report", "--camera-path", "in/emptyviews.json"},
         1,
         "error: --camera-path in/emptyviews.json: expected a non-empty list of {\"eye\",\"target\",\"up\",\"fov\"}"},
        {{"cull-report", "--camera-path", "in/object.json"},
         1,
         "error: --camera-path in/object.json: expected a non-empty list of {\"eye\",\"target\",\"up\",\"fov\"}"},
        {{"cull-report", "--camera-path", "in/noeye.json"},
         1,
         "error: --camera-path in/noeye.json: entry 0: eye: missing"},
        {{"cull-report", "--camera-path", "in/notarget.json"},
         1,
         "error: --camera-path in/notarget.json: entry 0: target: missing"},
        {{"cull-report", "--camera-path", "in/shorteye.json"},
         1,
         "error: --camera-path in/shorteye.json: entry 0: eye: expected 3 numbers"},
        {{"cull-report", "--camera-path", "in/wordeye.json"},
         1,
         "error: --camera-path in/wordeye.json: entry 0: eye: expected 3 numbers"},
        {{"cull-report", "--camera-path", "in/fov180.json"},
         1,
         "error: --camera-path in/fov180.json: entry 0: fov: expected degrees in (0, 180)"},
        {{"cull-report", "--camera-path", "in/fov0.json"},
         1,
         "error: --camera-path in/fov0.json: entry 1: fov: expected degrees in (0, 180)"},
        {{"cull-report", "--camera-path", "in/fovword.json"},
         1,
         "error: --camera-path in/fovword.json: entry 0: fov: expected degrees in (0, 180)"},
        {{"cull-report", "--camera-path", "in/hugeeye.json"},
         1,
         "error: --camera-path in/hugeeye.json: entry 0: eye: not a finite point"},
        {{"cull-report", "--camera-path", "in/hugeup.json"},
         1,
         "error: --camera-path in/hugeup.json: entry 0: up: not a finite point"},
        {{"cull-report", "--camera-path", "in/sameeye.json"},
         1,
         "error: --camera-path in/sameeye.json: entry 1: eye and target coincide at (0, 0, 5)"},
        {{"cull-report", "--camera-path", "in/fareye.json"},
         1,
         "error: --camera-path in/fareye.json: entry 0: eye (3e+38, 0, 0) and target (-3e+38, 0, 0) are too far apart "
         "for float"},
        {{"cull-report", "--camera-path", "in/parallelup.json"},
         1,
         "error: --camera-path in/parallelup.json: entry 0: up (0, 1, 0) is parallel to the view direction"},
        // cull-report: the scene
        {{"cull-report", "missing.glb"}, 1, "error: missing.glb: no such file"},
    };
    for (const BadCase& c : cases) {
        // Outputs asked for, to check that none is written on an error; small, software, quiet. They
        // go first, so the case's own arguments come last (and a missing value stays missing).
        std::vector<std::string> args = {c.args[0],  "--size", "64x48",  "--backend",
                                         "software", "-q",     "--json", "r.json"};
        if (c.args[0] == "render") {
            args.insert(args.end(), {"-o", "out.png"});
        } else {
            args.insert(args.end(), {"--csv", "r.csv", "--repeat", "1"});
            // Two views, unless the case chooses its views itself.
            const std::string line = test::joined(c.args);
            if (line.find("--camera-path") == std::string::npos && line.find("--eye") == std::string::npos &&
                line.find("--views") == std::string::npos)
                args.insert(args.end(), {"--views", "2"});
        }
        args.insert(args.end(), c.args.begin() + 1, c.args.end());
        SCOPED_TRACE(test::joined(args));
        const CliRun run = runFrugal(dir, args);
        EXPECT_EQ(run.status, c.status);
        ASSERT_EQ(run.errLines().size(), 1u) << run.err;
        if (c.message.size() > 3 && c.message.compare(c.message.size() - 3, 3, "...") == 0)
            EXPECT_EQ(run.err.rfind(c.message.substr(0, c.message.size() - 3), 0), 0u) << run.err;
        else
            EXPECT_EQ(run.err, c.message + "\n");
        EXPECT_EQ(run.out, "");
        EXPECT_FALSE(fs::exists(dir / "r.json"));
        EXPECT_FALSE(fs::exists(dir / "r.csv"));
        EXPECT_EQ(filesIn(dir), std::vector<std::string>{"in"}) << "no output file may be left behind";
    }
}

// The outputs are written whole or not at all: one that cannot be written leaves none of the others.
TEST(CullCliTest, CullReportWritesAllOutputsOrNone) {
    const fs::path dir = test::freshDir("CullCliOutputs");
    const CliRun run = runFrugal(dir, {"cull-report", "builtin:default", "--size", "64x48", "--views", "1", "--repeat",
                                       "1", "--backend", "software", "-q", "--csv", "r.csv", "--json", "nodir/r.json"});
    EXPECT_EQ(run.status, 1);
    ASSERT_EQ(run.errLines().size(), 1u) << run.err;
    EXPECT_EQ(run.err.rfind("error: nodir/r.json: ", 0), 0u) << run.err;
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{});
}

// A small report with the default methods, on the software backend: the summary on stdout, and
// one view per camera option.
TEST(CullCliTest, CullReportPrintsASummaryLinePerMethod) {
    const fs::path dir = test::freshDir("CullCliSummary");
    CliRun run = runFrugal(dir, {"cull-report", "builtin:cubes", "--size", "64x48", "--views", "3", "--repeat", "1",
                                 "--backend", "software", "--json", "r.json"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"r.json"});
    EXPECT_EQ(run.out.rfind("method ", 0), 0u) << run.out;
    for (const char* method :
         {"\nnone ", "\nsphere ", "\nbackface ", "\ncones ", "\npaper ", "\nconservative ", "\noracle "})
        EXPECT_NE(run.out.find(method), std::string::npos) << method << "\n" << run.out;
    EXPECT_NE(run.err.find("view 3/3"), std::string::npos) << run.err;
    nlohmann::json j = test::readJson(dir / "r.json");
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j["views"].size(), 3u);
    EXPECT_EQ(j["repeat"], 1);
    EXPECT_EQ(j["timing"], "cold");

    // --methods keeps the order given and drops repeats; one camera gives one view of class "camera".
    run = runFrugal(
        dir, {"cull-report", "builtin:cubes", "--size", "64x48", "--eye", "0,3,9", "--target", "0,0,0", "--methods",
              "oracle,conservative,oracle", "--repeat", "1", "--backend", "software", "-q", "--json", "r.json"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err, "");
    j = test::readJson(dir / "r.json");
    ASSERT_TRUE(j.is_object());
    ASSERT_EQ(j["views"].size(), 1u);
    EXPECT_EQ(j["views"][0]["class"], "camera");
    ASSERT_EQ(j["views"][0]["methods"].size(), 2u);
    EXPECT_EQ(j["views"][0]["methods"][0]["method"], "oracle");
    EXPECT_EQ(j["views"][0]["methods"][1]["method"], "conservative");
    EXPECT_EQ(j["summary"].size(), 2u);
}

// Occlusion's record per view, and its buffers as images (--masks), written with the report.
TEST(CullCliTest, CullReportGivesTheOcclusionPassAndItsBuffers) {
    const fs::path dir = test::freshDir("CullCliMasks");
    const CliRun run =
        runFrugal(dir, {"cull-report", "builtin:dominoes", "--size", "96x72", "--views", "3", "--repeat", "2",
                        "--backend", "software", "--methods", "conservative,occlusion", "--json", "r.json",
                        "--masks", "m"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("\nocclusion: the pass ran in "), std::string::npos) << run.out;
    EXPECT_NE(run.err.find("; occlusion pass "), std::string::npos) << run.err;
    const nlohmann::json j = test::readJson(dir / "r.json");
    ASSERT_EQ(j["views"].size(), 3u);
    std::size_t hidden = 0;
    for (std::size_t v = 0; v < 3; ++v) {
        const nlohmann::json& o = j["views"][v]["occlusion"];
        ASSERT_TRUE(o.is_object()) << v;
        EXPECT_EQ(o["frames"], 2);
        EXPECT_LE(o["runs"].get<int>(), 2);
        hidden += o["triangles_hidden"].get<std::size_t>();
        const std::string image = "m/occlusion-view-" + std::to_string(v) + ".png";
        EXPECT_EQ(o["image"], image);
        Result<DecodedImage> png = readPng((dir / image).string());
        ASSERT_TRUE(png) << png.error().message;
        EXPECT_EQ(png->width, 96);
        EXPECT_EQ(png->height, 72);
        // Each view's conservative plan less what occlusion hides is what the occlusion row submits
        // when the pass runs (its last timed frame may have skipped it).
        const nlohmann::json& rows = j["views"][v]["methods"];
        EXPECT_EQ(rows[0]["method"], "conservative");
        EXPECT_EQ(rows[1]["misses"], 0);
        EXPECT_EQ(rows[1]["pixels_differing"], 0);
    }
    EXPECT_GT(hidden, 0u) << "the dominoes hide one another";
}

// --- help -----------------------------------------------------------------------------------------

TEST(CullCliTest, HelpDescribesCullReportAndTheCullOptions) {
    const fs::path dir = test::freshDir("CullCliHelp");
    const CliRun top = runFrugal(dir, {"--help"});
    EXPECT_EQ(top.status, 0);
    EXPECT_NE(top.out.find("frugal cull-report"), std::string::npos) << top.out;
    EXPECT_NE(top.out.find("run 'frugal help COMMAND'"), std::string::npos) << top.out;
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"help", "cull-report"}, std::vector<std::string>{"cull-report", "--help"},
          std::vector<std::string>{"cull-report", "-h"}}) {
        SCOPED_TRACE(test::joined(args));
        const CliRun run = runFrugal(dir, args);
        EXPECT_EQ(run.status, 0);
        EXPECT_EQ(run.err, "");
        EXPECT_EQ(run.out.rfind("usage: frugal cull-report", 0), 0u) << run.out;
        for (const char* text : {"--views", "--camera-path", "--methods", "--repeat", "--cull-bins", "--json", "--csv",
                                 "--plot", "conservative", "oracle", "misses", "--size", "--backend"})
            EXPECT_NE(run.out.find(text), std::string::npos) << text;
    }
    const CliRun render = runFrugal(dir, {"help", "render"});
    EXPECT_EQ(render.status, 0);
    for (const char* text : {"--cull METHOD", "--cull-bins", "conservative", "oracle", "cull_ms"})
        EXPECT_NE(render.out.find(text), std::string::npos) << text;
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{});
}

}  // namespace
}  // namespace frugal
