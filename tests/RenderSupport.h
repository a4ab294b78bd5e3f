// Rendering a whole scene frame for a test: the suites that render through SceneRenderer share it.
// Header-only, because only the suites that link a backend include it.
#pragma once

#include <gtest/gtest.h>

#include "pipeline/Frame.h"
#include "pipeline/SceneRenderer.h"

namespace frugal::test {

struct RenderedFrame {
    Buffers buffers;
    View view;
};

// The scene at `time` through `camera` (default: the scene's own, planes fitted) on a fresh
// width × height target of depth `format` (destroyed after), cleared to `background`. Set-up
// failures are test failures, and give an empty frame.
inline RenderedFrame renderScene(Backend& backend, const Scene& scene, int width, int height, double time, bool ids,
                                 const glm::vec4& background, const Camera& camera = {},
                                 DepthFormat format = DepthFormat::D24) {
    const TargetHandle target = backend.createTarget(width, height, format);
    EXPECT_NE(target, kNoHandle);
    Result<SceneRenderer> renderer = SceneRenderer::create(backend, scene);
    Result<FrameSetup> setup = setUpFrame(scene, camera, time, width, height, ids, format);
    EXPECT_TRUE(renderer) << renderer.error().message;
    EXPECT_TRUE(setup) << setup.error().message;
    if (target == kNoHandle || !renderer || !setup) return {};
    renderer->renderFrame(target, width, height, setup->params, setup->world, background);
    RenderedFrame frame{backend.readBack(target), setup->view};
    backend.destroyTarget(target);
    return frame;
}

}  // namespace frugal::test
