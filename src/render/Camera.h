// Camera resolution: a scene camera (glTF), an explicit eye/target/up, or an automatic framing of
// the scene's bounds.
//
// Aspect ratio. The projection always takes the image's aspect ratio (width / height) and keeps the
// camera's vertical extent: the vertical field of view of a perspective camera, ymag of an
// orthographic one. A glTF camera's own aspectRatio (or xmag) is not used to stretch the picture, as
// no viewer does; it is kept in View::fileAspect, so that a caller can size the image to it or say
// that the two differ (aspectDiffers).
//
// Depth range. With DepthRange::Fit (the default) the near and far planes are moved inward to the
// nearest and farthest point of the scene's envelope (Scene::envelope: every triangle at every time)
// along the view direction, with a margin, and never outward past the planes the camera (or the
// user) gave: no triangle is clipped that the given planes keep, and the depth buffer's precision
// goes where the scene is. A file's 0.05 to 1,000,000 around an engine 1,400 units away becomes
// about 1,150 to 1,650. The envelope does not change with time, so a still camera keeps one
// projection while the scene moves (temporal reuse depends on it). DepthRange::File keeps the
// given planes.
//
// Projections. DepthFormat::D24: GL's (clip z in [-w, w]; glm::perspective, infinitePerspective,
// ortho). DepthFormat::D32F: reversed Z for glClipControl's zero-to-one clip space (clip z in [0, w],
// window z 1 at the near plane, 0 at the far one); an infinite far plane gives window z = near/d.
// A glTF camera without zfar gets an infinite far plane before the fit.
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "base/Result.h"
#include "render/Image.h"
#include "scene/Scene.h"

namespace frugal {

enum class DepthRange : std::uint8_t { Fit, File };
inline const char* depthRangeName(DepthRange range) { return range == DepthRange::File ? "file" : "fit"; }

struct CameraSpec {
    std::optional<int> sceneCamera;  // index into Scene::cameras
    std::optional<glm::vec3> eye, target;
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    std::optional<float> yfovDegrees;
    std::optional<float> znear, zfar;  // zfar 0 = infinite
    DepthRange depthRange = DepthRange::Fit;
    DepthFormat depthFormat = DepthFormat::D24;
};

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
    std::string source;  // "scene camera 0 'name'", "eye/target", "auto (fit bounds)"
};

// Rules: a scene camera index wins; else eye (and target) given → look-at; else the scene's first
// camera; else fit the bounds at `time` from the front (+z) and a little above.
// Errors: "camera N: the scene has M cameras", degenerate eye == target, up parallel to the view,
// near ≤ 0, far ≤ near, fov outside (0, 180).
Result<View> resolveCamera(const Scene& scene, const std::vector<glm::mat4>& world, double time,
                           const CameraSpec& spec, int width, int height);

// The distances along the view direction between which `bounds` lies (depth = −z in view space),
// in double; {0, 0} for empty bounds.
struct DepthExtent {
    double nearest = 0.0, farthest = 0.0;
};
DepthExtent depthExtent(const glm::mat4& view, const Bounds& bounds);

// True when the scene camera's own aspect ratio (fileAspect) and a width × height image's differ by
// more than rounding the image to whole pixels explains.
bool aspectDiffers(float fileAspect, int width, int height);

// The image size for a camera of aspect ratio `aspect` when none is asked for: the longer side
// `longSide` pixels, the other rounded (at least 1).
void sizeForAspect(float aspect, int longSide, int& width, int& height);

// The smallest difference in distance a depth buffer of `format` separates at distance `d` from the
// eye with planes `znear`, `zfar` (0 = infinite): one step of the stored value (24-bit unit or
// float ULP) turned into distance, and at least the float precision of the vertex transform,
// 2^-23·d. Perspective when `perspective`, else linear.
double depthResolution(DepthFormat format, bool perspective, double znear, double zfar, double d);

}  // namespace frugal
