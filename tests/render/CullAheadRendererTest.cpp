// Renderer::setNextFrame with cull occlusion-ahead: each frame's plan is made while the frame before
// draws, and the images are those of a plain render whatever the renderer was told: a right guess,
// a wrong one, a node moved in between. On the software backend and on GL.
#include <filesystem>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <frugal/Renderer.h>

#include "TestSupport.h"

namespace frugal {
namespace {

std::string aheadSceneName() {
    const char* bunny = "/usr/share/glmark2/models/bunny.obj";
    return std::filesystem::exists(bunny) ? std::string("builtin:copies?count=3&of=") + bunny
                                          : std::string("builtin:cubes?count=64");
}

Camera orbit(int i) {
    const float a = 0.35f * float(i);
    return Camera::lookAt({11.0f * std::sin(a), 2.0f, 11.0f * std::cos(a)}, {0.0f, 0.0f, 0.0f});
}

struct Pair {
    std::optional<Renderer> ahead, plain;
};

Pair makePair(BackendKind backend) {
    Pair out;
    for (Cull cull : {Cull::OcclusionAhead, Cull::None}) {
        // Single-sided: conservative culling alone then drops the back faces, whatever the
        // occlusion pass decides (it skips itself on frames where it does not pay, by their times).
        Result<Scene> scene = loadScene(aheadSceneName(), LoadOptions{true, false});
        EXPECT_TRUE(scene) << scene.error().message;
        if (!scene) return {};
        Settings settings;
        settings.backend = backend;
        settings.width = 160;
        settings.height = 120;
        settings.ids = true;
        settings.cull = cull;
        Result<Renderer> made = Renderer::create(std::move(*scene), settings);
        if (!made) {
            EXPECT_EQ(made.error().kind, ErrorKind::BackendUnavailable) << made.error().message;
            return {};
        }
        (cull == Cull::None ? out.plain : out.ahead).emplace(std::move(*made));
    }
    return out;
}

void expectSameImages(const Frame& a, const Frame& b, const std::string& label) {
    EXPECT_EQ(a.color.rgba, b.color.rgba) << label;
    EXPECT_EQ(a.depth.values, b.depth.values) << label;
    EXPECT_EQ(a.ids.ids, b.ids.ids) << label;
}

void checkSequence(BackendKind backend) {
    Pair pair = makePair(backend);
    if (!pair.ahead || !pair.plain) FRUGAL_SKIP_IF_NO_GL("no such backend here");
    Renderer& ahead = *pair.ahead;
    Renderer& plain = *pair.plain;
    Frame got, want;
    // A sequence told its next frame: every frame after the first takes a plan made ahead.
    constexpr int kFrames = 6;
    for (int i = 0; i < kFrames; ++i) {
        const std::string label = "frame " + std::to_string(i);
        if (i + 1 < kFrames) ahead.setNextFrame(orbit(i + 1), 0.0);
        ASSERT_TRUE(ahead.render(orbit(i), 0.0, got)) << label;
        ASSERT_TRUE(plain.render(orbit(i), 0.0, want)) << label;
        expectSameImages(got, want, label);
        ASSERT_TRUE(got.stats.cull && got.stats.cull->occlusion) << label;
        EXPECT_EQ(got.stats.cull->occlusion->ahead, i > 0) << label;
        EXPECT_GE(got.stats.cull->occlusion->aheadWaitMs, 0.0) << label;
        EXPECT_LT(got.stats.cull->pvs, got.stats.cull->tos) << label;
    }
    // A wrong guess: the frame is culled as usual, and the image is the same.
    ahead.setNextFrame(orbit(20), 0.0);
    ASSERT_TRUE(ahead.render(orbit(0), 0.0, got));
    ASSERT_TRUE(ahead.render(orbit(7), 0.0, got));
    ASSERT_TRUE(plain.render(orbit(7), 0.0, want));
    EXPECT_FALSE(got.stats.cull->occlusion->ahead) << "made for another camera";
    expectSameImages(got, want, "after a wrong guess");
    // A node moved between the frame that made the plan and the frame it was made for.
    ahead.setNextFrame(orbit(8), 0.0);
    ASSERT_TRUE(ahead.render(orbit(7), 0.0, got));
    const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(0.7f, 0.0f, 0.5f));
    ASSERT_TRUE(ahead.setTransform(0, moved));
    ASSERT_TRUE(plain.setTransform(0, moved));
    ASSERT_TRUE(ahead.render(orbit(8), 0.0, got));
    ASSERT_TRUE(plain.render(orbit(8), 0.0, want));
    EXPECT_FALSE(got.stats.cull->occlusion->ahead) << "made before the node moved";
    expectSameImages(got, want, "after a node moved");
}

TEST(CullAheadRendererTest, ASequenceOnTheSoftwareBackend) { checkSequence(BackendKind::Software); }
TEST(CullAheadRendererTest, ASequenceOnGl) { checkSequence(BackendKind::Auto); }

TEST(CullAheadRendererTest, OtherMethodsIgnoreTheNextFrame) {
    Result<Scene> scene = loadScene("builtin:cubes?count=8");
    ASSERT_TRUE(scene) << scene.error().message;
    Settings settings;
    settings.backend = BackendKind::Software;
    settings.width = 64;
    settings.height = 48;
    settings.cull = Cull::Occlusion;
    Result<Renderer> renderer = Renderer::create(std::move(*scene), settings);
    ASSERT_TRUE(renderer) << renderer.error().message;
    Frame frame;
    for (int i = 0; i < 3; ++i) {
        renderer->setNextFrame(orbit(i + 1), 0.0);
        ASSERT_TRUE(renderer->render(orbit(i), 0.0, frame));
        ASSERT_TRUE(frame.stats.cull && frame.stats.cull->occlusion);
        EXPECT_FALSE(frame.stats.cull->occlusion->ahead);
    }
}

TEST(CullAheadRendererTest, ReuseIsRefusedWithIt) {
    Result<Scene> scene = loadScene("builtin:cubes?count=8");
    ASSERT_TRUE(scene) << scene.error().message;
    Settings settings;
    settings.backend = BackendKind::Software;
    settings.cull = Cull::OcclusionAhead;
    settings.reuse = true;
    Result<Renderer> renderer = Renderer::create(std::move(*scene), settings);
    ASSERT_FALSE(renderer);
    EXPECT_NE(renderer.error().message.find("reuse with cull occlusion-ahead"), std::string::npos) << renderer.error().message;
}

}  // namespace
}  // namespace frugal
