// Everything one frame needs before anything is drawn: its scene time, the node transforms at that
// time, the camera, and the parameters a backend's beginFrame takes. Library work shared by the CLI,
// culling, reuse and tests, so that all of them set up a frame the same way.
#pragma once

#include <functional>

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Result.h>
#include <frugal/Scene.h>

#include "pipeline/Backend.h"
#include "pipeline/Camera.h"

namespace frugal {

struct FrameSetup {
    double time = 0.0;
    std::vector<glm::mat4> world;  // per node, at `time`
    View view;
    FrameParams params;
};

// The frame at scene time `time`, seen through `camera` on a width × height target whose depth
// buffer has `format`. Errors are resolveCamera's (pipeline/Camera.h): values, never command-line flags.
// `knownBounds`: scene.bounds(time) when the caller keeps it (resolveCamera).
Result<FrameSetup> setUpFrame(const Scene& scene, const Camera& camera, double time, int width, int height,
                              bool writeIds, DepthFormat format = DepthFormat::D24, const Bounds* knownBounds = nullptr);

// The punctual lights of `scene` placed by the nodes' world transforms `world`: the first
// kMaxLights nodes with a light, in node order (pipeline/Backend.h).
std::vector<FrameLight> frameLights(const Scene& scene, const std::vector<glm::mat4>& world);

// A sequence's frame `frame` with its camera and time resolved (setUpFrame): how a harness asks for
// the frames it measures. Errors as one line.
using FrameSetupOf = std::function<Result<FrameSetup>(int frame)>;

// A clear colour as the 8-bit target holds it (GL's unorm conversion: clamp to [0,1], ×255, round
// to nearest).
std::array<std::uint8_t, 4> colorBytes(const glm::vec4& color);

}  // namespace frugal
