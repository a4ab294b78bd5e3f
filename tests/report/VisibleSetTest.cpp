// Visible sets (TOS/PVS/RVS) on hand-built scenes and id images whose answers are known by hand.
#include <algorithm>
#include <chrono>
#include <numeric>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "pipeline/IndexRanges.h"
#include "cull/VisibleSet.h"

namespace frugal {
namespace {

using Members = std::vector<std::uint8_t>;

// Four triangles reordered from the file: triangle t came from primitive source[t]. Each triangle has
// its own three vertices, so its indices say which one it is (triangle t: 3t, 3t+1, 3t+2).
Mesh permutedMesh(const std::vector<std::uint32_t>& source, int material, const std::string& name) {
    Mesh mesh;
    mesh.name = name;
    mesh.material = material;
    for (std::size_t t = 0; t < source.size(); ++t) {
        const float x = float(t);
        mesh.positions.insert(mesh.positions.end(), {{x, 0, 0}, {x + 1, 0, 0}, {x, 1, 0}});
        mesh.normals.insert(mesh.normals.end(), 3, glm::vec3(0, 0, 1));
        mesh.uvs.insert(mesh.uvs.end(), {{0, 0}, {1, 0}, {0, 1}});
        for (std::uint32_t k = 0; k < 3; ++k) mesh.indices.push_back(std::uint32_t(3 * t) + k);
    }
    mesh.triangleSource = source;
    return mesh;
}

// Mesh 0 (4 triangles, sources {2, 0, 3, 1}) is shared by instances 0 (ids 20..23) and 1 (ids 1..4);
// mesh 1 (3 triangles, no triangleSource: source t = t) is instance 2 (ids 5..7). The instances are
// not in id order on purpose.
Scene sharedMeshScene() {
    Scene scene;
    scene.source = "hand-built";
    scene.materials = {Material{"red", glm::vec4(1, 0, 0, 1), -1, false},
                       Material{"textured", glm::vec4(1), 0, true}};
    scene.textures.push_back(Texture{"checker", 1, 1, {255, 255, 255, 255}, Wrap::Repeat, Wrap::Repeat, Filter::Nearest});
    scene.meshes.push_back(permutedMesh({2, 0, 3, 1}, 0, "shared"));
    Mesh plain = permutedMesh({0, 1, 2}, 1, "plain");
    plain.triangleSource.clear();
    scene.meshes.push_back(plain);
    scene.nodes.resize(3);
    scene.nodes[0].name = "a";
    scene.nodes[0].meshes = {0};
    scene.nodes[1].name = "b";
    scene.nodes[1].meshes = {0, 1};
    scene.nodes[2].name = "camera";
    scene.nodes[2].camera = 0;
    scene.roots = {0, 1, 2};
    scene.cameras.push_back(SceneCamera{});
    scene.animations.push_back(Animation{"spin", {}});
    scene.instances = {Instance{0, 0, 20}, Instance{1, 0, 1}, Instance{1, 1, 5}};
    return scene;
}

// A width × height frame with an id image of background (0).
Buffers idFrame(int width, int height) {
    Buffers b;
    b.width = width;
    b.height = height;
    b.rgba.assign(4 * b.pixelCount(), 0);
    b.ids.assign(b.pixelCount(), 0);
    return b;
}

// Buffers rows are bottom-up: image (x, y), y down from the top row → index.
std::uint32_t& idAt(Buffers& b, int x, int imageY) {
    return b.ids[std::size_t(b.height - 1 - imageY) * std::size_t(b.width) + std::size_t(x)];
}

TriangleSet visible(const Scene& scene, const Buffers& b) {
    Result<TriangleSet> set = visibleSet(scene, b);
    EXPECT_TRUE(set) << set.error().message;
    return set ? *set : TriangleSet{};
}

TEST(VisibleSetTest, EmptySetIsShapedLikeTheScene) {
    const TriangleSet set = emptySet(sharedMeshScene());
    ASSERT_EQ(set.perInstance.size(), 3u);
    EXPECT_EQ(set.perInstance[0], Members(4, 0));
    EXPECT_EQ(set.perInstance[1], Members(4, 0));
    EXPECT_EQ(set.perInstance[2], Members(3, 0));
    EXPECT_EQ(set.count, 0u);
}

TEST(VisibleSetTest, DrawnSetClampsRangesAndCountsOverlapsOnce) {
    const Scene scene = sharedMeshScene();
    const DrawList list = {
        {0, {{1, 2}, {2, 5}}},  // 1, 2, then 2 again and 3 (clamped at 4 triangles)
        {2, {{5, 3}, {0, 1}}},  // past the end: nothing; then triangle 0
        {2, {{0, 1}}},          // the same triangle in a second command
    };
    const TriangleSet set = drawnSet(scene, list);
    ASSERT_EQ(set.perInstance.size(), 3u);
    EXPECT_EQ(set.perInstance[0], (Members{0, 1, 1, 1}));
    EXPECT_EQ(set.perInstance[1], Members(4, 0));
    EXPECT_EQ(set.perInstance[2], (Members{1, 0, 0}));
    EXPECT_EQ(set.count, 4u);

    const TriangleSet full = drawnSet(scene, fullDrawList(scene));
    EXPECT_EQ(full.count, 11u);
    EXPECT_EQ(full.perInstance[1], Members(4, 1));
}

#ifdef NDEBUG
TEST(VisibleSetTest, DrawnSetIgnoresCommandsForInstancesTheSceneDoesNotHave) {
    const Scene scene = sharedMeshScene();
    const TriangleSet set = drawnSet(scene, {{-1, {{0, 1}}}, {3, {{0, 1}}}, {1, {{3, 1}}}});
    EXPECT_EQ(set.count, 1u);
    EXPECT_EQ(set.perInstance[1], (Members{0, 0, 0, 1}));
}
#endif

TEST(VisibleSetTest, IdsMapBackThroughFirstIdAndTriangleSource) {
    const Scene scene = sharedMeshScene();
    Buffers b = idFrame(4, 3);
    idAt(b, 0, 0) = 20;  // instance 0, source 0 → triangle 1
    idAt(b, 1, 0) = 20;
    idAt(b, 3, 1) = 23;  // instance 0, source 3 → triangle 2
    idAt(b, 2, 2) = 3;   // instance 1, source 2 → triangle 0
    idAt(b, 0, 2) = 4;   // instance 1, source 3 → triangle 2
    idAt(b, 1, 1) = 7;   // instance 2, source 2 = triangle 2
    idAt(b, 2, 1) = 20;  // again, not next to the first
    const TriangleSet set = visible(scene, b);
    ASSERT_EQ(set.perInstance.size(), 3u);
    EXPECT_EQ(set.perInstance[0], (Members{0, 1, 1, 0}));
    EXPECT_EQ(set.perInstance[1], (Members{1, 0, 1, 0}));
    EXPECT_EQ(set.perInstance[2], (Members{0, 0, 1}));
    EXPECT_EQ(set.count, 5u);

    // A background-only frame: the empty set.
    const TriangleSet none = visible(scene, idFrame(4, 3));
    EXPECT_EQ(none.count, 0u);
    EXPECT_EQ(none.perInstance[2], Members(3, 0));
}

TEST(VisibleSetTest, UnknownIdIsReportedWithItsImagePosition) {
    const Scene scene = sharedMeshScene();
    Buffers b = idFrame(4, 3);
    idAt(b, 0, 2) = 4;
    idAt(b, 2, 0) = 9;  // between instance 2 (5..7) and instance 0 (20..23)
    Result<TriangleSet> set = visibleSet(scene, b);
    ASSERT_FALSE(set);
    EXPECT_EQ(set.error().message, "id 9 at pixel (2, 0) belongs to no triangle of the scene");

    Buffers past = idFrame(4, 3);
    idAt(past, 1, 2) = 24;  // one past instance 0's last id
    set = visibleSet(scene, past);
    ASSERT_FALSE(set);
    EXPECT_EQ(set.error().message, "id 24 at pixel (1, 2) belongs to no triangle of the scene");

    // A source no triangle has (dropped while loading) names no triangle either.
    Scene holes = sharedMeshScene();
    holes.meshes[1].triangleSource = {0, 2, 3};  // instance 2: ids 5, 7, 8; 6 is unused
    Buffers hole = idFrame(2, 2);
    idAt(hole, 0, 0) = 8;
    EXPECT_TRUE(visibleSet(holes, hole));
    idAt(hole, 1, 1) = 6;
    set = visibleSet(holes, hole);
    ASSERT_FALSE(set);
    EXPECT_EQ(set.error().message, "id 6 at pixel (1, 1) belongs to no triangle of the scene");
}

TEST(VisibleSetTest, FrameWithoutIdsIsAnError) {
    Buffers b = idFrame(4, 3);
    b.ids.clear();
    const Result<TriangleSet> set = visibleSet(sharedMeshScene(), b);
    ASSERT_FALSE(set);
    EXPECT_EQ(set.error().message, "the frame has no id image");
}

TEST(VisibleSetTest, CompareSetsCountsMissesAndWaste) {
    const Scene scene = sharedMeshScene();
    TriangleSet pvs = emptySet(scene), rvs = emptySet(scene);
    pvs.perInstance[0] = {1, 1, 0, 0};
    pvs.perInstance[2] = {1, 1, 1};
    pvs.count = 5;
    rvs.perInstance[0] = {0, 1, 1, 0};  // triangle 2 missed, triangle 0 wasted
    rvs.perInstance[1] = {0, 0, 0, 1};  // missed
    rvs.perInstance[2] = {0, 1, 0};     // triangles 0 and 2 wasted
    rvs.count = 4;
    const SetCounts c = compareSets(scene, pvs, rvs);
    EXPECT_EQ(c.tos, 11u);
    EXPECT_EQ(c.pvs, 5u);
    EXPECT_EQ(c.rvs, 4u);
    EXPECT_EQ(c.misses, 2u);
    EXPECT_EQ(c.waste, 3u);

    const SetCounts same = compareSets(scene, rvs, rvs);
    EXPECT_EQ(same.misses, 0u);
    EXPECT_EQ(same.waste, 0u);
    EXPECT_EQ(same.pvs, 4u);
}

TEST(VisibleSetTest, OracleSceneHoldsExactlyTheSetWithTheSameIds) {
    const Scene scene = sharedMeshScene();
    TriangleSet set = emptySet(scene);
    set.perInstance[0] = {1, 0, 1, 1};
    set.perInstance[1] = {0, 1, 0, 0};
    set.perInstance[2] = {0, 0, 0};  // nothing visible: an empty mesh
    set.count = 4;
    const Scene oracle = oracleScene(scene, set);

    EXPECT_EQ(oracle.triangleCount(), 4u);
    ASSERT_EQ(oracle.instances.size(), 3u);
    ASSERT_EQ(oracle.meshes.size(), 3u);
    EXPECT_EQ(oracle.source, scene.source);
    ASSERT_EQ(oracle.materials.size(), 2u);
    EXPECT_EQ(oracle.materials[1].name, "textured");
    EXPECT_EQ(oracle.materials[1].baseColorTexture, 0);
    EXPECT_EQ(oracle.textures.size(), 1u);
    EXPECT_EQ(oracle.cameras.size(), 1u);
    EXPECT_EQ(oracle.animations.size(), 1u);
    EXPECT_EQ(oracle.roots, scene.roots);
    ASSERT_EQ(oracle.nodes.size(), scene.nodes.size());
    EXPECT_EQ(oracle.nodes[2].camera, 0);

    for (std::size_t i = 0; i < 3; ++i) {
        SCOPED_TRACE("instance " + std::to_string(i));
        const Instance& was = scene.instances[i];
        const Instance& now = oracle.instances[i];
        EXPECT_EQ(now.node, was.node);
        EXPECT_EQ(now.firstId, was.firstId);
        ASSERT_GE(now.mesh, 0);
        ASSERT_LT(std::size_t(now.mesh), oracle.meshes.size());
        for (std::size_t j = 0; j < i; ++j) EXPECT_NE(oracle.instances[j].mesh, now.mesh) << "a mesh of its own";
        const Mesh& from = scene.meshes[std::size_t(was.mesh)];
        const Mesh& mesh = oracle.meshes[std::size_t(now.mesh)];
        EXPECT_TRUE(isUploadable(mesh));
        EXPECT_EQ(mesh.name, from.name + " (visible)");
        EXPECT_EQ(mesh.material, from.material);
        EXPECT_EQ(mesh.positions, from.positions);
        EXPECT_EQ(mesh.normals, from.normals);
        EXPECT_EQ(mesh.uvs, from.uvs);
        const auto& nodeMeshes = oracle.nodes[std::size_t(now.node)].meshes;
        EXPECT_NE(std::find(nodeMeshes.begin(), nodeMeshes.end(), now.mesh), nodeMeshes.end());

        // The set's triangles in index-buffer order, with their vertices and their ids.
        const std::vector<std::uint32_t> fromSources = triangleSources(from);
        std::vector<std::uint32_t> expectedIndices, expectedIds, ids;
        for (std::size_t t = 0; t < from.triangleCount(); ++t) {
            if (!set.perInstance[i][t]) continue;
            expectedIndices.insert(expectedIndices.end(), from.indices.begin() + std::ptrdiff_t(3 * t),
                                   from.indices.begin() + std::ptrdiff_t(3 * t + 3));
            expectedIds.push_back(was.firstId + fromSources[t]);
        }
        for (std::uint32_t s : triangleSources(mesh)) ids.push_back(now.firstId + s);
        EXPECT_EQ(mesh.indices, expectedIndices);
        EXPECT_EQ(ids, expectedIds);
    }
    // By hand: instance 0 keeps triangles 0, 2, 3 (sources 2, 3, 1); instance 1 triangle 1 (source 0).
    EXPECT_EQ(oracle.meshes[std::size_t(oracle.instances[0].mesh)].triangleSource, (std::vector<std::uint32_t>{2, 3, 1}));
    EXPECT_EQ(oracle.meshes[std::size_t(oracle.instances[1].mesh)].triangleSource, (std::vector<std::uint32_t>{0}));
    EXPECT_EQ(oracle.meshes[std::size_t(oracle.instances[2].mesh)].triangleCount(), 0u);

    // Drawn whole, the oracle draws exactly the set.
    const TriangleSet drawn = drawnSet(oracle, fullDrawList(oracle));
    EXPECT_EQ(drawn.count, 4u);
}

TEST(VisibleSetTest, OracleOfAMeasuredSetSeesTheSameIds) {
    // The round trip the report makes: ids → set → oracle; the frame's ids are all the oracle's.
    const Scene scene = sharedMeshScene();
    Buffers b = idFrame(3, 2);
    idAt(b, 0, 0) = 21;
    idAt(b, 1, 0) = 2;
    idAt(b, 2, 1) = 6;
    const TriangleSet set = visible(scene, b);
    ASSERT_EQ(set.count, 3u);
    const Scene oracle = oracleScene(scene, set);
    EXPECT_EQ(oracle.triangleCount(), 3u);
    const TriangleSet again = visible(oracle, b);
    EXPECT_EQ(again.count, 3u);
    const SetCounts c = compareSets(oracle, drawnSet(oracle, fullDrawList(oracle)), again);
    EXPECT_EQ(c.tos, 3u);
    EXPECT_EQ(c.misses, 0u);
    EXPECT_EQ(c.waste, 0u);
}

TEST(VisibleSetTest, LargeFrameMatchesTheDistinctIds) {
    // 800×600 ids over 3 instances of a shuffled 70k-triangle mesh (210k triangles), in runs of a few
    // pixels as a render gives them. The count must equal the number of distinct ids.
    constexpr std::uint32_t kTriangles = 70000;
    std::vector<std::uint32_t> source(kTriangles);
    std::iota(source.begin(), source.end(), 0u);
    std::mt19937 random(7);
    std::shuffle(source.begin(), source.end(), random);
    Scene scene;
    Mesh mesh;
    mesh.positions.assign(3, glm::vec3(0));
    mesh.indices.assign(3 * kTriangles, 0);
    mesh.triangleSource = source;
    scene.meshes.push_back(std::move(mesh));
    scene.nodes.resize(3);
    for (int n = 0; n < 3; ++n) scene.nodes[std::size_t(n)].meshes = {0};
    scene.buildInstances();
    std::reverse(scene.instances.begin(), scene.instances.end());

    Buffers b = idFrame(800, 600);
    std::uniform_int_distribution<std::uint32_t> pick(0, 3 * kTriangles);  // 0 = background
    std::set<std::uint32_t> distinct;
    for (std::size_t p = 0; p < b.ids.size();) {
        const std::uint32_t id = pick(random);
        for (std::size_t k = 0; k < 4 && p < b.ids.size(); ++k) b.ids[p++] = id;
        if (id != 0) distinct.insert(id);
    }
    const auto start = std::chrono::steady_clock::now();
    const TriangleSet set = visible(scene, b);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    RecordProperty("visible_set_ms", std::to_string(ms));
    EXPECT_EQ(set.count, distinct.size());
    std::size_t members = 0;
    for (const Members& m : set.perInstance) members += std::size_t(std::count(m.begin(), m.end(), 1));
    EXPECT_EQ(members, set.count);
    // Spot check: the instance listed first now holds the last ids.
    const Instance& first = scene.instances[0];
    const std::uint32_t id = *distinct.rbegin();
    ASSERT_GE(id, first.firstId);
    const auto t = std::size_t(std::find(source.begin(), source.end(), id - first.firstId) - source.begin());
    EXPECT_EQ(set.perInstance[0][t], 1);
}

}  // namespace
}  // namespace frugal
