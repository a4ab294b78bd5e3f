// Cameras: what a frame is seen through, as asked for (Camera) and as resolved for one frame (View).
//
// Aspect ratio. The projection always takes the image's aspect ratio (width / height) and keeps the
// camera's vertical extent: the vertical field of view of a perspective camera, ymag of an
// orthographic one. A glTF camera's own aspectRatio (or xmag) does not stretch the picture, as in no
// viewer; it is kept in View::fileAspect.
//
// Depth range. With DepthRange::Fit (the default) the near and far planes are moved inward to the
// nearest and farthest point of the scene's envelope (Scene::envelope: every triangle at every time)
// along the view direction, with a margin, and never outward past the planes the camera gives: no
// triangle is clipped that the given planes keep, and the depth buffer's precision goes where the
// scene is. A file's 0.05 to 1,000,000 around an engine 1,400 units away becomes about 1,210 to
// 2,020. The envelope does not change with time, so a still camera keeps one projection while the
// scene moves. DepthRange::File keeps the given planes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Image.h>
#include <frugal/Result.h>

namespace frugal {

enum class DepthRange : std::uint8_t { Fit, File };
inline const char* depthRangeName(DepthRange range) { return range == DepthRange::File ? "file" : "fit"; }

// A camera as asked for. Rules: a scene camera index wins; else an eye (and a target, default the
// centre of the scene's bounds) gives a look-at; else the scene's first camera; else an automatic
// view that fits the scene's bounds at the frame's time, from the front (+z) and a little above.
// Unset values come from the scene camera, or the defaults: a 40° vertical field of view, planes just
// around the scene.
struct Camera {
    std::optional<int> sceneCamera;  // index into Scene::cameras
    std::optional<glm::vec3> eye, target;
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    std::optional<float> yfovDegrees;
    std::optional<float> znear, zfar;  // zfar 0 = infinite
    DepthRange depthRange = DepthRange::Fit;

    // The scene's camera `index` (its node's transform at the frame's time, its projection).
    static Camera fromScene(int index) {
        Camera c;
        c.sceneCamera = index;
        return c;
    }
    // From `eye` towards `target`, `up` as the image's up, a vertical field of view in degrees.
    static Camera lookAt(const glm::vec3& eye, const glm::vec3& target, float yfovDegrees = 40.0f,
                         const glm::vec3& up = {0.0f, 1.0f, 0.0f}) {
        Camera c;
        c.eye = eye;
        c.target = target;
        c.up = up;
        c.yfovDegrees = yfovDegrees;
        return c;
    }
    // A camera-to-world pose in OpenGL's convention (the camera looks down its −z, +y up; pyrender's
    // convention): eye = pose[3], towards −pose[2], up pose[1].
    static Camera fromPose(const glm::mat4& cameraToWorld, float yfovDegrees = 40.0f) {
        const glm::vec3 eye(cameraToWorld[3]);
        return lookAt(eye, eye - glm::vec3(cameraToWorld[2]), yfovDegrees, glm::vec3(cameraToWorld[1]));
    }
    // The automatic view of the scene's bounds (also what an empty Camera gives a scene without cameras).
    static Camera automatic() { return {}; }
};

// A camera resolved for one frame: matrices, planes, and where they came from.
struct View {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    // The same projection with the given planes (before the fit): the frustum culling tests. The fit
    // moves the planes only where no triangle is, so a triangle is inside both frusta or neither,
    // but a bounding sphere (paper 002's classes) may reach past the fitted planes.
    glm::mat4 givenProjection{1.0f};
    glm::vec3 eye{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};
    bool perspective = true;
    float yfov = 0.0f;                        // radians (perspective)
    float ymag = 0.0f;                        // half height (orthographic)
    float aspect = 1.0f;                      // width / height of the projection: the image's
    float fileAspect = 0.0f;                  // the scene camera's own (glTF aspectRatio, or xmag / ymag); 0 = none
    float znear = 0.0f, zfar = 0.0f;          // the planes drawn with; zfar 0 = infinite
    float givenNear = 0.0f, givenFar = 0.0f;  // the camera's or the user's planes, before the fit
    DepthRange depthRange = DepthRange::Fit;
    DepthFormat depthFormat = DepthFormat::D24;
    int width = 0, height = 0;  // the target's pixels (0: not known; culling then decides no facing)
    std::string source;  // "scene camera 0 'name'", "eye/target", "auto (fit bounds)"
};

// True when a scene camera's own aspect ratio (View::fileAspect) and a width × height image's differ
// by more than rounding the image to whole pixels explains (the image is then drawn with the
// camera's vertical extent and the image's aspect ratio, not stretched).
bool aspectDiffers(float fileAspect, int width, int height);

// The image size for a camera of aspect ratio `aspect` when none is asked for: the longer side
// `longSide` pixels, the other rounded (at least 1). The command line sizes its image so.
void sizeForAspect(float aspect, int longSide, int& width, int& height);

// `camera` resolved for a width × height frame of `scene` at `seconds`, as Renderer::render
// resolves it (Frame::view), without rendering: its matrices and planes before any backend opens.
// Errors (BadInput): "camera 3: the scene has 1 camera", "eye and target coincide at (0, 0, 0)", ...
struct Scene;
Result<View> resolveView(const Scene& scene, const Camera& camera, double seconds, int width, int height,
                         DepthFormat format = DepthFormat::D24);

// A camera path: the JSON file at `path`, a list of {"eye":[x,y,z],"target":[x,y,z],"up":[x,y,z],
// "fov":degrees} ("up" and "fov" optional; {"views": [...]} is taken too), one Camera an entry
// (eye, target, up, yfovDegrees). An entry that makes no view whatever the scene is refused with
// its number. Errors start with the setting (Error::aboutSetting): "camera-path F: cannot read the
// file" (Io), "camera-path F: entry 3: eye: expected 3 numbers", "... eye and target coincide at
// (0, 0, 0)", "... up (0, 1, 0) is parallel to the view direction" (BadInput).
Result<std::vector<Camera>> readCameraPath(const std::string& path);

}  // namespace frugal
