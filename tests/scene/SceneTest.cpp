// Scene model: hierarchy, animation sampling, mesh finalisation, instance ids.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <frugal/Scene.h>

#include "scene/MeshBuild.h"

namespace frugal {
namespace {

void expectNear(const glm::vec3& a, const glm::vec3& b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

Mesh triangleMesh() {
    Mesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    mesh.indices = {0, 1, 2, 1, 3, 2};
    return mesh;
}

TEST(SceneTest, WorldTransformsComposeParentFirstWhateverTheNodeOrder) {
    Scene scene;
    // Child listed before its parent.
    Node child;
    child.parent = 1;
    child.translation = {0, 0, 2};
    Node parent;
    parent.children = {0};
    parent.translation = {1, 0, 0};
    parent.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 1, 0));
    scene.nodes = {child, parent};
    const std::vector<glm::mat4> world = scene.worldTransforms(0.0);
    // Child origin: parent translation + rotate((0,0,2)) about y by 90° = (2,0,0) → (3,0,0).
    expectNear(glm::vec3(world[0] * glm::vec4(0, 0, 0, 1)), {3, 0, 0});
    expectNear(glm::vec3(world[1] * glm::vec4(0, 0, 0, 1)), {1, 0, 0});
}

TEST(SceneTest, MatrixNodesUseTheirMatrix) {
    Node node;
    node.hasMatrix = true;
    node.matrix = glm::scale(glm::mat4(1.0f), glm::vec3(2.0f));
    node.translation = {5, 5, 5};  // ignored: the matrix wins
    expectNear(glm::vec3(localMatrix(node) * glm::vec4(1, 1, 1, 1)), {2, 2, 2});
}

TEST(SceneTest, LinearStepAndClampedSampling) {
    AnimChannel channel;
    channel.path = AnimPath::Translation;
    channel.times = {1.0f, 2.0f, 4.0f};
    channel.values = {{0, 0, 0, 0}, {10, 0, 0, 0}, {10, 20, 0, 0}};
    EXPECT_FLOAT_EQ(sampleChannel(channel, 0.0).x, 0.0f);    // before the first key
    EXPECT_FLOAT_EQ(sampleChannel(channel, 1.5).x, 5.0f);
    EXPECT_FLOAT_EQ(sampleChannel(channel, 3.0).y, 10.0f);
    EXPECT_FLOAT_EQ(sampleChannel(channel, 9.0).y, 20.0f);   // after the last key
    channel.interpolation = Interp::Step;
    EXPECT_FLOAT_EQ(sampleChannel(channel, 1.99).x, 0.0f);
    EXPECT_FLOAT_EQ(sampleChannel(channel, 2.0).x, 10.0f);
}

TEST(SceneTest, EqualKeysHoldTheirValueBitForBit) {
    // A pose held between two equal keys must not drift by an ulp (temporal reuse compares poses
    // exactly): x·(1−t) + x·t is not always x in float.
    AnimChannel channel;
    channel.path = AnimPath::Translation;
    const glm::vec4 held{0.1f, 1.0f / 3.0f, 2.7182817f, 0.0f};
    channel.times = {0.0f, 1.0f, 2.0f};
    channel.values = {{0, 0, 0, 0}, held, held};
    for (int k = 1; k < 100; ++k) EXPECT_EQ(sampleChannel(channel, 1.0 + k / 100.0), held) << k;
    AnimChannel rotation = channel;
    rotation.path = AnimPath::Rotation;
    const glm::quat q = glm::angleAxis(0.7f, glm::normalize(glm::vec3(1, 2, 3)));
    rotation.values = {{0, 0, 0, 1}, {q.x, q.y, q.z, q.w}, {q.x, q.y, q.z, q.w}};
    for (int k = 1; k < 100; ++k) EXPECT_EQ(sampleChannel(rotation, 1.0 + k / 100.0), rotation.values[1]) << k;
}

TEST(SceneTest, RotationsSlerpAtConstantAngularSpeed) {
    AnimChannel channel;
    channel.path = AnimPath::Rotation;
    const glm::quat a = glm::angleAxis(0.0f, glm::vec3(0, 0, 1));
    const glm::quat b = glm::angleAxis(glm::radians(120.0f), glm::vec3(0, 0, 1));
    channel.times = {0.0f, 1.0f};
    channel.values = {{a.x, a.y, a.z, a.w}, {b.x, b.y, b.z, b.w}};
    const glm::vec4 q = sampleChannel(channel, 0.25);
    const glm::quat expected = glm::angleAxis(glm::radians(30.0f), glm::vec3(0, 0, 1));
    EXPECT_NEAR(q.z, expected.z, 1e-6f);  // a lerp would give a different (unnormalised) value
    EXPECT_NEAR(q.w, expected.w, 1e-6f);
}

TEST(SceneTest, CubicSplineHitsItsKeysAndUsesTangents) {
    AnimChannel channel;
    channel.path = AnimPath::Translation;
    channel.interpolation = Interp::CubicSpline;
    channel.times = {0.0f, 2.0f};
    // (in-tangent, value, out-tangent) per key.
    channel.values = {{0, 0, 0, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}, {2, 0, 0, 0}, {0, 0, 0, 0}};
    EXPECT_FLOAT_EQ(sampleChannel(channel, 0.0).x, 0.0f);
    EXPECT_FLOAT_EQ(sampleChannel(channel, 2.0).x, 2.0f);
    // t = 0.5, dt = 2: h00=0.5, h10=0.125, h01=0.5, h11=-0.125 → 0.125·2·1 + 0.5·2 − 0.125·2·1 = 1.
    EXPECT_FLOAT_EQ(sampleChannel(channel, 1.0).x, 1.0f);
}

TEST(SceneTest, FinalizeDropsNonFiniteTrianglesAndKeepsSourceIds) {
    Mesh mesh = triangleMesh();
    mesh.positions[3] = {NAN, 0, 0};
    const MeshBuildStats stats = finalizeMesh(mesh, true);
    EXPECT_EQ(stats.droppedNonFinite, 1u);
    ASSERT_EQ(mesh.triangleCount(), 1u);
    EXPECT_EQ(mesh.triangleSource, std::vector<std::uint32_t>{0});
    for (const glm::vec3& p : mesh.positions) EXPECT_TRUE(std::isfinite(p.x));
}

TEST(SceneTest, FinalizeComputesUnitNormalsFacingTheWinding) {
    Mesh mesh = triangleMesh();
    finalizeMesh(mesh, false);
    ASSERT_EQ(mesh.normals.size(), 4u);
    for (const glm::vec3& n : mesh.normals) expectNear(n, {0, 0, 1});
}

// Tangents point along increasing u; w makes cross(normal, tangent) · w point along decreasing v,
// "up" in the image (glTF's normal texture: +y is up).
TEST(SceneTest, GeneratedTangentsFollowUAndTheirSignMakesTheBitangentPointUp) {
    // A quad in the z = 0 plane facing +z, u along +x and v along −y (glTF: v = 0 is the image's top).
    Mesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    mesh.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    finalizeMesh(mesh, false);
    generateTangents(mesh);
    ASSERT_EQ(mesh.tangents.size(), 4u);
    for (const glm::vec4& t : mesh.tangents) {
        expectNear(glm::vec3(t), {1, 0, 0});
        EXPECT_EQ(t.w, 1.0f);
        expectNear(glm::cross(glm::vec3(0, 0, 1), glm::vec3(t)) * t.w, {0, 1, 0});
    }
    // Mirrored in u: the tangent turns round, and w keeps the bitangent up.
    for (glm::vec2& uv : mesh.uvs) uv.x = 1.0f - uv.x;
    generateTangents(mesh);
    for (const glm::vec4& t : mesh.tangents) {
        expectNear(glm::vec3(t), {-1, 0, 0});
        EXPECT_EQ(t.w, -1.0f);
        expectNear(glm::cross(glm::vec3(0, 0, 1), glm::vec3(t)) * t.w, {0, 1, 0});
    }
    // Degenerate texture coordinates, or none: a unit tangent perpendicular to the normal.
    for (glm::vec2& uv : mesh.uvs) uv = {0.5f, 0.5f};
    for (int pass = 0; pass < 2; ++pass) {
        generateTangents(mesh);
        for (std::size_t v = 0; v < 4; ++v) {
            EXPECT_NEAR(glm::length(glm::vec3(mesh.tangents[v])), 1.0f, 1e-6f);
            EXPECT_NEAR(glm::dot(glm::vec3(mesh.tangents[v]), mesh.normals[v]), 0.0f, 1e-6f);
            EXPECT_EQ(mesh.tangents[v].w, 1.0f);
        }
        mesh.uvs.clear();
    }
}

TEST(SceneTest, FinalizeRepairsTangentsItCannotUse) {
    Mesh mesh = triangleMesh();
    mesh.tangents.assign(mesh.positions.size(), glm::vec4(0.0f, 2.0f, 0.0f, -3.0f));
    mesh.tangents[1] = glm::vec4(0.0f);
    mesh.tangents[2] = glm::vec4(NAN, 0.0f, 0.0f, 1.0f);
    finalizeMesh(mesh, false);
    expectNear(glm::vec3(mesh.tangents[0]), {0, 1, 0});  // normalised; w its sign
    EXPECT_EQ(mesh.tangents[0].w, -1.0f);
    for (std::size_t v : {1u, 2u}) {
        EXPECT_NEAR(glm::length(glm::vec3(mesh.tangents[v])), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(glm::vec3(mesh.tangents[v]), mesh.normals[v]), 0.0f, 1e-6f);
    }
}

TEST(SceneTest, CacheOrderIsAPermutationThatCarriesSourceIds) {
    // A grid: enough triangles that meshoptimizer reorders them.
    Mesh mesh;
    const int n = 20;
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) mesh.positions.push_back({float(x), float(y), 0});
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const std::uint32_t i = std::uint32_t(y * (n + 1) + x);
            // Shuffle the file order so the reorder has work to do.
            const bool flip = (x * 7 + y * 3) % 2;
            const std::uint32_t tri[2][3] = {{i, i + 1, i + n + 2}, {i, i + n + 2, i + n + 1}};
            for (int t = 0; t < 2; ++t)
                for (int k = 0; k < 3; ++k) mesh.indices.push_back(tri[flip ? 1 - t : t][k]);
        }
    const Mesh original = mesh;
    finalizeMesh(mesh, true);
    ASSERT_EQ(mesh.triangleCount(), original.triangleCount());
    EXPECT_NE(mesh.indices, original.indices);
    std::vector<bool> seen(original.triangleCount(), false);
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t s = mesh.triangleSource[t];
        ASSERT_LT(s, seen.size());
        EXPECT_FALSE(seen[s]);
        seen[s] = true;
        for (int k = 0; k < 3; ++k) EXPECT_EQ(mesh.indices[3 * t + k], original.indices[3 * s + k]);
    }
}

TEST(SceneTest, InstancesGetDisjointIdRanges) {
    Scene scene;
    scene.meshes = {triangleMesh(), triangleMesh()};
    for (Mesh& m : scene.meshes) finalizeMesh(m, false);
    Node a, b;
    a.meshes = {0, 1};
    b.meshes = {0};
    scene.nodes = {a, b};
    scene.buildInstances();
    ASSERT_EQ(scene.instances.size(), 3u);
    EXPECT_EQ(scene.instances[0].firstId, 1u);
    EXPECT_EQ(scene.instances[1].firstId, 3u);
    EXPECT_EQ(scene.instances[2].firstId, 5u);
    EXPECT_EQ(scene.triangleCount(), 6u);

    // A hand-built mesh without triangleSource: triangle t is source t, so its ids still get a range.
    for (Mesh& m : scene.meshes) m.triangleSource.clear();
    scene.buildInstances();
    EXPECT_EQ(scene.instances[1].firstId, 3u);
    EXPECT_EQ(scene.instances[2].firstId, 5u);
}

}  // namespace
}  // namespace frugal
