#include "render/Camera.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "base/Format.h"

namespace frugal {

namespace {

glm::mat4 perspective(float yfov, float aspect, float znear, float zfar) {
    return zfar > 0.0f ? glm::perspective(yfov, aspect, znear, zfar) : glm::infinitePerspective(yfov, aspect, znear);
}

}  // namespace

Result<View> resolveCamera(const Scene& scene, const std::vector<glm::mat4>& world, double time,
                           const CameraSpec& spec, int width, int height) {
    const float viewportAspect = float(width) / float(std::max(height, 1));
    View v;

    std::optional<int> cameraIndex = spec.sceneCamera;
    if (!cameraIndex && !spec.eye && !scene.cameras.empty()) cameraIndex = 0;

    if (cameraIndex) {
        const int index = *cameraIndex;
        if (index < 0 || index >= int(scene.cameras.size()))
            return Error{"camera " + std::to_string(index) + ": the scene has " + std::to_string(scene.cameras.size()) +
                         " camera" + (scene.cameras.size() == 1 ? "" : "s")};
        const Camera& camera = scene.cameras[index];
        glm::mat4 cameraWorld = camera.node >= 0 ? world[camera.node] : glm::mat4(1.0f);
        // A camera node's scale must not reach the view: keep rotation and translation only.
        const glm::vec3 eye = glm::vec3(cameraWorld[3]);
        const glm::vec3 forward = -glm::vec3(cameraWorld[2]);
        const glm::vec3 up = glm::vec3(cameraWorld[1]);
        if (glm::length(forward) == 0.0f || glm::length(up) == 0.0f || !std::isfinite(glm::length(forward)))
            return Error{"camera " + std::to_string(index) + ": its node transform is degenerate"};
        v.view = glm::lookAt(eye, eye + glm::normalize(forward), glm::normalize(up));
        v.eye = eye;
        v.forward = glm::normalize(forward);
        v.perspective = camera.perspective;
        v.znear = spec.znear.value_or(camera.znear);
        v.zfar = spec.zfar.value_or(camera.zfar);
        v.yfov = spec.yfovDegrees ? glm::radians(*spec.yfovDegrees) : camera.yfov;
        v.source = "scene camera " + std::to_string(index) + quotedName(camera.name);
        if (!camera.perspective) {
            if (v.zfar <= v.znear) return Error{"camera " + std::to_string(index) + ": orthographic zfar " + fmt(v.zfar) + " must exceed znear " + fmt(v.znear)};
            v.projection = glm::ortho(-camera.xmag, camera.xmag, -camera.ymag, camera.ymag, v.znear, v.zfar);
            return v;
        }
        const float aspect = camera.aspect > 0.0f ? camera.aspect : viewportAspect;
        if (!(v.znear > 0.0f)) return Error{"camera " + std::to_string(index) + ": znear " + fmt(v.znear) + " must be > 0"};
        if (v.zfar != 0.0f && !(v.zfar > v.znear))
            return Error{"camera " + std::to_string(index) + ": zfar " + fmt(v.zfar) + " must exceed znear " + fmt(v.znear)};
        if (!(v.yfov > 0.0f && v.yfov < glm::pi<float>()))
            return Error{"camera " + std::to_string(index) + ": yfov " + fmt(glm::degrees(v.yfov)) + " degrees is outside (0, 180)"};
        v.projection = perspective(v.yfov, aspect, v.znear, v.zfar);
        return v;
    }

    const Bounds bounds = scene.bounds(time);
    const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
    const float radius = std::max(bounds.radius(), 1e-6f);
    v.yfov = glm::radians(spec.yfovDegrees.value_or(40.0f));
    if (!(v.yfov > 0.0f && v.yfov < glm::pi<float>()))
        return Error{"camera: yfov " + fmt(glm::degrees(v.yfov)) + " degrees is outside (0, 180)"};

    glm::vec3 eye, target;
    if (spec.eye) {
        eye = *spec.eye;
        target = spec.target.value_or(center);
        v.source = "eye/target";
    } else {
        // Fit the bounding sphere in the narrower of the two fields of view.
        const float fov = std::min(v.yfov, 2.0f * std::atan(std::tan(v.yfov / 2) * viewportAspect));
        const float distance = radius / std::sin(fov / 2) * 1.02f;
        target = center;
        eye = center + glm::normalize(glm::vec3(0.0f, 0.25f, 1.0f)) * distance;
        v.source = "auto (fit bounds)";
    }
    const glm::vec3 forward = target - eye;
    if (!(glm::length(forward) > 0.0f) || !std::isfinite(glm::length(forward)))
        return Error{"camera: eye and target must differ and be finite"};
    if (glm::length(glm::cross(glm::normalize(forward), spec.up)) < 1e-6f)
        return Error{"camera: up (" + fmt(spec.up.x) + "," + fmt(spec.up.y) + "," + fmt(spec.up.z) + ") is parallel to the view direction"};
    // Default clip range: just around the scene, so depth precision goes where the scene is.
    const float distance = glm::length(center - eye);
    v.znear = spec.znear.value_or(std::max(distance - radius * 1.1f, std::max(distance, radius) * 1e-3f));
    v.zfar = spec.zfar.value_or(distance + radius * 1.1f);
    // Say which plane was given and which was fitted, so the caller can tell its user what to change.
    const auto plane = [](const char* name, float value, bool given) {
        return std::string(name) + " plane " + fmt(value) + (given ? "" : " (fitted to the scene)");
    };
    if (!(v.znear > 0.0f)) return Error{"camera: " + plane("near", v.znear, spec.znear.has_value()) + " must be > 0"};
    if (v.zfar != 0.0f && !(v.zfar > v.znear))
        return Error{"camera: " + plane("far", v.zfar, spec.zfar.has_value()) + " must exceed the " +
                     plane("near", v.znear, spec.znear.has_value())};
    v.eye = eye;
    v.forward = glm::normalize(forward);
    v.view = glm::lookAt(eye, target, spec.up);
    v.projection = perspective(v.yfov, viewportAspect, v.znear, v.zfar);
    return v;
}

}  // namespace frugal
