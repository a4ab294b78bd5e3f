// Temporal reuse on the GL backend: the core sequences of tests/reuse/SequenceTest.cpp rendered
// fully and with reuse through llvmpipe, frame by frame identical in colour, depth and ids (the one
// scene made for depth ties aside, where the ties are counted and must be what the software
// reference counts). Skipped when no GL context can be created.
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ReuseSupport.h"
#include "TestSupport.h"
#include "gl/GlBackend.h"

namespace frugal::test {
namespace {

class ReuseGLTest : public ::testing::Test {
protected:
    void SetUp() override {
        Result<std::unique_ptr<Backend>> created = createGlBackend(BackendChoice::Auto);
        if (!created) FRUGAL_SKIP_IF_NO_GL(created.error().message);
        backend = std::move(*created);
    }

    // The sequence on the GL backend, exact (expectExactOn).
    SequenceResult expectExact(const Scene& scene, int width, int height, int frames, const Frames& frame,
                               const ReuseOptions& options = {}, bool tiesAllowed = false) {
        return expectExactOn(*backend, scene, width, height, frames, frame, options, tiesAllowed);
    }

    std::unique_ptr<Backend> backend;
};

TEST_F(ReuseGLTest, DominoesAtThePapersSizes) {
    for (const char* spec : {"builtin:dominoes?polygons=804&static=0.5544", "builtin:dominoes?polygons=1404&static=0.9866"}) {
        SCOPED_TRACE(spec);
        const Scene scene = loadOrFail(spec);
        for (bool paper : {false, true}) {
            const SequenceResult r =
                expectExact(scene, 200, 150, 16, animated(scene, {}, 200, 150), reuseOptions(16, 16, true, paper));
            EXPECT_EQ(r.modes(), "R" + std::string(15, 'U')) << r.describe();
        }
        expectExact(scene, 200, 150, 10, animated(scene, {}, 200, 150), reuseOptions(1, 8, false));
    }
}

TEST_F(ReuseGLTest, DefaultSceneWithItsTexturedFloor) {
    const Scene scene = loadOrFail("builtin:default");
    const SequenceResult r = expectExact(scene, 200, 150, 16, animated(scene, {}, 200, 150));
    EXPECT_EQ(r.modes(), "R" + std::string(15, 'U')) << r.describe();
}

TEST_F(ReuseGLTest, CubesEverythingDynamic) {
    const Scene scene = loadOrFail("builtin:cubes");
    const SequenceResult r = expectExact(scene, 160, 120, 10, animated(scene, {}, 160, 120));
    EXPECT_EQ(r.modes(), "RFFFFFFFFF") << r.describe();
    const SequenceResult forced = expectExact(scene, 160, 120, 10, animated(scene, {}, 160, 120), reuseOptions(16, 16, false));
    EXPECT_EQ(forced.modes(), "RUUUUUUUUU") << forced.describe();
}

TEST_F(ReuseGLTest, AllDynamicBuilt) {
    const Scene scene = allDynamicScene();
    const Camera camera = overviewCamera();
    EXPECT_EQ(expectExact(scene, 120, 90, 8, withCamera(scene, camera, 120, 90)).modes(), "RFFFFFFF");
    EXPECT_EQ(expectExact(scene, 120, 90, 8, withCamera(scene, camera, 120, 90), reuseOptions(16, 16, false)).modes(),
              "RUUUUUUU");
}

TEST_F(ReuseGLTest, CameraPathMovesStopsMovesAgain) {
    const Scene scene = loadOrFail("builtin:dominoes?polygons=1404&static=0.9866");
    const CameraPath path;
    const SequenceResult r = expectExact(scene, 200, 150, path.frames(), path.of(scene, 200, 150));
    EXPECT_EQ(r.modes(), path.modes) << r.describe();
}

TEST_F(ReuseGLTest, AnObjectFliesThroughTheCamera) {
    const Scene scene = flyThroughScene();
    const Camera camera = overviewCamera();
    for (bool fallback : {true, false})
        for (bool paper : {false, true}) {
            const SequenceResult r =
                expectExact(scene, 160, 120, 22, withCamera(scene, camera, 160, 120), reuseOptions(16, 16, fallback, paper));
            if (!fallback) {
                EXPECT_EQ(r.count(ReuseMode::Reuse), 21u) << r.describe();
            }
        }
}

TEST_F(ReuseGLTest, CulledDrawLists) {
    for (const char* spec : {"builtin:default", "builtin:cubes"}) {
        for (Cull method : {Cull::Sphere, Cull::Conservative}) {
            SCOPED_TRACE(std::string(spec) + " " + toString(method));
            Scene scene = loadOrFail(spec);
            const SceneCuller culler = SceneCuller::prepare(scene);  // before the upload
            int culled = 0;
            const Frames frames = culledFrames(scene, culler, method, 160, 120, culled);
            const SequenceResult r =
                expectExact(scene, 160, 120, int(kCullAngles.size()), frames, reuseOptions(16, 16, false));
            EXPECT_EQ(r.modes(), kCullModes) << r.describe();
            EXPECT_GT(culled, 0);
        }
    }
}

// The scene made for ties: on GL too, every difference is a tie, and frames 1..8 (the dynamic quad
// moving, drawn after the static one under reuse) tie on the whole overlap.
TEST_F(ReuseGLTest, CoplanarQuadsTieOnlyWhileOneMoves) {
    const Scene scene = coplanarQuadsScene();
    const Camera camera = coplanarQuadsCamera();
    const SequenceResult r =
        expectExact(scene, 160, 120, 12, withCamera(scene, camera, 160, 120), reuseOptions(16, 16, false), true);
    ASSERT_EQ(r.matches.size(), 12u);
    for (std::size_t i = 0; i < r.matches.size(); ++i) {
        EXPECT_EQ(r.matches[i].differing, r.matches[i].ties) << "frame " << i;
        if (i >= 1 && i <= 8) {
            EXPECT_GT(r.matches[i].ties, 500u) << "frame " << i;
        } else {
            EXPECT_EQ(r.matches[i].ties, 0u) << "frame " << i;
        }
    }
}

}  // namespace
}  // namespace frugal::test
