// Morph targets (frugal/Scene.h): weights sampled as any channel is (step, linear, cubic spline),
// the node's over the mesh's, the pose they make (posedMesh), the envelope that holds every pose,
// the checks of a mesh built in memory, and AnimatedMorphCube read from its file; the pose made in
// one pass and in ranges equal to the plain formula's.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <frugal/Scene.h>

#include "TestSupport.h"
#include "scene/Posing.h"

namespace frugal {
namespace {

AnimChannel twoWeights(Interp interpolation, std::vector<float> times, std::vector<float> weights) {
    AnimChannel channel;
    channel.node = 0;
    channel.path = AnimPath::Weights;
    channel.interpolation = interpolation;
    channel.times = std::move(times);
    channel.weights = std::move(weights);
    channel.weightCount = 2;
    return channel;
}

TEST(Morph, WeightsAreSampledStepLinearAndCubic) {
    const AnimChannel linear = twoWeights(Interp::Linear, {1.0f, 3.0f}, {0.0f, 10.0f, 1.0f, -1.0f});
    EXPECT_EQ(sampleWeights(linear, 0.0), (std::vector<float>{0.0f, 10.0f}));  // before the first key
    EXPECT_EQ(sampleWeights(linear, 2.0), (std::vector<float>{0.5f, 4.5f}));
    EXPECT_EQ(sampleWeights(linear, 9.0), (std::vector<float>{1.0f, -1.0f}));  // after the last
    const AnimChannel step = twoWeights(Interp::Step, {1.0f, 3.0f}, {0.0f, 10.0f, 1.0f, -1.0f});
    EXPECT_EQ(sampleWeights(step, 2.9), (std::vector<float>{0.0f, 10.0f}));
    EXPECT_EQ(sampleWeights(step, 3.0), (std::vector<float>{1.0f, -1.0f}));
    // Cubic: (in, value, out) a key, two weights each; zero tangents give smoothstep between keys.
    const AnimChannel cubic =
        twoWeights(Interp::CubicSpline, {0.0f, 2.0f}, {0, 0, 0.0f, 4.0f, 0, 0, 0, 0, 1.0f, 0.0f, 0, 0});
    const std::vector<float> half = sampleWeights(cubic, 1.0);
    EXPECT_FLOAT_EQ(half[0], 0.5f);
    EXPECT_FLOAT_EQ(half[1], 2.0f);
    const std::vector<float> quarter = sampleWeights(cubic, 0.5);
    EXPECT_FLOAT_EQ(quarter[0], 3 * 0.0625f - 2 * 0.015625f);  // 3t² − 2t³ at t = 1/4
}

TEST(Morph, APoseAddsEachTargetTimesItsWeight) {
    Mesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    mesh.indices = {0, 1, 2};
    MorphTarget a, b;
    a.positions = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    a.normals = {{1, 0, 0}, {0, 0, 0}, {0, 0, -1}};
    b.positions = {{1, 0, 0}, {0, 0, 0}, {0, 2, 0}};
    mesh.targets = {a, b};
    const Mesh posed = posedMesh(mesh, {-1.0f, 10.0f});
    EXPECT_EQ(posed.positions[0], glm::vec3(10, 0, -1));
    EXPECT_EQ(posed.positions[1], glm::vec3(1, 0, -1));
    EXPECT_EQ(posed.positions[2], glm::vec3(0, 21, -1));
    EXPECT_FLOAT_EQ(glm::length(posed.normals[0]), 1.0f);  // (-1, 0, 1), normalised
    EXPECT_EQ(posed.normals[1], glm::vec3(0, 0, 1));
    EXPECT_EQ(posed.normals[2], glm::vec3(0, 0, 1));  // (0, 0, 2) normalised
    EXPECT_TRUE(posed.targets.empty());
    EXPECT_EQ(posedMesh(mesh, {}).positions, mesh.positions);  // missing weights count 0
}

TEST(Morph, TheNodesWeightsOverrideTheMeshsAndAChannelBoth) {
    Scene scene = test::morphingScene({0.5f, -0.5f});
    const std::vector<std::vector<float>> at0 = scene.morphWeights(0.0), at1 = scene.morphWeights(1.0);
    int animated = -1, still = -1;
    for (int n = 0; n < int(scene.nodes.size()); ++n) {
        if (scene.nodes[std::size_t(n)].name == "animated") animated = n;
        if (scene.nodes[std::size_t(n)].name == "still") still = n;
    }
    ASSERT_GE(animated, 0);
    ASSERT_GE(still, 0);
    EXPECT_EQ(at0[std::size_t(still)], (std::vector<float>{0.5f, -0.5f}));
    EXPECT_EQ(at1[std::size_t(still)], (std::vector<float>{0.5f, -0.5f}));
    EXPECT_EQ(at0[std::size_t(animated)], (std::vector<float>{0.0f, 0.0f}));
    EXPECT_EQ(at1[std::size_t(animated)], (std::vector<float>{-1.0f, 10.0f}));
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        if (scene.nodes[n].meshes == std::vector<int>{0}) {
            EXPECT_TRUE(at1[n].empty());  // a static sphere: no weights
        }
    }
    EXPECT_TRUE(scene.deforms());
}

TEST(Morph, TheEnvelopeHoldsEveryPose) {
    const Scene scene = test::morphingScene();
    for (int k = 0; k <= 200; ++k) {
        const double time = 4.4 * k / 200.0;
        const Bounds b = scene.bounds(time);
        for (int axis = 0; axis < 3; ++axis) {
            EXPECT_LE(scene.envelope.min[axis], b.min[axis]) << "t = " << time;
            EXPECT_GE(scene.envelope.max[axis], b.max[axis]) << "t = " << time;
        }
    }
    // The pose at (−1, 10) reaches far beyond the rest shape: the envelope says so.
    EXPECT_GT(scene.bounds(1.0).max.x - scene.bounds(0.0).max.x, 0.5f);
}

TEST(Morph, AMeshInMemoryIsChecked) {
    Mesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.indices = {0, 1, 2};
    MorphTarget target;
    target.positions = {{0, 0, 1}, {0, 0, 1}};
    mesh.targets = {target};
    Scene scene;
    Result<int> added = scene.addMesh(mesh);
    ASSERT_FALSE(added);
    EXPECT_EQ(added.error().message,
              "mesh: morph target 0 2 position displacements for 3 vertices (one a vertex, or none)");
    mesh.targets[0].positions = {{0, 0, 1}, {0, NAN, 1}, {0, 0, 1}};
    added = scene.addMesh(mesh);
    ASSERT_FALSE(added);
    EXPECT_EQ(added.error().message, "mesh: morph target 0 position 1 is (0, nan, 1), not finite");
    mesh.targets[0].positions[1] = {0, 0, 1};
    mesh.weights = {1.0f, 2.0f};
    added = scene.addMesh(mesh);
    ASSERT_FALSE(added);
    EXPECT_EQ(added.error().message, "mesh: 2 morph weights for 1 targets");
    mesh.weights.clear();
    added = scene.addMesh(mesh);
    ASSERT_TRUE(added) << added.error().message;
    EXPECT_EQ(scene.meshes[std::size_t(*added)].weights, std::vector<float>{0.0f});  // all 0
}

TEST(Morph, AnimatedMorphCubeReadsItsTargetsAndTheirWeights) {
    const std::string path =
        std::string(FRUGAL_ASSIMP_GLTF2_DIR) + "/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf";
    Result<Scene> scene = loadScene(path);
    ASSERT_TRUE(scene) << scene.error().message;
    ASSERT_EQ(scene->meshes.size(), 1u);
    const Mesh& mesh = scene->meshes[0];
    ASSERT_EQ(mesh.targets.size(), 2u);
    EXPECT_EQ(mesh.targets[0].positions.size(), mesh.positions.size());
    EXPECT_EQ(mesh.targets[0].normals.size(), mesh.positions.size());
    EXPECT_EQ(mesh.weights.size(), 2u);
    ASSERT_EQ(scene->animations.size(), 1u);
    ASSERT_EQ(scene->animations[0].channels.size(), 1u);
    const AnimChannel& channel = scene->animations[0].channels[0];
    EXPECT_EQ(channel.path, AnimPath::Weights);
    EXPECT_EQ(channel.weightCount, 2);
    EXPECT_EQ(channel.weights.size(), channel.times.size() * 2);
    EXPECT_TRUE(scene->unsupported.empty());
    // The cube changes shape over its animation, within its envelope.
    const Bounds rest = scene->bounds(0.0), moved = scene->bounds(1.0);
    EXPECT_NE(rest.max, moved.max);
    for (int axis = 0; axis < 3; ++axis) EXPECT_GE(scene->envelope.max[axis], moved.max[axis]);
}

TEST(Skin, TheEnvelopeHoldsEveryPose) {
    for (const float scale : {0.0f, 3.0f, 1e4f})
        for (const bool affine : {true, false}) {
            const Scene scene = test::skinnedScene(scale, affine);
            for (int k = 0; k <= 100; ++k) {
                const double time = 4.2 * k / 100.0;
                const Bounds b = scene.bounds(time);
                for (int axis = 0; axis < 3; ++axis) {
                    EXPECT_LE(scene.envelope.min[axis], b.min[axis]) << "scale " << scale << ", t = " << time;
                    EXPECT_GE(scene.envelope.max[axis], b.max[axis]) << "scale " << scale << ", t = " << time;
                }
            }
        }
}

TEST(Skin, JointMatricesPoseTheMeshInItsNodesFrame) {
    const Scene scene = test::skinnedScene(2.0f);
    const std::vector<glm::mat4> world = scene.worldTransforms(1.0);
    const Instance& skinned = scene.instances[0];
    ASSERT_TRUE(scene.deforms(skinned));
    const std::vector<glm::mat4> joints = scene.jointMatrices(skinned, world);
    ASSERT_EQ(joints.size(), 3u);
    // The root joint has not moved: its matrix and the node's take a vertex where it was bound,
    // whatever the node's own offset (which the joints undo).
    const glm::vec4 p = world[std::size_t(skinned.node)] * joints[0] * glm::vec4(0.3f, 0.2f, 0.0f, 1.0f);
    EXPECT_NEAR(p.x, 0.3f, 1e-6f);
    EXPECT_NEAR(p.y, 0.2f, 1e-6f);
    const Mesh posed = posedMesh(scene.meshes[std::size_t(skinned.mesh)], {}, joints);
    EXPECT_NE(posed.positions.back(), scene.meshes[std::size_t(skinned.mesh)].positions.back());  // the top moved
    // A static sphere does not deform.
    EXPECT_FALSE(scene.deforms(scene.instances[1]));
}

TEST(Skin, SimpleSkinReadsItsSkin) {
    Result<Scene> scene = loadScene(std::string(FRUGAL_ASSIMP_GLTF2_DIR) + "/simple_skin/simple_skin.gltf");
    ASSERT_TRUE(scene) << scene.error().message;
    ASSERT_EQ(scene->skins.size(), 1u);
    EXPECT_EQ(scene->skins[0].joints.size(), 2u);
    ASSERT_EQ(scene->meshes.size(), 1u);
    ASSERT_EQ(scene->meshes[0].influences.size(), 1u);
    EXPECT_EQ(scene->meshes[0].influences[0].joints.size(), scene->meshes[0].positions.size());
    EXPECT_TRUE(scene->unsupported.empty());
    EXPECT_TRUE(scene->deforms());
    EXPECT_NE(scene->bounds(0.0).max, scene->bounds(1.0).max);  // it bends
}

}  // namespace
}  // namespace frugal

namespace frugal {
namespace {

// The pose as Scene.h states it, written the plain way (each target over every vertex, then glm's
// J · (p, 1) per influence): poseVertices, which makes it in one pass per vertex and in ranges that
// may run on threads of their own, must give these floats bit for bit, whatever the split.
PosedVertices plainPose(const Mesh& mesh, const std::vector<float>& weights, const std::vector<glm::mat4>& joints) {
    PosedVertices out{mesh.positions, mesh.normals, mesh.tangents};
    bool normals = false;
    for (std::size_t t = 0; t < mesh.targets.size() && t < weights.size(); ++t) {
        if (weights[t] == 0.0f) continue;
        const MorphTarget& target = mesh.targets[t];
        for (std::size_t v = 0; v < target.positions.size(); ++v) out.positions[v] += weights[t] * target.positions[v];
        for (std::size_t v = 0; v < target.normals.size(); ++v, normals = true)
            out.normals[v] += weights[t] * target.normals[v];
        for (std::size_t v = 0; v < target.tangents.size(); ++v)
            out.tangents[v] += glm::vec4(weights[t] * target.tangents[v], 0.0f);
    }
    for (std::size_t v = 0; v < out.positions.size() && !joints.empty(); ++v, normals = true) {
        glm::vec3 p(0.0f), n(0.0f), d(0.0f);
        for (const Mesh::Influences& set : mesh.influences)
            for (int k = 0; k < 4; ++k) {
                const float w = set.weights[v][k];
                const std::uint32_t j = set.joints[v][k];
                if (w == 0.0f || j >= joints.size()) continue;
                p += w * glm::vec3(joints[j] * glm::vec4(out.positions[v], 1.0f));
                n += w * (glm::transpose(glm::inverse(glm::mat3(joints[j]))) * out.normals[v]);
                d += w * (glm::mat3(joints[j]) * glm::vec3(out.tangents[v]));
            }
        out.positions[v] = p, out.normals[v] = n, out.tangents[v] = glm::vec4(d, out.tangents[v].w);
    }
    for (std::size_t v = 0; v < out.normals.size() && normals; ++v) {
        const float length = glm::length(out.normals[v]);
        out.normals[v] = length > 0.0f && std::isfinite(length) ? out.normals[v] / length : mesh.normals[v];
    }
    return out;
}

TEST(Pose, OnePassAndAnySplitGiveThePlainPoseBitForBit) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-2.0f, 2.0f);
    const auto vec3 = [&] { return glm::vec3(u(rng), u(rng), u(rng)); };
    Mesh mesh;
    const std::size_t n = 997;
    for (std::size_t v = 0; v < n; ++v) {
        mesh.positions.push_back(vec3());
        mesh.normals.push_back(glm::normalize(vec3()));
        mesh.tangents.push_back(glm::vec4(glm::normalize(vec3()), v % 2 ? 1.0f : -1.0f));
    }
    mesh.targets.resize(2);
    for (MorphTarget& target : mesh.targets)
        for (std::size_t v = 0; v < n; ++v) {
            target.positions.push_back(vec3());
            target.normals.push_back(vec3());
            target.tangents.push_back(vec3());
        }
    Mesh::Influences set;
    for (std::size_t v = 0; v < n; ++v) {
        set.joints.push_back({v % 5, (v + 1) % 5, (v + 2) % 7, 0});  // joint 5 and 6 do not exist: skipped
        set.weights.push_back({0.5f, 0.3f, v % 3 ? 0.2f : 0.0f, 0.0f});
    }
    mesh.influences = {set};
    std::vector<glm::mat4> joints;
    for (int j = 0; j < 5; ++j)
        joints.push_back(
            glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), vec3()), u(rng), glm::normalize(vec3())),
                       glm::vec3(0.5f + 0.2f * float(j), 1.0f, 2.0f)));
    const auto same = [](const PosedVertices& a, const PosedVertices& b) {
        return a.positions == b.positions && a.normals == b.normals && a.tangents == b.tangents;
    };
    for (const std::vector<float>& weights : {std::vector<float>{0.0f, 0.0f}, {-1.0f, 10.0f}, {0.3f, 0.0f}})
        for (const bool skinned : {false, true}) {
            const std::vector<glm::mat4> used = skinned ? joints : std::vector<glm::mat4>{};
            const PosedVertices expected = plainPose(mesh, weights, used);
            PosedVertices whole;
            poseVertices(mesh, weights, used, whole);
            EXPECT_TRUE(same(whole, expected))
                << "weights " << weights[0] << ", " << weights[1] << ", skinned " << skinned;
            PosedVertices split;
            const Posing posing(mesh, weights, used, split, true);
            for (const std::size_t at : {std::size_t(0), std::size_t(300), std::size_t(301), std::size_t(800)}) {
                const std::size_t end = at == 0 ? 300 : at == 300 ? 301 : at == 301 ? 800 : n;
                posing.run(at, end);
            }
            EXPECT_TRUE(same(split, expected));
            PosedVertices positionsOnly;
            poseVertices(mesh, weights, used, positionsOnly, /*frames=*/false);
            EXPECT_EQ(positionsOnly.positions, expected.positions);
            EXPECT_TRUE(positionsOnly.normals.empty() && positionsOnly.tangents.empty());
        }
}

}  // namespace
}  // namespace frugal
