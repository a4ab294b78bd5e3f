// Camera resolution and the projection conventions (GL clip space, window z in [0,1]).
#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "TestSupport.h"
#include "render/Camera.h"

namespace frugal {
namespace {

Scene unitScene() {
    Mesh mesh;
    mesh.positions = {{-1, -1, -1}, {1, -1, -1}, {1, 1, 1}};
    mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    mesh.indices = {0, 1, 2};
    mesh.triangleSource = {0};
    return test::oneMeshScene(mesh);
}

glm::vec3 toNdc(const View& v, const glm::vec3& p) {
    const glm::vec4 clip = v.projection * v.view * glm::vec4(p, 1.0f);
    return glm::vec3(clip) / clip.w;
}

TEST(CameraTest, AutoFramingKeepsTheBoundsInsideTheFrustum) {
    const Scene scene = unitScene();
    Result<View> view = resolveCamera(scene, scene.worldTransforms(0), 0, {}, 800, 600);
    ASSERT_TRUE(view) << view.error();
    for (const glm::vec3& p : scene.meshes[0].positions) {
        const glm::vec3 ndc = toNdc(*view, p);
        EXPECT_LE(std::abs(ndc.x), 1.0f);
        EXPECT_LE(std::abs(ndc.y), 1.0f);
        EXPECT_LE(std::abs(ndc.z), 1.0f);
    }
    EXPECT_EQ(view->source, "auto (fit bounds)");
}

TEST(CameraTest, LookAtPutsTheTargetAtTheCentreAndUpIsUp) {
    const Scene scene = unitScene();
    CameraSpec spec;
    spec.eye = glm::vec3(0, 0, 10);
    spec.target = glm::vec3(0, 0, 0);
    Result<View> view = resolveCamera(scene, scene.worldTransforms(0), 0, spec, 64, 64);
    ASSERT_TRUE(view) << view.error();
    const glm::vec3 centre = toNdc(*view, {0, 0, 0});
    EXPECT_NEAR(centre.x, 0.0f, 1e-6f);
    EXPECT_NEAR(centre.y, 0.0f, 1e-6f);
    EXPECT_GT(toNdc(*view, {0, 1, 0}).y, 0.0f);  // world +y is window up (origin bottom-left)
    EXPECT_GT(toNdc(*view, {1, 0, 0}).x, 0.0f);  // right-handed: +x is right when looking down -z
    // Nearer points get smaller depth (GL_LESS keeps the nearest).
    EXPECT_LT(toNdc(*view, {0, 0, 1}).z, toNdc(*view, {0, 0, -1}).z);
}

TEST(CameraTest, SceneCamerasFollowTheirNodeAndAnInfiniteFar) {
    Scene scene = unitScene();
    Camera camera;
    camera.yfov = glm::radians(60.0f);
    camera.znear = 0.5f;
    camera.zfar = 0.0f;  // infinite
    test::addCameraNode(scene, camera, {0, 0, 5});
    Result<View> view = resolveCamera(scene, scene.worldTransforms(0), 0, {}, 100, 100);
    ASSERT_TRUE(view) << view.error();
    EXPECT_EQ(view->source, "scene camera 0");
    EXPECT_NEAR(toNdc(*view, {0, 0, 0}).x, 0.0f, 1e-6f);
    EXPECT_LT(toNdc(*view, {0, 0, -1e6f}).z, 1.0f);  // far away is still in front of the far plane
}

TEST(CameraTest, BadCamerasAreErrorsWithNumbers) {
    const Scene scene = unitScene();
    const auto world = scene.worldTransforms(0);
    CameraSpec spec;
    spec.sceneCamera = 2;
    EXPECT_EQ(resolveCamera(scene, world, 0, spec, 8, 8).error(), "camera 2: the scene has 0 cameras");
    spec = {};
    spec.eye = glm::vec3(0, 5, 0);
    spec.target = glm::vec3(0, 0, 0);
    EXPECT_EQ(resolveCamera(scene, world, 0, spec, 8, 8).error(), "camera: up (0,1,0) is parallel to the view direction");
    spec.eye = glm::vec3(0, 0, 0);
    EXPECT_EQ(resolveCamera(scene, world, 0, spec, 8, 8).error(), "camera: eye and target must differ and be finite");
    spec = {};
    spec.znear = 5.0f;
    spec.zfar = 1.0f;
    EXPECT_EQ(resolveCamera(scene, world, 0, spec, 8, 8).error(), "camera: far plane 1 must exceed the near plane 5");
    // The library speaks of values; it says which one it fitted, never a command-line flag.
    spec.zfar.reset();
    spec.znear = 1e6f;
    const std::string error = resolveCamera(scene, world, 0, spec, 8, 8).error();
    EXPECT_EQ(error.find("--"), std::string::npos) << error;
    EXPECT_NE(error.find("(fitted to the scene) must exceed the near plane 1e+06"), std::string::npos) << error;
}

}  // namespace
}  // namespace frugal
