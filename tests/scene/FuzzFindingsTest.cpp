// Every input the loader fuzzers (fuzz/, scripts/fuzz) found a problem with, minimised, in
// tests/data/fuzz/<target>/, loaded as its fuzz target loads it: each must end in the outcome listed
// here, a clean one-line error or a scene, and the list names exactly the files of those folders.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "TestSupport.h"
#include "scene/Load.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

struct Finding {
    const char* file;               // under tests/data/fuzz/: <target>/<name>
    const char* error = nullptr;    // the message, or nullptr when the input loads
    const char* warning = nullptr;  // when it loads: its one warning, or nullptr for none
};
// Messages about a file start with "<name>: " (its name as loadAsFuzzed gives it), left out here;
// a built-in spec's messages are given whole (a scene named by of= names itself).

const std::vector<Finding>& findings() {
    static const std::vector<Finding> cases = {
        // A spec's control characters went into the message verbatim (here a lone line break).
        {.file = "builtin/newline",
         .error = ": no such built-in scene (there are builtin:default, builtin:dominoes, builtin:cubes, "
                  "builtin:copies, builtin:orbit, builtin:materials)"},
        // The same through of=: the path of a file that does not exist went into the message as it was.
        {.file = "builtin/newline-in-of", .error = ": no such file"},
        // A rejected number was still converted to int (UBSan: NaN does not fit an int).
        {.file = "builtin/nan-count", .error = "materials?draws=nan: draws=nan is not a number"},
        // stb_image grew its buffer to a PNG chunk's declared length (2 GB) before reading it (found
        // as a texture in a .glb with an OOM; this file is the same problem made small by hand).
        {.file = "glb/texture-idat-claims-2gb.glb",
         .warning = "image 0 cannot be decoded (truncated PNG: chunk 1 ('IDAT') at byte 33 declares 2147483632 "
                    "bytes and a CRC, 2 bytes follow): material 0 drawn without its base colour texture"},
        // tinyobjloader's exponent parser overflowed an int (UBSan).
        {.file = "obj/exponent-of-10-digits.obj",
         .error = "line 1: a number with an exponent of 10 digits (floats end at 1e38)"},
    };
    return cases;
}

// Loads `file` as its fuzz target does; `name` is what messages about it start with: the input's
// name in a folder that does not exist, as fuzz/FuzzSupport.h has it ("" for a built-in spec).
Result<Scene> loadAsFuzzed(const fs::path& file, std::string& name) {
    const std::string target = file.parent_path().filename().string();
    const std::string bytes = test::readAll(file);
    if (target == "builtin") {
        name.clear();
        return makeBuiltin(bytes);
    }
    name = "/nonexistent-frugal-fuzz/input." + target;
    return target == "obj" ? loadObjFromMemory(bytes, name) : loadGltfFromMemory(bytes, name);
}

std::string withName(const std::string& name, const char* message) {
    return name.empty() ? message : name + ": " + message;
}

const fs::path kDir = fs::path(FRUGAL_TEST_DATA_DIR) / "fuzz";

TEST(FuzzFindingsTest, TheTableListsExactlyTheFilesOfTheSceneTargets) {
    std::set<std::string> onDisk, listed;
    for (const char* target : {"gltf", "glb", "obj", "builtin"})
        if (fs::is_directory(kDir / target))
            for (const auto& entry : fs::directory_iterator(kDir / target))
                onDisk.insert(fs::relative(entry.path(), kDir).generic_string());
    for (const Finding& finding : findings()) EXPECT_TRUE(listed.insert(finding.file).second) << finding.file;
    EXPECT_EQ(onDisk, listed);
}

class FuzzFinding : public testing::TestWithParam<Finding> {};

TEST_P(FuzzFinding, EndsInItsOutcome) {
    const Finding& finding = GetParam();
    std::string name;
    const Result<Scene> scene = loadAsFuzzed(kDir / finding.file, name);
    if (finding.error) {
        ASSERT_FALSE(scene.ok()) << finding.file << " loaded";
        EXPECT_EQ(scene.error(), withName(name, finding.error));
        return;
    }
    ASSERT_TRUE(scene.ok()) << scene.error();
    const std::vector<std::string> expected =
        finding.warning ? std::vector<std::string>{withName(name, finding.warning)} : std::vector<std::string>{};
    EXPECT_EQ(scene->warnings, expected);
}

void PrintTo(const Finding& finding, std::ostream* out) { *out << finding.file; }

INSTANTIATE_TEST_SUITE_P(Inputs, FuzzFinding, testing::ValuesIn(findings()),
                         [](const testing::TestParamInfo<Finding>& param) {
                             std::string name = param.param.file;
                             for (char& ch : name)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return name;
                         });

// Found while writing the fuzzers, which read no files: the OBJ loader's material libraries.

TEST(FuzzFindingsTest, AMaterialLibraryThatIsADeviceIsNotRead) {
    // /dev/zero never ends: reading it as a material library grew a line until memory ran out.
    const Result<Scene> scene = loadObjFromMemory("mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "in.obj");
    ASSERT_TRUE(scene.ok()) << scene.error();
    EXPECT_EQ(scene->warnings, std::vector<std::string>{"in.obj: material library '/dev/zero' is not a readable file"});
}

TEST(FuzzFindingsTest, AMaterialLibraryWithAnExponentOfTenDigitsIsNotRead) {
    const fs::path dir = test::freshDir("FuzzFindingsMtlExponent");
    test::writeFile(dir / "m.mtl", "newmtl red\nKd 1 0 0\nNs 1e2147483648\n");
    test::writeFile(dir / "in.obj", "mtllib m.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const Result<Scene> scene = loadObj((dir / "in.obj").string());
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_FALSE(scene->warnings.empty());
    EXPECT_EQ(scene->warnings[0], (dir / "in.obj").string() +
                                      ": material library 'm.mtl' not read: line 3: a number with an exponent of 10 "
                                      "digits (floats end at 1e38)");
}

}  // namespace
}  // namespace frugal
