// Points and lines through the library: glTF's POINTS, LINES, LINE_LOOP and LINE_STRIP files of the
// glTF-Asset-Generator drawn by the GL backend and the software reference with the same pixels,
// ids and depth (1 and 4 samples), and the hidden-surface modes refusing a scene of points or lines
// with one line (they order polygons).
#include <string>

#include <gtest/gtest.h>

#include <frugal/Files.h>
#include <frugal/Renderer.h>

#include "TestSupport.h"

namespace frugal {
namespace {

Frame render(const std::string& path, BackendKind backend, int samples) {
    Result<Scene> scene = loadScene(path);
    EXPECT_TRUE(scene) << scene.error().message;
    if (!scene) return {};
    Settings settings;
    settings.backend = backend;
    settings.width = 200;
    settings.height = 150;
    settings.samples = samples;
    settings.ids = true;
    Result<Renderer> renderer = Renderer::create(std::move(*scene), settings);
    EXPECT_TRUE(renderer) << renderer.error().message;
    if (!renderer) return {};
    Result<Frame> frame = renderer->render(Camera::lookAt({0.87f, 0.7f, 1.74f}, {0.0f, 0.0f, 0.0f}), 0.0);
    EXPECT_TRUE(frame) << frame.error().message;
    return frame ? std::move(*frame) : Frame{};
}

TEST(PointsLinesRenderTest, PrimitiveModeFilesDrawTheSameOnBothBackends) {
    for (const char* n : {"00", "01", "02", "03", "07", "08", "09", "10"})
        for (const int samples : {1, 4}) {
            const std::string path = std::string(FRUGAL_ASSIMP_GLTF2_DIR) +
                                     "/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_" + n + ".gltf";
            SCOPED_TRACE(path + ", " + std::to_string(samples) + " samples");
            const Frame gl = render(path, BackendKind::Auto, samples);
            const Frame software = render(path, BackendKind::Software, samples);
            ASSERT_EQ(gl.ids.ids.size(), software.ids.ids.size());
            EXPECT_EQ(gl.ids.ids, software.ids.ids);
            EXPECT_EQ(gl.depth.values, software.depth.values);
            EXPECT_EQ(gl.color.rgba, software.color.rgba);
            std::size_t drawn = 0;
            for (const std::uint32_t id : gl.ids.ids) drawn += id != 0;
            EXPECT_GT(drawn, 30u) << "the file's points or lines were not drawn";
        }
}

TEST(PointsLinesRenderTest, HiddenSurfaceModesRefusePointsAndLines) {
    Settings settings;
    settings.backend = BackendKind::Software;
    settings.hsr = Hsr::DepthSort;
    const Result<Renderer> renderer = Renderer::create(test::pointsLinesScene(), settings);
    ASSERT_FALSE(renderer);
    EXPECT_EQ(renderer.error().message,
              "hsr depthsort: 'points and lines test scene' has lines (mesh 1), and the hidden-surface modes "
              "order polygons (zbuffer draws it)");
    settings.hsr = Hsr::ZBuffer;
    EXPECT_TRUE(Renderer::create(test::pointsLinesScene(), settings)) << "the z-buffer takes any scene";
}

}  // namespace
}  // namespace frugal
