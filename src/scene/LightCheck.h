// KHR_lights_punctual's ranges for a light's values (PunctualLight), the one rule the glTF loader
// and Scene::addLight both check, each naming the value in its own words. Internal to src/scene/.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>

#include <frugal/Scene.h>

namespace frugal {

enum class LightValue : std::uint8_t { Color, Intensity, Range, OuterCone, InnerCone };
struct LightProblem {
    LightValue value;
    int channel = 0;  // of the colour
};

// The first value out of its range, or nothing: each colour channel and the intensity finite and at
// least 0; the range finite and at least 0 (0: unbounded); a spot's outer cone angle in (0, π/2]
// and its inner one in [0, outer).
inline std::optional<LightProblem> lightProblem(const PunctualLight& light) {
    const auto atLeastZero = [](float v) { return v >= 0.0f && std::isfinite(v); };
    for (int c = 0; c < 3; ++c)
        if (!atLeastZero(light.color[c])) return LightProblem{LightValue::Color, c};
    if (!atLeastZero(light.intensity)) return LightProblem{LightValue::Intensity};
    if (!atLeastZero(light.range)) return LightProblem{LightValue::Range};
    if (light.type == LightType::Spot) {
        if (!(light.outerConeAngle > 0.0f && light.outerConeAngle <= 1.57079637f))
            return LightProblem{LightValue::OuterCone};
        if (!(light.innerConeAngle >= 0.0f && light.innerConeAngle < light.outerConeAngle))
            return LightProblem{LightValue::InnerCone};
    }
    return std::nullopt;
}

}  // namespace frugal
