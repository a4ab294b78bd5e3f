// Camera resolution and the projection conventions (GL clip space, window z in [0,1]).
#include <cmath>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "TestSupport.h"
#include "pipeline/Camera.h"

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
    ASSERT_TRUE(view) << view.error().message;
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
    Camera spec;
    spec.eye = glm::vec3(0, 0, 10);
    spec.target = glm::vec3(0, 0, 0);
    Result<View> view = resolveCamera(scene, scene.worldTransforms(0), 0, spec, 64, 64);
    ASSERT_TRUE(view) << view.error().message;
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
    SceneCamera camera;
    camera.yfov = glm::radians(60.0f);
    camera.znear = 0.5f;
    camera.zfar = 0.0f;  // infinite
    test::addCameraNode(scene, camera, {0, 0, 5});
    Camera spec;
    spec.depthRange = DepthRange::File;  // the camera's own planes
    Result<View> view = resolveCamera(scene, scene.worldTransforms(0), 0, spec, 100, 100);
    ASSERT_TRUE(view) << view.error().message;
    EXPECT_EQ(view->source, "scene camera 0");
    EXPECT_NEAR(toNdc(*view, {0, 0, 0}).x, 0.0f, 1e-6f);
    EXPECT_LT(toNdc(*view, {0, 0, -1e6f}).z, 1.0f);  // far away is still in front of the far plane
    EXPECT_EQ(view->zfar, 0.0f);
}

TEST(CameraTest, BadCamerasAreErrorsWithNumbers) {
    const Scene scene = unitScene();
    const auto world = scene.worldTransforms(0);
    Camera spec;
    spec.sceneCamera = 2;
    EXPECT_EQ(resolveCamera(scene, world, 0, spec, 8, 8).error().message, "camera 2: the scene has 0 cameras");
    spec = {};
    spec.eye = glm::vec3(0, 5, 0);
    spec.target = glm::vec3(0, 0, 0);
    EXPECT_EQ(resolveCamera(scene, world, 0, spec, 8, 8).error().message, "camera: up (0,1,0) is parallel to the view direction");
    spec.eye = glm::vec3(0, 0, 0);
    EXPECT_EQ(resolveCamera(scene, world, 0, spec, 8, 8).error().message, "camera: eye and target must differ and be finite");
    spec = {};
    spec.znear = 5.0f;
    spec.zfar = 1.0f;
    EXPECT_EQ(resolveCamera(scene, world, 0, spec, 8, 8).error().message, "camera: far plane 1 must exceed the near plane 5");
    // The library speaks of values; it says which one it fitted, never a command-line flag.
    spec.zfar.reset();
    spec.znear = 1e6f;
    const std::string error = resolveCamera(scene, world, 0, spec, 8, 8).error().message;
    EXPECT_EQ(error.find("--"), std::string::npos) << error;
    EXPECT_NE(error.find("(fitted to the scene) must exceed the near plane 1e+06"), std::string::npos) << error;
}

// A glTF camera's aspectRatio does not stretch the picture: the projection takes the image's aspect
// ratio and keeps the vertical field of view, as viewers do; the file's ratio is kept to be reported.
TEST(CameraTest, AFileCamerasAspectRatioIsNotStretchedOntoTheImage) {
    Scene scene = unitScene();
    SceneCamera square;
    square.yfov = glm::radians(50.0f);
    square.aspect = 1.0f;
    square.znear = 0.1f;
    square.zfar = 100.0f;
    test::addCameraNode(scene, square, {0, 0, 6});
    const auto world = scene.worldTransforms(0);
    for (const auto& [width, height] : {std::pair{800, 600}, {1920, 1080}, {600, 800}}) {
        Result<View> view = resolveCamera(scene, world, 0, {}, width, height);
        ASSERT_TRUE(view) << view.error().message;
        EXPECT_EQ(view->fileAspect, 1.0f);
        EXPECT_FLOAT_EQ(view->aspect, float(width) / float(height));
        // The same projection as an explicit camera with the image's aspect ratio.
        const glm::mat4 expected = glm::perspective(square.yfov, float(width) / float(height), view->znear, view->zfar);
        EXPECT_EQ(view->projection, expected) << width << "x" << height;
        // A point 45° off the axis horizontally lands where the horizontal field of view puts it.
        const float halfWidth = std::tan(square.yfov / 2) * float(width) / float(height);
        EXPECT_NEAR(toNdc(*view, {6.0f * halfWidth * 0.5f, 0, 0}).x, 0.5f, 1e-5f);
    }
    EXPECT_FALSE(aspectDiffers(1.0f, 800, 800));
    EXPECT_TRUE(aspectDiffers(1.0f, 800, 600));
    EXPECT_FALSE(aspectDiffers(16.0f / 9.0f, 800, 450));
    EXPECT_FALSE(aspectDiffers(1.5f, 800, 533));  // 533.33 rounded
    EXPECT_FALSE(aspectDiffers(0.0f, 800, 600));  // no ratio of its own
    int w = 0, h = 0;
    sizeForAspect(1.0f, 800, w, h);
    EXPECT_EQ(std::pair(w, h), std::pair(800, 800));
    sizeForAspect(4.0f / 3.0f, 800, w, h);
    EXPECT_EQ(std::pair(w, h), std::pair(800, 600));
    sizeForAspect(0.5f, 800, w, h);
    EXPECT_EQ(std::pair(w, h), std::pair(400, 800));
}

TEST(CameraTest, AnOrthographicCameraKeepsYmagAndTakesTheImagesAspectRatio) {
    Scene scene = unitScene();
    SceneCamera ortho;
    ortho.perspective = false;
    ortho.xmag = 1.0f;
    ortho.ymag = 2.0f;
    ortho.znear = 0.1f;
    ortho.zfar = 50.0f;
    test::addCameraNode(scene, ortho, {0, 0, 6});
    Result<View> view = resolveCamera(scene, scene.worldTransforms(0), 0, {}, 300, 100);
    ASSERT_TRUE(view) << view.error().message;
    EXPECT_EQ(view->fileAspect, 0.5f);
    EXPECT_NEAR(toNdc(*view, {0, 2, 0}).y, 1.0f, 1e-6f);
    EXPECT_NEAR(toNdc(*view, {6, 0, 0}).x, 1.0f, 1e-6f);  // xmag = ymag × 3
}

// The fitted planes hold the scene between them with a margin, never move outward past the given
// ones, and make the near/far ratio what the scene needs.
TEST(CameraTest, TheDepthRangeIsFittedToTheSceneInsideTheGivenPlanes) {
    Scene scene = unitScene();  // a triangle within [-1, 1]³
    SceneCamera camera;
    camera.yfov = glm::radians(40.0f);
    camera.znear = 0.05f;
    camera.zfar = 1e6f;
    test::addCameraNode(scene, camera, {0, 0, 10});
    const auto world = scene.worldTransforms(0);
    Result<View> fit = resolveCamera(scene, world, 0, {}, 64, 64);
    ASSERT_TRUE(fit) << fit.error().message;
    EXPECT_EQ(fit->depthRange, DepthRange::Fit);
    EXPECT_EQ(fit->givenNear, 0.05f);
    EXPECT_EQ(fit->givenFar, 1e6f);
    EXPECT_LT(fit->znear, 9.0f);  // the box's nearest corner is 9 away
    EXPECT_GT(fit->znear, 8.9f);
    EXPECT_GT(fit->zfar, 11.0f);
    EXPECT_LT(fit->zfar, 11.1f);
    for (const glm::vec3& corner : {glm::vec3(-1, -1, 1), glm::vec3(1, 1, -1)}) {
        const float z = toNdc(*fit, corner).z;
        EXPECT_GT(z, -1.0f);
        EXPECT_LT(z, 1.0f);
    }
    // The user's (or the file's) planes win where they are tighter than the scene.
    Camera spec;
    spec.znear = 9.5f;
    spec.zfar = 10.5f;
    Result<View> tight = resolveCamera(scene, world, 0, spec, 64, 64);
    ASSERT_TRUE(tight) << tight.error().message;
    EXPECT_EQ(tight->znear, 9.5f);
    EXPECT_EQ(tight->zfar, 10.5f);
    // An infinite far plane becomes the scene's far side; `file` keeps it infinite.
    spec = {};
    spec.zfar = 0.0f;
    Result<View> infinite = resolveCamera(scene, world, 0, spec, 64, 64);
    ASSERT_TRUE(infinite) << infinite.error().message;
    EXPECT_GT(infinite->zfar, 11.0f);
    EXPECT_EQ(infinite->givenFar, 0.0f);
    spec.depthRange = DepthRange::File;
    Result<View> file = resolveCamera(scene, world, 0, spec, 64, 64);
    ASSERT_TRUE(file) << file.error().message;
    EXPECT_EQ(file->znear, 0.05f);
    EXPECT_EQ(file->zfar, 0.0f);
    // A scene wholly behind the camera leaves the planes as given.
    spec = {};
    spec.eye = glm::vec3(0, 0, 10);
    spec.target = glm::vec3(0, 0, 20);
    spec.znear = 0.5f;
    spec.zfar = 100.0f;
    Result<View> behind = resolveCamera(scene, world, 0, spec, 64, 64);
    ASSERT_TRUE(behind) << behind.error().message;
    EXPECT_EQ(behind->znear, 0.5f);
    EXPECT_EQ(behind->zfar, 100.0f);
}

// Reversed Z: near → window z 1, far → 0 through glClipControl's zero-to-one clip space, finite and
// infinite, perspective and orthographic.
TEST(CameraTest, D32fProjectionsAreReversedZeroToOne) {
    Scene scene = unitScene();
    const auto world = scene.worldTransforms(0);
    Camera spec;
    spec.eye = glm::vec3(0, 0, 10);
    spec.target = glm::vec3(0, 0, 0);
    spec.depthRange = DepthRange::File;
    for (const float far : {100.0f, 0.0f}) {
        spec.znear = 2.0f;
        spec.zfar = far;
        Result<View> view = resolveCamera(scene, world, 0, spec, 64, 64, DepthFormat::D32F);
        ASSERT_TRUE(view) << view.error().message;
        EXPECT_EQ(view->depthFormat, DepthFormat::D32F);
        const auto windowZ = [&](float distance) {  // clip z / w: window z for zero-to-one
            const glm::vec4 clip = view->projection * view->view * glm::vec4(0, 0, 10.0f - distance, 1.0f);
            return clip.z / clip.w;
        };
        EXPECT_NEAR(windowZ(2.0f), 1.0f, 1e-6f);
        EXPECT_GT(windowZ(5.0f), windowZ(50.0f));  // nearer is greater (GL_GREATER)
        if (far > 0.0f)
            EXPECT_NEAR(windowZ(100.0f), 0.0f, 1e-6f);
        else
            EXPECT_NEAR(windowZ(1e6f), 2e-6f, 1e-9f);  // near / d
    }
}

// The envelope holds the scene at every time, whatever its animation does (sampled densely here),
// and does not change with time: a still camera keeps one projection while parts move.
TEST(CameraTest, TheEnvelopeHoldsAnAnimatedSceneAtEveryTime) {
    Mesh mesh;
    mesh.positions = {{0.5f, 0, 0}, {1.5f, 0, 0}, {1, 1, 0.3f}};
    mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    mesh.indices = {0, 1, 2};
    Scene scene = test::oneMeshScene(mesh);
    Node child;
    child.parent = 0;
    child.translation = {3, 0, 0};
    child.meshes = {0};
    scene.nodes[0].children.push_back(int(scene.nodes.size()));
    scene.nodes.push_back(child);
    Animation animation;
    AnimChannel spin{
        0, AnimPath::Rotation, Interp::Linear, {0, 1, 2}, {{0, 0, 0, 1}, {0, 0.7071f, 0, 0.7071f}, {0, 1, 0, 0}}, {},
        0};
    AnimChannel move{1,
                     AnimPath::Translation,
                     Interp::CubicSpline,
                     {0, 2},
                     {{0, 0, 0, 0}, {3, 0, 0, 0}, {0, 20, 0, 0}, {0, -20, 0, 0}, {3, 2, 0, 0}, {0, 0, 0, 0}},
                     {},
                     0};
    AnimChannel grow{1, AnimPath::Scale, Interp::Step, {0, 1}, {{1, 1, 1, 0}, {2, 0.5f, 1, 0}}, {}, 0};
    animation.channels = {spin, move, grow};
    scene.animations.push_back(animation);
    scene.buildInstances();
    const Bounds envelope = scene.envelope;
    ASSERT_FALSE(envelope.empty());
    for (int i = 0; i <= 400; ++i) {
        const double time = -0.5 + 3.0 * i / 400.0;
        const Bounds at = scene.bounds(time);
        for (int axis = 0; axis < 3; ++axis) {
            EXPECT_LE(envelope.min[axis], at.min[axis]) << "t " << time;
            EXPECT_GE(envelope.max[axis], at.max[axis]) << "t " << time;
        }
    }
    // The cubic piece overshoots its keys (tangent 20 over 2 s): the control points hold it.
    EXPECT_GT(scene.bounds(0.6).max.y, 2.5f);
    // One projection for every frame of a still camera.
    Camera spec;
    spec.eye = glm::vec3(0, 2, 15);
    spec.target = glm::vec3(0, 0, 0);
    Result<View> first = resolveCamera(scene, scene.worldTransforms(0), 0, spec, 64, 64);
    Result<View> later = resolveCamera(scene, scene.worldTransforms(1.3), 1.3, spec, 64, 64);
    ASSERT_TRUE(first && later);
    EXPECT_EQ(first->projection, later->projection);
    // A static scene's envelope is its box.
    const Scene still = unitScene();
    EXPECT_EQ(still.envelope.min, glm::vec3(std::nextafter(-1.0f, -2.0f)));
    EXPECT_EQ(still.envelope.max, glm::vec3(std::nextafter(1.0f, 2.0f)));
}

// The depth buffer's resolution at a distance, as `frugal info` prints it.
TEST(CameraTest, DepthResolutionFollowsTheFormatAndThePlanes) {
    // d24 with the engine's file planes (0.05, 1e6) at 1,400: about 2.3 units.
    EXPECT_NEAR(depthResolution(DepthFormat::D24, true, 0.05, 1e6, 1400.0), 1400.0 * 1400.0 / (0.05 * 16777215.0),
                0.01);
    // Fitted to the scene (1,150 to 1,650): a step is below a hundredth of a unit.
    EXPECT_LT(depthResolution(DepthFormat::D24, true, 1150, 1650, 1400.0), 0.001);
    // d32f: about 2^-23 of the distance at any ratio, infinite far included.
    for (const double far : {1e2, 1e6, 1e12, 0.0}) {
        const double step = depthResolution(DepthFormat::D32F, true, 1.0, far, 50.0);
        EXPECT_GE(step, std::ldexp(50.0, -23)) << far;
        EXPECT_LT(step, std::ldexp(50.0, -21)) << far;
    }
    EXPECT_NEAR(depthResolution(DepthFormat::D24, false, 0.0, 16777215.0, 5.0), 1.0, 1e-9);  // linear: one unit a step
}

}  // namespace
}  // namespace frugal
