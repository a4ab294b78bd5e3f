// Compressed glTF geometry (src/scene/GltfCompression.h): EXT_meshopt_compression and
// KHR_draco_mesh_compression decode to exactly the mesh of the uncompressed file, and every broken
// extension object or stream is one line naming where and why.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <frugal/Scene.h>

#include "TestSupport.h"
#include "lab/GltfCompress.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

using test::base64;
using test::bytesOf;

const std::vector<float> kPositions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::vector<std::uint16_t> kIndices = {0, 1, 2, 0, 2, 3};

// The test quad's document without its bufferViews and buffers: one node, one mesh, POSITION
// (accessor 0 on bufferView 0) and indices (accessor 1 on bufferView 1).
Json quadDocument() {
    return {{"asset", {{"version", "2.0"}}},
            {"scene", 0},
            {"scenes", {{{"nodes", {0}}}}},
            {"nodes", {{{"mesh", 0}}}},
            {"meshes", {{{"name", "quad"}, {"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
            {"accessors",
             {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
              {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}}};
}

// A quad (4 positions, 6 uint16 indices) whose two bufferViews are meshopt streams in buffer 0,
// decoded into buffer 1, a placeholder without data.
struct MeshoptQuad {
    Json json;
    std::string streams;  // buffer 0

    Json& view(int v) { return json["bufferViews"][v]; }
    Json& extension(int v) { return view(v)["extensions"]["EXT_meshopt_compression"]; }

    std::string write(const fs::path& dir, const std::string& name) const {
        Json out = json;
        out["buffers"] = {
            {{"byteLength", streams.size()}, {"uri", "data:application/octet-stream;base64," + base64(streams)}},
            {{"byteLength", 60}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};
        test::writeFile(dir / (name + ".gltf"), out.dump(1));
        return (dir / (name + ".gltf")).string();
    }
};

MeshoptQuad meshoptQuad() {
    std::vector<unsigned char> vertices(meshopt_encodeVertexBufferBound(4, 12));
    vertices.resize(meshopt_encodeVertexBuffer(vertices.data(), vertices.size(), kPositions.data(), 4, 12));
    const std::vector<unsigned> list(kIndices.begin(), kIndices.end());
    std::vector<unsigned char> indices(meshopt_encodeIndexSequenceBound(6, 4));
    indices.resize(meshopt_encodeIndexSequence(indices.data(), indices.size(), list.data(), 6));
    MeshoptQuad quad;
    quad.streams.assign(vertices.begin(), vertices.end());
    while (quad.streams.size() % 4 != 0) quad.streams += '\0';
    const std::size_t indexOffset = quad.streams.size();
    quad.streams.append(indices.begin(), indices.end());
    auto compressed = [](std::size_t offset, std::size_t length, int stride, int count, const char* mode) {
        return Json{{"EXT_meshopt_compression",
                     {{"buffer", 0},
                      {"byteOffset", offset},
                      {"byteLength", length},
                      {"byteStride", stride},
                      {"count", count},
                      {"mode", mode}}}};
    };
    quad.json = quadDocument();
    quad.json["extensionsUsed"] = quad.json["extensionsRequired"] = {"EXT_meshopt_compression"};
    quad.json.update({
        {"bufferViews",
         {{{"buffer", 1}, {"byteLength", 48}, {"extensions", compressed(0, vertices.size(), 12, 4, "ATTRIBUTES")}},
          {{"buffer", 1},
           {"byteOffset", 48},
           {"byteLength", 12},
           {"extensions", compressed(indexOffset, indices.size(), 2, 6, "INDICES")}}}}});
    return quad;
}

Result<Scene> load(const std::string& path) {
    LoadOptions options;
    options.optimizeOrder = false;
    return loadScene(path, options);
}

TEST(GltfCompression, AMeshoptQuadDecodesToTheQuad) {
    const std::string path = meshoptQuad().write(test::freshDir("MeshoptQuad"), "quad");
    const Result<Scene> scene = load(path);
    ASSERT_TRUE(scene) << scene.error().message;
    ASSERT_EQ(scene->meshes.size(), 1u);
    const Mesh& mesh = scene->meshes[0];
    ASSERT_EQ(mesh.positions.size(), 4u);
    for (std::size_t v = 0; v < 4; ++v)
        EXPECT_EQ(mesh.positions[v], glm::vec3(kPositions[3 * v], kPositions[3 * v + 1], kPositions[3 * v + 2]));
    EXPECT_EQ(mesh.indices, std::vector<std::uint32_t>(kIndices.begin(), kIndices.end()));
    EXPECT_TRUE(scene->unsupported.empty());
    ASSERT_EQ(scene->decompressed.size(), 1u);
    EXPECT_EQ(scene->decompressed[0].method, "EXT_meshopt_compression");
    EXPECT_EQ(scene->decompressed[0].items, 2u);
    EXPECT_EQ(scene->decompressed[0].decodedBytes, 60u);
}

struct BadMeshopt {
    const char* name;
    std::function<void(MeshoptQuad&)> mutate;
    std::string error;
};

std::vector<BadMeshopt> badMeshopt() {
    const std::string ext = "bufferViews[0].extensions.EXT_meshopt_compression";
    return {
        {"CorruptStream", [](MeshoptQuad& q) { q.streams[0] = char(0x11); },
         "bufferViews[0]: EXT_meshopt_compression: the ATTRIBUTES stream of 67 bytes does not decode to 4 elements "
         "of 12 bytes (meshoptimizer does not know its header)"},
        {"TruncatedStream", [](MeshoptQuad& q) { q.extension(0)["byteLength"] = 10; },
         "bufferViews[0]: EXT_meshopt_compression: the ATTRIBUTES stream of 10 bytes does not decode to 4 elements "
         "of 12 bytes (meshoptimizer finds it malformed or short)"},
        {"StrideNotOfFour", [](MeshoptQuad& q) { q.extension(0)["byteStride"] = 6; },
         ext + ".byteStride: 6 is not a multiple of 4 up to 256, as ATTRIBUTES needs"},
        {"CountAgainstTheView", [](MeshoptQuad& q) { q.extension(0)["count"] = 3; },
         ext + ": count 3 x byteStride 12 = 36 bytes, the bufferView's byteLength is 48"},
        {"TrianglesNotOfThree",
         [](MeshoptQuad& q) {
             q.extension(1)["mode"] = "TRIANGLES";
             q.extension(1)["count"] = 4;
             q.view(1)["byteLength"] = 8;
         },
         "bufferViews[1].extensions.EXT_meshopt_compression.count: 4 is not a multiple of 3, as TRIANGLES needs"},
        {"IndexStride", [](MeshoptQuad& q) { q.extension(1)["byteStride"] = 1; },
         "bufferViews[1].extensions.EXT_meshopt_compression.byteStride: 1 is not 2 or 4, as INDICES needs"},
        {"FilterOnIndices", [](MeshoptQuad& q) { q.extension(1)["filter"] = "OCTAHEDRAL"; },
         "bufferViews[1].extensions.EXT_meshopt_compression.filter: OCTAHEDRAL applies to ATTRIBUTES only, the mode "
         "is INDICES"},
        {"OctahedralStride", [](MeshoptQuad& q) { q.extension(0)["filter"] = "OCTAHEDRAL"; },
         ext + ".byteStride: 12 is not one the OCTAHEDRAL filter decodes (4 or 8)"},
        {"UnknownMode", [](MeshoptQuad& q) { q.extension(0)["mode"] = "VERTICES"; },
         ext + ".mode: \"VERTICES\" is not ATTRIBUTES, TRIANGLES or INDICES"},
        {"NoCount", [](MeshoptQuad& q) { q.extension(0).erase("count"); }, ext + ": 'count' is required"},
        {"NegativeOffset", [](MeshoptQuad& q) { q.extension(0)["byteOffset"] = -4; },
         ext + ".byteOffset: -4 is not an integer of at least 0"},
        {"StreamPastItsBuffer", [](MeshoptQuad& q) { q.extension(0)["byteOffset"] = 40; },
         ext + ": byteOffset 40 + byteLength 67 is beyond the end of buffer 0 (79 bytes)"},
        {"StreamInThePlaceholder", [](MeshoptQuad& q) { q.extension(0)["buffer"] = 1; },
         ext + ".buffer: buffer 1 has no data (no uri), so holds no compressed stream"},
        {"PlaceholderReadUncompressed", [](MeshoptQuad& q) { q.view(1).erase("extensions"); },
         "bufferViews[1]: buffer 1 has no data (no uri: an EXT_meshopt_compression fallback), and the view is not "
         "compressed"},
        {"ACountNoStreamHolds",
         [](MeshoptQuad& q) {
             q.extension(0)["count"] = 1 << 22;
             q.view(0)["byteLength"] = 12 << 22;
         },
         ext + ": 50331648 bytes cannot come from a stream of 67 bytes"},
    };
}

void PrintTo(const BadMeshopt& c, std::ostream* out) { *out << c.name; }

class GltfBadMeshopt : public testing::TestWithParam<BadMeshopt> {};

TEST_P(GltfBadMeshopt, FailsWithTheExactMessage) {
    const BadMeshopt& c = GetParam();
    MeshoptQuad quad = meshoptQuad();
    c.mutate(quad);
    const std::string path = quad.write(test::freshDir(std::string("GltfBadMeshopt_") + c.name), "bad");
    const Result<Scene> scene = load(path);
    ASSERT_FALSE(scene) << c.name << " loaded";
    EXPECT_EQ(scene.error().message, path + ": " + c.error);
}

INSTANTIATE_TEST_SUITE_P(Rules, GltfBadMeshopt, testing::ValuesIn(badMeshopt()),
                         [](const testing::TestParamInfo<BadMeshopt>& param) { return std::string(param.param.name); });

// The test quad with its buffer embedded, and its KHR_draco_mesh_compression copy (lab/GltfCompress.h).
std::string plainQuad(const fs::path& dir) {
    const std::string bin = bytesOf(kPositions) + bytesOf(kIndices);
    Json json = quadDocument();
    json["bufferViews"] = {{{"buffer", 0}, {"byteLength", 48}}, {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 12}}};
    json["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
    test::writeFile(dir / "quad.gltf", json.dump(1));
    return (dir / "quad.gltf").string();
}

Json dracoQuad(const fs::path& dir) {
    CompressOptions options;
    options.method = CompressOptions::Method::Draco;
    options.dracoSequential = true;
    const Result<std::string> text = compressGltf(plainQuad(dir), options);
    EXPECT_TRUE(text) << text.error().message;
    return text ? Json::parse(*text) : Json::object();
}

std::string writeJson(const fs::path& dir, const std::string& name, const Json& json) {
    test::writeFile(dir / (name + ".gltf"), json.dump(1));
    return (dir / (name + ".gltf")).string();
}

TEST(GltfCompression, ADracoQuadDecodesToTheQuad) {
    const fs::path dir = test::freshDir("DracoQuad");
    const Result<Scene> scene = load(writeJson(dir, "draco", dracoQuad(dir)));
    ASSERT_TRUE(scene) << scene.error().message;
    ASSERT_EQ(scene->meshes.size(), 1u);
    const Mesh& mesh = scene->meshes[0];
    ASSERT_EQ(mesh.positions.size(), 4u);
    for (std::size_t v = 0; v < 4; ++v)
        EXPECT_EQ(mesh.positions[v], glm::vec3(kPositions[3 * v], kPositions[3 * v + 1], kPositions[3 * v + 2]));
    EXPECT_EQ(mesh.indices, std::vector<std::uint32_t>(kIndices.begin(), kIndices.end()));
    ASSERT_EQ(scene->decompressed.size(), 1u);
    EXPECT_EQ(scene->decompressed[0].method, "KHR_draco_mesh_compression");
    EXPECT_EQ(scene->decompressed[0].items, 1u);
    EXPECT_EQ(scene->decompressed[0].decodedBytes, 48u + 24u);
}

struct BadDraco {
    const char* name;
    std::function<void(Json&)> mutate;
    std::string error;
};

Json& dracoExtension(Json& json) {
    return json["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"];
}

std::vector<BadDraco> badDraco() {
    const std::string ext = "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression";
    return {
        {"NotAStream", [](Json& j) { dracoExtension(j)["bufferView"] = 0; },
         "mesh 0 primitive 0: KHR_draco_mesh_compression: the 48-byte stream does not decode (Draco: Not a Draco "
         "file.)"},
        {"TruncatedStream", [](Json& j) { j["bufferViews"][2]["byteLength"] = 30; },
         "mesh 0 primitive 0: KHR_draco_mesh_compression: the 30-byte stream does not decode (Draco: Failed to "
         "decode point attributes.)"},
        {"NoSuchAttribute", [](Json& j) { dracoExtension(j)["attributes"]["POSITION"] = 7; },
         "mesh 0 primitive 0: KHR_draco_mesh_compression.attributes.POSITION: the stream has no attribute 7"},
        {"AttributeThePrimitiveLacks", [](Json& j) { dracoExtension(j)["attributes"]["NORMAL"] = 0; },
         ext + ".attributes.NORMAL: the primitive has no attribute NORMAL"},
        {"NoPosition", [](Json& j) { dracoExtension(j)["attributes"].erase("POSITION"); },
         ext + ".attributes: no POSITION, the one attribute every drawn primitive has"},
        {"Components",
         [](Json& j) {
             j["accessors"][j["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()]["type"] = "VEC4";
         },
         "mesh 0 primitive 0: KHR_draco_mesh_compression.attributes.POSITION: the stream's attribute has 3 "
         "components, the accessor 4"},
        {"Points", [](Json& j) { j["meshes"][0]["primitives"][0]["mode"] = 0; },
         ext + ": the primitive's mode is 0, Draco holds TRIANGLES (4) or TRIANGLE_STRIP (5)"},
        {"NoBufferView", [](Json& j) { dracoExtension(j).erase("bufferView"); }, ext + ": 'bufferView' is required"},
        {"BufferViewOutOfRange", [](Json& j) { dracoExtension(j)["bufferView"] = 9; },
         ext + ".bufferView: bufferView 9 out of range, the file has 3 bufferViews"},
    };
}

void PrintTo(const BadDraco& c, std::ostream* out) { *out << c.name; }

class GltfBadDraco : public testing::TestWithParam<BadDraco> {};

TEST_P(GltfBadDraco, FailsWithTheExactMessage) {
    const BadDraco& c = GetParam();
    const fs::path dir = test::freshDir(std::string("GltfBadDraco_") + c.name);
    Json json = dracoQuad(dir);
    c.mutate(json);
    const std::string path = writeJson(dir, "bad", json);
    const Result<Scene> scene = load(path);
    ASSERT_FALSE(scene) << c.name << " loaded";
    EXPECT_EQ(scene.error().message, path + ": " + c.error);
}

INSTANTIATE_TEST_SUITE_P(Rules, GltfBadDraco, testing::ValuesIn(badDraco()),
                         [](const testing::TestParamInfo<BadDraco>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace frugal
