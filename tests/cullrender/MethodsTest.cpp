// What each culling method promises besides never missing: none and oracle give the full list,
// sphere drops whole instances outside the frustum and keeps those inside, an instance behind the
// camera is dropped, plans are in instance order with ranges inside the mesh, no method keeps
// history, names parse, preparation is per mesh.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include "CullRenderSupport.h"
#include "TestSupport.h"
#include "lab/Views.h"

namespace frugal {
namespace {

using test::CullBench;

bool hasInstance(const DrawList& list, int instance) {
    for (const DrawCommand& command : list)
        if (command.instance == instance) return true;
    return false;
}

// Three blobs on the x axis (single-sided, mirrored, double-sided) and an empty mesh's instance.
Scene threeBlobs(float spacing) {
    Scene scene = test::singleMeshScene(test::finished(test::blobMesh(21)), false);
    test::addMeshNode(scene, 0, {spacing, 0.0f, 0.0f}, glm::angleAxis(0.4f, glm::vec3(0, 0, 1)), {-1.0f, 1.0f, 1.0f});
    Mesh second = test::finished(test::blobMesh(22));
    second.material = 1;
    scene.meshes.push_back(std::move(second));
    scene.meshes.push_back(Mesh{});  // empty: never in a plan
    scene.nodes[0].meshes = {0, 2};
    test::addMeshNode(scene, 1, {2.0f * spacing, 0.0f, 0.0f});
    scene.buildInstances();
    return scene;
}

TEST(CullMethodsTest, NamesParseBack) {
    for (Cull method : kCulls) {
        const std::optional<Cull> parsed = fromString(toString(method), kCulls);
        ASSERT_TRUE(parsed) << toString(method);
        EXPECT_EQ(*parsed, method);
    }
    EXPECT_FALSE(fromString("Conservative", kCulls));
    EXPECT_FALSE(fromString("", kCulls));
    EXPECT_EQ(namesOf(kCulls), "none, sphere, backface, cones, paper, conservative, occlusion, occlusion-ahead, oracle");
}

TEST(CullMethodsTest, NoneAndOracleGiveTheFullList) {
    CullBench bench(threeBlobs(3.0f), 96, 72);
    ASSERT_EQ(bench.scene.instances.size(), 4u);
    const DrawList full = fullDrawList(bench.scene);
    ASSERT_EQ(full.size(), 3u) << "the empty mesh's instance is not drawn";
    for (const Camera& spec : {test::lookAt({3, 0, 8}, {3, 0, 0}), test::lookAt({3, 0, -8}, {3, 0, 0}),
                               test::lookAt({40, 0, 0}, {80, 0, 0})}) {
        Result<FrameSetup> setup = setUpFrame(bench.scene, spec, 0.0, 96, 72, true);
        ASSERT_TRUE(setup) << setup.error().message;
        for (Cull method : {Cull::None, Cull::Oracle}) {
            const DrawList list = bench.culler.cull(method, bench.scene, setup->world, setup->view);
            EXPECT_TRUE(test::sameList(list, full)) << toString(method);
        }
    }
}

TEST(CullMethodsTest, SphereDropsAnInstanceOutsideTheFrustumAndKeepsOneInside) {
    CullBench bench(threeBlobs(3.0f), 96, 72);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    // Looking at blob 0 from close up: blob 0 whole in view, blob 1 (x = 3) partly, blob 2 (x = 6) out.
    Camera spec = test::lookAt({0.0f, 0.0f, 5.5f}, {0.4f, 0.0f, 0.0f});
    spec.yfovDegrees = 40.0f;
    const test::FrameResult frame = test::checkFrame(bench, spec, "sphere");
    ASSERT_TRUE(frame.rendered);
    const DrawList* sphere = frame.list(Cull::Sphere);
    ASSERT_NE(sphere, nullptr);
    EXPECT_TRUE(hasInstance(*sphere, 0));
    EXPECT_FALSE(hasInstance(*sphere, 3)) << "blob at x = 6 is outside the frustum";
    for (const DrawCommand& command : *sphere) {
        // Whole instances: one range over the mesh.
        ASSERT_EQ(command.ranges.size(), 1u);
        EXPECT_EQ(command.ranges[0].firstTriangle, 0u);
        EXPECT_EQ(std::size_t(command.ranges[0].triangleCount),
                  bench.scene.meshes[std::size_t(bench.scene.instances[std::size_t(command.instance)].mesh)].triangleCount());
    }
    Result<FrameSetup> setup = setUpFrame(bench.scene, spec, 0.0, 96, 72, true);
    ASSERT_TRUE(setup);
    EXPECT_EQ(bench.culler.classify(bench.scene, 0, setup->world, setup->view), SphereClass::Whole);
    EXPECT_EQ(bench.culler.classify(bench.scene, 3, setup->world, setup->view), SphereClass::Outside);
    // The other methods drop it too.
    for (Cull method : test::kNeverMiss) EXPECT_FALSE(hasInstance(*frame.list(method), 3)) << toString(method);
    // Looking straight at blob 2 only.
    const test::FrameResult other = test::checkFrame(bench, test::lookAt({6.0f, 0.0f, 3.5f}, {6.0f, 0.0f, 0.0f}), "other");
    EXPECT_TRUE(hasInstance(*other.list(Cull::Sphere), 3));
    EXPECT_FALSE(hasInstance(*other.list(Cull::Sphere), 0));
}

TEST(CullMethodsTest, InstanceBehindTheCameraIsDropped) {
    CullBench bench(threeBlobs(3.0f), 96, 72);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    // The eye between blob 1 and blob 2 looking at blob 2 (+x): blobs 0 and 1 are behind it.
    Camera spec = test::lookAt({4.5f, 0.0f, 0.0f}, {6.0f, 0.0f, 0.0f});
    spec.znear = 0.05f;
    spec.zfar = 100.0f;
    const test::FrameResult frame = test::checkFrame(bench, spec, "behind");
    ASSERT_TRUE(frame.rendered);
    for (Cull method : {Cull::Sphere, Cull::Backface, Cull::Conservative, Cull::Cones}) {
        const DrawList* list = frame.list(method);
        ASSERT_NE(list, nullptr);
        EXPECT_FALSE(hasInstance(*list, 0)) << toString(method) << " keeps the blob behind the camera";
        EXPECT_TRUE(hasInstance(*list, 3)) << toString(method) << " drops the blob in front";
    }
    // Even the far plane at infinity, and the paper method, see it as outside.
    spec.zfar = 0.0f;
    const test::FrameResult infinite = test::checkFrame(bench, spec, "behind, infinite far plane");
    for (Cull method : {Cull::Sphere, Cull::Backface, Cull::Conservative, Cull::Paper})
        EXPECT_FALSE(hasInstance(*infinite.list(method), 0)) << toString(method);
}

TEST(CullMethodsTest, PlansAreInInstanceOrderWithRangesInsideTheMesh) {
    Result<Scene> scene = loadScene("builtin:cubes?count=40&seed=3");
    ASSERT_TRUE(scene) << scene.error().message;
    CullBench bench(std::move(*scene), 96, 72);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    test::Tallies tallies;
    const double duration = bench.scene.duration();
    for (double time : {0.0, 0.5 * duration}) {
        // checkFrame checks the shape of every method's plan (expectWellFormed) and the renders.
        tallies.add(test::checkFrame(bench, {}, "cubes at " + std::to_string(time), time));
        test::Tallies views = test::checkReportViews(bench, 8, "cubes", time);
        EXPECT_GT(views.of(Cull::Conservative).rvs, 0u);
    }
    EXPECT_GT(tallies.of(Cull::Conservative).rvs, 0u);
    // A hand-made plan with an out-of-order instance would be caught: expectWellFormed is not vacuous.
    DrawList bad = fullDrawList(bench.scene);
    ASSERT_GE(bad.size(), 2u);
    std::swap(bad[0], bad[1]);
    EXPECT_NONFATAL_FAILURE(test::expectWellFormed(bench.scene, bad, "swapped"), "out of scene order");
}

// Every exact method stays exact with masked and blended surfaces (test::addAlpha): neither hides
// anything, so occlusion culling keeps what lies behind them, and blended ones are drawn last.
TEST(CullMethodsTest, MaskedAndBlendedSurfacesKeepEveryMethodExact) {
    Result<Scene> cubes = loadScene("builtin:cubes?count=40&seed=3");
    ASSERT_TRUE(cubes) << cubes.error().message;
    test::addAlpha(*cubes);
    CullBench bench(std::move(*cubes), 96, 72);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    test::Tallies views = test::checkReportViews(bench, 8, "cubes with alpha");
    EXPECT_GT(views.of(Cull::Conservative).rvs, 0u);

    Scene blobs = threeBlobs(2.5f);
    test::addAlpha(blobs);
    CullBench lined(std::move(blobs), 96, 72);
    ASSERT_TRUE(lined.canRender()) << lined.uploadError;
    for (const glm::vec3& eye : {glm::vec3(-6, 0.5f, 0), glm::vec3(11, -0.5f, 0.3f), glm::vec3(2.5f, 1, 7)})
        test::checkFrame(lined, test::lookAt(eye, {2.5f, 0, 0}), "blobs with alpha");
}

// The judge itself: a plan missing one visible triangle is seen as a miss, and its render differs.
TEST(CullMethodsTest, TheCheckSeesASingleDroppedTriangle) {
    CullBench bench(threeBlobs(3.0f), 96, 72);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    Result<FrameSetup> setup = setUpFrame(bench.scene, test::lookAt({3, 1, 7}, {3, 0, 0}), 0.0, 96, 72, true);
    ASSERT_TRUE(setup) << setup.error().message;
    bench.renderer->renderFrame(bench.target, 96, 72, setup->params, setup->world, test::kBackground);
    const Buffers full = bench.backend->readBack(bench.target);
    Result<TriangleSet> rvs = visibleSet(bench.scene, full);
    ASSERT_TRUE(rvs) << rvs.error().message;
    // Drop the visible triangle of the first drawn instance that has one.
    DrawList list = fullDrawList(bench.scene);
    bool dropped = false;
    for (DrawCommand& command : list) {
        const std::vector<std::uint8_t>& visible = rvs->perInstance[std::size_t(command.instance)];
        for (std::uint32_t t = 0; t < visible.size() && !dropped; ++t)
            if (visible[t]) {
                command.ranges = {{0, t}, {t + 1, std::uint32_t(visible.size()) - t - 1}};
                if (t == 0) command.ranges.erase(command.ranges.begin());
                dropped = true;
            }
        if (dropped) break;
    }
    ASSERT_TRUE(dropped);
    const SetCounts counts = compareSets(bench.scene, drawnSet(bench.scene, list), *rvs);
    EXPECT_EQ(counts.misses, 1u);
    bench.renderer->renderFrame(bench.target, 96, 72, setup->params, setup->world, test::kBackground, list);
    std::string first;
    EXPECT_GT(test::differingPixels(full, bench.backend->readBack(bench.target), first), 0u);
}

TEST(CullMethodsTest, NoMethodKeepsHistory) {
    CullBench bench(threeBlobs(2.5f), 96, 72);
    const Camera a = test::lookAt({1, 1, 6}, {2.5f, 0, 0}), b = test::lookAt({6, -2, -3}, {4, 0, 0});
    Result<FrameSetup> sa = setUpFrame(bench.scene, a, 0.0, 96, 72, true), sb = setUpFrame(bench.scene, b, 0.0, 96, 72, true);
    ASSERT_TRUE(sa && sb);
    for (Cull method : kCulls) {
        const DrawList first = bench.culler.cull(method, bench.scene, sa->world, sa->view);
        (void)bench.culler.cull(method, bench.scene, sb->world, sb->view);
        const DrawList again = bench.culler.cull(method, bench.scene, sa->world, sa->view);
        EXPECT_TRUE(test::sameList(first, again)) << toString(method);
    }
}

TEST(CullMethodsTest, PrepareMapsEveryMeshOnceAndReordersIt) {
    Scene scene = threeBlobs(3.0f);
    const Scene before = scene;
    const SceneCuller culler = SceneCuller::prepare(scene);
    ASSERT_EQ(culler.maps().size(), scene.meshes.size());
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        EXPECT_EQ(mesh.triangleCount(), before.meshes[m].triangleCount());
        EXPECT_EQ(mesh.positions, before.meshes[m].positions) << "vertices are untouched";
        EXPECT_EQ(culler.maps()[m].entries.size(), mesh.triangleCount());
        // The map's planes describe the reordered mesh.
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const glm::vec4 plane = culler.maps()[m].planes[t];
            if (glm::vec3(plane) == glm::vec3(0.0f)) continue;
            const glm::vec3 a = mesh.positions[mesh.indices[3 * t]];
            EXPECT_NEAR(glm::dot(glm::vec3(plane), a), plane.w, 1e-4f) << "mesh " << m << " triangle " << t;
        }
    }
    const PrepStats totals = culler.totals();
    std::size_t mapBytes = 0;
    for (const MeshMap& map : culler.maps()) mapBytes += map.stats.mapBytes;
    EXPECT_EQ(totals.mapBytes, mapBytes);
    EXPECT_GT(totals.accessBytes, 0u);
    EXPECT_GE(totals.totalMs(), 0.0);
}

}  // namespace
}  // namespace frugal
