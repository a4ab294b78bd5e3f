// Every command that loads a scene gets render's treatment (issue 11): a broken scene file, an
// impossible built-in, an impossible shared option each give one error line, its exit status, no
// output on stdout and no file written, before any work starts. The commands' own options are
// covered in their suites (CullCliTest, ReuseBenchCliTest, HsrCliTest, OrderCliTest, ...).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "CliSupport.h"
#include "TestSupport.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::FailingRun;

// Each command with the outputs it can write, so that "no file written" means something.
struct SceneCommand {
    std::vector<std::string> args;
};
const SceneCommand kCommands[] = {
    {{"render", "-o", "out.png", "--json", "r.json"}},
    {{"bench", "render", "--repeat", "1"}},
    {{"diff", "--out", "d"}},
    {{"cull-report", "--json", "r.json", "--csv", "r.csv"}},
    {{"reuse-bench", "--frames", "0:1", "--json", "r.json", "--csv", "r.csv"}},
    {{"hsr-bench", "--frames", "0:1", "--json", "r.json", "--csv", "r.csv"}},
    {{"order-bench", "--repeat", "1", "--json", "r.json", "--csv", "r.csv"}},
};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

TEST(MisuseCliTest, EveryCommandRefusesABrokenSceneWithOneLine) {
    const fs::path in = test::freshDir("MisuseInputs");
    test::writeFile(in / "broken.obj", "v 1 2 3\nf 1 2 3\n");
    test::writeFile(in / "trunc.glb", std::string("glTF\x02\x00\x00\x00", 8));
    test::writeFile(in / "empty.gltf", "");
    test::writeFile(in / "huge.gltf", R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":1e30}]})");
    fs::create_directories(in / "folder.gltf");
    const std::string dir = in.string() + "/";
    const std::vector<std::pair<std::string, std::string>> scenes = {
        {dir + "missing.gltf", "no such file"},
        {dir + "broken.obj", "shape 0 face 1: position index 2 out of range, the file has 1 positions"},
        {dir + "trunc.glb", "truncated GLB: 8 bytes, the header alone needs 12"},
        {dir + "empty.gltf", "file is empty"},
        {dir + "huge.gltf", "buffers[0].byteLength: expected a non-negative integer, got 1e+30"},
        {dir + "folder.gltf", "is a directory, not a file"},
        {"builtin:cubes?count=-1", "count=-1 is out of range [1, 1e+06]"},
        {"builtin:materials?draws=1e12", "draws=1e12 is out of range [1, 1e+06]"},
    };
    std::vector<FailingRun> runs;
    for (const SceneCommand& command : kCommands)
        for (const auto& [scene, why] : scenes)
            runs.push_back({with(command.args, {scene, "--size", "32x24", "-q"}), "error: " + scene + ": " + why, 1});
    test::expectOneErrorLine(test::freshDir("MisuseScenes"), runs);
}

TEST(MisuseCliTest, EveryCommandRefusesAnImpossibleSharedOptionWithOneLine) {
    const std::vector<std::pair<std::vector<std::string>, std::string>> options = {
        {{"--size", "0x0"}, "error: --size: '0x0' is not a size (WxH, each 1 to 65536)"},
        {{"--size", "70000x10"}, "error: --size: '70000x10' is not a size (WxH, each 1 to 65536)"},
        {{"--backend", "nope"},
         "error: --backend: 'nope' is not a backend (auto, egl, egl-device, egl-surfaceless, osmesa, software)"},
        {{"--time", "nan"}, "error: --time: 'nan' is not a number from -1e+09 to 1e+09"},
        {{"--threads", "-1"}, "error: --threads: '-1' is not a whole number from 0 to 256"},
        {{"--fov", "180"}, "error: --fov: '180' is not a number from 0.001 to 179.999"},
        {{"--eye", "0,0,nan"}, "error: --eye: '0,0,nan' is not a point (x,y,z: three finite numbers)"},
        {{"--background", "red"}, "error: --background: 'red' is not a colour (r,g,b or r,g,b,a, each 0 to 1)"},
        {{"--bogus"}, ""},  // names the command's help: any one error line
    };
    std::vector<FailingRun> runs;
    for (const SceneCommand& command : kCommands)
        for (const auto& [option, line] : options) runs.push_back({with(with(command.args, {"-q"}), option), line, 2});
    test::expectOneErrorLine(test::freshDir("MisuseOptions"), runs);
}

}  // namespace
}  // namespace frugal
