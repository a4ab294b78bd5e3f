// The glTF loader's check stages called directly, without a file or tinygltf: the container reader,
// the schema check and the structure checks (src/scene/Gltf*.h). GltfLoaderTest covers the same
// messages through loadGltf; these pin down what each stage accepts and refuses on its own, which is
// what a fuzz target for one stage relies on.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "scene/GltfCheck.h"
#include "scene/GltfContainer.h"
#include "scene/GltfSchema.h"
#include "scene/GltfStructure.h"

namespace frugal::gltf {
namespace {

// The message a check fails with, or "(accepted)".
template <class Fn>
std::string failureOf(Fn&& check) {
    try {
        check();
    } catch (const Failure& failure) {
        return failure.message;
    }
    return "(accepted)";
}

std::string u32(std::uint32_t v) {
    std::string out;
    for (int k = 0; k < 4; ++k) out += char((v >> (8 * k)) & 0xFF);
    return out;
}

// A GLB header declaring `length` bytes, followed by `rest`.
std::string glb(std::uint32_t length, const std::string& rest) { return "glTF" + u32(2) + u32(length) + rest; }

// A document with a valid asset and `members`, parsed from text as the loader parses files: nlohmann
// stores a non-negative integer read from text as unsigned, which the index checks require (a Json
// built in code from the literal 0 holds a signed integer, and fails them).
Json withAsset(const std::string& members) {
    return Json::parse(R"({"asset": {"version": "2.0"})" + (members.empty() ? "" : ", " + members) + "}");
}

TEST(GltfCheckTest, SplitGlbRefusesTruncatedChunks) {
    // The header promises more than the file holds.
    EXPECT_EQ(failureOf([] { splitGlb(glb(20, "1234")); }),
              "truncated GLB: the header declares 20 bytes, the file has 16");
    // Room for the header but not for a chunk header.
    EXPECT_EQ(failureOf([] { splitGlb(glb(16, "JSON")); }),
              "truncated GLB: chunk 0 at byte 12 needs an 8-byte header, 4 bytes remain");
    // A chunk longer than what follows it.
    EXPECT_EQ(failureOf([] { splitGlb(glb(24, u32(12) + "JSON" + "{}  ")); }),
              "truncated GLB: chunk 0 at byte 12 declares 12 bytes, 4 remain");
    // A BIN chunk that runs past the end, after a valid JSON chunk.
    EXPECT_EQ(failureOf([] { splitGlb(glb(32, u32(4) + "JSON" + "{}  " + u32(8) + "BIN" + '\0')); }),
              "truncated GLB: chunk 1 at byte 24 declares 8 bytes, 0 remain");
}

TEST(GltfCheckTest, SplitGlbFindsTheChunksAndCanonicalGlbRepacksThem) {
    // Unpadded JSON, an unknown chunk, then BIN: legal, but not what tinygltf reads.
    const std::string chunks = u32(2) + "JSON" + "{}" + u32(1) + "XTRA" + "x" + u32(3) + "BIN" + '\0' + "abc";
    const std::string file = glb(std::uint32_t(12 + chunks.size()), chunks);
    const GlbParts parts = splitGlb(file);
    EXPECT_EQ(parts.json, "{}");
    EXPECT_FALSE(parts.hasBin);  // BIN is only read as the second chunk
    EXPECT_FALSE(parts.canonical);

    const std::string binSecond = u32(2) + "JSON" + "{}" + u32(3) + "BIN" + '\0' + "abc";
    const std::string unalignedFile = glb(std::uint32_t(12 + binSecond.size()), binSecond);
    const GlbParts unaligned = splitGlb(unalignedFile);
    ASSERT_TRUE(unaligned.hasBin);
    EXPECT_FALSE(unaligned.canonical);
    const std::string repacked = canonicalGlb(unaligned);
    EXPECT_EQ(repacked.size() % 4, 0u);
    const GlbParts again = splitGlb(repacked);
    EXPECT_TRUE(again.canonical);
    EXPECT_EQ(again.json, "{}  ");
    EXPECT_EQ(again.bin, std::string("abc\0", 4));
}

TEST(GltfCheckTest, ParseJsonBoundsTheNestingDepth) {
    const auto nested = [](std::size_t levels) {
        return "{\"a\":" + std::string(levels - 1, '[') + std::string(levels - 1, ']') + "}";
    };
    EXPECT_EQ(failureOf([&] { parseJson(nested(kMaxJsonDepth)); }), "(accepted)");
    EXPECT_EQ(failureOf([&] { parseJson(nested(kMaxJsonDepth + 1)); }),
              "JSON nested deeper than 256 levels (at byte 260)");
    // Brackets inside strings, escaped quotes included, are not nesting.
    EXPECT_EQ(failureOf([] { parseJson("{\"a\": \"\\\"" + std::string(300, '[') + "\"}"); }), "(accepted)");
    EXPECT_EQ(failureOf([] { parseJson("\"text\""); }), "the JSON root is string \"text\", expected an object");
}

TEST(GltfCheckTest, IsBinaryGoesByExtensionOrMagic) {
    EXPECT_TRUE(isBinary("dir/Scene.GLB", "{}"));
    EXPECT_TRUE(isBinary("scene.gltf", "glTF...."));
    EXPECT_FALSE(isBinary("scene.gltf", "{}"));
    EXPECT_FALSE(isBinary("glb", "glT"));
}

TEST(GltfCheckTest, SchemaNamesTheWrongTypedFieldAndWhatItHolds) {
    struct Case {
        Json root;
        std::string error;
    };
    const std::vector<Case> cases = {
        {withAsset(R"("nodes": [{"mesh": "0"}])"),
         "nodes[0].mesh: expected a non-negative integer below 2^31, got string \"0\""},
        {withAsset(R"("nodes": [{"mesh": 2147483648}])"),
         "nodes[0].mesh: expected a non-negative integer below 2^31, got 2147483648"},
        {withAsset(R"("nodes": [{"scale": [1, 1]}])"), "nodes[0].scale: expected 3 numbers, got 2"},
        {withAsset(R"("accessors": [{"componentType": 5124, "count": 1, "type": "SCALAR"}])"),
         "accessors[0].componentType: 5124 is not one of 5120, 5121, 5122, 5123, 5125, 5126"},
        {withAsset(R"("meshes": [{"primitives": [{"attributes": {"POSITION": -1}}]}])"),
         "meshes[0].primitives[0].attributes.POSITION: expected a non-negative integer below 2^31, got -1"},
        {withAsset(R"("scenes": [{"extensions": {"KHR_x": 1}}])"),
         "scenes[0].extensions.KHR_x: expected an object, got 1"},
        {Json::parse("{}"), "glTF root: missing required property 'asset'"},
        // A wrong type is reported before a missing property, even a missing "asset".
        {Json::parse(R"({"scene": true})"), "scene: expected a non-negative integer below 2^31, got true"},
    };
    for (const Case& c : cases) EXPECT_EQ(failureOf([&] { checkSchema(c.root); }), c.error) << c.root.dump();
    EXPECT_EQ(failureOf([] { checkSchema(withAsset(R"("nodes": [{"mesh": 0, "extras": [null]}])")); }), "(accepted)");
}

TEST(GltfCheckTest, StructureRefusesOutOfRangeIndicesAndNodeGraphsThatAreNotForests) {
    struct Case {
        Json root;
        std::string error;
    };
    const std::vector<Case> cases = {
        {withAsset(R"("nodes": [{"mesh": 0}])"), "nodes[0].mesh: mesh 0 out of range, the file has 0 meshes"},
        {withAsset(R"("meshes": [{"primitives": [{"attributes": {}}]}], "nodes": [{"mesh": 1}])"),
         "nodes[0].mesh: mesh 1 out of range, the file has 1 mesh"},
        {withAsset(R"("nodes": [{"children": [1]}, {"children": [2]}, {"children": [0]}])"),
         "nodes form a cycle: 0 -> 1 -> 2 -> 0"},
        {withAsset(R"("nodes": [{"children": [0]}])"), "nodes[0].children[0]: node 0 is its own child"},
        {withAsset(R"("nodes": [{"children": [2]}, {"children": [2]}, {}])"),
         "node 2 has two parents: node 0 and node 1"},
        {withAsset(R"("nodes": [{"children": [1]}, {}], "scenes": [{"nodes": [1]}])"),
         "scenes[0].nodes[0]: node 1 is not a root, it is a child of node 0"},
        {withAsset(R"("scenes": [{}], "scene": 1)"), "scene: scene 1 out of range, the file has 1 scene"},
        {Json::parse(R"({"asset": {"version": "1.0"}})"), "asset.version: glTF 1.0 is not supported (2.x only)"},
    };
    for (const Case& c : cases) {
        ASSERT_EQ(failureOf([&] { checkSchema(c.root); }), "(accepted)") << c.root.dump();
        EXPECT_EQ(failureOf([&] { checkStructure(c.root); }), c.error) << c.root.dump();
    }
    const Json forest = withAsset(R"("nodes": [{"children": [1, 2]}, {}, {}], "scenes": [{"nodes": [0]}])");
    EXPECT_EQ(failureOf([&] { checkStructure(forest); }), "(accepted)");
}

TEST(GltfCheckTest, BuffersAreMeasuredWithTheDecoderPassedIn) {
    static int calls = 0;
    calls = 0;
    const DataUriDecoder threeBytes = [](const std::string&, std::vector<unsigned char>& bytes) {
        ++calls;
        bytes.assign(3, 0);
        return true;
    };
    const DataUriDecoder refuses = [](const std::string&, std::vector<unsigned char>&) { return false; };
    const Json dataUri =
        withAsset(R"("buffers": [{"byteLength": 4, "uri": "data:application/octet-stream;base64,AAAA"}])");
    EXPECT_EQ(failureOf([&] { checkBuffers(dataUri, ".", nullptr, threeBytes, {}); }),
              "buffers[0].uri: the data URI holds 3 bytes, byteLength says 4");
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(failureOf([&] { checkBuffers(dataUri, ".", nullptr, refuses, {}); }),
              "buffers[0].uri: cannot decode the data URI (frugal reads base64 application/octet-stream or "
              "application/gltf-buffer)");

    // Buffer 0 without a uri is the BIN chunk, which must hold byteLength bytes.
    const Json bin = withAsset(R"("buffers": [{"byteLength": 8}])");
    GlbParts parts;
    parts.json = "{}  ";
    EXPECT_EQ(failureOf([&] { checkBuffers(bin, ".", nullptr, refuses, {}); }),
              "buffers[0]: no uri (only buffer 0 of a .glb may use the BIN chunk)");
    EXPECT_EQ(failureOf([&] { checkBuffers(bin, ".", &parts, refuses, {}); }),
              "buffers[0]: no uri and the .glb has no BIN chunk");
    parts.bin = "abcd";
    parts.hasBin = true;
    EXPECT_EQ(failureOf([&] { checkBuffers(bin, ".", &parts, refuses, {}); }),
              "buffers[0]: byteLength 8 exceeds the GLB BIN chunk (4 bytes)");
    parts.bin = "abcdefgh";
    EXPECT_EQ(failureOf([&] { checkBuffers(bin, ".", &parts, refuses, {}); }), "(accepted)");
    EXPECT_EQ(calls, 1);
}

TEST(GltfCheckTest, UsedExtensionsListsEachNameOnceOutsideExtras) {
    const Json root = withAsset(R"("extensionsUsed": ["KHR_b"], "extensionsRequired": ["KHR_b", "KHR_a"],
        "extras": {"extensions": {"NOT_USED": {}}}, "nodes": [{"extensions": {"KHR_c": {}, "KHR_a": {}}}])");
    EXPECT_EQ(usedExtensions(root), (std::vector<std::string>{"KHR_b", "KHR_a", "KHR_c"}));
}

}  // namespace
}  // namespace frugal::gltf
