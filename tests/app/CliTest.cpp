// The `frugal` command line, end to end: the real binary in a child process (exit status, stdout,
// stderr, files left behind), over good scenes and every broken input the issue names.
#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include <frugal/Version.h>

#include "TestSupport.h"
#include "io/ImageIO.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::filesIn;
using test::readAll;
using test::runFrugal;  // the frugal binary in a child process

TEST(CliTest, HelpListsCommandsScenesAndExitCodes) {
    const fs::path dir = test::freshDir("CliHelp");
    const CliRun run = runFrugal(dir, {"--help"});
    EXPECT_EQ(run.status, 0);
    for (const char* text : {"frugal render", "frugal info", "frugal compare", "frugal diff", "frugal-lab help",
                             "builtin:dominoes", "builtin:cubes", "exit status"})
        EXPECT_NE(run.out.find(text), std::string::npos) << text;
    const CliRun render = runFrugal(dir, {"render", "--help"});
    EXPECT_EQ(render.status, 0);
    for (const char* text : {"--size", "--backend", "--frames", "--depth", "--ids", "--json", "--camera"})
        EXPECT_NE(render.out.find(text), std::string::npos) << text;
}

// The version printed is the CMake project's, and the library reports the same.
TEST(CliTest, VersionIsTheProjectVersion) {
    const fs::path dir = test::freshDir("CliVersion");
    const CliRun run = runFrugal(dir, {"--version"});
    EXPECT_EQ(run.status, 0);
    EXPECT_EQ(run.out, std::string("frugal ") + FRUGAL_PROJECT_VERSION + "\n");
    EXPECT_EQ(std::string(version()), FRUGAL_PROJECT_VERSION);
}

// frugal has the commands users run daily; frugal-lab (the research tree's) has the benchmarks and
// paper reproductions, and frugal's commands besides.
TEST(CliTest, TheResearchCommandsAreFrugalLabsOnly) {
    const fs::path dir = test::freshDir("CliLab");
    const CliRun frugal = runFrugal(dir, {"help"});
    for (const std::string& command : test::kLabCommands) {
        SCOPED_TRACE(command);
        EXPECT_EQ(frugal.out.find("  frugal " + command + " "), std::string::npos);
        const int status = std::system((std::string("'") + FRUGAL_CLI + "' " + command + " --help >/dev/null 2>&1").c_str());
        EXPECT_EQ(WEXITSTATUS(status), 2) << "frugal runs " << command;
        const CliRun lab = runFrugal(dir, {"help", command});
        EXPECT_EQ(lab.status, 0);
        EXPECT_NE(lab.out.find("usage: frugal-lab " + command), std::string::npos);
    }
    const int labStatus = std::system((std::string("'") + FRUGAL_LAB_CLI + "' help > lab-help.txt").c_str());
    EXPECT_EQ(WEXITSTATUS(labStatus), 0);
    const std::string lab = readAll("lab-help.txt");
    for (const std::string& command : test::kLabCommands) EXPECT_NE(lab.find("  frugal-lab " + command + " "), std::string::npos);
    for (const char* command : {"render", "report", "info", "compare", "diff", "cull-report", "batch"})
        EXPECT_NE(lab.find(std::string("  frugal-lab ") + command + " "), std::string::npos) << command;
    fs::remove("lab-help.txt");
}

TEST(CliTest, EveryCommandHasOneHelpTextWhicheverWayItIsAsked) {
    const fs::path dir = test::freshDir("CliHelpEach");
    for (const char* command : {"render", "report", "info", "bench", "compare", "diff", "cull-report", "reuse-bench", "hsr-bench",
                                "order-bench", "span-bench", "state-sim", "soak", "batch"}) {
        SCOPED_TRACE(command);
        const CliRun help = runFrugal(dir, {"help", command});
        const CliRun flag = runFrugal(dir, {command, "--help"});
        EXPECT_EQ(help.status, 0);
        EXPECT_EQ(flag.status, 0);
        EXPECT_EQ(help.out, flag.out);
        EXPECT_EQ(help.err, "");
        EXPECT_NE(help.out.find("usage: frugal"), std::string::npos);
        EXPECT_NE(help.out.find("exit status: 0 success"), std::string::npos);
        // Wrapped within 100 columns (characters, not UTF-8 bytes).
        std::stringstream lines(help.out);
        for (std::string line; std::getline(lines, line);)
            EXPECT_LE(std::count_if(line.begin(), line.end(), [](char c) { return (std::uint8_t(c) & 0xC0) != 0x80; }),
                      100)
                << line;
    }
    const CliRun unknown = runFrugal(dir, {"help", "wat"});
    EXPECT_EQ(unknown.status, 2);
    EXPECT_EQ(unknown.out, "");
    EXPECT_EQ(unknown.errLines().size(), 1u);
    EXPECT_EQ(unknown.err.rfind("error: help wat: no such command (commands: render, report, info, ", 0), 0u) << unknown.err;
    EXPECT_TRUE(filesIn(dir).empty());
}

TEST(CliTest, RendersTheDefaultSceneWithEveryOutput) {
    const fs::path dir = test::freshDir("CliDefault");
    const CliRun run = runFrugal(dir, {"render", "-o", "f.png", "--size", "160x120", "--depth", "d.png", "--ids", "i.png", "--json", "m.json"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"d.png", "f.png", "i.png", "m.json"}));
    Result<DecodedImage> color = readPng((dir / "f.png").string());
    ASSERT_TRUE(color) << color.error().message;
    EXPECT_EQ(color->width, 160);
    EXPECT_EQ(color->height, 120);
    // Not a blank frame: some pixels differ from the background colour (0.12,0.13,0.15 → 31,33,38).
    std::size_t lit = 0;
    for (std::size_t i = 0; i < color->pixels8.size(); i += 4)
        if (color->pixels8[i] != 31 || color->pixels8[i + 1] != 33 || color->pixels8[i + 2] != 38) ++lit;
    EXPECT_GT(lit, 160u * 120u / 4);
    const std::string json = readAll(dir / "m.json");
    for (const char* key : {"\"renderer\"", "\"llvmpipe", "\"triangles\": 1610", "\"render_ms\"", "\"camera\""})
        EXPECT_NE(json.find(key), std::string::npos) << key;
}

TEST(CliTest, SequencesAreNumbered) {
    const fs::path dir = test::freshDir("CliFrames");
    CliRun run = runFrugal(dir, {"render", "builtin:cubes?count=3", "--frames", "2:4", "--size", "32x24", "-o", "c.png", "-q"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"c_0002.png", "c_0003.png", "c_0004.png"}));
    run = runFrugal(dir, {"render", "builtin:cubes?count=3", "--frames", "0:1", "--size", "32x24", "-o", "s%03d.png", "-q"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_TRUE(fs::exists(dir / "s000.png") && fs::exists(dir / "s001.png"));
    // Animated frames differ.
    EXPECT_NE(readAll(dir / "c_0002.png"), readAll(dir / "c_0004.png"));
}

TEST(CliTest, InfoNamesWhatIsNotModelled) {
    const fs::path dir = test::freshDir("CliInfo");
    const CliRun run = runFrugal(dir, {"info", "builtin:cubes"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("triangles: 336"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("animations: 28"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("not modelled: none"), std::string::npos) << run.out;
    // The shading its meshes ask for: each distinct variant, with how many meshes use it.
    EXPECT_NE(run.out.find("shading: 1 variant\n  metallic-roughness BRDF, dielectric only: "), std::string::npos)
        << run.out;
}

TEST(CliTest, InfoListsEachShadingVariantWithItsMaps) {
    const fs::path dir = test::freshDir("CliInfoShading");
    const fs::path file = fs::path(FRUGAL_ASSIMP_GLTF2_DIR) / "ClearCoat-glTF" / "ClearCoatTest.gltf";
    if (!fs::exists(file)) FRUGAL_SKIP_IF_MISSING(file << " (assimp-testmodels)");
    const CliRun run = runFrugal(dir, {"info", file.string()});
    ASSERT_EQ(run.status, 0) << run.err;
    for (const char* line :
         {"shading: 11 variants\n", "  metallic-roughness BRDF, dielectric only, emissive map: 9 meshes\n",
          "  metallic-roughness BRDF, dielectric only, normal map (tangents generated): 4 meshes\n",
          "  metallic-roughness BRDF, dielectric only, base colour map, blended (drawn last, far to near): 1 mesh\n",
          "  metallic-roughness BRDF, dielectric only, clear coat, clear-coat roughness map: 1 mesh\n",
          "  metallic-roughness BRDF, dielectric only, normal map, clear coat, clear-coat normal map "
          "(tangents generated): 1 mesh\n",
          "  metallic-roughness BRDF, metallic-roughness map: 1 mesh\n"})
        EXPECT_NE(run.out.find(line), std::string::npos) << line << " in\n" << run.out;
    EXPECT_NE(run.out.find("512x512, linear filter, mipmaps blended, linear data\n"), std::string::npos) << run.out;
    // glTF's default material is a metal (metallic 1): drawn without the dielectric's terms.
    const fs::path metal = fs::path(FRUGAL_ASSIMP_GLTF2_DIR) / "cameras" / "Cameras.gltf";
    const CliRun metalInfo = runFrugal(dir, {"info", metal.string()});
    ASSERT_EQ(metalInfo.status, 0) << metalInfo.err;
    EXPECT_NE(metalInfo.out.find("  metallic-roughness BRDF, metal only: "), std::string::npos) << metalInfo.out;
    EXPECT_NE(run.out.find("single-sided, clear coat 1 of roughness 0.03, clear-coat normal map 5 at 1\n"),
              std::string::npos)
        << run.out;
}

struct BadCase {
    std::vector<std::string> args;
    int status;
    std::string message;  // the whole of stderr, one line
};

TEST(CliTest, BadCommandLinesAndInputsGetOneLineAndNoFile) {
    const fs::path dir = test::freshDir("CliBad");
    test::writeFile(dir / "in" / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    test::writeFile(dir / "in" / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const BadCase cases[] = {
        {{"render", "--size", "0x600"}, 2, "error: --size: '0x600' is not a size (WxH, each 1 to 65536)"},
        {{"render", "--size", "800"}, 2, "error: --size: '800' is not a size (WxH, each 1 to 65536)"},
        {{"render", "--size", "65536x65536", "-q"}, 1, "error: --size 65536x65536: egl-surfaceless cannot create a target that large (at most 16384 pixels a side)"},
        {{"render", "--backend", "vulkan"}, 2, "error: --backend: 'vulkan' is not a backend (auto, egl, egl-device, egl-surfaceless, osmesa, software)"},
        {{"render", "--frames", "5:2"}, 2, "error: --frames: '5:2' is not a frame range (A:B, first and last frame: 0 <= A <= B, at most 1000000 frames)"},
        {{"render", "--fov", "nan"}, 2, "error: --fov: 'nan' is not a number from 0.001 to 179.999"},
        {{"render", "--eye", "1,2"}, 2, "error: --eye: '1,2' is not a point (x,y,z: three finite numbers)"},
        {{"render", "-o", "x.jpg"}, 2, "error: -o x.jpg: the colour image is written as PNG; name it .png"},
        {{"render", "--wat"}, 2, "error: --wat: unknown option (see 'frugal help render')"},
        {{"render", "missing.glb"}, 1, "error: missing.glb: no such file"},
        {{"render", "builtin:cubes", "--camera", "3"}, 1, "error: builtin:cubes: camera 3: the scene has 1 camera"},
        {{"frobnicate"}, 2, "error: unknown command 'frobnicate' (commands: render, report, info, compare, diff, cull-report, batch, help)"},
        {{"info"}, 2, "error: info needs a SCENE (a file or builtin:NAME), or --state-costs"},
        {{"render", "--near", "5", "--far", "1"}, 2, "error: --far 1: must exceed --near 5"},
        // Only --near given: the library names the values, and which one it fitted.
        {{"render", "in/tri.obj", "--near", "1000"}, 1,
         "error: in/tri.obj: camera: far plane 2.88661 (fitted to the scene) must exceed the near plane 1000"},
        {{"bench", "render", "--repeat", "5x"}, 2, "error: --repeat: '5x' is not a whole number from 1 to 100000"},
        {{"bench", "render", "--warmup", "-1"}, 2, "error: --warmup: '-1' is not a whole number from 0 to 100000"},
        {{"bench", "render", "--wat"}, 2, "error: --wat: unknown option (see 'frugal-lab help bench')"},
        {{"diff", "a", "b"}, 2, "error: unexpected argument 'b' (one SCENE only)"},
        {{"compare", "a.png"}, 2, "error: compare: expected two images, A.png B.png (see 'frugal help compare')"},
        {{"info", "--wat"}, 2, "error: --wat: unknown option (see 'frugal help info')"},
    };
    for (const BadCase& c : cases) {
        std::string joined;
        for (const std::string& a : c.args) joined += a + " ";
        SCOPED_TRACE(joined);
        const CliRun run = runFrugal(dir, c.args);
        EXPECT_EQ(run.status, c.status);
        EXPECT_EQ(run.err, c.message + "\n");
        EXPECT_EQ(filesIn(dir), std::vector<std::string>{"in"}) << "no output file may be left behind";
    }
}

TEST(CliTest, OsMesaWithAMissingGalliumDriverFailsCleanly) {
    const fs::path dir = test::freshDir("CliGallium");
    const CliRun run = runFrugal(dir, {"render", "--backend", "osmesa", "-q"}, "GALLIUM_DRIVER=nosuchdriver");
    EXPECT_EQ(run.status, 3);
    ASSERT_EQ(run.errLines().size(), 1u) << run.err;
    EXPECT_EQ(run.err.rfind("error: --backend osmesa: ", 0), 0u) << run.err;
    EXPECT_NE(run.err.find("GALLIUM_DRIVER"), std::string::npos) << run.err;
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{});
}

// Every glTF 2.0 file of assimp-testmodels either renders (a PNG, nothing on stderr but warnings)
// or fails with exactly one "error: <file>: <why>" line, status 1, and no output file.
TEST(CliTest, EveryAssimpGltfFileRendersOrFailsWithOneLine) {
    const fs::path root = FRUGAL_ASSIMP_GLTF2_DIR;
    ASSERT_TRUE(fs::is_directory(root)) << root << " missing: install assimp-testmodels (scripts/install-deps --tests)";
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        const std::string ext = entry.path().extension().string();
        if (ext == ".gltf" || ext == ".glb") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    ASSERT_EQ(files.size(), 46u);
    int rendered = 0, failed = 0;
    for (const fs::path& file : files) {
        SCOPED_TRACE(file.string());
        const fs::path dir = test::freshDir("CliAssimp");
        const CliRun run = runFrugal(dir, {"render", file.string(), "--size", "64x48", "-o", "out.png", "-q"});
        if (run.status == 0) {
            ++rendered;
            EXPECT_EQ(filesIn(dir), std::vector<std::string>{"out.png"});
            for (const std::string& line : run.errLines()) EXPECT_EQ(line.rfind("warning: ", 0), 0u) << line;
        } else {
            ++failed;
            EXPECT_EQ(run.status, 1);
            ASSERT_EQ(run.errLines().size(), 1u) << run.err;
            EXPECT_EQ(run.err.rfind("error: " + file.string() + ": ", 0), 0u) << run.err;
            EXPECT_EQ(filesIn(dir), std::vector<std::string>{});
        }
    }
    std::cout << "assimp glTF 2.0 files: " << rendered << " render, " << failed << " fail with one line\n";
    EXPECT_GT(rendered, 20);
    EXPECT_GT(failed, 5);
}

}  // namespace
}  // namespace frugal
