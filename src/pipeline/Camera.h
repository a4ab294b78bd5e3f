// Camera resolution (frugal/Camera.h states the rules): a scene camera, an explicit eye/target/up,
// or an automatic framing of the scene's bounds, into the matrices of one frame.
//
// Projections. DepthFormat::D24: GL's (clip z in [-w, w]; glm::perspective, infinitePerspective,
// ortho). DepthFormat::D32F: reversed Z for glClipControl's zero-to-one clip space (clip z in [0, w],
// window z 1 at the near plane, 0 at the far one); an infinite far plane gives window z = near/d.
// A glTF camera without zfar gets an infinite far plane before the fit. The fit's margin is 10⁻³ of
// the scene's depth plus 10⁻⁵ of the coordinates' size, far above the float rounding of the vertex
// transform.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include <frugal/Camera.h>
#include <frugal/Image.h>
#include <frugal/Result.h>
#include <frugal/Scene.h>

namespace frugal {

// `camera` at scene time `time` (node transforms `world`) on a width × height image whose depth
// buffer has `format`. Errors: "camera N: the scene has M cameras", degenerate eye == target, up
// parallel to the view, near ≤ 0, far ≤ near, fov outside (0, 180). `knownBounds`, when given, is
// scene.bounds(time), which the caller keeps (it transforms every vertex: a still scene's are
// worth keeping across frames).
Result<View> resolveCamera(const Scene& scene, const std::vector<glm::mat4>& world, double time, const Camera& camera,
                           int width, int height, DepthFormat format = DepthFormat::D24,
                           const Bounds* knownBounds = nullptr);

// The distances along the view direction between which `bounds` lies (depth = −z in view space),
// in double; {0, 0} for empty bounds.
struct DepthExtent {
    double nearest = 0.0, farthest = 0.0;
};
DepthExtent depthExtent(const glm::mat4& view, const Bounds& bounds);

// The smallest difference in distance a depth buffer of `format` separates at distance `d` from the
// eye with planes `znear`, `zfar` (0 = infinite): one step of the stored value (24-bit unit or
// float ULP) turned into distance, and at least the float precision of the vertex transform,
// 2^-23·d. Perspective when `perspective`, else linear.
double depthResolution(DepthFormat format, bool perspective, double znear, double zfar, double d);

}  // namespace frugal
