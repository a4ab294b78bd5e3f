// Camera resolution: a scene camera (glTF), an explicit eye/target/up, or an automatic framing of
// the scene's bounds. Projections are GL's (clip z in [-w, w], window z in [0, 1]); a glTF camera
// without zfar gets an infinite far plane.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "base/Result.h"
#include "scene/Scene.h"

namespace frugal {

struct CameraSpec {
    std::optional<int> sceneCamera;  // index into Scene::cameras
    std::optional<glm::vec3> eye, target;
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    std::optional<float> yfovDegrees;
    std::optional<float> znear, zfar;  // zfar 0 = infinite
};

struct View {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    glm::vec3 eye{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};
    bool perspective = true;
    float yfov = 0.0f, znear = 0.0f, zfar = 0.0f;  // zfar 0 = infinite
    std::string source;  // "scene camera 0 'name'", "eye/target", "auto (fit bounds)"
};

// Rules: a scene camera index wins; else eye (and target) given → look-at; else the scene's first
// camera; else fit the bounds at `time` from the front (+z) and a little above.
// Errors: "camera N: the scene has M cameras", degenerate eye == target, up parallel to the view,
// near ≤ 0, far ≤ near, fov outside (0, 180).
Result<View> resolveCamera(const Scene& scene, const std::vector<glm::mat4>& world, double time,
                           const CameraSpec& spec, int width, int height);

}  // namespace frugal
