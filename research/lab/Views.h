// Views that exercise culling, for reports and tests: around a scene's bounding sphere, mixing the
// cases a culling method must get right.
//   whole    — the bounding sphere wholly inside the frustum (paper 002's Table 3 case);
//   partial  — less than half of the bounding sphere inside (Table 1's case): close, looking past
//              the centre;
//   grazing  — only a sliver of the sphere inside, at the edge of the frustum;
//   inside   — the camera inside the bounding sphere;
//   pole     — the view axis along ±z through the centre: through θ = 0 and θ = 180° of the map of
//              an untransformed mesh (SphereMap.h).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/Research.h"

namespace frugal {

struct ReportView {
    std::string viewClass;  // "whole", "partial", "grazing", "inside", "pole"
    Camera camera;          // eye, target, up and fov; near/far fitted by resolveCamera
};

// `count` views (≥ 1) of a sphere (world space) seen with a vertical field of view `yfovDegrees`
// on a target of aspect `aspect` (width / height). Deterministic: the same arguments give the same
// views. The first two are the poles (when count ≥ 2); the rest cycle whole, partial, whole,
// grazing, partial, inside, with eye directions spread over the sphere (Fibonacci lattice).
std::vector<ReportView> reportViews(const glm::vec3& center, float radius, int count, float yfovDegrees = 40.0f,
                                    float aspect = 4.0f / 3.0f);

}  // namespace frugal
