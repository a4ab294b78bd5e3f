// Scenes built in memory (Scene::add*, setTransform): every bad value refused with its numbers, a
// mesh finished as a loader finishes one, and a Renderer that moves a node between frames.
#include <thread>

#include <gtest/gtest.h>

#include <frugal/Renderer.h>
#include <frugal/Scene.h>

#include "scene/MeshBuild.h"

namespace frugal {
namespace {

Mesh quad() {
    Mesh mesh;
    mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    return mesh;
}

glm::mat4 at(float x, float y, float z) {
    glm::mat4 m(1.0f);
    m[3] = glm::vec4(x, y, z, 1.0f);
    return m;
}

TEST(SceneBuildTest, BadValuesAreRefusedWithTheirNumbers) {
    Scene scene;
    Mesh mesh = quad();
    mesh.indices[4] = 9;
    EXPECT_EQ(scene.addMesh(mesh).error().message, "mesh: index 9 (triangle 1) is past the 4 vertices");
    mesh = quad();
    mesh.positions[2].y = std::nanf("");
    EXPECT_EQ(scene.addMesh(mesh).error().message, "mesh: position 2 is (1, nan, 0), not finite");
    mesh = quad();
    mesh.indices.pop_back();
    EXPECT_EQ(scene.addMesh(mesh).error().message, "mesh: 5 indices are not whole triangles (3 a triangle)");
    mesh = quad();
    mesh.uvs.resize(3);
    mesh.name = "q";
    EXPECT_EQ(scene.addMesh(mesh).error().message, "mesh 'q': 3 uvs for 4 vertices (one a vertex, or none)");
    mesh = quad();
    mesh.material = 2;
    EXPECT_EQ(scene.addMesh(mesh).error().message, "mesh: material 2 does not exist (the scene has 0)");
    Texture texture;
    texture.width = texture.height = 64;
    texture.rgba.resize(12288);
    EXPECT_EQ(scene.addTexture(texture).error().message, "texture: 12288 bytes for 64x64 RGBA (16384 expected)");
    Material material;
    material.baseColorTexture = 0;
    EXPECT_EQ(scene.addMaterial(material).error().message, "material: texture 0 does not exist (the scene has 0)");
    material = {};
    material.normalTexture = 3;
    EXPECT_EQ(scene.addMaterial(material).error().message,
              "material: normal texture 3 does not exist (the scene has 0)");
    material = {};
    material.occlusionStrength = 1.5f;
    EXPECT_EQ(scene.addMaterial(material).error().message, "material: occlusion strength 1.5 is not in [0, 1]");
    material = {};
    material.normalScale = std::nanf("");
    EXPECT_EQ(scene.addMaterial(material).error().message, "material: normal scale nan is not finite");
    mesh = quad();
    mesh.tangents.assign(4, glm::vec4(1, 0, 0, 1));
    mesh.tangents[1].w = INFINITY;
    EXPECT_EQ(scene.addMesh(mesh).error().message, "mesh: tangent 1 is (1, 0, 0, inf), not finite");
    EXPECT_EQ(scene.addInstance(0, glm::mat4(1.0f)).error().message, "instance: mesh 0 does not exist (the scene has 0)");
    EXPECT_TRUE(scene.meshes.empty() && scene.textures.empty() && scene.materials.empty() && scene.nodes.empty());

    ASSERT_EQ(*scene.addMesh(quad()), 0);
    glm::mat4 infinite(1.0f);
    infinite[3][1] = INFINITY;
    EXPECT_EQ(scene.addInstance(0, infinite).error().message, "instance: transform: row 1, column 3 is inf, not finite");
    EXPECT_EQ(scene.setTransform(3, glm::mat4(1.0f)).error().message, "node 3 does not exist (the scene has 0)");
}

// Punctual lights: each placed by a new root node; a light no glTF file could hold is refused with
// its number, and adds nothing.
TEST(SceneBuildTest, LightsArePlacedByNewNodesOrRefused) {
    Scene scene;
    PunctualLight spot;
    spot.name = "beam";
    spot.type = LightType::Spot;
    spot.innerConeAngle = 0.2f;
    spot.outerConeAngle = 0.5f;
    glm::mat4 at(1.0f);
    at[3] = glm::vec4(1.0f, 2.0f, 3.0f, 1.0f);
    const Result<int> node = scene.addLight(spot, at, "lamp");
    ASSERT_TRUE(node) << node.error().message;
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.nodes[std::size_t(*node)].light, 0);
    EXPECT_EQ(scene.nodes[std::size_t(*node)].name, "lamp");
    EXPECT_EQ(scene.roots, std::vector<int>{*node});

    const auto refused = [&](PunctualLight light, glm::mat4 transform = glm::mat4(1.0f)) {
        const Result<int> r = scene.addLight(light, transform);
        EXPECT_EQ(scene.lights.size(), 1u);
        return r ? std::string("accepted") : r.error().message;
    };
    PunctualLight bad = spot;
    bad.innerConeAngle = 0.5f;
    EXPECT_EQ(refused(bad), "light 'beam': inner cone angle 0.5 is not in [0, the outer angle 0.5)");
    bad = spot;
    bad.outerConeAngle = 2.0f;
    EXPECT_EQ(refused(bad), "light 'beam': outer cone angle 2 is not in (0, pi/2]");
    bad = {};
    bad.intensity = -1.0f;
    EXPECT_EQ(refused(bad), "light: intensity -1 is not finite and at least 0");
    bad = {};
    bad.color.g = std::nanf("");
    EXPECT_EQ(refused(bad), "light: colour nan is not finite and at least 0");
    bad = {};
    bad.range = -2.0f;
    EXPECT_EQ(refused(bad), "light: range -2 is not finite and at least 0 (0 = unbounded)");
    glm::mat4 infinite(1.0f);
    infinite[3][1] = INFINITY;
    EXPECT_EQ(refused({}, infinite), "light: transform: row 1, column 3 is inf, not finite");
}

TEST(SceneBuildTest, AMeshIsFinishedAsALoaderFinishesIt) {
    Scene scene;
    Mesh expected = quad();
    finalizeMesh(expected, true);
    const int index = *scene.addMesh(quad());
    const Mesh& added = scene.meshes[std::size_t(index)];
    EXPECT_EQ(added.indices, expected.indices);
    EXPECT_EQ(added.triangleSource, expected.triangleSource);
    EXPECT_EQ(added.normals, expected.normals);
    const int node = *scene.addInstance(index, at(1, 2, 3), "placed");
    scene.buildInstances();
    ASSERT_EQ(scene.instances.size(), 1u);
    EXPECT_EQ(scene.instances[0].node, node);
    EXPECT_EQ(scene.roots, std::vector<int>{node});
    EXPECT_EQ(scene.worldTransforms(0.0)[std::size_t(node)], at(1, 2, 3));
}

// The renderer's own scene moves: the frame after setTransform shows the quad where it went, on a
// thread other than the one that made the renderer (releaseThread hands the context over).
TEST(SceneBuildTest, ARendererMovesANodeBetweenFrames) {
    Scene scene;
    const int node = *scene.addInstance(*scene.addMesh(quad()), at(-2, 0, 0));
    scene.buildInstances();
    Settings settings;
    settings.width = 64;
    settings.height = 32;
    settings.ids = true;
    Result<Renderer> renderer = Renderer::create(std::move(scene), settings);
    ASSERT_TRUE(renderer) << renderer.error().message;
    const Camera camera = Camera::lookAt({0, 0, 8}, {0, 0, 0}, 40.0f);
    const auto covered = [](const Frame& f, bool left) {
        std::size_t n = 0;
        for (int y = 0; y < f.ids.height; ++y)
            for (int x = 0; x < f.ids.width; ++x)
                n += f.ids.ids[std::size_t(y * f.ids.width + x)] != 0 && (x < f.ids.width / 2) == left;
        return n;
    };
    Result<Frame> before = renderer->render(camera, 0.0);
    ASSERT_TRUE(before) << before.error().message;
    EXPECT_GT(covered(*before, true), 0u);
    EXPECT_EQ(covered(*before, false), 0u);
    ASSERT_TRUE(renderer->setTransform(node, at(2, 0, 0)));
    renderer->releaseThread();
    std::optional<Result<Frame>> after;
    std::thread([&] {
        after.emplace(renderer->render(camera, 0.0));
        renderer->releaseThread();
    }).join();
    ASSERT_TRUE(*after) << after->error().message;
    EXPECT_EQ(covered(**after, true), 0u);
    EXPECT_EQ(covered(**after, false), covered(*before, true));
    EXPECT_EQ(renderer->setTransform(node, at(0, NAN, 0)).error().message, "node 0: transform: row 1, column 3 is nan, not finite");
}

}  // namespace
}  // namespace frugal
