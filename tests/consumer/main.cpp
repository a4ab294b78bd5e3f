// Renders builtin:cubes at 64×48 through the installed library and checks that something was drawn.
#include <cstdio>

#include "gl/GlBackend.h"
#include "render/Frame.h"
#include "render/SceneRenderer.h"
#include "scene/Load.h"

int main() {
    frugal::Result<frugal::Scene> scene = frugal::loadScene("builtin:cubes");
    if (!scene) return std::fprintf(stderr, "error: %s\n", scene.error().c_str()), 1;
    frugal::Result<std::unique_ptr<frugal::Backend>> backend = frugal::createGlBackend(frugal::BackendChoice::Auto);
    if (!backend) return std::fprintf(stderr, "error: %s\n", backend.error().c_str()), 3;
    const frugal::TargetHandle target = (*backend)->createTarget(64, 48);
    frugal::Result<frugal::SceneRenderer> renderer = frugal::SceneRenderer::create(**backend, *scene);
    if (!renderer) return std::fprintf(stderr, "error: %s\n", renderer.error().c_str()), 1;
    frugal::Result<frugal::FrameSetup> frame = frugal::setUpFrame(*scene, {}, 0.0, 64, 48, true);
    if (!frame) return std::fprintf(stderr, "error: %s\n", frame.error().c_str()), 1;
    renderer->renderFrame(target, 64, 48, frame->params, frame->world, glm::vec4(0, 0, 0, 1));
    const frugal::Buffers buffers = (*backend)->readBack(target);
    std::size_t covered = 0;
    for (std::uint32_t id : buffers.ids) covered += id != 0;
    std::printf("covered %zu of %zu pixels\n", covered, buffers.pixelCount());
    return covered > 0 ? 0 : 1;
}
