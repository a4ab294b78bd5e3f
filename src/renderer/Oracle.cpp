#include "renderer/Oracle.h"

#include <chrono>

namespace frugal {

Result<Oracle> makeOracle(SceneRenderer& full, TargetHandle target, int width, int height, FrameParams frame,
                          const std::vector<glm::mat4>& world, const glm::vec4& background) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    frame.writeIds = true;
    full.renderFrame(target, width, height, frame, world, background);
    Result<TriangleSet> rvs = visibleSet(full.scene(), full.backend().readBack(target));
    if (!rvs) return Error{rvs.error().message};
    Oracle oracle;
    oracle.rvs = std::move(*rvs);
    oracle.scene = std::make_unique<Scene>(oracleScene(full.scene(), oracle.rvs));
    oracle.ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    Result<SceneRenderer> renderer = SceneRenderer::create(full.backend(), *oracle.scene);
    if (!renderer) return Error{"oracle: " + renderer.error().message};
    oracle.renderer.emplace(std::move(*renderer));
    return oracle;
}

}  // namespace frugal
