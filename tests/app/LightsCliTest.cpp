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
