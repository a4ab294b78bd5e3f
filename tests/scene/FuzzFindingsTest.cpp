// Every input the loader fuzzers (fuzz/, scripts/fuzz) found a problem with, minimised (or made small
// by hand), and inputs made by hand for the checks those findings led to, in tests/data/fuzz/<target>/,
// loaded as its fuzz target loads it: each must end in the outcome listed here, a clean one-line error
// or a scene, and the list names exactly the files of those folders (docs/fuzz/README.md tells them).
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <cstring>
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
        // Made by hand for the checks that finding led to: a JPEG texture declaring a size over the limit
        // (stb would allocate 1.2 GB before finding no data), and a GIF, which stb reads and glTF forbids.
        {.file = "glb/texture-jpeg-beyond-limit.glb",
         .warning = "image 0 cannot be decoded (JPEG of 20000x20000 pixels, more than frugal's limit of 268435456 "
                    "(16384x16384)): material 0 drawn without its base colour texture"},
        // fuzz_glb (scripts/test, 2026-12-05): a JPEG of 8270x20000 pixels in 800 bytes; stb_image
        // decoded it as if zero bits followed, 165 MB of pixels, 50 s under the fuzzer's sanitizers.
        {.file = "glb/texture-jpeg-beyond-data.glb",
         .warning = "image 0 cannot be decoded (corrupt JPEG: 8270x20000 pixels need at least 323047 bytes of coded "
                    "data (a bit per 8x8 block), 2 bytes follow its frame header): material 0 drawn without its base "
                    "colour texture"},
        {.file = "glb/texture-gif.glb",
         .warning = "image 0 cannot be decoded (neither PNG nor JPEG, the formats glTF 2.0 allows): material 0 drawn "
                    "without its base colour texture"},
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
        EXPECT_EQ(scene.error().message, withName(name, finding.error));
        return;
    }
    ASSERT_TRUE(scene.ok()) << scene.error().message;
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

// Found while writing fuzz_builtin, by measuring what the largest parameters ask for: a spec of a few
// characters could ask for 10^12 animation keys, or build for minutes.
TEST(FuzzFindingsTest, BuiltinScenesOverTheBudgetAreRefusedWithTheirNumbers) {
    const std::pair<const char*, const char*> cases[] = {
        {"builtin:dominoes?polygons=6e6&static=0",
         "builtin:dominoes?polygons=6e6&static=0: 1000000 dominoes falling over 1000000 frames each need 1e+12 "
         "animation keys, more than frugal's limit of 67108864"},
        {"builtin:cubes?count=3000&seconds=3600",
         "builtin:cubes?count=3000&seconds=3600: 3000 cubes turning for 3600 s need 8.6403e+07 animation keys, more "
         "than frugal's limit of 67108864"},
        {"builtin:cubes?count=1000000&seconds=1",
         "builtin:cubes?count=1000000&seconds=1: 1000000 cubes turning for 1 s need 2e+06 nodes and meshes, more "
         "than frugal's limit of 131072"},
        {"builtin:materials?draws=1000000",
         "builtin:materials?draws=1000000: 1000000 draws of 40 meshes need 1.00004e+06 nodes and meshes, more than "
         "frugal's limit of 131072"},
        {"builtin:copies?count=1000&of=builtin:cubes?count=200",
         "builtin:copies?count=1000&of=builtin:cubes?count=200: 1000 copies of a scene of 201 nodes need 202200 "
         "nodes and meshes, more than frugal's limit of 131072"},
    };
    for (const auto& [spec, error] : cases) {
        const Result<Scene> scene = makeBuiltin(spec);
        ASSERT_FALSE(scene.ok()) << spec;
        EXPECT_EQ(scene.error().message, error);
    }
}

// Found while writing the fuzzers, which read no files: the OBJ loader's material libraries.

TEST(FuzzFindingsTest, AMaterialLibraryThatIsNotARegularFileIsNotRead) {
    // `mtllib /dev/zero` grew a line until memory ran out: only regular files are read. A FIFO stands
    // for the device here (it never ends either, and opening it would wait for a writer): a sandbox
    // may show no /dev/zero, and a test must not depend on what /dev holds. A folder neither.
    const fs::path dir = test::freshDir("FuzzFindingsMtlNotAFile");
    ASSERT_EQ(::mkfifo((dir / "pipe.mtl").c_str(), 0600), 0) << std::strerror(errno);
    fs::create_directory(dir / "folder.mtl");
    for (const char* name : {"pipe.mtl", "folder.mtl"}) {
        const fs::path obj = dir / "in.obj";
        test::writeFile(obj, std::string("mtllib ") + name + "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        const Result<Scene> scene = loadObj(obj.string());
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        EXPECT_EQ(scene->warnings,
                  std::vector<std::string>{obj.string() + ": material library '" + name + "' is not a readable file"});
    }
}

TEST(FuzzFindingsTest, AMaterialLibraryWithAnExponentOfTenDigitsIsNotRead) {
    const fs::path dir = test::freshDir("FuzzFindingsMtlExponent");
    test::writeFile(dir / "m.mtl", "newmtl red\nKd 1 0 0\nNs 1e2147483648\n");
    test::writeFile(dir / "in.obj", "mtllib m.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const Result<Scene> scene = loadObj((dir / "in.obj").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_FALSE(scene->warnings.empty());
    EXPECT_EQ(scene->warnings[0], (dir / "in.obj").string() +
                                      ": material library 'm.mtl' not read: line 3: a number with an exponent of 10 "
                                      "digits (floats end at 1e38)");
}

}  // namespace
}  // namespace frugal
