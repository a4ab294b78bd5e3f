// --no-mipmaps through the command line (the real binary): a file whose minified texture asks for
// mipmaps draws otherwise without them (base level only), GL and the software reference agree on
// it, a scene without mipmapped textures is the same image byte for byte, and frugal report weighs
// it as a shading trade where the scene has mipmaps.
#include <filesystem>
#include <set>
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
using test::readAll;
using test::runFrugal;

const std::string kBoxTextured = std::string(FRUGAL_ASSIMP_GLTF2_DIR) + "/BoxTextured-glTF/BoxTextured.gltf";

TEST(MipmapsCliTest, NoMipmapsSamplesTheBaseLevel) {
    const fs::path dir = test::freshDir("MipmapsCli");
    // Small enough that the box's 256x256 texture is minified on every face.
    const std::vector<std::string> box = {"render", kBoxTextured, "--size", "64x48"};
    const auto with = [&](std::vector<std::string> args, const std::vector<std::string>& extra) {
        args.insert(args.end(), extra.begin(), extra.end());
        return args;
    };
    const std::vector<std::uint8_t> mipmapped = test::renderedPixels(dir, "mipmapped", box);
    const std::vector<std::uint8_t> base = test::renderedPixels(dir, "base", with(box, {"--no-mipmaps"}));
    ASSERT_EQ(base.size(), mipmapped.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < base.size(); i += 4)
        differing += base[i] != mipmapped[i] || base[i + 1] != mipmapped[i + 1];
    EXPECT_GT(differing, 50u) << "the minified texture aliases without its mipmaps";
    const CliRun diff = runFrugal(dir, {"diff", kBoxTextured, "--size", "64x48", "--no-mipmaps", "--tolerance", "1"});
    EXPECT_EQ(diff.status, 0) << diff.out << diff.err;

    test::renderedPixels(dir, "plain", {"render", "builtin:materials", "--size", "96x72"});
    test::renderedPixels(dir, "plain-no-mipmaps", {"render", "builtin:materials", "--size", "96x72", "--no-mipmaps"});
    EXPECT_EQ(readAll(dir / "plain.png"), readAll(dir / "plain-no-mipmaps.png")) << "nothing to leave out";

    const CliRun report = runFrugal(
        dir, {"report", kBoxTextured, "--views", "1", "--size", "64x48", "--repeat", "1", "-o", "report", "-q"});
    ASSERT_EQ(report.status, 0) << report.err;
    const nlohmann::json rows = test::readJson(dir / "report" / "report.json")["rows"];
    std::set<std::string> names;
    for (const nlohmann::json& r : rows) names.insert(r["name"].get<std::string>());
    EXPECT_TRUE(names.count("no mipmaps"));
    EXPECT_TRUE(names.count("shading lambert"));
}

}  // namespace
}  // namespace frugal
