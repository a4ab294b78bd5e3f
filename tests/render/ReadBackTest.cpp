// Renderer::render with ReadBack: an image no file needs is not read back (Frame::depth stays
// empty), and what is read is what a full read-back gives, on the software backend and on GL.
#include <gtest/gtest.h>

#include <frugal/Renderer.h>

#include "TestSupport.h"

namespace frugal {
namespace {

void expectDepthLeftOut(BackendKind backend) {
    Result<Scene> scene = loadScene("builtin:cubes?count=4");
    ASSERT_TRUE(scene) << scene.error().message;
    Settings settings;
    settings.backend = backend;
    settings.width = 64;
    settings.height = 48;
    settings.ids = true;
    Result<Renderer> renderer = Renderer::create(std::move(*scene), settings);
    if (!renderer && renderer.error().kind == ErrorKind::BackendUnavailable) FRUGAL_SKIP_IF_NO_GL(renderer.error().message);
    ASSERT_TRUE(renderer) << renderer.error().message;
    Frame full, colorOnly;
    ASSERT_TRUE(renderer->render(Camera::automatic(), 0.0, full));
    ASSERT_TRUE(renderer->render(Camera::automatic(), 0.0, colorOnly, {.depth = false}));
    EXPECT_TRUE(colorOnly.depth.values.empty());
    EXPECT_EQ(full.depth.values.size(), 64u * 48u);
    EXPECT_EQ(colorOnly.color.rgba, full.color.rgba);
    EXPECT_EQ(colorOnly.ids.ids, full.ids.ids) << "ids are read whenever they are drawn";
    // The same Frame read back in full again gets its depth back.
    ASSERT_TRUE(renderer->render(Camera::automatic(), 0.0, colorOnly));
    EXPECT_EQ(colorOnly.depth.values, full.depth.values);
}

TEST(ReadBackTest, TheDepthLeftOutOnTheSoftwareBackend) { expectDepthLeftOut(BackendKind::Software); }
TEST(ReadBackTest, TheDepthLeftOutOnGl) { expectDepthLeftOut(BackendKind::Auto); }

}  // namespace
}  // namespace frugal
