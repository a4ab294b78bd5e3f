// A compressed glTF file renders as its original does (on the software reference, which GL matches
// on any mesh): byte for byte in colour, depth and ids where the codec keeps the data and its order
// (Draco's sequential encoder without quantization, meshopt's ATTRIBUTES and INDICES codecs); the
// same covered pixels, colour on almost every pixel, where it keeps the triangles but not their
// order (Draco's Edgebreaker, which reorders faces and rotates their corners; meshopt's TRIANGLES
// codec, which rotates corners): depth is interpolated from another corner, so its last bits move,
// and ids follow the decoded order; and within the quantization where a codec quantizes (Draco at
// 14 bits, meshopt's octahedral normals and 15-bit exponential positions). The copies are made by
// frugal-lab compress's code (lab/GltfCompress.h).
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <frugal/Files.h>
#include <frugal/Renderer.h>

#include "TestSupport.h"
#include "lab/GltfCompress.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

Frame render(const std::string& path, int width = 160, int height = 120) {
    Result<Scene> scene = loadScene(path);
    EXPECT_TRUE(scene) << scene.error().message;
    if (!scene) return {};
    Settings settings;
    settings.backend = BackendKind::Software;
    settings.width = width;
    settings.height = height;
    settings.ids = true;
    Result<Renderer> renderer = Renderer::create(std::move(*scene), settings);
    EXPECT_TRUE(renderer) << renderer.error().message;
    if (!renderer) return {};
    Result<Frame> frame = renderer->render(Camera::automatic(), 0.0);
    EXPECT_TRUE(frame) << frame.error().message;
    return frame ? std::move(*frame) : Frame{};
}

std::string compressed(const std::string& file, const CompressOptions& options, const std::string& name) {
    const Result<std::string> text = compressGltf(std::string(FRUGAL_ASSIMP_GLTF2_DIR) + "/" + file, options);
    EXPECT_TRUE(text) << text.error().message;
    const fs::path path = test::freshDir("CompressedMesh_" + name) / "copy.gltf";
    test::writeFile(path, text ? *text : std::string());
    return path.string();
}

struct Difference {
    std::size_t colour = 0, coverage = 0;  // pixels whose colour differs; pixels covered in one only
};

Difference differences(const Frame& a, const Frame& b) {
    Difference d;
    for (std::size_t p = 0; p < a.ids.ids.size(); ++p) {
        d.coverage += (a.ids.ids[p] == 0) != (b.ids.ids[p] == 0);
        for (std::size_t c = 0; c < 4; ++c)
            if (a.color.rgba[4 * p + c] != b.color.rgba[4 * p + c]) {
                ++d.colour;
                break;
            }
    }
    return d;
}

const std::vector<std::string> kFiles = {"BoxTextured-glTF/BoxTextured.gltf",
                                         "ClearCoat-glTF/ClearCoatTest.gltf",
                                         "textureTransform/TextureTransformTest.gltf",
                                         "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_13.gltf",
                                         "simple_skin/simple_skin.gltf",
                                         "issue_3269/texcoord_crash.gltf"};

std::string slug(std::string s) {
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return s;
}

TEST(CompressedMesh, LosslessCodecsThatKeepTheOrderRenderByteForByte) {
    for (const std::string& file : kFiles) {
        const Frame original = render(std::string(FRUGAL_ASSIMP_GLTF2_DIR) + "/" + file);
        CompressOptions draco;
        draco.method = CompressOptions::Method::Draco;
        draco.dracoSequential = true;
        CompressOptions meshopt;
        meshopt.method = CompressOptions::Method::Meshopt;
        for (const auto& [name, options] : {std::pair{"draco", draco}, std::pair{"meshopt", meshopt}}) {
            const Frame copy = render(compressed(file, options, std::string(name) + slug(file)));
            EXPECT_EQ(copy.color.rgba, original.color.rgba) << name << " " << file;
            EXPECT_EQ(copy.depth.values, original.depth.values) << name << " " << file;
            EXPECT_EQ(copy.ids.ids, original.ids.ids) << name << " " << file;
        }
    }
}

TEST(CompressedMesh, CodecsThatReorderKeepTheCoverageAndAlmostEveryColour) {
    for (const std::string& file : kFiles) {
        const Frame original = render(std::string(FRUGAL_ASSIMP_GLTF2_DIR) + "/" + file);
        CompressOptions edgebreaker;
        edgebreaker.method = CompressOptions::Method::Draco;
        CompressOptions triangles;
        triangles.method = CompressOptions::Method::Meshopt;
        triangles.meshoptTriangles = true;
        for (const auto& [name, options] : {std::pair{"edgebreaker", edgebreaker}, std::pair{"triangles", triangles}}) {
            const Frame copy = render(compressed(file, options, std::string(name) + slug(file)));
            const Difference d = differences(copy, original);
            EXPECT_EQ(d.coverage, 0u) << name << " " << file;
            EXPECT_LE(d.colour, original.ids.ids.size() / 200) << name << " " << file;  // 0.5 %
        }
    }
}

TEST(CompressedMesh, QuantizingCodecsStayWithinTheirQuantization) {
    for (const std::string& file : kFiles) {
        const Frame original = render(std::string(FRUGAL_ASSIMP_GLTF2_DIR) + "/" + file);
        CompressOptions draco;
        draco.method = CompressOptions::Method::Draco;
        draco.dracoBits = 14;
        CompressOptions filters;
        filters.method = CompressOptions::Method::Meshopt;
        filters.meshoptFilters = true;
        for (const auto& [name, options] : {std::pair{"draco14", draco}, std::pair{"filters", filters}}) {
            const Frame copy = render(compressed(file, options, std::string(name) + slug(file)));
            const Difference d = differences(copy, original);
            EXPECT_LE(d.coverage, original.ids.ids.size() / 500) << name << " " << file;  // 0.2 %
            EXPECT_LE(d.colour, original.ids.ids.size() / 50) << name << " " << file;     // 2 %
        }
    }
}

// The Draco engine of assimp-testmodels (Edgebreaker, quantized by its exporter) beside the same
// model uncompressed: the same picture but for its quantization.
TEST(CompressedMesh, TheDracoEngineLooksLikeTheUncompressedOne) {
    const std::string dir = FRUGAL_ASSIMP_GLTF2_DIR;
    const Frame draco = render(dir + "/draco/2CylinderEngine.gltf", 400, 300);
    const Frame plain = render(dir + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", 400, 300);
    const Difference d = differences(draco, plain);
    EXPECT_LE(d.coverage, draco.ids.ids.size() / 1000);  // 0.1 %
    EXPECT_LE(d.colour, draco.ids.ids.size() / 20);      // 5 %
}

}  // namespace
}  // namespace frugal
