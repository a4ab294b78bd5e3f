// Whole scenes through SceneRenderer on the GL backend (llvmpipe) and on the software backend:
// builtin:default, builtin:cubes at several times, the Stanford bunny (glmark2-data) and every glTF
// model of assimp-testmodels that loads. Coverage and depth must be identical, ids agree on at least
// 99.99 % of the pixels, colour within 1 (all four are identical as measured; the thresholds are the
// task's). Plus textures: every wrap mode pair and both filters on power-of-two and other sizes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <string>
#include <vector>

#include "GlReference.h"
#include "RenderSupport.h"
#include "pipeline/Frame.h"
#include "pipeline/SceneRenderer.h"
#include "scene/Load.h"
#include "lab/ImageCompare.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

const glm::vec4 kBackground{0.12f, 0.13f, 0.15f, 1.0f};

// A file name out of a scene spec: "builtin:cubes" → "builtin-cubes".
std::string safeName(std::string text) {
    for (char& c : text)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '-';
    return text;
}

class SceneGLTest : public test::ReferencePairTest {
protected:
    // Renders `scene` on both and checks the thresholds; returns the comparison for the log.
    test::Comparison check(const Scene& scene, const std::string& name, int width, int height, double time = 0.0,
                           bool ids = true) {
        const Buffers a = test::renderScene(*reference, scene, width, height, time, ids, kBackground).buffers;
        const Buffers b = test::renderScene(*software, scene, width, height, time, ids, kBackground).buffers;
        const std::string label = safeName(name) + "-" + std::to_string(width) + "x" + std::to_string(height) +
                                  (ids ? "" : "-noids") + (time != 0.0 ? "-t" + std::to_string(int(time * 10)) : "");
        test::expectMatches("Scene-" + label, a, b);
        const test::Comparison c = test::compareBuffers(a, b);
        std::printf("[ %s ] %s\n", label.c_str(), c.summary().c_str());
        return c;
    }
};

TEST_F(SceneGLTest, BuiltinDefault) {
    Result<Scene> scene = loadScene("builtin:default");
    ASSERT_TRUE(scene) << scene.error().message;
    EXPECT_GT(check(*scene, "builtin:default", 800, 600).covered, 0u);
    check(*scene, "builtin:default", 61, 47);
    check(*scene, "builtin:default", 320, 240, 0.0, false);
}

TEST_F(SceneGLTest, BuiltinCubesOverTime) {
    Result<Scene> scene = loadScene("builtin:cubes");
    ASSERT_TRUE(scene) << scene.error().message;
    for (double time : {0.0, 2.5, 7.0}) EXPECT_GT(check(*scene, "builtin:cubes", 800, 600, time).covered, 0u);
}

TEST_F(SceneGLTest, Bunny) {
    Result<Scene> scene = loadScene(FRUGAL_BUNNY_OBJ);
    ASSERT_TRUE(scene) << scene.error().message << " (install glmark2-data: scripts/install-deps --tests)";
    EXPECT_GT(check(*scene, "bunny", 800, 600).covered, 0u);
    check(*scene, "bunny", 800, 600, 0.0, false);
    check(*scene, "bunny", 1920, 1080);
}

// Every glTF file of the package that loads (broken ones are the loader tests' business).
TEST_F(SceneGLTest, AssimpGltfModels) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(FRUGAL_ASSIMP_GLTF2_DIR)) {
        const std::string ext = entry.path().extension().string();
        if (entry.is_regular_file() && (ext == ".gltf" || ext == ".glb")) files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    ASSERT_FALSE(files.empty()) << FRUGAL_ASSIMP_GLTF2_DIR << " (install assimp-testmodels)";
    int rendered = 0, textured = 0;
    for (const fs::path& file : files) {
        Result<Scene> scene = loadScene(file.string());
        if (!scene || scene->triangleCount() == 0) continue;
        SCOPED_TRACE(file.string());
        const std::string name = fs::relative(file, FRUGAL_ASSIMP_GLTF2_DIR).string();
        check(*scene, name, 320, 240);
        ++rendered;
        textured += !scene->textures.empty();
    }
    EXPECT_GE(rendered, 20);
    EXPECT_GE(textured, 5);
}

// A perspective quad with texture coordinates from −1.3 to 2.2: every wrap pair, both filters,
// power-of-two and other sizes, sRGB and linear. llvmpipe takes its 8-bit AoS path for linear
// repeat/clamp pairs and the float path as soon as one axis mirrors or the texture is sRGB
// (Shading.h); all are reproduced exactly, and the colours differ only where the display
// encoding's power does (one step, on at most 0.1 % of pixels).
TEST_F(SceneGLTest, TextureSampling) {
    const int width = 97, height = 83;
    const TargetHandle targets[2] = {reference->createTarget(width, height), software->createTarget(width, height)};
    Backend* backends[2] = {reference.get(), software.get()};
    Mesh mesh;
    mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    mesh.normals.assign(4, glm::vec3(0, 0, 1));
    mesh.uvs = {{-1.3f, -0.7f}, {2.2f, -0.7f}, {2.2f, 1.9f}, {-1.3f, 1.9f}};
    mesh.colors = {{1, 1, 1, 1}, {0.5f, 1, 1, 1}, {1, 0.5f, 1, 0.5f}, {1, 1, 0.5f, 1}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    MeshHandle meshes[2] = {reference->uploadMesh(mesh), software->uploadMesh(mesh)};
    std::mt19937 rng(3);
    const int sizes[][2] = {{4, 4}, {5, 3}, {8, 2}, {3, 7}, {1, 1}, {16, 16}, {64, 32}};
    const Wrap wraps[] = {Wrap::Repeat, Wrap::ClampToEdge, Wrap::MirroredRepeat};
    const char* wrapNames[] = {"repeat", "clamp", "mirror"};
    for (const auto& size : sizes)
        for (Filter filter : {Filter::Nearest, Filter::Linear})
            for (int s = 0; s < 3; ++s)
                for (int t = 0; t < 3; ++t) {
                    Texture texture;
                    texture.srgb = (s + t) % 2 == 0;
                    texture.width = size[0];
                    texture.height = size[1];
                    texture.filter = filter;
                    texture.wrapS = wraps[s];
                    texture.wrapT = wraps[t];
                    texture.rgba.resize(std::size_t(size[0]) * size[1] * 4);
                    for (auto& byte : texture.rgba) byte = std::uint8_t(rng() & 255u);
                    Buffers out[2];
                    for (int i = 0; i < 2; ++i) {
                        const TextureHandle handle = backends[i]->uploadTexture(texture);
                        ASSERT_NE(handle, kNoHandle);
                        backends[i]->clear(targets[i], Rect{0, 0, width, height}, kBackground, 1.0f);
                        FrameParams frame;
                        frame.view = glm::lookAt(glm::vec3(0.3f, -0.4f, 1.6f), glm::vec3(0.0f), glm::vec3(0, 1, 0));
                        frame.projection = glm::perspective(1.2f, float(width) / float(height), 0.1f, 10.0f);
                        backends[i]->beginFrame(targets[i], frame);
                        DrawParams draw;
                        draw.mesh = meshes[i];
                        draw.texture = handle;
                        draw.doubleSided = true;
                        draw.baseColorFactor = {0.9f, 1.0f, 0.8f, 1.0f};
                        const IndexRange all{0, 2};
                        backends[i]->draw(draw, {&all, 1});
                        out[i] = backends[i]->readBack(targets[i]);
                    }
                    const std::string name = "Texture-" + std::to_string(size[0]) + "x" + std::to_string(size[1]) +
                                             "-" + (filter == Filter::Linear ? "linear" : "nearest") + "-" +
                                             wrapNames[s] + "-" + wrapNames[t] + (texture.srgb ? "-srgb" : "");
                    test::expectMatches(name, out[0], out[1], 1.0);
                }
}

}  // namespace
}  // namespace frugal
