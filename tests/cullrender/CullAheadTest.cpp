// A plan made ahead (cull/CullAhead.h): it is the plan the frame's own cull gives, and it is handed
// out only for exactly the frame it was made for.
#include "CullRenderSupport.h"
#include "cull/CullAhead.h"
#include "TestSupport.h"

namespace frugal {
namespace {

using test::CullBench;

// Three bunnies when glmark2-data is there, else a row of boxes one behind the other.
Scene aheadScene() {
    if (test::loadBunny(false)) {
        Result<Scene> three = makeBuiltin("copies?count=3&of=/usr/share/glmark2/models/bunny.obj");
        if (three) {
            for (Material& m : three->materials) m.doubleSided = false;
            return std::move(*three);
        }
    }
    Result<Scene> boxes = makeBuiltin("cubes");
    EXPECT_TRUE(boxes) << boxes.error().message;
    return boxes ? std::move(*boxes) : Scene{};
}

FrameSetup setupOf(const CullBench& bench, const Camera& camera) {
    Result<FrameSetup> setup = setUpFrame(bench.scene, camera, 0.0, bench.width, bench.height, true);
    EXPECT_TRUE(setup) << setup.error().message;
    return setup ? std::move(*setup) : FrameSetup{};
}

TEST(CullAheadTest, ThePlanMadeAheadIsTheFramesOwn) {
    CullBench bench(aheadScene(), 200, 150);
    const FrameSetup a = setupOf(bench, {});
    const FrameSetup b = setupOf(bench, test::lookAt({3.0f, 1.0f, 9.0f}, {0.0f, 0.0f, 0.0f}));
    const OcclusionTarget target = bench.occlusionTarget();
    const DrawList ownA = bench.culler.cull(Cull::OcclusionAhead, bench.scene, a.world, a.view, target);
    const DrawList ownB = bench.culler.cull(Cull::OcclusionAhead, bench.scene, b.world, b.view, target);
    // The same plan as occlusion's, and it removes something.
    EXPECT_TRUE(test::sameList(ownA, bench.culler.cull(Cull::Occlusion, bench.scene, a.world, a.view, target)));
    EXPECT_LT(submittedTriangles(bench.scene, ownA),
              submittedTriangles(bench.scene, bench.culler.cull(Cull::Conservative, bench.scene, a.world, a.view)));

    CullAhead ahead;
    EXPECT_FALSE(ahead.take(Cull::OcclusionAhead, a.world, a.view, target)) << "nothing was started";
    // Made on its own thread with one band, for frame b: taken for frame b, it is b's plan.
    ahead.start(bench.culler, Cull::OcclusionAhead, bench.scene, b.world, b.view, aheadTarget(target));
    EXPECT_TRUE(ahead.pending());
    ahead.wait();
    std::optional<DrawList> taken = ahead.take(Cull::OcclusionAhead, b.world, b.view, target);
    ASSERT_TRUE(taken);
    EXPECT_TRUE(test::sameList(*taken, ownB));
    EXPECT_FALSE(ahead.pending());
    EXPECT_FALSE(ahead.take(Cull::OcclusionAhead, b.world, b.view, target)) << "a plan is taken once";

    // Any other frame gets nothing: another view, other transforms, another target, another method.
    const auto refused = [&](Cull method, const std::vector<glm::mat4>& world, const View& view,
                             const OcclusionTarget& at, const char* why) {
        ahead.start(bench.culler, Cull::OcclusionAhead, bench.scene, b.world, b.view, aheadTarget(target));
        EXPECT_FALSE(ahead.take(method, world, view, at)) << why;
        EXPECT_FALSE(ahead.pending()) << why << ": what was started is dropped";
    };
    refused(Cull::OcclusionAhead, a.world, a.view, target, "another view and world");
    std::vector<glm::mat4> moved = b.world;
    ASSERT_FALSE(moved.empty());
    moved.back()[3][0] += 1e-3f;
    refused(Cull::OcclusionAhead, moved, b.view, target, "a node moved");
    View nearer = b.view;
    nearer.znear *= 0.5f;
    refused(Cull::OcclusionAhead, b.world, nearer, target, "another near plane");
    OcclusionTarget wider = target;
    wider.width += 1;
    refused(Cull::OcclusionAhead, b.world, b.view, wider, "another target");
    refused(Cull::Occlusion, b.world, b.view, target, "another method");

    // settle() waits and drops; the culler is then free, and culls as before.
    ahead.start(bench.culler, Cull::OcclusionAhead, bench.scene, b.world, b.view, aheadTarget(target));
    ahead.settle();
    EXPECT_FALSE(ahead.pending());
    EXPECT_TRUE(test::sameList(bench.culler.cull(Cull::OcclusionAhead, bench.scene, a.world, a.view, target), ownA));
}

TEST(CullAheadTest, ItsOneBandGivesTheSamePlanAsEveryCore) {
    // aheadTarget walks in one band, so as to leave the draw its cores; the plan is the same.
    CullBench bench(aheadScene(), 240, 180);
    const FrameSetup a = setupOf(bench, {});
    const OcclusionTarget target = bench.occlusionTarget();
    EXPECT_EQ(aheadTarget(target).threads, 1);
    EXPECT_TRUE(test::sameList(bench.culler.cull(Cull::OcclusionAhead, bench.scene, a.world, a.view, aheadTarget(target)),
                               bench.culler.cull(Cull::OcclusionAhead, bench.scene, a.world, a.view, target)));
}

}  // namespace
}  // namespace frugal
