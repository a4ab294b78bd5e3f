#include "lab/Views.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace frugal {

namespace {

// Any unit vector not parallel to `forward`, made orthogonal to it: the camera's up.
glm::vec3 upFor(const glm::vec3& forward) {
    const glm::vec3 y(0.0f, 1.0f, 0.0f);
    const glm::vec3 candidate = std::abs(glm::dot(forward, y)) < 0.9f ? y : glm::vec3(1.0f, 0.0f, 0.0f);
    return glm::normalize(candidate - glm::dot(candidate, forward) * forward);
}

}  // namespace

std::vector<ReportView> reportViews(const glm::vec3& center, float radius, int count, float yfovDegrees, float aspect) {
    std::vector<ReportView> views;
    if (count < 1) return views;
    const float r = radius > 0.0f && std::isfinite(radius) ? radius : 1.0f;
    const double half = glm::radians(double(yfovDegrees)) / 2.0;
    const double halfX = std::atan(std::tan(half) * double(aspect));
    const double narrow = std::min(half, halfX);
    // Distance at which the sphere just fits the narrower field of view.
    const float fit = float(double(r) / std::sin(narrow));

    auto make = [&](const std::string& viewClass, const glm::vec3& eye, const glm::vec3& target,
                    const glm::vec3& up) {
        ReportView view;
        view.viewClass = viewClass;
        view.camera.eye = eye;
        view.camera.target = target;
        view.camera.up = up;
        view.camera.yfovDegrees = yfovDegrees;
        views.push_back(view);
    };
    // Looking from `eye` (at `distance` from the centre along `dir`) past the centre: the view axis
    // turned by β from the centre towards `side`, the camera's up. The centre then lies β − half
    // beyond the bottom plane: at distance·sin(β − half) from it.
    auto lookPast = [&](const std::string& viewClass, const glm::vec3& dir, const glm::vec3& side, float distance,
                        double depthOutside) {
        const double beta = half + std::asin(std::clamp(depthOutside / double(distance), -1.0, 1.0));
        const glm::vec3 forward = float(std::cos(beta)) * -dir + float(std::sin(beta)) * side;
        const glm::vec3 up = float(std::cos(beta)) * side + float(std::sin(beta)) * dir;
        const glm::vec3 eye = center + dir * distance;
        make(viewClass, eye, eye + forward * distance, up);
    };

    if (count >= 2) {
        make("pole", center + glm::vec3(0.0f, 0.0f, 1.25f * fit), center, glm::vec3(0.0f, 1.0f, 0.0f));
        make("pole", center - glm::vec3(0.0f, 0.0f, 1.25f * fit), center, glm::vec3(0.0f, 1.0f, 0.0f));
    }
    static const char* const kCycle[] = {"whole", "partial", "whole", "grazing", "partial", "inside"};
    const int rest = count - int(views.size());
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int k = 0; k < rest; ++k) {
        // Fibonacci lattice: even spread of eye directions, none exactly on a pole.
        const double z = 1.0 - (2.0 * k + 1.0) / double(rest);
        const double ring = std::sqrt(std::max(0.0, 1.0 - z * z));
        const glm::vec3 dir(float(ring * std::cos(golden * k)), float(ring * std::sin(golden * k)), float(z));
        const glm::vec3 side = upFor(-dir);                  // orthogonal to the view axis
        const std::string viewClass = kCycle[k % 6];
        if (viewClass == "whole") {
            make(viewClass, center + dir * (fit * (1.15f + 0.1f * float(k % 3))), center, side);
        } else if (viewClass == "partial") {
            // Close, the centre half a radius outside the bottom plane: less than half of the sphere
            // is inside the frustum.
            lookPast(viewClass, dir, side, 1.6f * r, 0.5 * r);
        } else if (viewClass == "grazing") {
            // The centre 0.95 radii outside the bottom plane: a sliver of the sphere inside.
            lookPast(viewClass, dir, side, 2.0f * fit, 0.95 * r);
        } else {  // inside
            make(viewClass, center + dir * (0.45f * r), center - dir * r, side);
        }
    }
    return views;
}

}  // namespace frugal
