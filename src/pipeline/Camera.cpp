#include "pipeline/Camera.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "base/Format.h"

namespace frugal {

namespace {

glm::mat4 perspectiveProjection(float yfov, float aspect, float znear, float zfar, DepthFormat format) {
    if (format == DepthFormat::D24)
        return zfar > 0.0f ? glm::perspective(yfov, aspect, znear, zfar)
                           : glm::infinitePerspective(yfov, aspect, znear);
    // Reversed Z in [0, w]: the zero-to-one projection with the planes swapped maps near → 1, far → 0.
    if (zfar > 0.0f) return glm::perspectiveRH_ZO(yfov, aspect, zfar, znear);
    glm::mat4 m = glm::perspectiveRH_ZO(yfov, aspect, znear, 2.0f * znear);  // x, y and w rows
    m[2][2] = 0.0f;  // clip z = near, w = d: window z = near / d
    m[3][2] = znear;
    return m;
}

glm::mat4 orthographicProjection(float xmag, float ymag, float znear, float zfar, DepthFormat format) {
    if (format == DepthFormat::D24) return glm::ortho(-xmag, xmag, -ymag, ymag, znear, zfar);
    return glm::orthoRH_ZO(-xmag, xmag, -ymag, ymag, zfar, znear);  // reversed, as above
}

// The planes fitted to the scene's envelope (the top of Camera.h). The margin covers the float
// rounding of the vertex transform (a few 2^-24 of the coordinates' size, here 10^-5) and a
// thousandth of the scene's depth, which costs nothing in precision.
void fitPlanes(const Bounds& envelope, View& v) {
    if (envelope.empty()) return;
    const DepthExtent extent = depthExtent(v.view, envelope);
    if (!std::isfinite(extent.nearest) || !std::isfinite(extent.farthest)) return;
    const double size = std::max({double(glm::length(envelope.min)), double(glm::length(envelope.max)),
                                  double(glm::length(v.eye)), std::abs(extent.nearest), std::abs(extent.farthest)});
    const double margin = 1e-3 * (extent.farthest - extent.nearest) + 1e-5 * size;
    const double znear = std::max(double(v.givenNear), extent.nearest - margin);
    const double zfar =
        v.givenFar == 0.0f ? extent.farthest + margin : std::min(double(v.givenFar), extent.farthest + margin);
    // Nothing of the scene between the given planes (all of it behind the eye, say): keep them.
    if (!(zfar > znear) || !std::isfinite(zfar)) return;
    v.znear = float(znear);
    v.zfar = std::max(float(zfar), std::nextafter(v.znear, INFINITY));
}

Result<View> finish(View v, const Bounds& envelope, DepthRange range, DepthFormat format) {
    v.givenNear = v.znear;
    v.givenFar = v.zfar;
    v.depthRange = range;
    v.depthFormat = format;
    const auto project = [&v, format](float znear, float zfar) {
        return v.perspective ? perspectiveProjection(v.yfov, v.aspect, znear, zfar, format)
                             : orthographicProjection(v.ymag * v.aspect, v.ymag, znear, zfar, format);
    };
    v.givenProjection = project(v.znear, v.zfar);
    if (range == DepthRange::Fit) fitPlanes(envelope, v);
    v.projection = project(v.znear, v.zfar);
    return v;
}

}  // namespace

DepthExtent depthExtent(const glm::mat4& view, const Bounds& bounds) {
    if (bounds.empty()) return {};
    const glm::dmat4 m(view);
    DepthExtent e{INFINITY, -INFINITY};
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p(corner & 1 ? bounds.max.x : bounds.min.x, corner & 2 ? bounds.max.y : bounds.min.y,
                           corner & 4 ? bounds.max.z : bounds.min.z);
        const double depth = -(m * glm::dvec4(p, 1.0)).z;
        e.nearest = std::min(e.nearest, depth);
        e.farthest = std::max(e.farthest, depth);
    }
    return e;
}

bool aspectDiffers(float fileAspect, int width, int height) {
    if (!(fileAspect > 0.0f)) return false;
    // A width rounded from a·h is within 0.5 of it; a height rounded from w/a puts w within a/2.
    const double a = fileAspect;
    return std::abs(double(width) - a * double(height)) > 0.5 * std::max(1.0, a) + 1e-9;
}

void sizeForAspect(float aspect, int longSide, int& width, int& height) {
    const double a = aspect > 0.0f && std::isfinite(aspect) ? double(aspect) : 4.0 / 3.0;
    if (a >= 1.0) {
        width = longSide;
        height = std::max(1, int(std::lround(longSide / a)));
    } else {
        width = std::max(1, int(std::lround(longSide * a)));
        height = longSide;
    }
}

double depthResolution(DepthFormat format, bool perspective, double n, double f, double d) {
    const double computed = std::ldexp(d, -23);  // the vertex transform's own float precision
    double step = 0.0;
    if (format == DepthFormat::D24) {
        // Window z = f(d − n)/(d(f − n)) (infinite f: 1 − n/d); one 24-bit step over its slope.
        const double slope = perspective ? (f > 0.0 ? f * n / ((f - n) * d * d) : n / (d * d)) : 1.0 / (f - n);
        step = (1.0 / 16777215.0) / slope;
    } else {
        // Reversed: window z = n(f − d)/(d(f − n)) (infinite f: n/d); one float ULP at that value.
        const double z = perspective ? (f > 0.0 ? n * (f - d) / (d * (f - n)) : n / d) : (f - d) / (f - n);
        const double slope = perspective ? (f > 0.0 ? f * n / ((f - n) * d * d) : n / (d * d)) : 1.0 / (f - n);
        const float zf = std::max(float(z), std::numeric_limits<float>::denorm_min());
        step = double(std::nextafter(zf, INFINITY) - zf) / slope;
    }
    return std::max(step, computed);
}

Result<View> resolveCamera(const Scene& scene, const std::vector<glm::mat4>& world, double time, const Camera& spec,
                           int width, int height, DepthFormat format, const Bounds* knownBounds) {
    const float viewportAspect = float(width) / float(std::max(height, 1));
    View v;
    v.aspect = viewportAspect;
    v.width = width;
    v.height = height;

    std::optional<int> cameraIndex = spec.sceneCamera;
    if (!cameraIndex && !spec.eye && !scene.cameras.empty()) cameraIndex = 0;

    if (cameraIndex) {
        const int index = *cameraIndex;
        if (index < 0 || index >= int(scene.cameras.size()))
            return Error{"camera " + std::to_string(index) + ": the scene has " + std::to_string(scene.cameras.size()) +
                         " camera" + (scene.cameras.size() == 1 ? "" : "s")};
        const SceneCamera& camera = scene.cameras[index];
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
            v.ymag = camera.ymag;
            v.fileAspect = camera.fileAspect();
            return finish(v, scene.envelope, spec.depthRange, format);
        }
        v.fileAspect = camera.fileAspect();
        if (!(v.znear > 0.0f)) return Error{"camera " + std::to_string(index) + ": znear " + fmt(v.znear) + " must be > 0"};
        if (v.zfar != 0.0f && !(v.zfar > v.znear))
            return Error{"camera " + std::to_string(index) + ": zfar " + fmt(v.zfar) + " must exceed znear " + fmt(v.znear)};
        if (!(v.yfov > 0.0f && v.yfov < glm::pi<float>()))
            return Error{"camera " + std::to_string(index) + ": yfov " + fmt(glm::degrees(v.yfov)) + " degrees is outside (0, 180)"};
        return finish(v, scene.envelope, spec.depthRange, format);
    }

    // The scene's bounds at this time: every vertex transformed, so only when something needs them
    // (the automatic view, a default target, a scene without an envelope).
    const bool needsBounds = !spec.eye || !spec.target || scene.envelope.empty();
    const Bounds bounds = !needsBounds ? Bounds{} : knownBounds ? *knownBounds : scene.bounds(time);
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
    // Default clip range: just around the scene at every time (its envelope, which the fit then
    // tightens), so that a still camera keeps its planes while parts move.
    const Bounds& around = scene.envelope.empty() ? bounds : scene.envelope;
    const float distance = glm::length(around.center() - eye);
    const float extent = std::max(around.radius(), 1e-6f);
    v.znear = spec.znear.value_or(std::max(distance - extent * 1.1f, std::max(distance, extent) * 1e-3f));
    v.zfar = spec.zfar.value_or(distance + extent * 1.1f);
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
    return finish(v, scene.envelope, spec.depthRange, format);
}

}  // namespace frugal
