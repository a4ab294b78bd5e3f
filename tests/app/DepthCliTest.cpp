// A file's camera and the depth buffer through the command line (the real binary): the image sized
// to the camera's aspect ratio and the warning when --size differs from it; the planes and the
// format in the render JSON and in the depth PNG's text; --depth-range and --depth-format refused
// with one line when wrong; culling, reuse, the hidden-surface modes and the id pass giving the same
// bytes in d32f as the plain d32f render; `frugal info` printing what each format separates.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "CliSupport.h"
#include "JsonSupport.h"
#include "TestSupport.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::readAll;
using test::runFrugal;

std::string enginePath() {
    return std::string(FRUGAL_ASSIMP_GLTF2_DIR) + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
}

// The PNG's tEXt chunks, keyword → text (no CRC check: the encoder's own output).
std::vector<std::pair<std::string, std::string>> pngText(const std::string& png) {
    std::vector<std::pair<std::string, std::string>> out;
    std::size_t at = 8;
    while (at + 8 <= png.size()) {
        const auto byte = [&](std::size_t i) { return std::uint32_t(static_cast<unsigned char>(png[i])); };
        const std::uint32_t length = byte(at) << 24 | byte(at + 1) << 16 | byte(at + 2) << 8 | byte(at + 3);
        const std::string type = png.substr(at + 4, 4);
        if (type == "tEXt") {
            const std::string data = png.substr(at + 8, length);
            const std::size_t zero = data.find('\0');
            out.emplace_back(data.substr(0, zero), data.substr(zero + 1));
        }
        at += 12 + length;
    }
    return out;
}

TEST(DepthCliTest, AFilesCameraSizesTheImageAndSaysWhenSizeDiffers) {
    const fs::path dir = test::freshDir("DepthCliAspect");
    const CliRun sized = runFrugal(dir, {"render", enginePath(), "-o", "a.png", "--json", "a.json", "-q"});
    ASSERT_EQ(sized.status, 0) << sized.err;
    EXPECT_EQ(sized.err, "") << "no warning when the image takes the camera's aspect ratio";
    const nlohmann::json a = test::readJson(dir / "a.json");
    EXPECT_EQ(a["size"], nlohmann::json::array({800, 800}));  // aspectRatio 1, the longer side 800
    EXPECT_EQ(a["camera"]["aspect_ratio"], 1.0);
    EXPECT_EQ(a["camera"]["file_aspect_ratio"], 1.0);
    EXPECT_EQ(a["camera"]["aspect_ratio_differs"], false);

    const CliRun wide =
        runFrugal(dir, {"render", enginePath(), "--size", "320x180", "-o", "b.png", "--json", "b.json", "-q"});
    ASSERT_EQ(wide.status, 0) << wide.err;
    ASSERT_EQ(wide.errLines().size(), 1u) << wide.err;
    EXPECT_EQ(wide.errLines()[0], "warning: " + enginePath() +
                                      ": camera 0 has aspect ratio 1, the image 1.77778 (320x180): drawn with the "
                                      "camera's vertical field of view and the image's aspect ratio, not stretched");
    const nlohmann::json b = test::readJson(dir / "b.json");
    EXPECT_NEAR(b["camera"]["aspect_ratio"].get<double>(), 16.0 / 9.0, 1e-6);
    EXPECT_EQ(b["camera"]["aspect_ratio_differs"], true);

    // A scene whose camera leaves the ratio to the image: 800x600, no warning, null.
    const CliRun builtin = runFrugal(dir, {"render", "builtin:cubes", "-o", "c.png", "--json", "c.json", "-q"});
    ASSERT_EQ(builtin.status, 0) << builtin.err;
    EXPECT_EQ(builtin.err, "");
    const nlohmann::json c = test::readJson(dir / "c.json");
    EXPECT_EQ(c["size"], nlohmann::json::array({800, 600}));
    EXPECT_TRUE(c["camera"]["file_aspect_ratio"].is_null());
}

TEST(DepthCliTest, ThePlanesAndTheFormatAreInTheJsonAndTheDepthPng) {
    const fs::path dir = test::freshDir("DepthCliPlanes");
    for (const std::string range : {"fit", "file"})
        for (const std::string format : {"d24", "d32f"}) {
            SCOPED_TRACE(range + " " + format);
            const std::string tag = range + "-" + format;
            const CliRun run =
                runFrugal(dir, {"render", enginePath(), "--size", "160x160", "--depth-range", range, "--depth-format",
                                format, "-o", tag + ".png", "--depth", tag + "-d.png", "--json", tag + ".json", "-q"});
            ASSERT_EQ(run.status, 0) << run.err;
            const nlohmann::json camera = test::readJson(dir / (tag + ".json"))["camera"];
            EXPECT_EQ(camera["depth_range"], range);
            EXPECT_EQ(camera["depth_format"], format);
            EXPECT_NEAR(camera["given_znear"].get<double>(), 0.05, 1e-7);
            EXPECT_EQ(camera["given_zfar"], 1e6);
            if (range == "file") {
                EXPECT_EQ(camera["znear"], camera["given_znear"]);
                EXPECT_EQ(camera["zfar"], camera["given_zfar"]);
            } else {  // the engine lies 1,200 to 2,000 units away
                EXPECT_GT(camera["znear"].get<double>(), 1000.0);
                EXPECT_LT(camera["zfar"].get<double>(), 2100.0);
            }
            const auto text = pngText(readAll(dir / (tag + "-d.png")));
            ASSERT_EQ(text.size(), 5u);
            EXPECT_EQ(text[0].first, "depth_format");
            EXPECT_EQ(text[0].second, format);
            EXPECT_EQ(text[1].first, "depth_znear");
            EXPECT_NEAR(std::stod(text[1].second), camera["znear"].get<double>(), 1e-3);
            EXPECT_EQ(text[2].first, "depth_zfar");
            EXPECT_NEAR(std::stod(text[2].second), camera["zfar"].get<double>(), 1e-3 * camera["zfar"].get<double>());
            EXPECT_EQ(text[3].first, "depth_projection");
            EXPECT_EQ(text[3].second, "perspective");
            EXPECT_EQ(text[4].first, "depth_encoding");
        }
}

TEST(DepthCliTest, BadDepthOptionsAreOneLine) {
    const fs::path dir = test::freshDir("DepthCliBad");
    test::expectOneErrorLine(
        dir,
        {
            {{"render", "--depth-format", "d16"}, "error: --depth-format: 'd16' is not a depth format (d24, d32f)"},
            {{"render", "--depth-range", "tight"}, "error: --depth-range: 'tight' is not a depth range (fit, file)"},
            {{"render", "--depth-format"}, "error: --depth-format: missing value"},
            {{"render", "--backend", "software", "--interp", "span", "--depth-format", "d32f"},
             "error: --interp span with --depth-format d32f: the span engine interpolates a 24-bit depth"},
        });
}

// Every shortcut keeps its promise in d32f too: culling that never misses, reuse and adaptive give
// the plain d32f render's bytes (colour, ids, float depth); the software reference equals llvmpipe.
TEST(DepthCliTest, ShortcutsKeepTheirBytesInD32f) {
    const fs::path dir = test::freshDir("DepthCliShortcuts");
    const std::vector<std::string> common = {"--depth-format", "d32f", "--size", "96x72", "-q"};
    const auto render = [&](const std::string& tag, const std::string& scene, std::vector<std::string> extra) {
        std::vector<std::string> args = {"render", scene,          "-o",      tag + ".png",
                                         "--ids",  tag + "-i.png", "--depth", tag + "-d.pfm"};
        args.insert(args.end(), common.begin(), common.end());
        args.insert(args.end(), extra.begin(), extra.end());
        const CliRun run = runFrugal(dir, args);
        EXPECT_EQ(run.status, 0) << test::joined(args) << ": " << run.err;
    };
    const auto expectSame = [&](const std::string& a, const std::string& b) {
        for (const std::string suffix : {".png", "-i.png", "-d.pfm"}) {
            const std::string x = readAll(dir / (a + suffix)), y = readAll(dir / (b + suffix));
            EXPECT_FALSE(x.empty()) << a << suffix;
            EXPECT_TRUE(x == y) << a << suffix << " differs from " << b << suffix;
        }
    };
    const std::string bunny = FRUGAL_BUNNY_OBJ;
    render("bunny", bunny, {});
    render("bunny-conservative", bunny, {"--cull", "conservative"});
    render("bunny-sphere", bunny, {"--cull", "sphere"});
    expectSame("bunny-conservative", "bunny");
    expectSame("bunny-sphere", "bunny");
    render("cubes", "builtin:cubes", {"--time", "0.4"});
    render("cubes-adaptive", "builtin:cubes", {"--time", "0.4", "--hsr", "adaptive"});
    render("cubes-software", "builtin:cubes", {"--time", "0.4", "--backend", "software"});
    expectSame("cubes-adaptive", "cubes");
    expectSame("cubes-software", "cubes");
    // Reuse over a sequence: every frame's files equal the plain render's.
    for (const std::string tag : {"dominoes", "dominoes-reuse"}) {
        std::vector<std::string> args = {"render",  "builtin:dominoes", "--frames", "0:5",
                                         "-o",      tag + "_%d.png",    "--ids",    tag + "_%d-i.png",
                                         "--depth", tag + "_%d-d.pfm"};
        args.insert(args.end(), common.begin(), common.end());
        if (tag == "dominoes-reuse") args.push_back("--reuse");
        const CliRun run = runFrugal(dir, args);
        ASSERT_EQ(run.status, 0) << run.err;
    }
    for (int frame = 0; frame <= 5; ++frame)
        expectSame("dominoes-reuse_" + std::to_string(frame), "dominoes_" + std::to_string(frame));
}

TEST(DepthCliTest, InfoSaysWhatEachFormatSeparates) {
    const fs::path dir = test::freshDir("DepthCliInfo");
    const CliRun run = runFrugal(dir, {"info", enginePath()});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("detail: 1 % of the triangle edges are shorter than "), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("along the view (its bounds over the whole animation)"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("      d24   fit "), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("      d32f  fit "), std::string::npos) << run.out;
    // The file's planes leave d24 steps of whole units at the engine: coarser than its detail.
    EXPECT_NE(run.out.find("warning: coarser than the scene's detail"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("d24 with file"), std::string::npos) << run.out;
    EXPECT_EQ(run.out.find("d24 with fit"), std::string::npos) << run.out;
    EXPECT_EQ(run.out.find("d32f with"), std::string::npos) << run.out;
    // A scene without a camera: the automatic view.
    const CliRun cubes = runFrugal(dir, {"info", FRUGAL_BUNNY_OBJ});
    ASSERT_EQ(cubes.status, 0) << cubes.err;
    EXPECT_NE(cubes.out.find("the automatic view (no camera in the scene):"), std::string::npos) << cubes.out;
}

}  // namespace
}  // namespace frugal
