// The plan vocabulary both backends and future planners (culling, reuse) share: the full draw list,
// index-range normalisation, handle tables, rectangle clipping and frame set-up.
#include <type_traits>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "pipeline/Frame.h"
#include "pipeline/Handles.h"
#include "pipeline/IndexRanges.h"
#include "pipeline/Plan.h"

namespace frugal {
namespace {

Mesh triangles(int count) {
    Mesh mesh;
    for (int t = 0; t < count; ++t) {
        const auto base = std::uint32_t(mesh.positions.size());
        for (const glm::vec3& p : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}) {
            mesh.positions.push_back(p);
            mesh.normals.push_back(glm::vec3(0, 0, 1));
        }
        for (std::uint32_t k = 0; k < 3; ++k) mesh.indices.push_back(base + k);
    }
    return mesh;
}

// Three nodes: node 0 draws mesh 2 (3 triangles), node 1 draws the empty mesh 1 and then mesh 0
// (2 triangles), node 2 draws mesh 0 again.
Scene threeNodeScene() {
    Scene scene;
    scene.meshes = {triangles(2), Mesh{}, triangles(3)};
    scene.nodes.resize(3);
    scene.nodes[0].meshes = {2};
    scene.nodes[1].meshes = {1, 0};
    scene.nodes[2].meshes = {0};
    scene.roots = {0, 1, 2};
    scene.buildInstances();
    return scene;
}

TEST(PlanTest, FullDrawListIsEveryNonEmptyInstanceInInstanceOrder) {
    const Scene scene = threeNodeScene();
    ASSERT_EQ(scene.instances.size(), 4u);
    const DrawList list = fullDrawList(scene);
    ASSERT_EQ(list.size(), 3u);  // the empty mesh's instance (1) is left out
    const int instances[3] = {0, 2, 3};
    const std::uint32_t counts[3] = {3, 2, 2};
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(list[k].instance, instances[k]);
        ASSERT_EQ(list[k].ranges.size(), 1u);
        EXPECT_EQ(list[k].ranges[0].firstTriangle, 0u);
        EXPECT_EQ(list[k].ranges[0].triangleCount, counts[k]);
        EXPECT_EQ(std::size_t(counts[k]), scene.meshes[scene.instances[instances[k]].mesh].triangleCount());
    }
}

TEST(PlanTest, NormalizeRangesKeepsOrderDropsEmptyAndMergesOnlyAdjacentRuns) {
    std::vector<IndexRange> out;
    const IndexRange in[] = {{4, 2}, {6, 3}, {0, 0}, {2, 1}, {3, 1}, {9, 1}, {0, 2}};
    EXPECT_EQ(normalizeRanges(in, 10, out), 10u);
    const std::vector<std::pair<std::uint32_t, std::uint32_t>> expected = {{4, 5}, {2, 2}, {9, 1}, {0, 2}};
    ASSERT_EQ(out.size(), expected.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        EXPECT_EQ(out[i].firstTriangle, expected[i].first) << i;
        EXPECT_EQ(out[i].triangleCount, expected[i].second) << i;
    }
    EXPECT_EQ(normalizeRanges({}, 10, out), 0u);
    EXPECT_TRUE(out.empty());
}

TEST(PlanTest, TriangleSourcesDefaultToTheTriangleIndex) {
    Mesh mesh = triangles(3);
    EXPECT_EQ(triangleSources(mesh), (std::vector<std::uint32_t>{0, 1, 2}));
    mesh.triangleSource = {7, 5, 6};
    EXPECT_EQ(triangleSources(mesh), mesh.triangleSource);
}

// Handles are typed: a mesh's does not pass as a target's, nor does a bare number; kNoHandle is
// every kind's "none".
static_assert(!std::is_convertible_v<MeshHandle, TargetHandle>);
static_assert(!std::is_convertible_v<TextureHandle, MeshHandle>);
static_assert(!std::is_convertible_v<std::uint32_t, TargetHandle>);
static_assert(TargetHandle(kNoHandle) == TargetHandle{} && MeshHandle{} == kNoHandle && !(MeshHandle{1} == kNoHandle));

TEST(PlanTest, HandleTableNeverHandsOutZeroAndReusesFreedSlots) {
    HandleTable<int, MeshHandle> table;
    const MeshHandle a = table.add(10), b = table.add(20);
    EXPECT_EQ(a.id, 1u);
    EXPECT_EQ(b.id, 2u);
    EXPECT_EQ(table.find(kNoHandle), nullptr);
    EXPECT_EQ(table.find(MeshHandle{3}), nullptr);
    int* address = table.find(b);
    table.remove(a);
    EXPECT_EQ(table.find(a), nullptr);
    table.remove(a);  // twice is harmless
    EXPECT_EQ(table.add(30), a);
    EXPECT_EQ(table.find(b), address);  // objects do not move
    int sum = 0;
    table.forEach([&sum](int v) { sum += v; });
    EXPECT_EQ(sum, 50);
}

TEST(PlanTest, ClipRectKeepsThePartInsideTheTarget) {
    const Rect r = clipRect(Rect{-5, 3, 20, 100}, 10, 8);
    EXPECT_EQ(r.x, 0);
    EXPECT_EQ(r.y, 3);
    EXPECT_EQ(r.width, 10);
    EXPECT_EQ(r.height, 5);
    EXPECT_TRUE(clipRect(Rect{10, 0, 4, 4}, 10, 8).empty());
    EXPECT_TRUE(clipRect(Rect{2, 2, -3, 4}, 10, 8).empty());
}

TEST(PlanTest, SetUpFrameSamplesTheSceneAndTheCameraAtItsTime) {
    Scene scene = test::oneMeshScene(triangles(1));
    AnimChannel channel;
    channel.node = 0;
    channel.path = AnimPath::Translation;
    channel.times = {0.0f, 1.0f};
    channel.values = {glm::vec4(0, 0, 0, 0), glm::vec4(4, 0, 0, 0)};
    scene.animations.push_back({"move", {channel}});
    Camera camera;
    camera.eye = glm::vec3(0, 0, 10);
    camera.target = glm::vec3(0, 0, 0);
    Result<FrameSetup> setup = setUpFrame(scene, camera, frameTime(15, 30.0), 64, 48, true);
    ASSERT_TRUE(setup) << setup.error().message;
    EXPECT_DOUBLE_EQ(setup->time, 0.5);
    EXPECT_FLOAT_EQ(setup->world[0][3].x, 2.0f);
    EXPECT_TRUE(setup->params.writeIds);
    EXPECT_EQ(setup->params.view, setup->view.view);
    EXPECT_EQ(setup->params.projection, setup->view.projection);
    camera.target = camera.eye;
    EXPECT_EQ(setUpFrame(scene, camera, 0.0, 64, 48, false).error().message, "camera: eye and target must differ and be finite");
}

TEST(PlanTest, ColorBytesRoundAndClampLikeTheUnormConversion) {
    EXPECT_EQ(colorBytes(glm::vec4(0.12f, 0.13f, 0.15f, 1.0f)), (std::array<std::uint8_t, 4>{31, 33, 38, 255}));
    EXPECT_EQ(colorBytes(glm::vec4(-1.0f, 2.0f, 0.5f, 0.0f)), (std::array<std::uint8_t, 4>{0, 255, 128, 0}));
}

}  // namespace
}  // namespace frugal
