// Whole scenes through SceneRenderer on every GL backend: known colours at known pixels, background
// elsewhere, bit-identical repeats, and EGL and OSMesa images identical byte for byte.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "RenderSupport.h"
#include "ShadingReference.h"
#include "TestSupport.h"
#include "gl/GlBackend.h"
#include "io/ImageIO.h"
#include "pipeline/Frame.h"
#include "pipeline/SceneRenderer.h"
#include "scene/Load.h"
#include "scene/MeshBuild.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

const glm::vec4 kBackground{0.12f, 0.13f, 0.15f, 1.0f};

using Frame = test::RenderedFrame;

Frame render(Backend& backend, const Scene& scene, int w, int h, double time = 0.0, bool ids = true,
             const Camera& camera = {}) {
    return test::renderScene(backend, scene, w, h, time, ids, kBackground, camera);
}

// Saves both images when they differ, so a failure can be looked at.
void expectIdentical(const Buffers& a, const Buffers& b, const std::string& name) {
    auto differing = [](const auto& x, const auto& y) {
        std::size_t n = 0;
        for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) n += x[i] != y[i];
        return n + (x.size() > y.size() ? x.size() - y.size() : y.size() - x.size());
    };
    const std::size_t colour = differing(a.rgba, b.rgba), depth = differing(a.depth, b.depth), ids = differing(a.ids, b.ids);
    const bool same = colour + depth + ids == 0;
    EXPECT_TRUE(same) << name << ": images differ: " << colour << " colour bytes, " << depth << " depth values, " << ids
                      << " ids; see " << test::outputDir() / name;
    if (!same) {
        fs::create_directories(test::outputDir() / name);
        (void)writeFileAtomic((test::outputDir() / name / "a.png").string(), encodeColorPng(a));
        (void)writeFileAtomic((test::outputDir() / name / "b.png").string(), encodeColorPng(b));
    }
}

// The kinds this build has, without creating any: test listing must not open GL contexts.
std::vector<BackendChoice> builtChoices() {
    std::vector<BackendChoice> choices;
    for (ContextKind kind : availableContextKinds()) {
        if (kind == ContextKind::EglSurfaceless) choices.push_back(BackendChoice::EglSurfaceless);
        if (kind == ContextKind::OsMesa) choices.push_back(BackendChoice::OsMesa);
    }
    return choices;
}

class SceneRenderGLTest : public ::testing::TestWithParam<BackendChoice> {
protected:
    void SetUp() override {
        Result<std::unique_ptr<Backend>> created = createGlBackend(GetParam());
        ASSERT_TRUE(created) << created.error().message;
        backend = std::move(*created);
    }
    std::unique_ptr<Backend> backend;
};

// A single square facing the camera, coloured by its material: the shading formula in linear
// values, then the display encoding rgb^(1/2.2), checked against the number computed here
// (Backend.h, Lighting).
TEST_P(SceneRenderGLTest, ShadingModelGivesTheExpectedColour) {
    Mesh quad;
    quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    finalizeMesh(quad, false);
    Material material;
    material.baseColorFactor = {0.8f, 0.4f, 0.2f, 1.0f};
    Scene scene = test::oneMeshScene(quad, material);
    SceneCamera camera;
    camera.yfov = glm::radians(60.0f);
    camera.znear = 1.0f;
    camera.zfar = 10.0f;
    test::addCameraNode(scene, camera, {0, 0, 4});

    // The camera's planes as given (the fit would hug the flat square: pipeline/Camera.h).
    Camera given;
    given.depthRange = DepthRange::File;
    const Frame frame = render(*backend, scene, 64, 48, 0.0, true, given);
    // glTF's default material (metallic 1, roughness 1) seen head-on at the centre; and a rough
    // dielectric.
    const std::size_t centre = std::size_t(24) * 64 + 32;
    const glm::dvec3 n(0, 0, 1), v(0, 0, 1);
    const glm::dvec3 metal =
        test::displayedRgb(test::referenceShade({glm::dvec3(material.baseColorFactor), 1.0, 1.0}, n, v, Lighting{}));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(frame.buffers.rgba[centre * 4 + c], metal[c] * 255.0, 1.0) << "channel " << c;
    scene.materials[0].metallicFactor = 0.0f;
    scene.materials[0].roughnessFactor = 0.6f;
    const Frame plastic = render(*backend, scene, 64, 48, 0.0, true, given);
    const glm::dvec3 dielectric =
        test::displayedRgb(test::referenceShade({glm::dvec3(material.baseColorFactor), 0.0, 0.6}, n, v, Lighting{}));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(plastic.buffers.rgba[centre * 4 + c], dielectric[c] * 255.0, 1.0) << "channel " << c;
    // The square spans about ±10 pixels around the centre; the diagonal (0,0)-(1,1) splits source
    // triangle 0 (below it, id 1) from source triangle 1 (above it, id 2).
    EXPECT_EQ(frame.buffers.ids[std::size_t(20) * 64 + 38], 1u);
    EXPECT_EQ(frame.buffers.ids[std::size_t(28) * 64 + 26], 2u);
    // Window z of a point at distance 4 with near 1, far 10: (f+n)/(f-n)·... mapped to [0,1].
    const double ndcZ = (10.0 + 1.0) / (10.0 - 1.0) - 2.0 * 10.0 * 1.0 / ((10.0 - 1.0) * 4.0);
    EXPECT_NEAR(double(frame.buffers.depth[centre]), (ndcZ * 0.5 + 0.5) * kDepthMax, 2.0);
    // Corner: background colour, far depth, id 0.
    EXPECT_EQ(frame.buffers.ids[0], 0u);
    EXPECT_EQ(frame.buffers.depth[0], kDepthMax);
    EXPECT_EQ(frame.buffers.rgba[0], 31);  // 0.12 · 255 = 30.6
}

TEST_P(SceneRenderGLTest, BunnyIsLitWhiteInTheMiddleAndBackgroundAtTheCorners) {
    Result<Scene> scene = loadScene(FRUGAL_BUNNY_OBJ);
    ASSERT_TRUE(scene) << scene.error().message << " (install glmark2-data: scripts/install-deps --tests)";
    ASSERT_EQ(scene->triangleCount(), 69666u);
    const Frame frame = render(*backend, *scene, 200, 150);
    const Buffers& b = frame.buffers;
    std::size_t covered = 0;
    for (std::size_t i = 0; i < b.pixelCount(); ++i) {
        if (b.ids[i] == 0) {
            EXPECT_EQ(b.depth[i], kDepthMax);
            continue;
        }
        ++covered;
        ASSERT_LE(b.ids[i], 69666u);
        // White material, white light: grey levels only.
        EXPECT_EQ(b.rgba[4 * i], b.rgba[4 * i + 1]);
        EXPECT_EQ(b.rgba[4 * i], b.rgba[4 * i + 2]);
        EXPECT_GE(b.rgba[4 * i], std::uint8_t(0.3f * 255.0f - 1.0f));  // at least the environment's 0.3
    }
    // The bunny fills a good part of the fitted view, not all of it.
    EXPECT_GT(covered, b.pixelCount() / 8);
    EXPECT_LT(covered, b.pixelCount() * 3 / 4);
    for (std::size_t corner : {std::size_t(0), std::size_t(199), b.pixelCount() - 1}) EXPECT_EQ(b.ids[corner], 0u);
    const std::size_t centre = std::size_t(75) * 200 + 100;
    EXPECT_NE(b.ids[centre], 0u);
}

TEST_P(SceneRenderGLTest, RepeatedRendersAreBitIdentical) {
    Result<Scene> scene = loadScene("builtin:default");
    ASSERT_TRUE(scene) << scene.error().message;
    const Frame a = render(*backend, *scene, 160, 120, 1.0);
    const Frame b = render(*backend, *scene, 160, 120, 1.0);
    expectIdentical(a.buffers, b.buffers, "repeat");
    // The id pass does not change colour or depth.
    const Frame c = render(*backend, *scene, 160, 120, 1.0, false);
    EXPECT_EQ(a.buffers.rgba, c.buffers.rgba);
    EXPECT_EQ(a.buffers.depth, c.buffers.depth);
    EXPECT_TRUE(std::all_of(c.buffers.ids.begin(), c.buffers.ids.end(), [](std::uint32_t id) { return id == 0; }));
}

INSTANTIATE_TEST_SUITE_P(Backends, SceneRenderGLTest, ::testing::ValuesIn(builtChoices()),
                         [](const auto& p) { return p.param == BackendChoice::OsMesa ? "osmesa" : "egl_surfaceless"; });

// The two context kinds run the same llvmpipe: images must match byte for byte, on the built-in
// scenes, the bunny and every assimp glTF 2.0 model that loads.
TEST(BackendsAgreeGLTest, EglAndOsMesaImagesAreIdentical) {
    Result<std::unique_ptr<Backend>> egl = createGlBackend(BackendChoice::EglSurfaceless);
    Result<std::unique_ptr<Backend>> osmesa = createGlBackend(BackendChoice::OsMesa);
    ASSERT_TRUE(egl) << egl.error().message;
    if (!osmesa) FRUGAL_SKIP_IF_NO_GL("OSMesa: " << osmesa.error().message);

    std::vector<std::string> specs = {"builtin:default", "builtin:dominoes?polygons=1404&static=0.9866", "builtin:cubes",
                                      FRUGAL_BUNNY_OBJ};
    for (const auto& entry : fs::recursive_directory_iterator(FRUGAL_ASSIMP_GLTF2_DIR)) {
        const std::string ext = entry.path().extension().string();
        if (ext == ".gltf" || ext == ".glb") specs.push_back(entry.path().string());
    }
    std::sort(specs.begin() + 4, specs.end());
    int compared = 0;
    for (const std::string& spec : specs) {
        SCOPED_TRACE(spec);
        Result<Scene> scene = loadScene(spec);
        if (!scene) continue;  // broken files: covered by the loader and CLI tests
        for (double time : {0.0, 0.7}) {
            const Frame a = render(**egl, *scene, 96, 72, time);
            const Frame b = render(**osmesa, *scene, 96, 72, time);
            expectIdentical(a.buffers, b.buffers, "egl-vs-osmesa-" + fs::path(spec).stem().string());
        }
        ++compared;
    }
    EXPECT_GT(compared, 24);
}

}  // namespace
}  // namespace frugal
