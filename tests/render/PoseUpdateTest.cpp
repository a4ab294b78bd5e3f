// A deforming scene over many frames through one renderer: after the first frame each pose is
// written into the uploaded mesh in place (Backend::updateVertices), the id pass's expanded copy
// with it, and the GL backend and the software reference keep drawing the same pixels, depth and
// ids as at the first frame of each time (a fresh renderer) — frame after frame, forwards and back.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <frugal/Renderer.h>

#include "TestSupport.h"

namespace frugal {
namespace {

Settings settingsFor(BackendKind backend) {
    Settings settings;
    settings.backend = backend;
    settings.width = 160;
    settings.height = 120;
    settings.ids = true;
    return settings;
}

void expectSameFrames(const Frame& a, const Frame& b, const std::string& what) {
    EXPECT_EQ(a.ids.ids, b.ids.ids) << what;
    EXPECT_EQ(a.depth.values, b.depth.values) << what;
    std::size_t differing = 0;
    int worst = 0;
    for (std::size_t i = 0; i < a.color.rgba.size() && i < b.color.rgba.size(); ++i) {
        const int d = std::abs(int(a.color.rgba[i]) - int(b.color.rgba[i]));
        differing += d != 0;
        worst = std::max(worst, d);
    }
    EXPECT_LE(worst, 1) << what << ": " << differing << " channels differ";
}

TEST(PoseUpdateTest, InPlacePosesDrawWhatAFreshUploadDraws) {
    const Camera camera = Camera::lookAt({0.5f, 1.0f, 7.0f}, {0.5f, 0.3f, 0.0f});
    for (Scene (*make)() : {+[] { return test::skinnedScene(3.0f); }, +[] { return test::morphingScene(); }}) {
        const Scene scene = make();
        SCOPED_TRACE(scene.source);
        Result<Renderer> gl = Renderer::create(scene, settingsFor(BackendKind::Auto));
        Result<Renderer> software = Renderer::create(scene, settingsFor(BackendKind::Software));
        ASSERT_TRUE(gl && software);
        for (const double time : {0.0, 0.7, 1.3, 2.0, 1.3, 3.6, 4.0}) {
            const std::string at = "t = " + std::to_string(time);
            Result<Frame> a = gl->render(camera, time);
            Result<Frame> b = software->render(camera, time);
            ASSERT_TRUE(a && b);
            expectSameFrames(*a, *b, "GL and software, " + at);
            // A renderer that draws this time first uploads the pose as a new mesh.
            Result<Renderer> fresh = Renderer::create(scene, settingsFor(BackendKind::Auto));
            ASSERT_TRUE(fresh);
            Result<Frame> c = fresh->render(camera, time);
            ASSERT_TRUE(c);
            EXPECT_EQ(a->ids.ids, c->ids.ids) << at;
            EXPECT_EQ(a->depth.values, c->depth.values) << at;
            EXPECT_EQ(a->color.rgba, c->color.rgba) << at;
        }
    }
}

}  // namespace
}  // namespace frugal
