// Built-in procedural scenes: parameters, counts and the per-frame static share.
#include <array>

#include <gtest/gtest.h>

#include "scene/Load.h"

namespace frugal {
namespace {

// Instances whose world transform changes between frame f-1 and f.
int changedInstances(const Scene& scene, int frame) {
    const std::vector<glm::mat4> before = scene.worldTransforms((frame - 1) / scene.fps);
    const std::vector<glm::mat4> now = scene.worldTransforms(frame / scene.fps);
    int changed = 0;
    for (const Instance& instance : scene.instances)
        if (before[instance.node] != now[instance.node]) ++changed;
    return changed;
}

struct DominoCase {
    const char* spec;
    std::size_t polygons;  // quads
    int moving;
};

TEST(BuiltinTest, DominoesMatchThePaperSceneSizes) {
    const DominoCase cases[] = {
        {"builtin:dominoes", 804, 60},                                  // paper 000: 804 polygons, 55.44 % static
        {"builtin:dominoes?polygons=1404&static=0.9866", 1404, 3},      // 1,404 polygons, 98.66 % static
    };
    for (const DominoCase& c : cases) {
        SCOPED_TRACE(c.spec);
        Result<Scene> scene = loadScene(c.spec);
        ASSERT_TRUE(scene) << scene.error().message;
        EXPECT_EQ(scene->triangleCount(), 2 * c.polygons);
        for (int frame : {c.moving, c.moving + 5, int(c.polygons / 6) - 1}) EXPECT_EQ(changedInstances(*scene, frame), c.moving);
        EXPECT_EQ(scene->cameras.size(), 1u);
    }
}

TEST(BuiltinTest, DefaultHasATexturedFloor) {
    Result<Scene> scene = loadScene("builtin:default");
    ASSERT_TRUE(scene) << scene.error().message;
    ASSERT_EQ(scene->textures.size(), 1u);
    EXPECT_EQ(scene->triangleCount(), 2u * 804 + 2);
    Result<Scene> bare = loadScene("builtin:dominoes");
    ASSERT_TRUE(bare) << bare.error().message;
    EXPECT_TRUE(bare->textures.empty()) << "the floor is what builtin:default adds";

    // Exactly one instance samples the texture: a flat two-triangle quad facing up, lying under
    // every domino, with texture coordinates that repeat the checker.
    int textured = -1;
    for (int i = 0; i < int(scene->instances.size()); ++i) {
        const Mesh& mesh = scene->meshes[scene->instances[i].mesh];
        if (mesh.material >= 0 && scene->materials[mesh.material].baseColorTexture == 0) {
            EXPECT_EQ(textured, -1) << "a second textured instance: " << i;
            textured = i;
        }
    }
    ASSERT_GE(textured, 0);
    const Instance& floor = scene->instances[textured];
    const Mesh& quad = scene->meshes[floor.mesh];
    ASSERT_EQ(quad.triangleCount(), 2u);
    ASSERT_EQ(quad.uvs.size(), quad.positions.size());
    const glm::mat4 world = scene->worldTransforms(0.0)[floor.node];
    Bounds quadBounds;
    for (const glm::vec3& p : quad.positions) quadBounds.add(glm::vec3(world * glm::vec4(p, 1.0f)));
    for (const glm::vec3& n : quad.normals) EXPECT_GT(glm::dot(glm::mat3(world) * n, glm::vec3(0, 1, 0)), 0.99f);
    EXPECT_EQ(quadBounds.min.y, quadBounds.max.y) << "flat";
    const Bounds all = bare->bounds(0.0);
    EXPECT_LE(quadBounds.max.y, all.min.y + 1e-4f) << "under the dominoes";
    EXPECT_LE(quadBounds.min.x, all.min.x);
    EXPECT_GE(quadBounds.max.x, all.max.x);
    EXPECT_LE(quadBounds.min.z, all.min.z);
    EXPECT_GE(quadBounds.max.z, all.max.z);
    float uvSpan = 0.0f;
    for (const glm::vec2& uv : quad.uvs) uvSpan = std::max(uvSpan, std::max(uv.x, uv.y));
    EXPECT_GT(uvSpan, 1.0f) << "the checker repeats across the floor";

    // The texture is a checker: two colours, and every texel's right and upper neighbours in the
    // next cell have the other colour.
    const Texture& checker = scene->textures[0];
    ASSERT_GT(checker.width, 1);
    ASSERT_EQ(checker.rgba.size(), std::size_t(checker.width) * checker.height * 4);
    const auto texel = [&](int x, int y) {
        const std::uint8_t* p = &checker.rgba[(std::size_t(y) * checker.width + x) * 4];
        return std::array<std::uint8_t, 4>{p[0], p[1], p[2], p[3]};
    };
    const auto light = texel(0, 0);
    std::array<std::uint8_t, 4> dark{};
    bool sawDark = false;
    for (int y = 0; y < checker.height; ++y)
        for (int x = 0; x < checker.width; ++x) {
            const auto t = texel(x, y);
            if (t == light) continue;
            if (!sawDark) dark = t, sawDark = true;
            EXPECT_EQ(t, dark) << "a third colour at " << x << "," << y;
        }
    ASSERT_TRUE(sawDark);
    EXPECT_NE(texel(0, 0), texel(checker.width - 1, 0)) << "an even number of cells across: the corners differ";
}

TEST(BuiltinTest, CubesSpinAndAreReproducible) {
    Result<Scene> a = loadScene("builtin:cubes");
    Result<Scene> b = loadScene("builtin:cubes?count=28&seed=1");
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->triangleCount(), 28u * 12);
    EXPECT_EQ(a->worldTransforms(1.0), b->worldTransforms(1.0));
    EXPECT_EQ(changedInstances(*a, 3), 28);
    Result<Scene> c = loadScene("builtin:cubes?seed=2");
    ASSERT_TRUE(c);
    EXPECT_NE(a->worldTransforms(1.0), c->worldTransforms(1.0));
}

TEST(BuiltinTest, BadSpecsGetOneLineErrors) {
    const std::pair<const char*, const char*> cases[] = {
        {"builtin:nope", "builtin:nope: no such built-in scene (there are builtin:default, builtin:dominoes, builtin:cubes, builtin:copies, builtin:orbit, builtin:materials)"},
        {"builtin:cubes?count=abc", "builtin:cubes?count=abc: count=abc is not a number"},
        {"builtin:cubes?count=0", "builtin:cubes?count=0: count=0 is out of range [1, 1e+06]"},
        {"builtin:dominoes?static=2", "builtin:dominoes?static=2: static=2 is out of range [0, 1]"},
        {"builtin:dominoes?colour=red", "builtin:dominoes?colour=red: unknown parameter 'colour'"},
        {"builtin:dominoes?polygons", "builtin:dominoes?polygons: parameter 'polygons' is not key=value"},
        {"builtin:cubes?count=nan", "builtin:cubes?count=nan: count=nan is not a number"},
    };
    for (const auto& [spec, message] : cases) {
        Result<Scene> scene = loadScene(spec);
        ASSERT_FALSE(scene) << spec;
        EXPECT_EQ(scene.error().message, message);
    }
}

TEST(BuiltinTest, UnknownFormatsAndMissingFiles) {
    EXPECT_EQ(loadScene("/nonexistent/scene.fbx").error().message, "/nonexistent/scene.fbx: no such file");
    EXPECT_EQ(loadScene("/etc/hostname").error().message,
              "/etc/hostname: unknown scene format '' (frugal reads .gltf, .glb, .obj and builtin:NAME)");
}

}  // namespace
}  // namespace frugal

namespace frugal {
namespace {

TEST(BuiltinTest, CopiesLaySeveralScenesSideBySideWithTheirOwnIds) {
    Result<Scene> one = loadScene("builtin:cubes?count=2&seed=5");
    Result<Scene> three = loadScene("builtin:copies?count=3&of=builtin:cubes?count=2&seed=5");
    ASSERT_TRUE(one) << one.error().message;
    ASSERT_TRUE(three) << three.error().message;
    EXPECT_EQ(three->triangleCount(), 3 * 24u);
    EXPECT_EQ(three->meshes.size(), 2u) << "meshes are shared";
    EXPECT_TRUE(three->cameras.empty());
    ASSERT_EQ(three->instances.size(), 6u);
    EXPECT_EQ(three->instances[5].firstId, 1u + 5 * 12);
    // Copies sit apart along x and keep animating.
    const Bounds b = three->bounds(0.0);
    EXPECT_GT(b.max.x - b.min.x, 2.5f * (one->bounds(0.0).max.x - one->bounds(0.0).min.x));
    EXPECT_NE(three->worldTransforms(0.0), three->worldTransforms(1.0));

    EXPECT_EQ(loadScene("builtin:copies?count=2").error().message, "builtin:copies?count=2: parameter 'of' (the scene to copy) is missing");
    EXPECT_EQ(loadScene("builtin:copies?of=/nonexistent.obj").error().message, "/nonexistent.obj: no such file");
}

}  // namespace
}  // namespace frugal

namespace frugal {
namespace {

TEST(BuiltinTest, OrbitCirclesAStaticSceneWithCubesThatStartAndStop) {
    Result<Scene> base = loadScene("builtin:cubes?count=3");
    Result<Scene> orbit = loadScene("builtin:orbit?count=5&seconds=2&duty=0.5&of=builtin:cubes?count=3");
    ASSERT_TRUE(base.ok() && orbit.ok()) << (orbit.ok() ? "" : orbit.error().message);
    EXPECT_EQ(orbit->instances.size(), base->instances.size() + 5);
    ASSERT_EQ(orbit->cameras.size(), 1u);  // one fixed camera of its own
    // The camera node is not animated: the view is the same at every frame.
    EXPECT_EQ(orbit->worldTransforms(0.0)[orbit->cameras[0].node], orbit->worldTransforms(1.3)[orbit->cameras[0].node]);

    // With duty 0.5 every cube rests (bit-identical pose) on some frames and moves on others.
    const std::size_t first = base->instances.size();
    std::vector<int> rested(5, 0), moved(5, 0);
    for (int frame = 1; frame < 60; ++frame) {
        const std::vector<glm::mat4> before = orbit->worldTransforms((frame - 1) / orbit->fps);
        const std::vector<glm::mat4> now = orbit->worldTransforms(frame / orbit->fps);
        for (std::size_t k = 0; k < 5; ++k) {
            const int node = orbit->instances[first + k].node;
            (before[node] == now[node] ? rested : moved)[k] += 1;
        }
    }
    for (std::size_t k = 0; k < 5; ++k) {
        EXPECT_GT(rested[k], 10) << "cube " << k;
        EXPECT_GT(moved[k], 10) << "cube " << k;
    }

    Result<Scene> continuous = loadScene("builtin:orbit?count=2&of=builtin:cubes?count=1");
    ASSERT_TRUE(continuous.ok());
    EXPECT_EQ(changedInstances(*continuous, 5), 3);  // the spinning cube and both orbiters

    Result<Scene> missing = loadScene("builtin:orbit?count=2");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("parameter 'of'"), std::string::npos) << missing.error().message;
    EXPECT_FALSE(loadScene("builtin:orbit?duty=0&of=builtin:cubes").ok());
}

}  // namespace
TEST(BuiltinTest, MaterialsSpreadsDrawsOverMeshesMaterialsAndTextures) {
    Result<Scene> scene = loadScene("builtin:materials?draws=50&meshes=10&shapes=3&materials=6&textures=2&seed=7");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->instances.size(), 50u);
    EXPECT_EQ(scene->meshes.size(), 10u);
    EXPECT_EQ(scene->materials.size(), 6u);
    EXPECT_EQ(scene->textures.size(), 2u);
    EXPECT_EQ(scene->materials[1].baseColorTexture, 1);
    EXPECT_EQ(scene->materials[2].baseColorTexture, -1);
    EXPECT_TRUE(scene->materials[2].doubleSided);
    // Submitted in a random order: consecutive instances mostly draw different meshes.
    std::size_t repeats = 0;
    for (std::size_t i = 1; i < scene->instances.size(); ++i) repeats += scene->instances[i].mesh == scene->instances[i - 1].mesh;
    EXPECT_LT(repeats, 15u);
}

}  // namespace frugal
