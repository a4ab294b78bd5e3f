// glTF loader: every file of assimp's glTF2 test set, one hand-written file per validation rule, every
// truncated prefix of a small .glb, and round trips of what the loader fills in.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestSupport.h"
#include "pipeline/Frame.h"
#include "scene/Load.h"

namespace frugal {
namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Building small glTF files.

using test::base64;
using test::bytesOf;

constexpr int kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123, kFloat = 5126;

// A glTF document and the contents of its one buffer.
struct Asset {
    Json json;
    std::string bin;

    // Appends `data` as a new bufferView and an accessor over it; returns the accessor index.
    int accessor(const std::string& data, int componentType, const char* type, std::size_t count,
                 bool normalized = false) {
        while (bin.size() % 4 != 0) bin += '\0';
        json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", data.size()}});
        bin += data;
        Json a = {{"bufferView", json["bufferViews"].size() - 1},
                  {"componentType", componentType},
                  {"count", count},
                  {"type", type}};
        if (normalized) a["normalized"] = true;
        json["accessors"].push_back(a);
        return int(json["accessors"].size() - 1);
    }
    Json& primitive(int mesh = 0, int p = 0) { return json["meshes"][mesh]["primitives"][p]; }
};

// One node with one mesh: a unit quad in z = 0 facing +z, two indexed triangles.
Asset quad() {
    Asset asset;
    asset.json = {
        {"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", {{{"nodes", {0}}}}}, {"nodes", {{{"mesh", 0}}}}};
    const int position = asset.accessor(bytesOf<float>({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}), kFloat, "VEC3", 4);
    const int indices = asset.accessor(bytesOf<std::uint16_t>({0, 1, 2, 0, 2, 3}), kUShort, "SCALAR", 6);
    const Json primitive = {{"attributes", {{"POSITION", position}}}, {"indices", indices}};
    asset.json["meshes"] = Json::array({{{"name", "quad"}, {"primitives", Json::array({primitive})}}});
    return asset;
}

// .gltf with the buffer in "<name>.bin" beside it.
std::string writeGltf(const fs::path& dir, const std::string& name, Asset asset) {
    asset.json["buffers"] = {{{"byteLength", asset.bin.size()}, {"uri", name + ".bin"}}};
    test::writeFile(dir / (name + ".bin"), asset.bin);
    test::writeFile(dir / (name + ".gltf"), asset.json.dump(1));
    return (dir / (name + ".gltf")).string();
}

std::string writeEmbedded(const fs::path& dir, const std::string& name, Asset asset) {
    asset.json["buffers"] = {
        {{"byteLength", asset.bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(asset.bin)}}};
    test::writeFile(dir / (name + ".gltf"), asset.json.dump(1));
    return (dir / (name + ".gltf")).string();
}

std::string glbBytes(Asset asset) {
    asset.json["buffers"] = {{{"byteLength", asset.bin.size()}}};
    std::string json = asset.json.dump();
    while (json.size() % 4 != 0) json += ' ';
    std::string bin = asset.bin;
    while (bin.size() % 4 != 0) bin += '\0';
    auto u32 = [](std::size_t v) { return bytesOf<std::uint32_t>({std::uint32_t(v)}); };
    return "glTF" + u32(2) + u32(12 + 8 + json.size() + 8 + bin.size()) + u32(json.size()) + "JSON" + json +
           u32(bin.size()) + std::string("BIN\0", 4) + bin;
}

std::string writeGlb(const fs::path& dir, const std::string& name, const Asset& asset) {
    test::writeFile(dir / (name + ".glb"), glbBytes(asset));
    return (dir / (name + ".glb")).string();
}

Result<Scene> load(const std::string& path) {
    LoadOptions options;
    options.optimizeOrder = false;  // keep the file's triangle order, to compare indices
    return loadGltf(path, options);
}

// A minimal PNG writer (stored deflate blocks), to test decoding of every PNG colour type.
std::uint32_t crc32(const std::string& data) {
    std::uint32_t crc = 0xFFFFFFFFu;
    for (char c : data) {
        crc ^= std::uint8_t(c);
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

std::string bigEndian(std::uint32_t v) {
    return {char(v >> 24), char((v >> 16) & 0xFF), char((v >> 8) & 0xFF), char(v & 0xFF)};
}

std::string png(int width, int height, int colorType, int bitDepth, const std::string& samples) {
    auto chunk = [](const std::string& type, const std::string& data) {
        return bigEndian(std::uint32_t(data.size())) + type + data + bigEndian(crc32(type + data));
    };
    const std::size_t rowBytes = samples.size() / std::size_t(height);
    std::string raw;
    for (int y = 0; y < height; ++y) raw += '\0' + samples.substr(std::size_t(y) * rowBytes, rowBytes);
    std::uint32_t a = 1, b = 0;
    for (char c : raw) {
        a = (a + std::uint8_t(c)) % 65521;
        b = (b + a) % 65521;
    }
    const auto length = std::uint16_t(raw.size());
    std::string zlib = "\x78\x01";
    zlib += '\x01';  // final stored block
    zlib += bytesOf<std::uint16_t>({length, std::uint16_t(~length)});
    zlib += raw + bigEndian((b << 16) | a);
    const std::string header = bigEndian(std::uint32_t(width)) + bigEndian(std::uint32_t(height)) + char(bitDepth) +
                               char(colorType) + std::string(3, '\0');
    return "\x89PNG\r\n\x1a\n" + chunk("IHDR", header) + chunk("IDAT", zlib) + chunk("IEND", "");
}

// ---------------------------------------------------------------------------------------------
// Every .gltf/.glb of assimp-testmodels.

struct AssimpCase {
    const char* file;             // relative to FRUGAL_ASSIMP_GLTF2_DIR
    const char* error = nullptr;  // expected message after "<path>: ", or nullptr if the file loads
    std::size_t meshes = 0, triangles = 0, instances = 0, textures = 0, cameras = 0, warnings = 0;
    std::size_t segments = 0, points = 0;       // of Topology::Lines and Points meshes
    std::vector<std::string> unsupported = {};  // any order
    bool facesPlusZ = false;  // every triangle is counter-clockwise seen from +z (Asset Generator quads)
};

const std::vector<AssimpCase>& assimpCases() {
    static const std::vector<AssimpCase> cases = {
        {.file = "2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
         .meshes = 34,
         .triangles = 121496,
         .instances = 115,
         .cameras = 1},
        {.file = "BoxBadNormals-glTF-Binary/BoxBadNormals.glb", .meshes = 1, .triangles = 12, .instances = 1},
        {.file = "BoxTexcoords-glTF/boxTexcoords.gltf",
         .meshes = 1,
         .triangles = 12,
         .instances = 1,
         .textures = 1,
         // Its metallic-roughness texture samples TEXCOORD_1, the base colour TEXCOORD_0.
         .unsupported = {"textures of one material on different coordinates (the first one's are used)"}},
        {.file = "BoxTextured-glTF-Binary/BoxTextured.glb",
         .meshes = 1,
         .triangles = 12,
         .instances = 1,
         .textures = 1},
        {.file = "BoxTextured-glTF-Embedded/BoxTextured.gltf",
         .meshes = 1,
         .triangles = 12,
         .instances = 1,
         .textures = 1},
        {.file = "BoxTextured-glTF-pbrSpecularGlossiness/BoxTextured.gltf",
         .meshes = 1,
         .triangles = 12,
         .instances = 1,
         .textures = 1},
        // A glTF 1.0 style material (technique + values) declared through a required extension: the
        // geometry loads, the material is the default one, the extension is reported.
        {.file = "BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf",
         .meshes = 1,
         .triangles = 12,
         .instances = 1,
         .unsupported = {"KHR_technique_webgl"}},
        {.file = "BoxTextured-glTF/BoxTextured.gltf", .meshes = 1, .triangles = 12, .instances = 1, .textures = 1},
        // Every triangle touches an infinite position: all dropped, with a warning.
        {.file = "BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb",
         .meshes = 1,
         .triangles = 0,
         .instances = 1,
         .warnings = 1},
        {.file = "ClearCoat-glTF/ClearCoatTest.gltf",
         .meshes = 27,
         .triangles = 37116,
         .instances = 27,
         .textures = 10},
        {.file = "IncorrectVertexArrays/Cube.gltf",
         .error = "bufferViews[2]: byteOffset 504 + byteLength 432 is beyond the end of buffer 0 (514 bytes)"},
        {.file = "IndexOutOfRange/AllIndicesOutOfRange.gltf",
         .error = "accessor 0 (indices of mesh 0 primitive 0): index 65535 out of range, mesh has 24 vertices"},
        {.file = "IndexOutOfRange/IndexOutOfRange.gltf",
         .error = "accessor 0 (indices of mesh 0 primitive 0): index 255 out of range, mesh has 24 vertices"},
        {.file = "MissingBin/BoxTextured.gltf", .error = "buffers[0].uri: no such file 'BoxTextured0.bin'"},
        {.file = "RecursiveNodes/RecursiveNodes.gltf", .error = "nodes form a cycle: 0 -> 1 -> 0"},
        {.file = "SchemaFailures/sceneWrongType.gltf",
         .error = "scene: expected a non-negative integer below 2^31, got string \"hello\""},
        {.file = "TestNoRootNode/NoScene.gltf", .error = "scene: scene 0 out of range, the file has 0 scenes"},
        {.file = "TestNoRootNode/SceneWithoutNodes.gltf"},
        {.file = "cameras/Cameras.gltf", .meshes = 1, .triangles = 2, .instances = 1, .cameras = 2},
        {.file = "draco/2CylinderEngine.gltf", .meshes = 34, .triangles = 110336, .instances = 115, .cameras = 1},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf",
         .meshes = 1,
         .instances = 1,
         .points = 1024},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_01.gltf",
         .meshes = 1,
         .instances = 1,
         .segments = 4},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_02.gltf",
         .meshes = 1,
         .instances = 1,
         .segments = 4},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_03.gltf",
         .meshes = 1,
         .instances = 1,
         .segments = 4},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_04.gltf",
         .meshes = 1,
         .triangles = 2,
         .instances = 1,
         .facesPlusZ = true},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_05.gltf",
         .meshes = 1,
         .triangles = 2,
         .instances = 1,
         .facesPlusZ = true},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_06.gltf",
         .meshes = 1,
         .triangles = 2,
         .instances = 1,
         .facesPlusZ = true},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_07.gltf",
         .meshes = 1,
         .instances = 1,
         .points = 1024},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_08.gltf",
         .meshes = 1,
         .instances = 1,
         .segments = 4},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_09.gltf",
         .meshes = 1,
         .instances = 1,
         .segments = 4},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_10.gltf",
         .meshes = 1,
         .instances = 1,
         .segments = 4},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_11.gltf",
         .meshes = 1,
         .triangles = 2,
         .instances = 1,
         .facesPlusZ = true},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_12.gltf",
         .meshes = 1,
         .triangles = 2,
         .instances = 1,
         .facesPlusZ = true},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_13.gltf",
         .meshes = 1,
         .triangles = 2,
         .instances = 1,
         .facesPlusZ = true},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_14.gltf",
         .meshes = 1,
         .triangles = 2,
         .instances = 1,
         .facesPlusZ = true},
        {.file = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_15.gltf",
         .meshes = 1,
         .triangles = 2,
         .instances = 1,
         .facesPlusZ = true},
        {.file = "glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf",
         .meshes = 1,
         .triangles = 12,
         .instances = 1},
        // One primitive lacks the TEXCOORD_0 its material's texture needs: drawn untextured, with a warning.
        {.file = "issue_3269/texcoord_crash.gltf",
         .meshes = 5,
         .triangles = 10,
         .instances = 5,
         .textures = 1,
         .warnings = 1},
        {.file = "simple_skin/simple_skin.gltf", .meshes = 1, .triangles = 8, .instances = 1},
        {.file = "textureTransform/TextureTransformTest.gltf",
         .meshes = 9,
         .triangles = 24,
         .instances = 12,
         .textures = 5},
        {.file = "wrongTypes/badArray.gltf", .error = "meshes[0].primitives: expected an array, got an object"},
        {.file = "wrongTypes/badExtension.gltf",
         .error = "materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform: expected an "
                  "object, got string \"Not an object\""},
        {.file = "wrongTypes/badNumber.gltf",
         .error = "materials[0].normalTexture.scale: expected a number, got string \"not a number\""},
        {.file = "wrongTypes/badObject.gltf",
         .error = "materials[0].pbrMetallicRoughness: expected an object, got an array"},
        {.file = "wrongTypes/badString.gltf", .error = "scenes[0].name: expected a string, got 42"},
        {.file = "wrongTypes/badUint.gltf",
         .error = "materials[0].pbrMetallicRoughness.baseColorTexture.index: expected a non-negative integer below "
                  "2^31, got -1"},
    };
    return cases;
}

TEST(GltfAssimpModelsTest, TheTableListsExactlyTheFilesOfTheFolder) {
    std::set<std::string> onDisk;
    for (const auto& entry : fs::recursive_directory_iterator(FRUGAL_ASSIMP_GLTF2_DIR)) {
        const std::string ext = entry.path().extension().string();
        if (ext == ".gltf" || ext == ".glb")
            onDisk.insert(fs::relative(entry.path(), FRUGAL_ASSIMP_GLTF2_DIR).generic_string());
    }
    std::set<std::string> listed;
    for (const AssimpCase& c : assimpCases()) EXPECT_TRUE(listed.insert(c.file).second) << "listed twice: " << c.file;
    EXPECT_EQ(onDisk, listed);
    EXPECT_EQ(listed.size(), 46u);
}

void PrintTo(const AssimpCase& c, std::ostream* out) { *out << c.file; }

class GltfAssimpModel : public testing::TestWithParam<AssimpCase> {};

TEST_P(GltfAssimpModel, LoadsOrFailsAsExpected) {
    const AssimpCase& c = GetParam();
    const std::string path = std::string(FRUGAL_ASSIMP_GLTF2_DIR) + "/" + c.file;
    const Result<Scene> scene = loadGltf(path);
    if (c.error) {
        ASSERT_FALSE(scene.ok()) << path << " loaded";
        EXPECT_EQ(scene.error().message, path + ": " + c.error);
        return;
    }
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->meshes.size(), c.meshes);
    EXPECT_EQ(scene->triangleCount(), c.triangles);
    std::size_t segments = 0, points = 0;
    for (const Mesh& mesh : scene->meshes) {
        if (mesh.topology == Topology::Lines) segments += mesh.primitiveCount();
        if (mesh.topology == Topology::Points) points += mesh.primitiveCount();
    }
    EXPECT_EQ(segments, c.segments);
    EXPECT_EQ(points, c.points);
    EXPECT_EQ(scene->instances.size(), c.instances);
    EXPECT_EQ(scene->textures.size(), c.textures);
    EXPECT_EQ(scene->cameras.size(), c.cameras);
    EXPECT_EQ(scene->warnings.size(), c.warnings) << (scene->warnings.empty() ? "" : scene->warnings[0]);
    EXPECT_EQ(std::multiset<std::string>(scene->unsupported.begin(), scene->unsupported.end()),
              std::multiset<std::string>(c.unsupported.begin(), c.unsupported.end()));
    EXPECT_EQ(scene->source, path);
    for (const Mesh& mesh : scene->meshes) {
        if (mesh.triangles()) {
            EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
        }
        ASSERT_LT(mesh.material, int(scene->materials.size()));
        if (mesh.material >= 0 && scene->materials[std::size_t(mesh.material)].baseColorTexture >= 0) {
            EXPECT_EQ(mesh.uvs.size(), mesh.positions.size()) << "a textured mesh without uvs";
        }
        EXPECT_EQ(mesh.triangleSource.size(), mesh.primitiveCount());
        for (std::uint32_t index : mesh.indices) ASSERT_LT(index, mesh.positions.size());
        if (!c.facesPlusZ) continue;
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                            d = mesh.positions[mesh.indices[3 * t + 2]];
            EXPECT_GT(glm::cross(b - a, d - a).z, 0.0f) << "triangle " << t << " is clockwise seen from +z";
        }
    }
}

INSTANTIATE_TEST_SUITE_P(AllFiles, GltfAssimpModel, testing::ValuesIn(assimpCases()),
                         [](const testing::TestParamInfo<AssimpCase>& param) {
                             std::string name = fs::path(param.param.file).parent_path().filename().string() + "_" +
                                                fs::path(param.param.file).stem().string();
                             for (char& ch : name)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return name;
                         });

TEST(GltfAssimpModelsTest, TexturedBoxHasItsImageSamplerAndUvs) {
    const Result<Scene> scene = loadGltf(std::string(FRUGAL_ASSIMP_GLTF2_DIR) + "/BoxTextured-glTF/BoxTextured.gltf");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->textures.size(), 1u);
    const Texture& texture = scene->textures[0];
    EXPECT_EQ(texture.width, 211);  // CesiumLogoFlat.png
    EXPECT_EQ(texture.height, 211);
    EXPECT_EQ(texture.rgba.size(), 211u * 211u * 4u);
    EXPECT_EQ(texture.wrapS, Wrap::MirroredRepeat);  // sampler: wrapS 33648, wrapT 33071
    EXPECT_EQ(texture.wrapT, Wrap::ClampToEdge);
    EXPECT_EQ(texture.filter, Filter::Linear);      // magFilter 9729
    EXPECT_EQ(texture.minFilter, Filter::Nearest);  // minFilter 9986, NEAREST_MIPMAP_LINEAR
    EXPECT_EQ(texture.mipmaps, MipFilter::Linear);
    ASSERT_EQ(scene->materials.size(), 1u);
    EXPECT_EQ(scene->materials[0].baseColorTexture, 0);
    EXPECT_EQ(scene->meshes[0].uvs.size(), scene->meshes[0].positions.size());
}

TEST(GltfAssimpModelsTest, APrimitiveWithoutTheUvsOfItsTextureGetsAnUntexturedMaterial) {
    const std::string path = std::string(FRUGAL_ASSIMP_GLTF2_DIR) + "/issue_3269/texcoord_crash.gltf";
    const Result<Scene> scene = loadGltf(path);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    // Mesh 0 ("TopRightMesh") has only TEXCOORD_1; its material 4 ("TopRightMat") samples TEXCOORD_0.
    ASSERT_EQ(scene->materials.size(), 6u);
    EXPECT_EQ(scene->materials[5].name, "TopRightMat (untextured)");
    EXPECT_EQ(scene->materials[5].baseColorTexture, -1);
    EXPECT_EQ(scene->materials[5].baseColorFactor, scene->materials[4].baseColorFactor);
    EXPECT_EQ(scene->materials[4].baseColorTexture, 0);
    EXPECT_EQ(scene->meshes[0].name, "TopRightMesh");
    EXPECT_EQ(scene->meshes[0].material, 5);
    EXPECT_TRUE(scene->meshes[0].uvs.empty());
    EXPECT_EQ(scene->meshes[1].material, 3);
    EXPECT_EQ(scene->warnings,
              (std::vector<std::string>{path + ": mesh 0 primitive 0: material 4 samples its textures "
                                               "with TEXCOORD_0, which the primitive lacks: "
                                               "drawn untextured"}));
}

// ---------------------------------------------------------------------------------------------
// One hand-written file per validation rule, with the exact message.

struct BadCase {
    const char* name;
    std::function<void(Asset&)> mutate;
    std::string error;  // after "<path>: "
};

std::vector<BadCase> badCases() {
    return {
        {"IndexOutOfRange",
         [](Asset& a) {
             a.accessor(bytesOf<std::uint16_t>({0, 1, 4}), kUShort, "SCALAR", 3);
             a.primitive()["indices"] = 2;
         },
         "accessor 2 (indices of mesh 0 primitive 0): index 4 out of range, mesh has 4 vertices"},
        {"BufferViewOutsideBuffer", [](Asset& a) { a.json["bufferViews"][1]["byteLength"] = 16; },
         "bufferViews[1]: byteOffset 48 + byteLength 16 is beyond the end of buffer 0 (60 bytes)"},
        {"AccessorOutsideBufferView", [](Asset& a) { a.json["accessors"][0]["count"] = 5; },
         "accessor 0 (POSITION of mesh 0 primitive 0): 5 elements of 12 bytes (stride 12) from byteOffset 0 need 60 "
         "bytes, bufferView 0 has 48"},
        {"AccessorByteOffsetPastView", [](Asset& a) { a.json["accessors"][0]["byteOffset"] = 4; },
         "accessor 0 (POSITION of mesh 0 primitive 0): 4 elements of 12 bytes (stride 12) from byteOffset 4 need 52 "
         "bytes, bufferView 0 has 48"},
        {"AccessorCountTimesStrideOverflows",
         [](Asset& a) { a.json["accessors"][0]["count"] = std::uint64_t(1) << 61; },
         "accessor 0 (POSITION of mesh 0 primitive 0): count 2305843009213693952 x stride 12 overflows"},
        {"AccessorCountZero", [](Asset& a) { a.json["accessors"][0]["count"] = 0; },
         "accessor 0 (POSITION of mesh 0 primitive 0): count must be at least 1"},
        {"ByteStrideSmallerThanElement", [](Asset& a) { a.json["bufferViews"][0]["byteStride"] = 8; },
         "accessor 0 (POSITION of mesh 0 primitive 0): bufferView 0 byteStride 8 is smaller than the 12-byte element"},
        {"ByteStrideNotMultipleOf4", [](Asset& a) { a.json["bufferViews"][0]["byteStride"] = 6; },
         "bufferViews[0].byteStride: 6 is not a multiple of 4 between 4 and 252"},
        {"WrongAccessorType",
         [](Asset& a) {
             a.json["accessors"][0]["type"] = "VEC2";
             a.json["accessors"][0]["count"] = 6;
         },
         "accessor 0 (POSITION of mesh 0 primitive 0): type VEC2, expected VEC3"},
        {"FloatIndices",
         [](Asset& a) {
             a.accessor(bytesOf<float>({0, 1, 2}), kFloat, "SCALAR", 3);
             a.primitive()["indices"] = 2;
         },
         "accessor 2 (indices of mesh 0 primitive 0): component type FLOAT is not allowed here"},
        {"AttributeCountMismatch",
         [](Asset& a) {
             a.primitive()["attributes"]["NORMAL"] =
                 a.accessor(bytesOf<float>({0, 0, 1, 0, 0, 1, 0, 0, 1}), kFloat, "VEC3", 3);
         },
         "accessor 2 (NORMAL of mesh 0 primitive 0): 3 elements, POSITION has 4"},
        {"TrianglesNotMultipleOf3", [](Asset& a) { a.json["accessors"][1]["count"] = 5; },
         "mesh 0 primitive 0: TRIANGLES with 5 vertices, which is not a multiple of 3"},
        {"NodeCycle",
         [](Asset& a) {
             a.json["nodes"] = {{{"mesh", 0}}, {{"children", {2}}}, {{"children", {3}}}, {{"children", {1}}}};
         },
         "nodes form a cycle: 1 -> 2 -> 3 -> 1"},
        {"NodeIsItsOwnChild", [](Asset& a) { a.json["nodes"][0]["children"] = {0}; },
         "nodes[0].children[0]: node 0 is its own child"},
        {"NodeWithTwoParents",
         [](Asset& a) {
             a.json["nodes"] = {{{"children", {2}}}, {{"children", {2}}}, {{"mesh", 0}}};
             a.json["scenes"][0]["nodes"] = {0, 1};
         },
         "node 2 has two parents: node 0 and node 1"},
        {"ChildListedTwice",
         [](Asset& a) {
             a.json["nodes"] = {{{"children", {1, 1}}}, {{"mesh", 0}}};
         },
         "nodes[0].children: node 1 is listed twice"},
        {"SceneListsAChild",
         [](Asset& a) {
             a.json["nodes"] = {{{"children", {1}}}, {{"mesh", 0}}};
             a.json["scenes"][0]["nodes"] = {0, 1};
         },
         "scenes[0].nodes[1]: node 1 is not a root, it is a child of node 0"},
        {"SceneListsANodeTwice",
         [](Asset& a) {
             a.json["scenes"][0]["nodes"] = {0, 0};
         },
         "scenes[0].nodes: node 0 is listed twice"},
        {"SceneOutOfRange", [](Asset& a) { a.json["scene"] = 1; }, "scene: scene 1 out of range, the file has 1 scene"},
        {"SceneNodeOutOfRange", [](Asset& a) { a.json["scenes"][0]["nodes"] = {3}; },
         "scenes[0].nodes[0]: node 3 out of range, the file has 1 node"},
        {"ChildOutOfRange", [](Asset& a) { a.json["nodes"][0]["children"] = {1}; },
         "nodes[0].children[0]: node 1 out of range, the file has 1 node"},
        {"MeshOutOfRange", [](Asset& a) { a.json["nodes"][0]["mesh"] = 2; },
         "nodes[0].mesh: mesh 2 out of range, the file has 1 mesh"},
        {"CameraOutOfRange", [](Asset& a) { a.json["nodes"][0]["camera"] = 0; },
         "nodes[0].camera: camera 0 out of range, the file has 0 cameras"},
        {"SkinOutOfRange", [](Asset& a) { a.json["nodes"][0]["skin"] = 0; },
         "nodes[0].skin: skin 0 out of range, the file has 0 skins"},
        {"MaterialOutOfRange", [](Asset& a) { a.primitive()["material"] = 0; },
         "meshes[0].primitives[0].material: material 0 out of range, the file has 0 materials"},
        {"AttributeAccessorOutOfRange", [](Asset& a) { a.primitive()["attributes"]["NORMAL"] = 9; },
         "meshes[0].primitives[0].attributes.NORMAL: accessor 9 out of range, the file has 2 accessors"},
        {"IndicesAccessorOutOfRange", [](Asset& a) { a.primitive()["indices"] = 2; },
         "meshes[0].primitives[0].indices: accessor 2 out of range, the file has 2 accessors"},
        {"AccessorBufferViewOutOfRange", [](Asset& a) { a.json["accessors"][0]["bufferView"] = 5; },
         "accessors[0].bufferView: bufferView 5 out of range, the file has 2 bufferViews"},
        {"BufferOutOfRange", [](Asset& a) { a.json["bufferViews"][0]["buffer"] = 1; },
         "bufferViews[0].buffer: buffer 1 out of range, the file has 1 buffer"},
        {"TextureOutOfRange",
         [](Asset& a) {
             a.json["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
         },
         "materials[0].pbrMetallicRoughness.baseColorTexture.index: texture 0 out of range, the file has 0 textures"},
        {"NormalTextureOutOfRange",
         [](Asset& a) {
             a.json["materials"] = {{{"normalTexture", {{"index", 3}}}}};
         },
         "materials[0].normalTexture.index: texture 3 out of range, the file has 0 textures"},
        {"ImageOutOfRange",
         [](Asset& a) {
             a.json["textures"] = {{{"source", 0}}};
         },
         "textures[0].source: image 0 out of range, the file has 0 images"},
        {"SamplerOutOfRange",
         [](Asset& a) {
             a.json["textures"] = {{{"sampler", 1}}};
             a.json["samplers"] = Json::array({Json::object()});
         },
         "textures[0].sampler: sampler 1 out of range, the file has 1 sampler"},
        {"ImageBufferViewOutOfRange",
         [](Asset& a) {
             a.json["images"] = {{{"bufferView", 2}, {"mimeType", "image/png"}}};
         },
         "images[0].bufferView: bufferView 2 out of range, the file has 2 bufferViews"},
        {"ImageWithoutSource", [](Asset& a) { a.json["images"] = Json::array({Json::object()}); },
         "images[0]: has neither uri nor bufferView"},
        {"AnimationChannelNodeOutOfRange",
         [](Asset& a) {
             a.json["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"node", 4}, {"path", "rotation"}}}}}},
                                      {"samplers", {{{"input", 0}, {"output", 0}}}}}};
         },
         "animations[0].channels[0].target.node: node 4 out of range, the file has 1 node"},
        {"AnimationChannelSamplerOutOfRange",
         [](Asset& a) {
             a.json["animations"] = {{{"channels", {{{"sampler", 1}, {"target", {{"node", 0}, {"path", "rotation"}}}}}},
                                      {"samplers", {{{"input", 0}, {"output", 0}}}}}};
         },
         "animations[0].channels[0].sampler: sampler 1 out of range, the file has 1 sampler"},
        {"AnimationInputOutOfRange",
         [](Asset& a) {
             a.json["animations"] = {{{"channels", Json::array()}, {"samplers", {{{"input", 7}, {"output", 0}}}}}};
         },
         "animations[0].samplers[0].input: accessor 7 out of range, the file has 2 accessors"},
        {"SkinJointOutOfRange",
         [](Asset& a) {
             a.json["skins"] = {{{"joints", {0, 5}}}};
         },
         "skins[0].joints[1]: node 5 out of range, the file has 1 node"},
        {"KeyTimesNotIncreasing",
         [](Asset& a) {
             const int in = a.accessor(bytesOf<float>({0, 1, 1}), kFloat, "SCALAR", 3);
             const int out = a.accessor(bytesOf<float>({0, 0, 0, 1, 0, 0, 2, 0, 0}), kFloat, "VEC3", 3);
             a.json["animations"] = {
                 {{"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}},
                  {"samplers", {{{"input", in}, {"output", out}}}}}};
         },
         "animation 0 sampler 0: key times must increase, time 2 (1) follows 1"},
        {"KeyTimeNotFinite",
         [](Asset& a) {
             const int in = a.accessor(bytesOf<float>({0, INFINITY}), kFloat, "SCALAR", 2);
             const int out = a.accessor(bytesOf<float>({0, 0, 0, 1, 0, 0}), kFloat, "VEC3", 2);
             a.json["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "scale"}}}}}},
                                      {"samplers", {{{"input", in}, {"output", out}}}}}};
         },
         "animation 0 sampler 0: key time 1 is not finite"},
        {"KeyTimesNotFloat",
         [](Asset& a) {
             const int in = a.accessor(bytesOf<std::uint8_t>({0, 1}), kUByte, "SCALAR", 2, true);
             const int out = a.accessor(bytesOf<float>({0, 0, 0, 1, 0, 0}), kFloat, "VEC3", 2);
             a.json["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "scale"}}}}}},
                                      {"samplers", {{{"input", in}, {"output", out}}}}}};
         },
         "accessor 2 (input of animation 0 sampler 0): component type UNSIGNED_BYTE is not allowed here"},
        {"OutputCountMismatch",
         [](Asset& a) {
             const int in = a.accessor(bytesOf<float>({0, 1, 2}), kFloat, "SCALAR", 3);
             const int out = a.accessor(bytesOf<float>({0, 0, 0, 1, 0, 0}), kFloat, "VEC3", 2);
             a.json["animations"] = {
                 {{"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}},
                  {"samplers", {{{"input", in}, {"output", out}}}}}};
         },
         "animation 0 sampler 0: output has 2 elements, expected 3 (one per key)"},
        {"CubicOutputCountMismatch",
         [](Asset& a) {
             const int in = a.accessor(bytesOf<float>({0, 1}), kFloat, "SCALAR", 2);
             const int out = a.accessor(bytesOf<float>({0, 0, 0, 1, 0, 0}), kFloat, "VEC3", 2);
             a.json["animations"] = {
                 {{"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}},
                  {"samplers", {{{"input", in}, {"output", out}, {"interpolation", "CUBICSPLINE"}}}}}};
         },
         "animation 0 sampler 0: output has 2 elements, expected 6 (3 per key, CUBICSPLINE)"},
        {"RotationOutputNotVec4",
         [](Asset& a) {
             const int in = a.accessor(bytesOf<float>({0, 1}), kFloat, "SCALAR", 2);
             const int out = a.accessor(bytesOf<float>({0, 0, 0, 1, 0, 0}), kFloat, "VEC3", 2);
             a.json["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "rotation"}}}}}},
                                      {"samplers", {{{"input", in}, {"output", out}}}}}};
         },
         "accessor 3 (output of animation 0 sampler 0): type VEC3, expected VEC4"},
        {"AnimatedNodeWithMatrix",
         [](Asset& a) {
             a.json["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
             a.json["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "scale"}}}}}},
                                      {"samplers", {{{"input", 0}, {"output", 0}}}}}};
         },
         "animations[0].channels[0].target.node: node 0 has a matrix, but glTF animates only nodes with "
         "translation/rotation/scale"},
        {"WrongTypedField", [](Asset& a) { a.json["nodes"][0]["mesh"] = "0"; },
         "nodes[0].mesh: expected a non-negative integer below 2^31, got string \"0\""},
        {"FractionalIndex", [](Asset& a) { a.json["nodes"][0]["mesh"] = 0.5; },
         "nodes[0].mesh: expected a non-negative integer below 2^31, got 0.5"},
        {"WrongArrayLength",
         [](Asset& a) {
             a.json["nodes"][0]["translation"] = {1, 2};
         },
         "nodes[0].translation: expected 3 numbers, got 2"},
        {"WrongTypedArrayElement",
         [](Asset& a) {
             a.json["nodes"][0]["scale"] = {1, "2", 3};
         },
         "nodes[0].scale[1]: expected a number, got string \"2\""},
        {"WrongTypedBoolean",
         [](Asset& a) {
             a.json["materials"] = {{{"doubleSided", 1}}};
         },
         "materials[0].doubleSided: expected true or false, got 1"},
        {"NotAnObjectInArray", [](Asset& a) { a.json["nodes"][0] = 3; }, "nodes[0]: expected an object, got 3"},
        {"MissingRequiredProperty", [](Asset& a) { a.json["accessors"][1].erase("count"); },
         "accessors[1]: missing required property 'count'"},
        {"MissingAsset", [](Asset& a) { a.json.erase("asset"); }, "glTF root: missing required property 'asset'"},
        {"BadComponentType", [](Asset& a) { a.json["accessors"][1]["componentType"] = 5124; },
         "accessors[1].componentType: 5124 is not one of 5120, 5121, 5122, 5123, 5125, 5126"},
        {"BadAccessorType", [](Asset& a) { a.json["accessors"][1]["type"] = "VEC5"; },
         "accessors[1].type: \"VEC5\" is not one of SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3, MAT4"},
        {"BadMode", [](Asset& a) { a.primitive()["mode"] = 7; },
         "meshes[0].primitives[0].mode: 7 is not one of 0, 1, 2, 3, 4, 5, 6"},
        {"BadWrap",
         [](Asset& a) {
             a.json["samplers"] = {{{"wrapS", 10496}}};
         },
         "samplers[0].wrapS: 10496 is not one of 33071, 33648, 10497"},
        {"BadAlphaMode",
         [](Asset& a) {
             a.json["materials"] = {{{"alphaMode", "opaque"}}};
         },
         "materials[0].alphaMode: \"opaque\" is not one of OPAQUE, MASK, BLEND"},
        {"ExtensionNotAnObject",
         [](Asset& a) {
             a.json["nodes"][0]["extensions"] = {{"EXT_foo", 1}};
         },
         "nodes[0].extensions.EXT_foo: expected an object, got 1"},
        {"NameNotAString", [](Asset& a) { a.json["meshes"][0]["name"] = Json::array(); },
         "meshes[0].name: expected a string, got an array"},
        {"GltfVersion1", [](Asset& a) { a.json["asset"]["version"] = "1.0"; },
         "asset.version: glTF 1.0 is not supported (2.x only)"},
        {"MinVersionTooNew", [](Asset& a) { a.json["asset"]["minVersion"] = "2.1"; },
         "asset.minVersion: the file needs glTF 2.1, frugal reads 2.0"},
        {"TranslationOverflowsFloat",
         [](Asset& a) {
             a.json["nodes"][0]["translation"] = {1e39, 0, 0};
         },
         "nodes[0].translation[0]: 1e+39 does not fit a float"},
        {"ZeroQuaternion",
         [](Asset& a) {
             a.json["nodes"][0]["rotation"] = {0, 0, 0, 0};
         },
         "nodes[0].rotation: not a unit quaternion (length 0)"},
        {"CameraWithoutItsObject",
         [](Asset& a) {
             a.json["cameras"] = {{{"type", "perspective"}}};
         },
         "cameras[0]: type perspective but no 'perspective' object"},
        {"CameraZeroFov",
         [](Asset& a) {
             a.json["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0}, {"znear", 0.1}}}}};
         },
         "cameras[0].perspective.yfov: must be > 0, got 0"},
        {"CameraFarBeforeNear",
         [](Asset& a) {
             a.json["cameras"] = {
                 {{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 2}, {"zfar", 1}}}}};
         },
         "cameras[0].orthographic.zfar: must be greater than znear 2, got 1"},
        {"SparseIndexOutOfRange",
         [](Asset& a) {
             a.accessor(bytesOf<std::uint16_t>({7, 0}), kUShort, "SCALAR", 2);
             a.json["accessors"][0]["sparse"] = {{"count", 1},
                                                 {"indices", {{"bufferView", 2}, {"componentType", kUShort}}},
                                                 {"values", {{"bufferView", 0}}}};
         },
         "accessor 0 (POSITION of mesh 0 primitive 0): sparse index 7 out of range, the accessor has 4 elements"},
        {"SparseIndicesNotIncreasing",
         [](Asset& a) {
             a.accessor(bytesOf<std::uint16_t>({2, 1}), kUShort, "SCALAR", 2);
             a.json["accessors"][0]["sparse"] = {{"count", 2},
                                                 {"indices", {{"bufferView", 2}, {"componentType", kUShort}}},
                                                 {"values", {{"bufferView", 0}}}};
         },
         "accessor 0 (POSITION of mesh 0 primitive 0): sparse indices must increase, 1 follows 2"},
        {"SparseCountTooLarge",
         [](Asset& a) {
             a.json["accessors"][0]["sparse"] = {{"count", 5},
                                                 {"indices", {{"bufferView", 1}, {"componentType", kUShort}}},
                                                 {"values", {{"bufferView", 0}}}};
         },
         "accessor 0 (POSITION of mesh 0 primitive 0): sparse count 5 outside [1, 4]"},
        {"DracoStreamThatIsNot",
         [](Asset& a) {
             a.json["accessors"][0].erase("bufferView");
             a.primitive()["extensions"] = {
                 {"KHR_draco_mesh_compression", {{"bufferView", 0}, {"attributes", {{"POSITION", 0}}}}}};
             a.json["extensionsRequired"] = {"KHR_draco_mesh_compression"};
         },
         "mesh 0 primitive 0: KHR_draco_mesh_compression: the 48-byte stream does not decode (Draco: Not a Draco "
         "file.)"},
        {"IndicesWithoutBufferView", [](Asset& a) { a.json["accessors"][1].erase("bufferView"); },
         "meshes[0].primitives[0].indices: accessor 1 has no bufferView, which frugal does not support for indices"},
    };
}

void PrintTo(const BadCase& c, std::ostream* out) { *out << c.name; }

class GltfBadFile : public testing::TestWithParam<BadCase> {};

TEST_P(GltfBadFile, FailsWithTheExactMessage) {
    const BadCase& c = GetParam();
    Asset asset = quad();
    c.mutate(asset);
    const std::string path = writeGltf(test::freshDir(std::string("GltfBadFile_") + c.name), "bad", asset);
    const Result<Scene> scene = load(path);
    ASSERT_FALSE(scene.ok()) << c.name << " loaded";
    EXPECT_EQ(scene.error().message, path + ": " + c.error);
    EXPECT_EQ(scene.error().message.find('\n'), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Rules, GltfBadFile, testing::ValuesIn(badCases()),
                         [](const testing::TestParamInfo<BadCase>& param) { return std::string(param.param.name); });

TEST(GltfLoaderTest, TheUnmodifiedTestQuadLoadsInEveryContainer) {
    const fs::path dir = test::freshDir("GltfQuadContainers");
    for (const std::string& path : {writeGltf(dir, "external", quad()), writeEmbedded(dir, "embedded", quad()),
                                    writeGlb(dir, "binary", quad())}) {
        const Result<Scene> scene = load(path);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        ASSERT_EQ(scene->meshes.size(), 1u);
        EXPECT_EQ(scene->meshes[0].name, "quad");
        EXPECT_EQ(scene->meshes[0].indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
        EXPECT_EQ(scene->meshes[0].triangleSource, (std::vector<std::uint32_t>{0, 1}));
        EXPECT_EQ(scene->instances.size(), 1u);
        EXPECT_TRUE(scene->unsupported.empty());
        EXPECT_TRUE(scene->warnings.empty());
    }
}

TEST(GltfLoaderTest, FileProblemsAreReported) {
    const fs::path dir = test::freshDir("GltfFileProblems");
    struct Case {
        std::string file, contents, error;
    };
    const std::vector<Case> cases = {
        {"empty.gltf", "", "file is empty"},
        {"garbage.gltf", "xyz",
         "invalid JSON: parse error at line 1, column 1: syntax error while parsing value - invalid literal; last "
         "read: 'x'"},
        {"binary-garbage.gltf", std::string("\xff\xfe\x00\x01", 4),
         "invalid JSON: parse error at line 1, column 1: syntax error while parsing value - invalid literal; last "
         "read: '?'"},
        {"array.gltf", "[1, 2]", "the JSON root is an array, expected an object"},
        {"unterminated.gltf", "{\"asset\": {\"version\": \"2.0\"}",
         "invalid JSON: parse error at line 1, column 29: syntax error while parsing object - unexpected end of input; "
         "expected '}'"},
        {"deep.gltf", "{\"extras\": " + std::string(300, '[') + std::string(300, ']') + "}",
         "JSON nested deeper than 256 levels (at byte 266)"},
        {"short.glb", "glTF", "truncated GLB: 4 bytes, the header alone needs 12"},
        {"magic.glb", std::string("glTX\x02\0\0\0\x0c\0\0\0", 12),
         "not a binary glTF file (the first 4 bytes are not 'glTF')"},
        {"version.glb", std::string("glTF\x01\0\0\0\x0c\0\0\0", 12), "GLB container version 1, frugal reads version 2"},
        {"nochunk.glb", std::string("glTF\x02\0\0\0\x0c\0\0\0", 12), "GLB has no JSON chunk"},
        {"long.glb", std::string("glTF\x02\0\0\0\x0c\0\0\0", 12) + "xx",
         "GLB header declares 12 bytes but the file has 14"},
        {"binchunk.glb", std::string("glTF\x02\0\0\0\x18\0\0\0\x04\0\0\0BIN\0{}  ", 24),
         "GLB chunk 0 is not the JSON chunk (type 0x4e4942)"},
    };
    for (const Case& c : cases) {
        test::writeFile(dir / c.file, c.contents);
        const std::string path = (dir / c.file).string();
        const Result<Scene> scene = loadGltf(path);
        ASSERT_FALSE(scene.ok()) << c.file;
        EXPECT_EQ(scene.error().message, path + ": " + c.error);
    }
    EXPECT_EQ(loadGltf((dir / "missing.gltf").string()).error().message, (dir / "missing.gltf").string() + ": no such file");
    EXPECT_EQ(loadGltf(dir.string()).error().message, dir.string() + ": is a directory, not a file");
}

TEST(GltfLoaderTest, BufferProblemsAreReportedWithTheirSizes) {
    const fs::path dir = test::freshDir("GltfBufferProblems");
    const std::string path = writeGltf(dir, "short", quad());
    test::writeFile(dir / "short.bin", quad().bin.substr(0, 50));
    EXPECT_EQ(load(path).error().message, path + ": buffers[0].uri: 'short.bin' has 50 bytes, byteLength says 60");

    Asset embedded = quad();
    embedded.json["buffers"] = {
        {{"byteLength", 64}, {"uri", "data:application/octet-stream;base64," + base64(embedded.bin)}}};
    test::writeFile(dir / "embedded.gltf", embedded.json.dump());
    EXPECT_EQ(load((dir / "embedded.gltf").string()).error().message,
              (dir / "embedded.gltf").string() + ": buffers[0].uri: the data URI holds 60 bytes, byteLength says 64");

    Asset noUri = quad();
    noUri.json["buffers"] = {{{"byteLength", 60}}};
    test::writeFile(dir / "nouri.gltf", noUri.json.dump());
    EXPECT_EQ(load((dir / "nouri.gltf").string()).error().message,
              (dir / "nouri.gltf").string() + ": buffers[0]: no uri (only buffer 0 of a .glb may use the BIN chunk)");

    // A .glb whose buffer claims more bytes than its BIN chunk holds.
    Asset big = quad();
    std::string glb = glbBytes(big);
    const std::string declared = "\"byteLength\":60";
    glb.replace(glb.find(declared), declared.size(), "\"byteLength\":64");
    test::writeFile(dir / "big.glb", glb);
    EXPECT_EQ(load((dir / "big.glb").string()).error().message,
              (dir / "big.glb").string() + ": buffers[0]: byteLength 64 exceeds the GLB BIN chunk (60 bytes)");
}

TEST(GltfLoaderTest, EveryTruncatedPrefixOfAGlbFailsCleanly) {
    Asset asset = quad();
    asset.json["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    asset.json["textures"] = {{{"source", 0}}};
    const std::string image = png(2, 1, 6, 8, "\x10\x20\x30\x40\x50\x60\x70\x80");
    asset.json["images"] = {{{"bufferView", 2}, {"mimeType", "image/png"}}};
    asset.accessor(image, kUByte, "SCALAR", image.size());  // only for its bufferView
    asset.primitive()["material"] = 0;
    asset.primitive()["attributes"]["TEXCOORD_0"] =
        asset.accessor(bytesOf<float>({0, 0, 1, 0, 1, 1, 0, 1}), kFloat, "VEC2", 4);
    const std::string bytes = glbBytes(asset);
    const fs::path dir = test::freshDir("GltfTruncatedGlb");
    const fs::path file = dir / "prefix.glb";
    const std::string path = file.string();

    test::writeFile(file, bytes);
    const Result<Scene> whole = load(path);
    ASSERT_TRUE(whole.ok()) << whole.error().message;
    ASSERT_EQ(whole->textures.size(), 1u);

    for (std::size_t length = 0; length < bytes.size(); ++length) {
        test::writeFile(file, bytes.substr(0, length));
        const Result<Scene> scene = load(path);
        ASSERT_FALSE(scene.ok()) << "prefix of " << length << " bytes loaded";
        ASSERT_EQ(scene.error().message.rfind(path + ": ", 0), 0u) << scene.error().message;
        ASSERT_EQ(scene.error().message.find('\n'), std::string::npos) << scene.error().message;
    }
    test::writeFile(file, bytes.substr(0, 7));
    EXPECT_EQ(load(path).error().message, path + ": truncated GLB: 7 bytes, the header alone needs 12");
    test::writeFile(file, bytes.substr(0, 100));
    EXPECT_EQ(load(path).error().message, path + ": truncated GLB: the header declares " + std::to_string(bytes.size()) +
                                      " bytes, the file has 100");
}

TEST(GltfLoaderTest, GlbWithUnalignedChunksAndAnExtraChunkIsRepacked) {
    Asset asset = quad();
    asset.json["buffers"] = {{{"byteLength", asset.bin.size()}}};
    const std::string json = asset.json.dump();  // not padded to 4 bytes
    auto u32 = [](std::size_t v) { return bytesOf<std::uint32_t>({std::uint32_t(v)}); };
    const std::string extra = u32(3) + "XTRA" + "abc";  // an unknown chunk type, ignored by the spec
    const std::string body =
        u32(json.size()) + "JSON" + json + u32(asset.bin.size()) + std::string("BIN\0", 4) + asset.bin + extra;
    const fs::path dir = test::freshDir("GltfRepackedGlb");
    test::writeFile(dir / "loose.glb", "glTF" + u32(2) + u32(12 + body.size()) + body);
    const Result<Scene> scene = load((dir / "loose.glb").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->triangleCount(), 2u);
}

// ---------------------------------------------------------------------------------------------
// Round trips: what the file says is what the Scene holds.

void expectNear(const glm::vec3& a, const glm::vec3& b) {
    EXPECT_NEAR(a.x, b.x, 1e-5f);
    EXPECT_NEAR(a.y, b.y, 1e-5f);
    EXPECT_NEAR(a.z, b.z, 1e-5f);
}

TEST(GltfLoaderTest, NodeHierarchyAndTransformsRoundTrip) {
    Asset asset = quad();
    // Node 2 is listed before its parent 1 on purpose; node 3 is outside the scene.
    const double s = std::sqrt(0.5);
    asset.json["nodes"] = {
        {{"name", "root"}, {"children", {2}}, {"translation", {1, 2, 3}}},
        {{"name", "leaf"}, {"mesh", 0}, {"scale", {2, 2, 2}}},
        {{"name", "middle"}, {"children", {1}}, {"rotation", {0, 0, s, s}}},  // 90° about +z
        {{"name", "elsewhere"}, {"mesh", 0}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1}}},
    };
    const std::string path = writeGltf(test::freshDir("GltfHierarchy"), "tree", asset);
    const Result<Scene> scene = load(path);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->nodes.size(), 4u);
    EXPECT_EQ(scene->roots, (std::vector<int>{0}));
    EXPECT_EQ(scene->nodes[0].name, "root");
    EXPECT_EQ(scene->nodes[0].parent, -1);
    EXPECT_EQ(scene->nodes[2].parent, 0);
    EXPECT_EQ(scene->nodes[1].parent, 2);
    EXPECT_EQ(scene->nodes[2].children, (std::vector<int>{1}));
    EXPECT_FALSE(scene->nodes[0].hasMatrix);
    expectNear(scene->nodes[0].translation, {1, 2, 3});
    EXPECT_NEAR(scene->nodes[2].rotation.w, s, 1e-6);
    EXPECT_NEAR(scene->nodes[2].rotation.z, s, 1e-6);
    expectNear(scene->nodes[1].scale, {2, 2, 2});
    EXPECT_TRUE(scene->nodes[3].hasMatrix);
    expectNear(glm::vec3(scene->nodes[3].matrix[3]), {5, 6, 7});  // column-major, like glTF
    // Only the node in the scene is instanced.
    EXPECT_EQ(scene->nodes[1].meshes, (std::vector<int>{0}));
    EXPECT_TRUE(scene->nodes[3].meshes.empty());
    ASSERT_EQ(scene->instances.size(), 1u);
    EXPECT_EQ(scene->instances[0].node, 1);

    // Leaf corner (1,0,0): scaled to (2,0,0), rotated to (0,2,0), translated to (1,4,3).
    const std::vector<glm::mat4> world = scene->worldTransforms(0.0);
    expectNear(glm::vec3(world[1] * glm::vec4(1, 0, 0, 1)), {1, 4, 3});
}

TEST(GltfLoaderTest, SceneChoiceDefaultSceneThenSceneZeroThenAllRoots) {
    Asset asset = quad();
    asset.json["nodes"] = {{{"mesh", 0}}, {{"mesh", 0}, {"translation", {2, 0, 0}}}, {{"mesh", 0}}};
    asset.json["scenes"] = {{{"nodes", {0}}}, {{"nodes", {1, 2}}}};
    asset.json["scene"] = 1;
    const fs::path dir = test::freshDir("GltfSceneChoice");
    Result<Scene> scene = load(writeGltf(dir, "default", asset));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->roots, (std::vector<int>{1, 2}));
    EXPECT_EQ(scene->instances.size(), 2u);

    asset.json.erase("scene");
    scene = load(writeGltf(dir, "first", asset));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->roots, (std::vector<int>{0}));
    EXPECT_EQ(scene->instances.size(), 1u);

    asset.json.erase("scenes");
    asset.json["nodes"][0]["children"] = {2};
    scene = load(writeGltf(dir, "none", asset));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->roots, (std::vector<int>{0, 1}));
    EXPECT_EQ(scene->instances.size(), 3u);
}

// A strip or fan of vertices in z = 0, non-indexed; every triangle must come out counter-clockwise.
Asset stripAsset(int mode, std::initializer_list<float> positions, std::size_t count) {
    Asset asset = quad();
    asset.json["accessors"] = Json::array();
    asset.json["bufferViews"] = Json::array();
    asset.bin.clear();
    const int position = asset.accessor(bytesOf<float>(positions), kFloat, "VEC3", count);
    asset.json["meshes"][0]["primitives"] = {{{"attributes", {{"POSITION", position}}}, {"mode", mode}}};
    return asset;
}

TEST(GltfLoaderTest, TriangleStripsAndFansKeepTheirWinding) {
    const fs::path dir = test::freshDir("GltfStripFan");
    // Strip with top row 0, 2, 4 and bottom row 1, 3 (spec: triangle i = i, i+1+i%2, i+2-i%2).
    const Result<Scene> strip =
        load(writeGltf(dir, "strip", stripAsset(5, {0, 1, 0, 0, 0, 0, 1, 1, 0, 1, 0, 0, 2, 1, 0}, 5)));
    ASSERT_TRUE(strip.ok()) << strip.error().message;
    const Mesh& s = strip->meshes[0];
    EXPECT_EQ(s.indices, (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2, 2, 3, 4}));
    EXPECT_EQ(s.triangleSource, (std::vector<std::uint32_t>{0, 1, 2}));
    // Fan around vertex 0 (spec: triangle i = i+1, i+2, 0).
    const Result<Scene> fan =
        load(writeGltf(dir, "fan", stripAsset(6, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 1, 0}, 5)));
    ASSERT_TRUE(fan.ok()) << fan.error().message;
    const Mesh& f = fan->meshes[0];
    EXPECT_EQ(f.indices, (std::vector<std::uint32_t>{1, 2, 0, 2, 3, 0, 3, 4, 0}));
    EXPECT_EQ(f.triangleSource, (std::vector<std::uint32_t>{0, 1, 2}));
    for (const Mesh* mesh : {&s, &f})
        for (std::size_t t = 0; t < mesh->triangleCount(); ++t) {
            const glm::vec3 a = mesh->positions[mesh->indices[3 * t]], b = mesh->positions[mesh->indices[3 * t + 1]],
                            c = mesh->positions[mesh->indices[3 * t + 2]];
            EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << "triangle " << t;
        }
    // Fewer than three vertices: no triangle, no error.
    const Result<Scene> tiny = load(writeGltf(dir, "tiny", stripAsset(5, {0, 0, 0, 1, 0, 0}, 2)));
    ASSERT_TRUE(tiny.ok()) << tiny.error().message;
    EXPECT_EQ(tiny->triangleCount(), 0u);
}

TEST(GltfLoaderTest, PointsAndLineModesBecomePointsAndSegments) {
    const fs::path dir = test::freshDir("GltfPointsLines");
    const auto loadMode = [&](const char* name, int mode, std::size_t count) {
        return load(writeGltf(dir, name, stripAsset(mode, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, count)));
    };
    struct Expect {
        const char* name;
        int mode;
        Topology topology;
        std::vector<std::uint32_t> indices;
    };
    // glTF's numbering of each mode's primitives (spec, "Topology types"): ids follow it.
    for (const Expect& e :
         {Expect{"points", 0, Topology::Points, {0, 1, 2, 3}}, Expect{"lines", 1, Topology::Lines, {0, 1, 2, 3}},
          Expect{"loop", 2, Topology::Lines, {0, 1, 1, 2, 2, 3, 3, 0}},
          Expect{"strip", 3, Topology::Lines, {0, 1, 1, 2, 2, 3}}}) {
        const Result<Scene> scene = loadMode(e.name, e.mode, 4);
        ASSERT_TRUE(scene.ok()) << e.name << ": " << scene.error().message;
        const Mesh& mesh = scene->meshes[0];
        EXPECT_EQ(mesh.topology, e.topology) << e.name;
        EXPECT_EQ(mesh.indices, e.indices) << e.name;
        EXPECT_EQ(mesh.primitiveCount(), e.indices.size() / verticesPerPrimitive(e.topology)) << e.name;
        EXPECT_EQ(mesh.triangleCount(), 0u) << e.name;
        std::vector<std::uint32_t> identity(mesh.primitiveCount());
        for (std::uint32_t i = 0; i < identity.size(); ++i) identity[i] = i;
        EXPECT_EQ(mesh.triangleSource, identity) << e.name;
        EXPECT_TRUE(mesh.normals.empty()) << e.name << ": no normals are made up for points and lines";
        EXPECT_TRUE(scene->unsupported.empty()) << e.name;
        // Ids: the instance's range is the primitive count.
        EXPECT_EQ(scene->instances[0].firstId, 1u);
    }
    // A strip or loop of one vertex has no segment; LINES of an odd count is a broken file.
    const Result<Scene> one = loadMode("one", 3, 1);
    ASSERT_TRUE(one.ok()) << one.error().message;
    EXPECT_EQ(one->meshes[0].primitiveCount(), 0u);
    const Result<Scene> odd = loadMode("odd", 1, 3);
    ASSERT_FALSE(odd.ok());
    EXPECT_NE(odd.error().message.find("mesh 0 primitive 0: LINES with 3 vertices, which is not a multiple of 2"),
              std::string::npos)
        << odd.error().message;
}

TEST(GltfLoaderTest, NormalizedIntegerAttributesFollowTheSpecFormulas) {
    Asset asset = quad();
    Json& attributes = asset.primitive()["attributes"];
    attributes["COLOR_0"] = asset.accessor(
        bytesOf<std::uint8_t>({255, 0, 128, 255, 0, 255, 0, 51, 1, 2, 3, 4, 10, 20, 30, 40}), kUByte, "VEC4", 4, true);
    attributes["NORMAL"] =
        asset.accessor(bytesOf<std::int8_t>({0, 0, 127, 0, 0, -127, 0, -128, 0, 127, 0, 0}), kByte, "VEC3", 4, true);
    asset.json["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", 1}}}}}}};
    asset.json["textures"] = {{{"source", 0}}};
    asset.json["images"] = {{{"uri", "missing.png"}}};
    asset.primitive()["material"] = 0;
    attributes["TEXCOORD_0"] = asset.accessor(bytesOf<float>({9, 9, 9, 9, 9, 9, 9, 9}), kFloat, "VEC2", 4);
    attributes["TEXCOORD_1"] =
        asset.accessor(bytesOf<std::uint16_t>({0, 65535, 32768, 0, 65535, 65535, 1, 2}), kUShort, "VEC2", 4, true);
    const Result<Scene> scene = load(writeGltf(test::freshDir("GltfNormalized"), "normalized", asset));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Mesh& mesh = scene->meshes[0];
    ASSERT_EQ(mesh.colors.size(), 4u);
    EXPECT_FLOAT_EQ(mesh.colors[0].r, 1.0f);
    EXPECT_FLOAT_EQ(mesh.colors[0].b, 128.0f / 255.0f);
    EXPECT_FLOAT_EQ(mesh.colors[1].a, 51.0f / 255.0f);
    ASSERT_EQ(mesh.normals.size(), 4u);
    expectNear(mesh.normals[0], {0, 0, 1});
    expectNear(mesh.normals[1], {0, 0, -1});
    expectNear(mesh.normals[2], {0, -1, 0});  // -128 clamps to -1
    // The base colour texture samples TEXCOORD_1, so those are the uvs kept.
    ASSERT_EQ(mesh.uvs.size(), 4u);
    EXPECT_FLOAT_EQ(mesh.uvs[0].y, 1.0f);
    EXPECT_FLOAT_EQ(mesh.uvs[1].x, 32768.0f / 65535.0f);
    // The image file is missing: a warning, and the material is drawn untextured.
    EXPECT_EQ(scene->materials[0].baseColorTexture, -1);
    ASSERT_EQ(scene->warnings.size(), 1u);
    EXPECT_NE(scene->warnings[0].find("image 0 ('missing.png') could not be read: material 0 drawn without its base "
                                      "colour texture"),
              std::string::npos)
        << scene->warnings[0];
}

TEST(GltfLoaderTest, ColoursAsVec3AndUnsignedShortsGetAlphaOne) {
    Asset asset = quad();
    asset.primitive()["attributes"]["COLOR_0"] = asset.accessor(
        bytesOf<std::uint16_t>({65535, 0, 0, 0, 65535, 0, 0, 0, 65535, 0, 0, 0}), kUShort, "VEC3", 4, true);
    const Result<Scene> scene = load(writeGltf(test::freshDir("GltfColourVec3"), "rgb", asset));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Mesh& mesh = scene->meshes[0];
    ASSERT_EQ(mesh.colors.size(), 4u);
    EXPECT_EQ(mesh.colors[1], glm::vec4(0, 1, 0, 1));
    EXPECT_EQ(mesh.colors[3], glm::vec4(0, 0, 0, 1));
}

TEST(GltfLoaderTest, StridedAndSparseAccessorsAreRead) {
    Asset asset = quad();
    // Positions interleaved with 4 padding bytes (stride 16), then 2 of them replaced sparsely.
    std::string interleaved;
    const float corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (const auto& corner : corners) interleaved += bytesOf<float>({corner[0], corner[1], corner[2], -1.0f});
    const int position = asset.accessor(interleaved, kFloat, "VEC3", 4);
    asset.json["bufferViews"][2]["byteStride"] = 16;
    asset.accessor(bytesOf<std::uint8_t>({1, 3}), kUByte, "SCALAR", 2);     // bufferView 3
    asset.accessor(bytesOf<float>({5, 0, 0, 0, 5, 0}), kFloat, "VEC3", 2);  // bufferView 4
    asset.json["accessors"][position]["sparse"] = {
        {"count", 2}, {"indices", {{"bufferView", 3}, {"componentType", kUByte}}}, {"values", {{"bufferView", 4}}}};
    asset.primitive()["attributes"]["POSITION"] = position;
    const Result<Scene> scene = load(writeGltf(test::freshDir("GltfSparse"), "sparse", asset));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Mesh& mesh = scene->meshes[0];
    ASSERT_EQ(mesh.positions.size(), 4u);
    expectNear(mesh.positions[0], {0, 0, 0});
    expectNear(mesh.positions[1], {5, 0, 0});
    expectNear(mesh.positions[2], {1, 1, 0});
    expectNear(mesh.positions[3], {0, 5, 0});
}

TEST(GltfLoaderTest, NonFinitePositionsDropTheirTrianglesWithAWarning) {
    Asset asset = quad();
    asset.json["accessors"][0]["bufferView"] = 2;
    asset.accessor(bytesOf<float>({0, 0, 0, 1, 0, 0, 1, NAN, 0, 0, 1, 0}), kFloat, "VEC3", 4);
    const std::string path = writeGltf(test::freshDir("GltfNonFinite"), "nan", asset);
    const Result<Scene> scene = load(path);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->triangleCount(), 0u);  // both triangles use vertex 2
    ASSERT_EQ(scene->warnings.size(), 1u);
    EXPECT_EQ(scene->warnings[0], path + ": mesh 'quad' primitive 0: dropped 2 triangles with non-finite positions");
}

TEST(GltfLoaderTest, CamerasAreAttachedToTheirNodes) {
    Asset asset = quad();
    asset.json["cameras"] = {
        {{"name", "persp"},
         {"type", "perspective"},
         {"perspective", {{"yfov", 0.5}, {"aspectRatio", 1.5}, {"znear", 0.1}, {"zfar", 50}}}},
        {{"name", "ortho"},
         {"type", "orthographic"},
         {"orthographic", {{"xmag", 2}, {"ymag", 3}, {"znear", 0}, {"zfar", 10}}}},
        {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.5}}}},
    };
    asset.json["nodes"] = {{{"mesh", 0}, {"children", {1, 2}}},
                           {{"camera", 1}, {"translation", {0, 0, 5}}},
                           {{"camera", 0}},
                           {{"camera", 2}}};  // node 3 is outside the scene
    const Result<Scene> scene = load(writeGltf(test::freshDir("GltfCameras"), "cameras", asset));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->cameras.size(), 2u);
    const SceneCamera& ortho = scene->cameras[0];  // in node order: node 1 first
    EXPECT_EQ(ortho.name, "ortho");
    EXPECT_EQ(ortho.node, 1);
    EXPECT_FALSE(ortho.perspective);
    EXPECT_FLOAT_EQ(ortho.xmag, 2.0f);
    EXPECT_FLOAT_EQ(ortho.ymag, 3.0f);
    EXPECT_FLOAT_EQ(ortho.znear, 0.0f);
    EXPECT_FLOAT_EQ(ortho.zfar, 10.0f);
    const SceneCamera& persp = scene->cameras[1];
    EXPECT_EQ(persp.name, "persp");
    EXPECT_EQ(persp.node, 2);
    EXPECT_TRUE(persp.perspective);
    EXPECT_FLOAT_EQ(persp.yfov, 0.5f);
    EXPECT_FLOAT_EQ(persp.aspect, 1.5f);
    EXPECT_FLOAT_EQ(persp.znear, 0.1f);
    EXPECT_FLOAT_EQ(persp.zfar, 50.0f);
    EXPECT_EQ(scene->nodes[1].camera, 0);
    EXPECT_EQ(scene->nodes[2].camera, 1);
    EXPECT_EQ(scene->nodes[3].camera, -1);

    // Absent aspect ratio and far plane: 0 (viewport aspect, infinite far plane).
    asset.json["nodes"][2]["camera"] = 2;
    const Result<Scene> infinite = load(writeGltf(test::freshDir("GltfCamerasInfinite"), "cameras", asset));
    ASSERT_TRUE(infinite.ok()) << infinite.error().message;
    EXPECT_FLOAT_EQ(infinite->cameras[1].aspect, 0.0f);
    EXPECT_FLOAT_EQ(infinite->cameras[1].zfar, 0.0f);
}

TEST(GltfLoaderTest, AnimationChannelsRoundTrip) {
    Asset asset = quad();
    const int times = asset.accessor(bytesOf<float>({0, 1, 3}), kFloat, "SCALAR", 3);
    const int translations = asset.accessor(bytesOf<float>({0, 0, 0, 1, 2, 3, 4, 5, 6}), kFloat, "VEC3", 3);
    // Rotations as normalised shorts, which glTF allows for rotation outputs: 32767 → 1.
    const int rotations = asset.accessor(bytesOf<std::int16_t>({0, 0, 0, 32767, 32767, 0, 0, 0, 0, 0, 0, 32767}),
                                         kShort, "VEC4", 3, true);
    const int cubicTimes = asset.accessor(bytesOf<float>({0, 2}), kFloat, "SCALAR", 2);
    const int cubicScales =
        asset.accessor(bytesOf<float>({0, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 2, 2, 2, 0, 0, 0}), kFloat, "VEC3", 6);
    const int weights = asset.accessor(bytesOf<float>({0, 1, 1}), kFloat, "SCALAR", 3);
    asset.json["animations"] = {
        {{"name", "move"},
         {"channels",
          {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}},
           {{"sampler", 1}, {"target", {{"node", 0}, {"path", "rotation"}}}},
           {{"sampler", 2}, {"target", {{"node", 0}, {"path", "scale"}}}},
           {{"sampler", 3}, {"target", {{"node", 0}, {"path", "weights"}}}},
           {{"sampler", 0}, {"target", {{"path", "translation"}}}}}},  // no node: ignored
         {"samplers",
          {{{"input", times}, {"output", translations}, {"interpolation", "STEP"}},
           {{"input", times}, {"output", rotations}},
           {{"input", cubicTimes}, {"output", cubicScales}, {"interpolation", "CUBICSPLINE"}},
           {{"input", times}, {"output", weights}}}}},
    };
    const Result<Scene> scene = load(writeGltf(test::freshDir("GltfAnimation"), "animated", asset));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->animations.size(), 1u);
    const Animation& animation = scene->animations[0];
    EXPECT_EQ(animation.name, "move");
    ASSERT_EQ(animation.channels.size(), 3u);
    const AnimChannel& t = animation.channels[0];
    EXPECT_EQ(t.node, 0);
    EXPECT_EQ(t.path, AnimPath::Translation);
    EXPECT_EQ(t.interpolation, Interp::Step);
    EXPECT_EQ(t.times, (std::vector<float>{0, 1, 3}));
    ASSERT_EQ(t.values.size(), 3u);
    EXPECT_EQ(t.values[2], glm::vec4(4, 5, 6, 0));
    const AnimChannel& r = animation.channels[1];
    EXPECT_EQ(r.path, AnimPath::Rotation);
    EXPECT_EQ(r.interpolation, Interp::Linear);
    EXPECT_EQ(r.values[0], glm::vec4(0, 0, 0, 1));  // x, y, z, w
    EXPECT_EQ(r.values[1], glm::vec4(1, 0, 0, 0));
    const AnimChannel& s = animation.channels[2];
    EXPECT_EQ(s.path, AnimPath::Scale);
    EXPECT_EQ(s.interpolation, Interp::CubicSpline);
    ASSERT_EQ(s.values.size(), 6u);  // in-tangent, value, out-tangent per key
    EXPECT_EQ(s.values[1], glm::vec4(1, 1, 1, 0));
    EXPECT_EQ(s.values[4], glm::vec4(2, 2, 2, 0));
    EXPECT_DOUBLE_EQ(scene->duration(), 3.0);
    // The quad has no morph targets: its weights channel is ignored, with a warning.
    EXPECT_TRUE(scene->unsupported.empty());
    ASSERT_EQ(scene->warnings.size(), 1u);
    EXPECT_NE(scene->warnings[0].find("animation 0 sampler 3: animates the morph weights of node 0, whose mesh has no "
                                      "morph targets: ignored"),
              std::string::npos)
        << scene->warnings[0];
}

TEST(GltfLoaderTest, TexturesOfEveryPngFormatBecomeRgba8) {
    struct Format {
        int colorType, bitDepth;
        std::string samples;             // two pixels
        std::vector<std::uint8_t> rgba;  // expected
    };
    const std::vector<Format> formats = {
        {0, 8, std::string("\x0a\xc8", 2), {10, 10, 10, 255, 200, 200, 200, 255}},             // grey
        {4, 8, std::string("\x0a\x14\xc8\x64", 4), {10, 10, 10, 20, 200, 200, 200, 100}},      // grey + alpha
        {2, 8, std::string("\x01\x02\x03\x04\x05\x06", 6), {1, 2, 3, 255, 4, 5, 6, 255}},      // RGB
        {6, 8, std::string("\x01\x02\x03\x04\x05\x06\x07\x08", 8), {1, 2, 3, 4, 5, 6, 7, 8}},  // RGBA
        // 16 bits, big-endian in the PNG: 0x1234 → round(0x1234 * 255 / 65535) = 18, 0xffff → 255, 0x0080 → 0.
        {6,
         16,
         std::string("\x12\x34\xff\xff\x00\x80\x80\x00\x00\x00\x00\x00\xff\xff\x00\x01", 16),
         {18, 255, 0, 128, 0, 0, 255, 0}},
        {0, 16, std::string("\xff\xff\x80\x80", 4), {255, 255, 255, 255, 128, 128, 128, 255}},  // grey 16
    };
    for (std::size_t i = 0; i < formats.size(); ++i) {
        const Format& format = formats[i];
        Asset asset = quad();
        const std::string image = png(2, 1, format.colorType, format.bitDepth, format.samples);
        asset.accessor(image, kUByte, "SCALAR", image.size());  // bufferView 2 holds the PNG
        asset.json["images"] = {{{"bufferView", 2}, {"mimeType", "image/png"}}};
        asset.json["samplers"] = {{{"magFilter", 9728}, {"minFilter", 9987}, {"wrapS", 33071}, {"wrapT", 33648}}};
        asset.json["textures"] = {{{"source", 0}, {"sampler", 0}, {"name", "tex"}}};
        asset.json["materials"] = {
            {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"baseColorFactor", {0.5, 1, 1, 1}}}},
             {"doubleSided", true},
             {"name", "mat"}}};
        asset.primitive()["material"] = 0;
        asset.primitive()["attributes"]["TEXCOORD_0"] =
            asset.accessor(bytesOf<float>({0, 0, 1, 0, 1, 1, 0, 1}), kFloat, "VEC2", 4);
        const Result<Scene> scene = load(writeGlb(test::freshDir("GltfPng" + std::to_string(i)), "png", asset));
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        ASSERT_EQ(scene->textures.size(), 1u);
        const Texture& texture = scene->textures[0];
        EXPECT_EQ(texture.name, "tex");
        EXPECT_EQ(texture.width, 2);
        EXPECT_EQ(texture.height, 1);
        EXPECT_EQ(texture.rgba, format.rgba) << "format " << i;
        EXPECT_EQ(texture.filter, Filter::Nearest);    // magFilter 9728
        EXPECT_EQ(texture.minFilter, Filter::Linear);  // minFilter 9987, LINEAR_MIPMAP_LINEAR
        EXPECT_EQ(texture.mipmaps, MipFilter::Linear);
        EXPECT_EQ(texture.wrapS, Wrap::ClampToEdge);
        EXPECT_EQ(texture.wrapT, Wrap::MirroredRepeat);
        const Material& material = scene->materials[0];
        EXPECT_EQ(material.name, "mat");
        EXPECT_EQ(material.baseColorTexture, 0);
        EXPECT_EQ(material.baseColorFactor, glm::vec4(0.5f, 1, 1, 1));
        EXPECT_TRUE(material.doubleSided);
        EXPECT_TRUE(scene->unsupported.empty());
    }
}

// Each of glTF's minification filters, and what a file that leaves the filters undefined gets: the
// Khronos glTF Sample Renderer's defaults, LINEAR and LINEAR_MIPMAP_LINEAR.
// KHR_lights_punctual: each kind of light with its fields (defaults where the file leaves them out),
// placed by nodes in and out of the chosen scene; bad lights and references refused with one line.
TEST(GltfLoaderTest, PunctualLightsArePlacedByTheirNodes) {
    const auto withLights = [](const Json& lights, const Json& nodeExtension, const std::string& name) {
        Asset asset = quad();
        asset.json["extensionsUsed"] = {"KHR_lights_punctual"};
        asset.json["extensions"] = {{"KHR_lights_punctual", {{"lights", lights}}}};
        asset.json["nodes"].push_back({{"name", "lamp"}, {"translation", {1, 2, 3}}, {"extensions", nodeExtension}});
        asset.json["nodes"].push_back(
            {{"name", "elsewhere"}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
        asset.json["scenes"][0]["nodes"] = {0, 1};
        return load(writeGlb(test::freshDir("GltfLights" + name), name, asset));
    };
    const Json lights = Json::array({{{"type", "spot"},
                                      {"name", "beam"},
                                      {"color", {1, 0.5, 0.25}},
                                      {"intensity", 20},
                                      {"range", 7},
                                      {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.5}}}},
                                     {{"type", "directional"}},
                                     {{"type", "point"}, {"intensity", 0}}});
    const Result<Scene> scene = withLights(lights, {{"KHR_lights_punctual", {{"light", 0}}}}, "good");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->unsupported.empty());
    ASSERT_EQ(scene->lights.size(), 3u);
    const PunctualLight& spot = scene->lights[0];
    EXPECT_EQ(spot.name, "beam");
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_EQ(spot.color, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_EQ(spot.intensity, 20.0f);
    EXPECT_EQ(spot.range, 7.0f);
    EXPECT_EQ(spot.innerConeAngle, 0.1f);
    EXPECT_EQ(spot.outerConeAngle, 0.5f);
    const PunctualLight& sun = scene->lights[1];
    EXPECT_EQ(sun.type, LightType::Directional);
    EXPECT_EQ(sun.color, glm::vec3(1.0f));
    EXPECT_EQ(sun.intensity, 1.0f);
    EXPECT_EQ(scene->lights[2].intensity, 0.0f);
    ASSERT_EQ(scene->nodes.size(), 3u);
    EXPECT_EQ(scene->nodes[0].light, -1);
    EXPECT_EQ(scene->nodes[1].light, 0);
    EXPECT_EQ(scene->nodes[2].light, -1) << "a node outside the chosen scene places nothing";
    const std::vector<FrameLight> placed = frameLights(*scene, scene->worldTransforms(0.0));
    ASSERT_EQ(placed.size(), 1u);
    EXPECT_EQ(placed[0].position, glm::vec3(1.0f, 2.0f, 3.0f));
    EXPECT_EQ(placed[0].direction, glm::vec3(0.0f, 0.0f, -1.0f));
    EXPECT_EQ(placed[0].intensity, glm::vec3(20.0f, 10.0f, 5.0f));
    EXPECT_FLOAT_EQ(placed[0].outerCos, std::cos(0.5f));
    EXPECT_FLOAT_EQ(placed[0].innerCos, std::cos(0.1f));

    // Nine lit nodes: the first eight light a frame, and the file is told so.
    Asset many = quad();
    many.json["extensions"] = {{"KHR_lights_punctual", {{"lights", Json::array({{{"type", "point"}}})}}}};
    for (int k = 0; k < 9; ++k) {
        many.json["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
        many.json["scenes"][0]["nodes"].push_back(k + 1);
    }
    const Result<Scene> crowded = load(writeGlb(test::freshDir("GltfLightsMany"), "many", many));
    ASSERT_TRUE(crowded.ok()) << crowded.error().message;
    EXPECT_EQ(crowded->unsupported, (std::vector<std::string>{"more than 8 punctual lights (the first 8 are drawn)"}));
    EXPECT_EQ(frameLights(*crowded, crowded->worldTransforms(0.0)).size(), std::size_t(kMaxLights));

    struct Bad {
        Json lights, node;
        std::string message;
    };
    const Json use0 = {{"KHR_lights_punctual", {{"light", 0}}}};
    const std::vector<Bad> bad = {
        {Json::array({{{"type", "area"}}}), use0, "lights[0].type: 'area' is not a light type"},
        {Json::array({{{"type", "point"}, {"intensity", -1}}}), use0, "lights[0].intensity: -1 is not an intensity"},
        {Json::array({{{"type", "point"}, {"color", {1, -1, 0}}}}), use0, "lights[0].color[1]: -1 is not a colour"},
        {Json::array({{{"type", "point"}, {"range", -2}}}), use0, "lights[0].range: -2 is not a range"},
        {Json::array({{{"type", "spot"}, {"spot", {{"innerConeAngle", 0.6}, {"outerConeAngle", 0.5}}}}}), use0,
         "lights[0].spot.innerConeAngle: 0.6 is not in [0, outerConeAngle 0.5)"},
        {Json::array({{{"type", "spot"}, {"spot", {{"outerConeAngle", 2}}}}}), use0,
         "lights[0].spot.outerConeAngle: 2 is not in (0, pi/2]"},
        {Json::array({{{"type", "point"}}}),
         {{"KHR_lights_punctual", {{"light", 3}}}},
         "nodes[1].extensions.KHR_lights_punctual.light: 3 is not a light index (the file has 1)"},
    };
    for (std::size_t i = 0; i < bad.size(); ++i) {
        const Result<Scene> refused = withLights(bad[i].lights, bad[i].node, "bad" + std::to_string(i));
        ASSERT_FALSE(refused.ok()) << bad[i].message;
        EXPECT_NE(refused.error().message.find(bad[i].message), std::string::npos) << refused.error().message;
        EXPECT_EQ(refused.error().message.find('\n'), std::string::npos) << refused.error().message;
    }
}

TEST(GltfLoaderTest, SamplersGiveTheFiltersAndMipmapsTheyName) {
    struct Case {
        int magFilter, minFilter;  // -1: undefined; both -1 and no sampler at all for the last case
        Filter filter, minified;
        MipFilter mipmaps;
    };
    const Case cases[] = {
        {9728, 9728, Filter::Nearest, Filter::Nearest, MipFilter::None},
        {9729, 9729, Filter::Linear, Filter::Linear, MipFilter::None},
        {9729, 9984, Filter::Linear, Filter::Nearest, MipFilter::Nearest},
        {9728, 9985, Filter::Nearest, Filter::Linear, MipFilter::Nearest},
        {9729, 9986, Filter::Linear, Filter::Nearest, MipFilter::Linear},
        {9729, 9987, Filter::Linear, Filter::Linear, MipFilter::Linear},
        {9728, -1, Filter::Nearest, Filter::Linear, MipFilter::Linear},
        {-1, -1, Filter::Linear, Filter::Linear, MipFilter::Linear},
    };
    for (std::size_t i = 0; i < std::size(cases); ++i) {
        const Case& c = cases[i];
        Asset asset = quad();
        const std::string image = png(2, 1, 0, 8, std::string("\x0a\xc8", 2));
        asset.accessor(image, kUByte, "SCALAR", image.size());  // bufferView 2 holds the PNG
        asset.json["images"] = {{{"bufferView", 2}, {"mimeType", "image/png"}}};
        Json sampler = Json::object();
        if (c.magFilter >= 0) sampler["magFilter"] = c.magFilter;
        if (c.minFilter >= 0) sampler["minFilter"] = c.minFilter;
        const bool last = i + 1 == std::size(cases);
        if (!last) asset.json["samplers"] = Json::array({sampler});
        asset.json["textures"] = Json::array({last ? Json{{"source", 0}} : Json{{"source", 0}, {"sampler", 0}}});
        asset.json["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
        asset.primitive()["material"] = 0;
        asset.primitive()["attributes"]["TEXCOORD_0"] =
            asset.accessor(bytesOf<float>({0, 0, 1, 0, 1, 1, 0, 1}), kFloat, "VEC2", 4);
        const Result<Scene> scene = load(writeGlb(test::freshDir("GltfSampler" + std::to_string(i)), "sampler", asset));
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        ASSERT_EQ(scene->textures.size(), 1u);
        const Texture& texture = scene->textures[0];
        EXPECT_EQ(texture.filter, c.filter) << "case " << i;
        EXPECT_EQ(texture.minFilter, c.minified) << "case " << i;
        EXPECT_EQ(texture.mipmaps, c.mipmaps) << "case " << i;
        EXPECT_TRUE(scene->unsupported.empty()) << "case " << i;
    }
}

TEST(GltfLoaderTest, UndecodableImageLeavesTheMaterialUntexturedWithAWarning) {
    Asset asset = quad();
    asset.json["images"] = {{{"uri", "data:image/png;base64," + base64("not a png at all")}}};
    asset.json["textures"] = {{{"source", 0}}};
    asset.json["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    asset.primitive()["material"] = 0;
    const Result<Scene> scene = load(writeGltf(test::freshDir("GltfBadImage"), "bad", asset));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->materials[0].baseColorTexture, -1);
    EXPECT_TRUE(scene->textures.empty());
    // Two warnings: the primitive has no TEXCOORD_0, and the image does not decode.
    ASSERT_EQ(scene->warnings.size(), 2u);
    EXPECT_NE(scene->warnings[1].find("image 0 cannot be decoded"), std::string::npos) << scene->warnings[1];
}

TEST(GltfLoaderTest, MetallicAndRoughnessFactorsAreReadWithGltfDefaults) {
    Asset asset = quad();
    asset.json["extensionsUsed"] = {"KHR_materials_emissive_strength"};
    const Json first = {{"pbrMetallicRoughness", {{"metallicFactor", 0.25}, {"roughnessFactor", 0.75}}},
                        {"emissiveFactor", {0.5, 0.25, 0}},
                        {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}};
    const Json second = {{"name", "defaults"}};
    const Json third = {{"pbrMetallicRoughness", {{"metallicFactor", 1.5}, {"roughnessFactor", -0.5}}}};
    asset.json["materials"] = Json::array({first, second, third});
    asset.json["meshes"][0]["primitives"].push_back(asset.primitive());
    asset.json["meshes"][0]["primitives"].push_back(asset.primitive());
    for (int m = 0; m < 3; ++m) asset.primitive(0, m)["material"] = m;
    const Result<Scene> scene = load(writeGltf(test::freshDir("GltfFactors"), "factors", asset));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->materials.size(), 3u);
    EXPECT_EQ(scene->materials[0].metallicFactor, 0.25f);
    EXPECT_EQ(scene->materials[0].roughnessFactor, 0.75f);
    EXPECT_EQ(scene->materials[1].metallicFactor, 1.0f);  // glTF's defaults
    EXPECT_EQ(scene->materials[1].roughnessFactor, 1.0f);
    EXPECT_EQ(scene->materials[2].metallicFactor, 1.0f);  // outside [0, 1]: clamped, as viewers do
    EXPECT_EQ(scene->materials[2].roughnessFactor, 0.0f);
    EXPECT_FALSE(scene->materials[0].unlit);
    EXPECT_EQ(scene->materials[0].emissiveFactor, glm::vec3(2.0f, 1.0f, 0.0f));  // × emissive strength
    EXPECT_EQ(scene->materials[1].emissiveFactor, glm::vec3(0.0f));
    EXPECT_TRUE(scene->unsupported.empty());
}

TEST(GltfLoaderTest, TextureTransformIsTheExtensionsMatrixAndSet) {
    const auto withTransform = [](const Json& transform) {
        Asset asset = quad();
        const std::string image = png(2, 1, 6, 8, std::string("\x01\x02\x03\x04\x05\x06\x07\x08", 8));
        asset.accessor(image, kUByte, "SCALAR", image.size());
        asset.json["images"] = {{{"bufferView", 2}, {"mimeType", "image/png"}}};
        asset.json["textures"] = {{{"source", 0}}};
        asset.json["extensionsUsed"] = {"KHR_texture_transform"};
        asset.json["materials"] = {
            {{"pbrMetallicRoughness",
              {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}}}}}}};
        asset.primitive()["material"] = 0;
        asset.primitive()["attributes"]["TEXCOORD_1"] =
            asset.accessor(bytesOf<float>({0, 0, 1, 0, 1, 1, 0, 1}), kFloat, "VEC2", 4);
        return load(writeGlb(test::freshDir("GltfTransform"), "transform", asset));
    };
    const Result<Scene> scene =
        withTransform({{"offset", {0.5, -0.25}}, {"rotation", 0.5}, {"scale", {2, 3}}, {"texCoord", 1}});
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->unsupported.empty()) << scene->unsupported.front();
    // uv' = T · R · S · uv: the corner (1, 0) goes to offset + 2·(cos 0.5, −sin 0.5).
    const glm::vec3 corner = scene->materials[0].baseColorTransform * glm::vec3(1, 0, 1);
    EXPECT_NEAR(corner.x, 0.5 + 2 * std::cos(0.5), 1e-6);
    EXPECT_NEAR(corner.y, -0.25 - 2 * std::sin(0.5), 1e-6);
    const glm::vec3 up = scene->materials[0].baseColorTransform * glm::vec3(0, 1, 1);
    EXPECT_NEAR(up.x, 0.5 + 3 * std::sin(0.5), 1e-6);
    EXPECT_NEAR(up.y, -0.25 + 3 * std::cos(0.5), 1e-6);
    ASSERT_EQ(scene->meshes.size(), 1u);
    EXPECT_FALSE(scene->meshes[0].uvs.empty()) << "texCoord 1 of the extension is the set read";

    const Result<Scene> bad = withTransform({{"scale", {2}}});
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("KHR_texture_transform.scale: not an array of 2 numbers"), std::string::npos)
        << bad.error().message;
}

// The maps: each texture decoded as its use says (colour sRGB, data linear), one scene texture per
// image and decoding; all sampled at one set of coordinates.
TEST(GltfLoaderTest, MapsAreReadAndDecodedAsTheirUseSays) {
    const auto withMaps = [](const Json& material, const std::string& name) {
        Asset asset = quad();
        const std::string image = png(2, 1, 6, 8, std::string("\x01\x02\x03\x04\x05\x06\x07\x08", 8));
        asset.accessor(image, kUByte, "SCALAR", image.size());
        asset.json["images"] = {{{"bufferView", 2}, {"mimeType", "image/png"}}};
        asset.json["textures"] = {{{"source", 0}}};
        asset.json["materials"] = {material};
        asset.primitive()["material"] = 0;
        asset.primitive()["attributes"]["TEXCOORD_0"] =
            asset.accessor(bytesOf<float>({0, 0, 1, 0, 1, 1, 0, 1}), kFloat, "VEC2", 4);
        asset.primitive()["attributes"]["NORMAL"] =
            asset.accessor(bytesOf<float>({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}), kFloat, "VEC3", 4);
        asset.primitive()["attributes"]["TANGENT"] =
            asset.accessor(bytesOf<float>({0, 1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1}), kFloat, "VEC4", 4);
        return load(writeGlb(test::freshDir("GltfMaps" + name), name, asset));
    };
    const Json texture = {{"index", 0}};
    const Result<Scene> scene = withMaps({{"pbrMetallicRoughness", {{"baseColorTexture", texture},
                                                                    {"metallicRoughnessTexture", texture}}},
                                          {"occlusionTexture", {{"index", 0}, {"strength", 0.25}}},
                                          {"emissiveTexture", texture},
                                          {"normalTexture", {{"index", 0}, {"scale", -2}}},
                                          {"emissiveFactor", {1, 0.5, 0}}},
                                         "all");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->unsupported.empty()) << scene->unsupported.front();
    ASSERT_EQ(scene->textures.size(), 2u) << "the image once as colour, once as data";
    const Material& m = scene->materials[0];
    ASSERT_GE(m.baseColorTexture, 0);
    ASSERT_GE(m.metallicRoughnessTexture, 0);
    EXPECT_TRUE(scene->textures[std::size_t(m.baseColorTexture)].srgb);
    EXPECT_FALSE(scene->textures[std::size_t(m.metallicRoughnessTexture)].srgb);
    EXPECT_EQ(scene->textures[0].rgba, scene->textures[1].rgba);
    EXPECT_EQ(m.occlusionTexture, m.metallicRoughnessTexture);
    EXPECT_EQ(m.emissiveTexture, m.baseColorTexture);
    EXPECT_EQ(m.occlusionStrength, 0.25f);
    EXPECT_EQ(m.emissiveFactor, glm::vec3(1.0f, 0.5f, 0.0f));
    EXPECT_EQ(m.normalTexture, m.metallicRoughnessTexture) << "normals are data";
    EXPECT_EQ(m.normalScale, -2.0f);
    ASSERT_EQ(scene->meshes[0].tangents.size(), 4u) << "the file's tangents, for the normal map";
    EXPECT_EQ(scene->meshes[0].tangents[0], glm::vec4(0, 1, 0, -1));

    // An emissive map on another set of coordinates than the base colour's is left out, and so is
    // its emission (a factor alone would light the whole surface).
    const Result<Scene> other = withMaps({{"pbrMetallicRoughness", {{"baseColorTexture", texture}}},
                                          {"emissiveTexture", {{"index", 0}, {"texCoord", 1}}},
                                          {"emissiveFactor", {1, 1, 1}}},
                                         "other");
    ASSERT_TRUE(other.ok()) << other.error().message;
    EXPECT_TRUE(other->meshes[0].tangents.empty()) << "no normal map: no tangents kept";
    EXPECT_EQ(other->materials[0].emissiveTexture, -1);
    EXPECT_EQ(other->materials[0].emissiveFactor, glm::vec3(0.0f));
    const std::string differing = "textures of one material on different coordinates (the first one's are used)";
    EXPECT_EQ(other->unsupported, std::vector<std::string>{differing});

    // KHR_materials_pbrSpecularGlossiness: the diffuse colour and texture become the base colour's
    // (pbrMetallicRoughness is the fallback and unread); both of its textures are read as linear,
    // as the Khronos renderer reads them.
    const Json sgMaterial = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.1, 0.1, 0.1, 1}},
                                                       {"metallicRoughnessTexture", texture}}},
                             {"extensions",
                              {{"KHR_materials_pbrSpecularGlossiness",
                                {{"diffuseFactor", {0.5, 0.25, 1.0, 0.75}},
                                 {"specularFactor", {0.2, 0.3, 0.4}},
                                 {"glossinessFactor", 0.625},
                                 {"diffuseTexture", texture},
                                 {"specularGlossinessTexture", texture}}}}}};
    const Result<Scene> sg = withMaps(sgMaterial, "sg");
    ASSERT_TRUE(sg.ok()) << sg.error().message;
    EXPECT_TRUE(sg->unsupported.empty()) << sg->unsupported.front();
    const Material& g = sg->materials[0];
    EXPECT_TRUE(g.specularGlossiness);
    EXPECT_EQ(g.baseColorFactor, glm::vec4(0.5f, 0.25f, 1.0f, 0.75f));
    EXPECT_EQ(g.specularFactor, glm::vec3(0.2f, 0.3f, 0.4f));
    EXPECT_EQ(g.glossinessFactor, 0.625f);
    EXPECT_EQ(g.metallicRoughnessTexture, -1) << "not read under the extension";
    ASSERT_GE(g.specularGlossinessTexture, 0);
    EXPECT_EQ(g.specularGlossinessTexture, g.baseColorTexture) << "both linear: one texture";
    EXPECT_FALSE(sg->textures[std::size_t(g.baseColorTexture)].srgb);
    for (const auto& [member, value, message] :
         {std::tuple<std::string, Json, std::string>{"glossinessFactor", 1.5, ".glossinessFactor: 1.5 is not in [0, 1]"},
          {"specularFactor", {1, 1}, ".specularFactor: not an array of 3 numbers"},
          {"diffuseFactor", {1, 1, 1, -1}, ".diffuseFactor[3]: -1 is not in [0, 1]"},
          {"diffuseTexture", {{"index", 3}}, ".diffuseTexture.index: 3 is not a texture (the file has 1)"},
          {"specularGlossinessTexture", {{"texCoord", 0}}, ".specularGlossinessTexture: no index"}}) {
        Json bad = sgMaterial;
        bad["extensions"]["KHR_materials_pbrSpecularGlossiness"][member] = value;
        const Result<Scene> refused = withMaps(bad, "sgbad");
        ASSERT_FALSE(refused.ok()) << member;
        EXPECT_NE(refused.error().message.find("materials[0].extensions.KHR_materials_pbrSpecularGlossiness" + message),
                  std::string::npos)
            << refused.error().message;
    }

    // KHR_materials_clearcoat: its factors and three linear maps; the coat's normal map keeps the
    // file's tangents. Without a coat (factor 0, the default) nothing of it is read.
    const Json ccMaterial = {{"pbrMetallicRoughness", {{"baseColorTexture", texture}}},
                             {"extensions",
                              {{"KHR_materials_clearcoat",
                                {{"clearcoatFactor", 0.75},
                                 {"clearcoatRoughnessFactor", 0.125},
                                 {"clearcoatTexture", texture},
                                 {"clearcoatRoughnessTexture", texture},
                                 {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}}}}}}}};
    const Result<Scene> cc = withMaps(ccMaterial, "cc");
    ASSERT_TRUE(cc.ok()) << cc.error().message;
    EXPECT_TRUE(cc->unsupported.empty()) << cc->unsupported.front();
    const Material& c = cc->materials[0];
    EXPECT_TRUE(c.clearcoat());
    EXPECT_EQ(c.clearcoatFactor, 0.75f);
    EXPECT_EQ(c.clearcoatRoughnessFactor, 0.125f);
    EXPECT_EQ(c.clearcoatNormalScale, 0.5f);
    ASSERT_GE(c.clearcoatTexture, 0);
    EXPECT_FALSE(cc->textures[std::size_t(c.clearcoatTexture)].srgb);
    EXPECT_EQ(c.clearcoatRoughnessTexture, c.clearcoatTexture);
    EXPECT_EQ(c.clearcoatNormalTexture, c.clearcoatTexture);
    EXPECT_NE(c.baseColorTexture, c.clearcoatTexture) << "the base colour is sRGB";
    EXPECT_TRUE(c.tangentSpace());
    EXPECT_EQ(cc->meshes[0].tangents.size(), 4u) << "the file's tangents, for the coat's normal map";
    Json uncoated = ccMaterial;
    uncoated["extensions"]["KHR_materials_clearcoat"].erase("clearcoatFactor");
    const Result<Scene> none = withMaps(uncoated, "ccnone");
    ASSERT_TRUE(none.ok()) << none.error().message;
    EXPECT_FALSE(none->materials[0].clearcoat());
    EXPECT_EQ(none->materials[0].clearcoatTexture, -1);
    EXPECT_EQ(none->materials[0].clearcoatNormalTexture, -1);
    EXPECT_TRUE(none->meshes[0].tangents.empty()) << "no coat: its normal map needs no tangents";
    EXPECT_EQ(none->textures.size(), 1u) << "only the base colour's";
    for (const auto& [member, value, message] :
         {std::tuple<std::string, Json, std::string>{"clearcoatFactor", 1.5, ".clearcoatFactor: 1.5 is not in [0, 1]"},
          {"clearcoatRoughnessFactor", -0.5, ".clearcoatRoughnessFactor: -0.5 is not in [0, 1]"},
          {"clearcoatFactor", "1", ".clearcoatFactor: not a number"},
          {"clearcoatTexture", {{"index", 3}}, ".clearcoatTexture.index: 3 is not a texture (the file has 1)"},
          {"clearcoatNormalTexture", {{"index", 0}, {"scale", "x"}}, ".clearcoatNormalTexture.scale: not a number"}}) {
        Json bad = ccMaterial;
        bad["extensions"]["KHR_materials_clearcoat"][member] = value;
        const Result<Scene> refused = withMaps(bad, "ccbad");
        ASSERT_FALSE(refused.ok()) << member;
        EXPECT_NE(refused.error().message.find("materials[0].extensions.KHR_materials_clearcoat" + message),
                  std::string::npos)
            << refused.error().message;
    }

    const Result<Scene> strong = withMaps({{"occlusionTexture", {{"index", 0}, {"strength", 1.5}}}}, "strong");
    ASSERT_FALSE(strong.ok());
    EXPECT_NE(strong.error().message.find("occlusionTexture.strength: 1.5 is not in [0, 1]"), std::string::npos)
        << strong.error().message;
}

TEST(GltfLoaderTest, UnmodelledFeaturesAreReportedOnceByName) {
    Asset asset = quad();
    asset.json["extensionsUsed"] = {"KHR_materials_sheen", "KHR_materials_unlit", "KHR_mesh_quantization"};
    asset.json["materials"] = {
        {{"alphaMode", "MASK"},  // modelled: not reported
         {"normalTexture", {{"index", 0}}},  // modelled: not reported
         {"emissiveFactor", {1, 0, 0}},
         {"extensions", {{"KHR_materials_unlit", Json::object()}}}},
        {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},  // unused: not reported
         {"emissiveTexture", {{"index", 0}, {"texCoord", 1}}}},
    };
    asset.json["textures"] = {{{"source", 0}}};
    asset.json["images"] = {{{"uri", "unused.png"}}};
    asset.json["meshes"][0]["primitives"].push_back(asset.primitive());
    asset.primitive(0, 0)["material"] = 0;
    asset.primitive(0, 1)["material"] = 0;
    asset.primitive(0, 1)["targets"] = {{{"POSITION", 0}}};
    asset.json["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}}, {"mode", 1}});
    asset.json["nodes"][0]["skin"] = 0;
    asset.json["skins"] = {{{"joints", {0}}}};
    asset.json["nodes"][0]["extensions"] = {{"EXT_lights_image_based", Json::object()}};
    asset.json["nodes"][0]["extras"] = {{"extensions", {{"NOT_AN_EXTENSION", Json::object()}}}};
    const Result<Scene> scene = load(writeGltf(test::freshDir("GltfUnsupported"), "features", asset));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const std::vector<std::string> expected = {"KHR_materials_sheen", "EXT_lights_image_based"};
    EXPECT_TRUE(scene->materials[0].unlit) << "KHR_materials_unlit is modelled";
    EXPECT_EQ(std::multiset<std::string>(scene->unsupported.begin(), scene->unsupported.end()),
              std::multiset<std::string>(expected.begin(), expected.end()));
    ASSERT_EQ(scene->meshes.size(), 3u);  // the LINES primitive too
    EXPECT_EQ(scene->meshes[0].name, "quad #0");
    EXPECT_EQ(scene->meshes[1].name, "quad #1");
    EXPECT_EQ(scene->meshes[2].topology, Topology::Lines);
}

TEST(GltfLoaderTest, AlphaModesAndCutoffsAreReadAsGltfDefinesThem) {
    Asset asset = quad();
    asset.json["materials"] = {Json::object(),
                               {{"alphaMode", "MASK"}},
                               {{"alphaMode", "MASK"}, {"alphaCutoff", 0.0}},
                               {{"alphaMode", "BLEND"}, {"alphaCutoff", 0.9}},
                               {{"alphaMode", "OPAQUE"}}};
    const Json first = asset.primitive();
    for (int m = 1; m < 5; ++m) {
        asset.json["meshes"][0]["primitives"].push_back(first);
        asset.primitive(0, m)["material"] = m;
    }
    asset.primitive(0, 0)["material"] = 0;
    const Result<Scene> scene = load(writeGltf(test::freshDir("GltfAlpha"), "alpha", asset));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->materials.size(), 5u);
    const AlphaMode modes[] = {AlphaMode::Opaque, AlphaMode::Mask, AlphaMode::Mask, AlphaMode::Blend, AlphaMode::Opaque};
    const float cutoffs[] = {0.5f, 0.5f, 0.0f, 0.9f, 0.5f};  // glTF's default cutoff is 0.5
    for (std::size_t m = 0; m < 5; ++m) {
        EXPECT_EQ(scene->materials[m].alphaMode, modes[m]) << m;
        EXPECT_EQ(scene->materials[m].alphaCutoff, cutoffs[m]) << m;
    }
    EXPECT_TRUE(scene->unsupported.empty()) << scene->unsupported.front();

    asset.json["materials"][1]["alphaCutoff"] = -0.25;
    const Result<Scene> negative = load(writeGltf(test::freshDir("GltfAlphaNegative"), "alpha", asset));
    ASSERT_FALSE(negative.ok());
    EXPECT_NE(negative.error().message.find("materials[1].alphaCutoff: -0.25 is negative"), std::string::npos)
        << negative.error().message;
}

TEST(GltfLoaderTest, APrimitiveWithoutPositionsIsSkippedWithAWarning) {
    Asset asset = quad();
    asset.primitive()["attributes"] = {{"NORMAL", 0}};
    const std::string path = writeGltf(test::freshDir("GltfNoPosition"), "nopos", asset);
    const Result<Scene> scene = load(path);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->meshes.empty());
    EXPECT_EQ(scene->warnings,
              (std::vector<std::string>{path + ": mesh 0 primitive 0: no POSITION attribute, not drawn"}));
}

}  // namespace
}  // namespace frugal
