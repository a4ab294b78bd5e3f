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
    return setup;
}

std::array<std::uint8_t, 4> colorBytes(const glm::vec4& color) {
    std::array<std::uint8_t, 4> bytes{};
    for (int k = 0; k < 4; ++k) bytes[k] = std::uint8_t(std::lround(std::clamp(color[k], 0.0f, 1.0f) * 255.0f));
    return bytes;
}

}  // namespace frugal
