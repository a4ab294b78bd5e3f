// KHR_lights_punctual through the command line (the real binary): a floor under a spot light is lit
// by the spot (and the environment) instead of the default light, GL and the software reference
// agree on it (frugal diff), and frugal info names the light; a scene without lights says it gets
// the default one.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "CliSupport.h"
#include "TestSupport.h"
#include "io/ImageIO.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::readAll;
using test::runFrugal;

// A 4×4 floor at y = 0 and, 2 above its centre, a spot light pointing down (node −Z turned to −Y);
// `lit` false leaves the node (and so the light) out of the scene.
std::string floorUnderSpot(bool lit) {
    return std::string(R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": )") +
           (lit ? "[0, 1]" : "[0]") + R"(}],
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [{"type": "spot", "name": "beam", "intensity": 30,
    "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.5}}]}},
  "nodes": [{"mesh": 0}, {"name": "lamp", "translation": [0, 2, 0], "rotation": [-0.7071068, 0, 0, 0.7071068],
    "extensions": {"KHR_lights_punctual": {"light": 0}}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"byteLength": 60, "uri":
    "data:application/octet-stream;base64,AAAAwAAAAAAAAADAAAAAQAAAAAAAAADAAAAAQAAAAAAAAABAAAAAwAAAAAAAAABAAAACAAEAAAADAAIA"}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-2, 0, -2],
    "max": [2, 0, 2]}, {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
}

TEST(LightsCliTest, ASpotLightLightsTheFloorAlikeOnBothBackends) {
    const fs::path dir = test::freshDir("LightsCli");
    test::writeFile(dir / "spot.gltf", floorUnderSpot(true));
    test::writeFile(dir / "dark.gltf", floorUnderSpot(false));
    const std::vector<std::string> view = {"--size", "160x120", "--eye", "0,4,4", "--target", "0,0,0", "-q"};
    const auto run = [&](std::vector<std::string> args) {
        args.insert(args.end(), view.begin(), view.end());
        const CliRun r = runFrugal(dir, args);
        EXPECT_EQ(r.status, 0) << test::joined(args) << ": " << r.out << r.err;
        return r;
    };
    run({"render", "spot.gltf", "-o", "spot.png"});
    run({"render", "dark.gltf", "-o", "dark.png"});
    EXPECT_NE(readAll(dir / "spot.png"), readAll(dir / "dark.png")) << "the spot replaces the default light";
    run({"diff", "spot.gltf", "--tolerance", "1", "--out", "diff"});

    const CliRun info = runFrugal(dir, {"info", "spot.gltf"});
    ASSERT_EQ(info.status, 0) << info.err;
    EXPECT_NE(info.out.find("lights: 1\n  'beam' spot on node 'lamp', colour 1,1,1 x 30 cd, range unbounded, cone "
                            "5.72958 to 28.6479 deg\n"),
              std::string::npos)
        << info.out;
    EXPECT_NE(info.out.find("not modelled: none"), std::string::npos) << info.out;
    const CliRun dark = runFrugal(dir, {"info", "dark.gltf"});
    EXPECT_NE(dark.out.find("lights: 0 (the default directional light)\n"), std::string::npos) << dark.out;
}

}  // namespace
}  // namespace frugal

namespace frugal {
namespace {

// --light and --environment: without the default light the lit pixels darken and the background
// stays; a brighter environment brightens them; no light and no environment leaves a scene without
// emission black; a file's own lights shine with --light none; GL and the software reference agree
// under each; bad values are one line.
TEST(LightsCliTest, TheDefaultLightAndTheEnvironmentAreSettings) {
    const fs::path dir = test::freshDir("LightSettingsCli");
    const auto render = [&](const std::string& name, const std::string& scene, std::vector<std::string> extra) {
        std::vector<std::string> args = {"render", scene, "--size", "120x90", "--background", "0,0,0"};
        args.insert(args.end(), extra.begin(), extra.end());
        return test::renderedPixels(dir, name, args);
    };
    // Sums of the rgb of the pixels that are not background, and how many there are.
    const auto lit = [](const std::vector<std::uint8_t>& p) {
        std::pair<std::uint64_t, std::uint64_t> sum{0, 0};
        for (std::size_t i = 0; i < p.size(); i += 4)
            if (p[i] || p[i + 1] || p[i + 2]) sum.first += p[i] + p[i + 1] + p[i + 2], ++sum.second;
        return sum;
    };
    const auto plain = lit(render("plain", "builtin:cubes", {}));
    render("given", "builtin:cubes", {"--light", "default", "--environment", "0.3"});
    EXPECT_EQ(readAll(dir / "plain.png"), readAll(dir / "given.png")) << "the defaults are today's light";
    const auto noLight = lit(render("no-light", "builtin:cubes", {"--light", "none"}));
    const auto bright = lit(render("bright", "builtin:cubes", {"--environment", "1.2"}));
    EXPECT_GT(plain.second, 1000u);
    EXPECT_LT(noLight.first, plain.first * 3 / 4);
    EXPECT_GT(bright.first, plain.first * 5 / 4);
    EXPECT_EQ(lit(render("dark", "builtin:cubes", {"--light", "none", "--environment", "0"})).second, 0u)
        << "nothing lights the cubes";
    // A file's own light still shines without the default light.
    const fs::path spot = dir / "spot.gltf";
    test::writeFile(spot, floorUnderSpot(true));
    const auto spotLit = lit(render("spot", spot.string(), {"--light", "none", "--environment", "0"}));
    EXPECT_GT(spotLit.second, 100u);
    for (const std::vector<std::string>& extra : {std::vector<std::string>{"--light", "none"},
                                                  {"--environment", "2.5"},
                                                  {"--light", "none", "--environment", "0"}}) {
        std::vector<std::string> args = {"diff", "builtin:materials", "--size", "120x90", "--tolerance", "1"};
        args.insert(args.end(), extra.begin(), extra.end());
        const CliRun diff = runFrugal(dir, args);
        EXPECT_EQ(diff.status, 0) << test::joined(args) << ": " << diff.out << diff.err;
    }
    test::expectOneErrorLine(
        test::freshDir("LightSettingsCliBad"),
        {{{"render", "--light", "sun"}, "error: --light: 'sun' is not a light (default, none)"},
         {{"render", "--environment", "-1"}, "error: --environment: '-1' is not a number from 0 to 1000000"},
         {{"render", "--environment", "nan"}, "error: --environment: 'nan' is not a number from 0 to 1000000"},
         {{"render", "--environment", "bright"}, "error: --environment: 'bright' is not a number from 0 to 1000000"}});
}

}  // namespace
}  // namespace frugal

namespace frugal {
namespace {

// builtin:materials at 160x120 with `extra`, into DIR/NAME.png and its ids into DIR/NAME-ids.png:
// the colour's bytes.
std::vector<std::uint8_t> renderMaterials(const fs::path& dir, const std::string& name,
                                          const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"render", "builtin:materials", "--size", "160x120", "--ids", name + "-ids.png"};
    args.insert(args.end(), extra.begin(), extra.end());
    return test::renderedPixels(dir, name, args);
}

// --shading lambert: the diffuse approximation. It changes the lit pixels of a scene of every kind
// of material (specular highlights and maps gone), leaves unlit pixels and the background alone,
// and GL and the software reference agree on it.
TEST(LightsCliTest, LambertShadingIsTheDiffuseTermAlone) {
    const fs::path dir = test::freshDir("ShadingCli");
    const auto render = [&dir](const std::string& name, const std::vector<std::string>& extra) {
        return renderMaterials(dir, name, extra);
    };
    const std::vector<std::uint8_t> full = render("full", {});
    render("full-given", {"--shading", "full"});
    EXPECT_EQ(readAll(dir / "full.png"), readAll(dir / "full-given.png"));
    const std::vector<std::uint8_t> lambert = render("lambert", {"--shading", "lambert"});
    ASSERT_EQ(full.size(), lambert.size());
    std::size_t changed = 0;
    for (std::size_t i = 0; i < full.size(); i += 4) changed += full[i] != lambert[i] || full[i + 1] != lambert[i + 1];
    EXPECT_GT(changed, full.size() / 4 / 10);
    EXPECT_EQ(readAll(dir / "full-ids.png"), readAll(dir / "lambert-ids.png")) << "the same triangles";
    const CliRun diff =
        runFrugal(dir, {"diff", "builtin:materials", "--size", "160x120", "--shading", "lambert", "--tolerance", "1"});
    EXPECT_EQ(diff.status, 0) << diff.out << diff.err;
    test::expectOneErrorLine(test::freshDir("ShadingCliBad"), {{{"render", "--shading", "phong"},
                                                                "error: --shading: 'phong' is not a shading model "
                                                                "(full, lambert)"}});
}

// --no-environment-specular: the environment lights the diffuse lobe alone. It darkens the lit
// pixels of every material that reflects it (the metals most), keeps the triangles, agrees between
// GL and the software reference, and has nothing to leave out without an environment or under
// the Lambert model.
TEST(LightsCliTest, NoEnvironmentSpecularKeepsTheDiffuseLobe) {
    const fs::path dir = test::freshDir("EnvironmentSpecularCli");
    const auto render = [&dir](const std::string& name, const std::vector<std::string>& extra) {
        return renderMaterials(dir, name, extra);
    };
    const std::vector<std::uint8_t> full = render("full", {});
    const std::vector<std::uint8_t> diffuse = render("diffuse", {"--no-environment-specular"});
    ASSERT_EQ(full.size(), diffuse.size());
    std::size_t darker = 0, brighter = 0;
    for (std::size_t i = 0; i < full.size(); i += 4) {
        const int before = full[i] + full[i + 1] + full[i + 2], after = diffuse[i] + diffuse[i + 1] + diffuse[i + 2];
        darker += after < before;
        brighter += after > before;
    }
    EXPECT_GT(darker, full.size() / 4 / 10);
    EXPECT_EQ(brighter, 0u) << "leaving out light never brightens";
    EXPECT_EQ(readAll(dir / "full-ids.png"), readAll(dir / "diffuse-ids.png")) << "the same triangles";

    render("lambert", {"--shading", "lambert"});
    render("lambert-diffuse", {"--shading", "lambert", "--no-environment-specular"});
    EXPECT_EQ(readAll(dir / "lambert.png"), readAll(dir / "lambert-diffuse.png")) << "Lambert has no such term";
    render("dark", {"--environment", "0", "--backend", "software"});
    render("dark-diffuse", {"--environment", "0", "--backend", "software", "--no-environment-specular"});
    EXPECT_EQ(readAll(dir / "dark.png"), readAll(dir / "dark-diffuse.png")) << "no environment, nothing to leave out";

    const CliRun diff = runFrugal(
        dir, {"diff", "builtin:materials", "--size", "160x120", "--no-environment-specular", "--tolerance", "1"});
    EXPECT_EQ(diff.status, 0) << diff.out << diff.err;
}

// --environment-map FILE.hdr: the map lights instead of the uniform environment. A uniform map of
// radiance 0.25 draws what --environment 0.25 draws (within the prefilter's float sums: one level);
// a sky changes the lit pixels; GL and the software reference agree; a file that cannot be read,
// or another uniform radiance beside a map, is one error line.
TEST(LightsCliTest, AnEnvironmentMapLightsInsteadOfTheUniformEnvironment) {
    const fs::path dir = test::freshDir("EnvironmentMapCli");
    test::writeFile(dir / "uniform.hdr", test::radianceFile(64, 32, std::vector<float>(64 * 32 * 3, 0.25f)));
    test::writeFile(dir / "sky.hdr", test::radianceFile(128, 64, test::testSky(128, 64)));
    const std::vector<std::string> base = {"render", "builtin:materials", "--size", "160x120"};
    const auto render = [&](const std::string& name, std::vector<std::string> extra) {
        std::vector<std::string> args = base;
        args.insert(args.end(), extra.begin(), extra.end());
        return test::renderedPixels(dir, name, args);
    };
    for (const char* backend : {"auto", "software"}) {
        const std::string b = backend;
        const std::vector<std::uint8_t> uniform = render("uniform-" + b, {"--environment", "0.25", "--backend", b});
        const std::vector<std::uint8_t> mapped =
            render("mapped-" + b, {"--environment-map", (dir / "uniform.hdr").string(), "--backend", b});
        ASSERT_EQ(uniform.size(), mapped.size());
        int worst = 0;
        for (std::size_t i = 0; i < uniform.size(); ++i)
            worst = std::max(worst, std::abs(int(uniform[i]) - int(mapped[i])));
        EXPECT_LE(worst, 1) << backend;
        const std::vector<std::uint8_t> sky =
            render("sky-" + b, {"--environment-map", (dir / "sky.hdr").string(), "--backend", b});
        std::size_t changed = 0;
        for (std::size_t i = 0; i < sky.size(); i += 4) changed += sky[i] != mapped[i] || sky[i + 2] != mapped[i + 2];
        EXPECT_GT(changed, sky.size() / 4 / 10) << backend;
    }
    const CliRun diff = runFrugal(dir, {"diff", "builtin:materials", "--size", "160x120", "--environment-map",
                                        (dir / "sky.hdr").string(), "--tolerance", "1"});
    EXPECT_EQ(diff.status, 0) << diff.out << diff.err;
    const CliRun run = runFrugal(dir, {"render", "builtin:cubes", "--size", "32x24", "--environment-map",
                                       (dir / "sky.hdr").string(), "-o", "x.png"});
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.err.find("environment-map " + (dir / "sky.hdr").string() + ": 128x64, read and prefiltered in "),
              std::string::npos)
        << run.err;

    test::writeFile(dir / "broken.hdr", "#?RADIANCE\n\n-Y 2 +X 2\nab");
    test::expectOneErrorLine(
        test::freshDir("EnvironmentMapCliBad"),
        {{{"render", "builtin:cubes", "--environment-map", (dir / "none.hdr").string()},
          "error: --environment-map " + (dir / "none.hdr").string() + ": cannot open it (No such file or directory)",
          1},
         {{"render", "builtin:cubes", "--environment-map", (dir / "broken.hdr").string()},
          "error: --environment-map " + (dir / "broken.hdr").string() + ": the data ends in scan line 0",
          1},
         {{"render", "builtin:cubes", "--environment-map", (dir / "sky.hdr").string(), "--environment", "1"},
          "error: --environment 1 with --environment-map " + (dir / "sky.hdr").string() +
              ": a map gives the environment's radiance itself"}});
}

// The research harnesses shade their frames with the settings too: bench render times the frame
// the settings ask for (its minimal program draws the same variant, tests/gl/MinimalFrameGLTest).
TEST(LightsCliTest, BenchRenderTimesTheShadingAsked) {
    const fs::path dir = test::freshDir("ShadingBench");
    const CliRun run = runFrugal(dir, {"bench", "render", "builtin:cubes", "--size", "32x24", "--backend", "software",
                                       "--repeat", "2", "--warmup", "0", "--shading", "lambert", "--tonemap", "aces", "-q"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("\"shading\": \"lambert\""), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("\"tonemap\": \"aces\""), std::string::npos) << run.out;
}

}  // namespace
}  // namespace frugal
