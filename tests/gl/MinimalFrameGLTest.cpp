// The bench's minimal frame (gl/MinimalFrame.h) against the GL backend: the same colour and depth,
// bit for bit, on the bunny (both cullings, both triangle orders) and on built-in scenes; a clear
// reason for the scenes it does not draw.
//
// The bunny at 1920×1080 is chosen on purpose: there, feeding the shader an interpolated white
// vertex colour instead of none changes one pixel (the interpolated 1.0 is 1 − 2⁻²⁴ on some
// pixels), so these tests also hold the backend to "no colours = exactly white".
#include <algorithm>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "gl/GlBackend.h"
#include "gl/GlContext.h"
#include "io/ImageIO.h"
#include "lab/MinimalFrame.h"
#include "pipeline/Frame.h"
#include "pipeline/SceneRenderer.h"
#include "scene/Load.h"

namespace frugal {
namespace {

const glm::vec4 kBackground{0.12f, 0.13f, 0.15f, 1.0f};


class MinimalFrameGLTest : public ::testing::TestWithParam<ContextKind> {
protected:
    // Renders `spec` at `time` through GlBackend + SceneRenderer and through MinimalFrame, both with
    // a fresh context of the test's kind, and compares colour and depth.
    void expectSamePixels(const std::string& spec, const LoadOptions& load, double time, int width, int height,
                          const std::string& name, ShadingModel shading = ShadingModel::Full,
                          ToneMap tonemap = ToneMap::None) {
        Result<Scene> scene = loadScene(spec, load);
        ASSERT_TRUE(scene) << scene.error().message;
        Result<FrameSetup> setup = setUpFrame(*scene, Camera{}, time, width, height, /*writeIds=*/false);
        ASSERT_TRUE(setup) << setup.error().message;
        setup->params.shading = shading;
        setup->params.tonemap = tonemap;

        Result<std::unique_ptr<GlContext>> context = createContext(GetParam());
        ASSERT_TRUE(context) << context.error().message;
        Result<std::unique_ptr<Backend>> backend = makeGlBackend(std::move(*context));
        ASSERT_TRUE(backend) << backend.error().message;
        Result<SceneRenderer> renderer = SceneRenderer::create(**backend, *scene);
        ASSERT_TRUE(renderer) << renderer.error().message;
        const TargetHandle target = (*backend)->createTarget(width, height);
        ASSERT_NE(target, kNoHandle);

        Result<std::unique_ptr<MinimalFrame>> minimal = createMinimalFrame(GetParam(), *scene, width, height);
        ASSERT_TRUE(minimal) << minimal.error().message;

        // Two frames each, interleaved as the bench runs them (the contexts take turns).
        for (int i = 0; i < 2; ++i) {
            renderer->renderFrame(target, width, height, setup->params, setup->world, kBackground);
            (*minimal)->render(setup->params, setup->world, kBackground);
        }
        const Buffers expected = (*backend)->readBack(target);
        const Buffers actual = (*minimal)->readBack();
        ASSERT_EQ(actual.width, width);
        ASSERT_EQ(actual.height, height);
        const bool sameColour = actual.rgba == expected.rgba, sameDepth = actual.depth == expected.depth;
        if (!sameColour || !sameDepth) {
            std::size_t colour = 0, depth = 0;
            for (std::size_t p = 0; p < expected.pixelCount(); ++p) {
                colour += !std::equal(&actual.rgba[4 * p], &actual.rgba[4 * p + 4], &expected.rgba[4 * p]);
                depth += actual.depth[p] != expected.depth[p];
            }
            const std::filesystem::path dir = test::freshDir("minimal-" + name);
            (void)writeFileAtomic((dir / "minimal.png").string(), encodeColorPng(actual));
            (void)writeFileAtomic((dir / "backend.png").string(), encodeColorPng(expected));
            ADD_FAILURE() << name << ": " << colour << " colour and " << depth << " depth pixels differ; images in "
                          << dir;
        }
        // Not a trivially empty frame.
        const std::size_t drawn = std::size_t(std::count_if(expected.depth.begin(), expected.depth.end(),
                                                            [](std::uint32_t d) { return d != kDepthMax; }));
        EXPECT_GT(drawn, expected.pixelCount() / 50) << name;
    }
};

TEST_P(MinimalFrameGLTest, BunnyMatchesTheBackend) {
    ASSERT_TRUE(std::filesystem::exists(FRUGAL_BUNNY_OBJ)) << FRUGAL_BUNNY_OBJ << " (Debian glmark2-data)";
    LoadOptions load;
    expectSamePixels(FRUGAL_BUNNY_OBJ, load, 0.0, 1920, 1080, "bunny-double-sided");
    load.objDoubleSided = false;
    expectSamePixels(FRUGAL_BUNNY_OBJ, load, 0.0, 800, 600, "bunny-culled");
    load.optimizeOrder = false;
    expectSamePixels(FRUGAL_BUNNY_OBJ, load, 0.0, 800, 600, "bunny-culled-file-order");
}

TEST_P(MinimalFrameGLTest, BuiltinScenesMatchTheBackend) {
    expectSamePixels("builtin:cubes", {}, 2.5, 640, 480, "cubes");
    expectSamePixels("builtin:dominoes?polygons=804&floor=0", {}, 0.5, 320, 240, "dominoes");
}

// The frame's shading model and tone mapping select the minimal program's variant as they select
// the backend's (the bench times both with the frame's settings).
TEST_P(MinimalFrameGLTest, ShadingAndToneMappingMatchTheBackend) {
    expectSamePixels("builtin:cubes", {}, 2.5, 320, 240, "cubes-lambert", ShadingModel::Lambert);
    expectSamePixels("builtin:cubes", {}, 2.5, 320, 240, "cubes-lambert-aces", ShadingModel::Lambert, ToneMap::Aces);
    expectSamePixels("builtin:cubes", {}, 2.5, 320, 240, "cubes-neutral", ShadingModel::Full, ToneMap::PbrNeutral);
}

TEST_P(MinimalFrameGLTest, RefusesWhatItDoesNotDraw) {
    Result<Scene> textured = loadScene("builtin:default");
    ASSERT_TRUE(textured) << textured.error().message;
    EXPECT_NE(minimalFrameUnsupported(*textured).find("has a texture"), std::string::npos);
    Result<std::unique_ptr<MinimalFrame>> refused = createMinimalFrame(GetParam(), *textured, 64, 48);
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().message.rfind("minimal frame: material ", 0), 0u) << refused.error().message;

    Mesh mesh;
    mesh.name = "painted";
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.normals.assign(3, glm::vec3(0, 0, 1));
    mesh.colors.assign(3, glm::vec4(1, 0, 0, 1));
    mesh.indices = {0, 1, 2};
    const Scene colored = test::oneMeshScene(mesh);
    EXPECT_EQ(minimalFrameUnsupported(colored),
              "mesh 0 'painted' has vertex colours, which the minimal frame does not draw");

    Result<Scene> cubes = loadScene("builtin:cubes");
    ASSERT_TRUE(cubes) << cubes.error().message;
    EXPECT_EQ(minimalFrameUnsupported(*cubes), "");
    Scene unlit = *cubes;
    unlit.materials.at(0).unlit = true;
    EXPECT_NE(minimalFrameUnsupported(unlit).find("unlit"), std::string::npos) << minimalFrameUnsupported(unlit);
    Scene lit = *cubes;
    lit.lights.emplace_back();
    EXPECT_EQ(minimalFrameUnsupported(lit), "the scene has 1 light, which the minimal frame does not draw");
}

// write-bench's read-back experiment: through pixel buffer objects, in one step or a frame late,
// the images are glReadPixels' own, in both depth formats.
TEST_P(MinimalFrameGLTest, PixelBuffersReadWhatReadPixelsReads) {
    Result<Scene> scene = loadScene("builtin:cubes");
    ASSERT_TRUE(scene) << scene.error().message;
    for (const DepthFormat format : {DepthFormat::D24, DepthFormat::D32F}) {
        SCOPED_TRACE(depthFormatName(format));
        Result<std::unique_ptr<MinimalFrame>> made = createMinimalFrame(GetParam(), *scene, 64, 48, format);
        if (!made && format == DepthFormat::D32F) continue;  // no glClipControl
        ASSERT_TRUE(made) << made.error().message;
        MinimalFrame& minimal = **made;
        const auto draw = [&](double time) {
            Result<FrameSetup> setup = setUpFrame(*scene, Camera{}, time, 64, 48, false, format);
            ASSERT_TRUE(setup) << setup.error().message;
            minimal.render(setup->params, setup->world, kBackground);
        };
        draw(0.0);
        const Buffers first = minimal.readBack();
        draw(2.5);
        const Buffers second = minimal.readBack();
        ASSERT_NE(first.rgba, second.rgba) << "two different frames";
        EXPECT_TRUE(minimal.readBack(false).depth.empty());

        minimal.startReadBack(0, true);
        Buffers read;
        minimal.endReadBack(0, read, true);
        EXPECT_EQ(read.rgba, second.rgba);
        EXPECT_EQ(read.depth, second.depth);
        // A frame late: each slot keeps the frame drawn before its read, whatever is drawn after.
        draw(0.0);
        minimal.startReadBack(1, true);
        draw(2.5);
        minimal.startReadBack(0, false);
        minimal.endReadBack(1, read, true);
        EXPECT_EQ(read.rgba, first.rgba);
        EXPECT_EQ(read.depth, first.depth);
        minimal.endReadBack(0, read, false);
        EXPECT_EQ(read.rgba, second.rgba);
        EXPECT_TRUE(read.depth.empty());
    }
}

std::string kindName(const ::testing::TestParamInfo<ContextKind>& info) {
    std::string name = contextKindName(info.param);
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
}

INSTANTIATE_TEST_SUITE_P(Contexts, MinimalFrameGLTest, ::testing::ValuesIn(availableContextKinds()), kindName);

}  // namespace
}  // namespace frugal
