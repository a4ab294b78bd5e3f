#include "pipeline/Frame.h"

#include <algorithm>
#include <cmath>

namespace frugal {

double frameTime(int frame, double fps) { return double(frame) / fps; }

Result<View> resolveView(const Scene& scene, const Camera& camera, double seconds, int width, int height,
                         DepthFormat format) {
    Result<FrameSetup> setup = setUpFrame(scene, camera, seconds, width, height, false, format);
    if (!setup) return setup.error();
    return setup->view;
}

Result<FrameSetup> setUpFrame(const Scene& scene, const Camera& camera, double time, int width, int height,
                              bool writeIds, DepthFormat format, const Bounds* knownBounds) {
    FrameSetup setup;
    setup.time = time;
    setup.world = scene.worldTransforms(time);
    Result<View> view = resolveCamera(scene, setup.world, time, camera, width, height, format, knownBounds);
    if (!view) return Error{view.error().message};
    setup.view = *view;
    setup.params.view = view->view;
    setup.params.projection = view->projection;
    setup.params.depthFormat = view->depthFormat;
    setup.params.writeIds = writeIds;
    setup.params.time = time;
    setup.params.lighting.lights = frameLights(scene, setup.world);
    return setup;
}

std::vector<FrameLight> frameLights(const Scene& scene, const std::vector<glm::mat4>& world) {
    std::vector<FrameLight> lights;
    for (std::size_t n = 0; n < scene.nodes.size() && lights.size() < std::size_t(kMaxLights); ++n) {
        const int index = scene.nodes[n].light;
        if (index < 0 || index >= int(scene.lights.size())) continue;
        const PunctualLight& src = scene.lights[std::size_t(index)];
        FrameLight light;
        light.type = src.type;
        light.position = glm::vec3(world[n][3]);
        const glm::vec3 axis = glm::mat3(world[n]) * glm::vec3(0.0f, 0.0f, -1.0f);
        const float length = glm::length(axis);
        light.direction = length > 0.0f && std::isfinite(length) ? axis / length : glm::vec3(0.0f, 0.0f, -1.0f);
        light.intensity = src.color * src.intensity;
        light.range = src.type == LightType::Directional ? 0.0f : src.range;
        if (src.type == LightType::Spot) {
            light.outerCos = std::cos(src.outerConeAngle);
            light.innerCos = std::cos(src.innerConeAngle);
        }
        lights.push_back(light);
    }
    return lights;
}

std::array<std::uint8_t, 4> colorBytes(const glm::vec4& color) {
    std::array<std::uint8_t, 4> bytes{};
    for (int k = 0; k < 4; ++k) bytes[k] = std::uint8_t(std::lround(std::clamp(color[k], 0.0f, 1.0f) * 255.0f));
    return bytes;
}

}  // namespace frugal
