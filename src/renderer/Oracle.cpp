#include "renderer/Oracle.h"

#include <chrono>

namespace frugal {

namespace {

// Adds the members of `more` to `set` (both shaped like one scene).
void unite(TriangleSet& set, const TriangleSet& more) {
    for (std::size_t i = 0; i < set.perInstance.size() && i < more.perInstance.size(); ++i)
        for (std::size_t t = 0; t < set.perInstance[i].size() && t < more.perInstance[i].size(); ++t)
            if (more.perInstance[i][t] != 0 && set.perInstance[i][t] == 0) {
                set.perInstance[i][t] = 1;
                ++set.count;
            }
}

}  // namespace

Result<Oracle> makeOracle(SceneRenderer& full, TargetHandle target, int width, int height, FrameParams frame,
                          const std::vector<glm::mat4>& world, const glm::vec4& background) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const Scene& scene = full.scene();
    frame.writeIds = true;
    full.renderFrame(target, width, height, frame, world, background);
    Result<TriangleSet> rvs = visibleSet(scene, full.backend().readBack(target));
    if (!rvs) return Error{rvs.error().message};
    Oracle oracle;
    oracle.rvs = std::move(*rvs);
    TriangleSet drawn = oracle.rvs;
    if (anyBlended(scene)) {
        // What is seen through blended surfaces: the ids of a frame without them. Blended triangles
        // are kept whole (one behind another blended one shows through it, which no id image
        // records); the visible set counts those the full frame's ids show.
        DrawList opaque;
        for (const DrawCommand& command : full.fullList())
            if (!blendedInstance(scene, command.instance)) opaque.push_back(command);
        full.renderFrame(target, width, height, frame, world, background, opaque);
        Result<TriangleSet> behind = visibleSet(scene, full.backend().readBack(target));
        if (!behind) return Error{behind.error().message};
        unite(oracle.rvs, *behind);
        drawn = oracle.rvs;
        for (std::size_t i = 0; i < drawn.perInstance.size(); ++i)
            if (blendedInstance(scene, int(i))) {
                TriangleSet whole;
                whole.perInstance.resize(drawn.perInstance.size());
                whole.perInstance[i].assign(drawn.perInstance[i].size(), 1);
                unite(drawn, whole);
            }
    }
    oracle.scene = std::make_unique<Scene>(oracleScene(scene, drawn));
    oracle.ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    Result<SceneRenderer> renderer = SceneRenderer::create(full.backend(), *oracle.scene);
    if (!renderer) return Error{"oracle: " + renderer.error().message};
    oracle.renderer.emplace(std::move(*renderer));
    return oracle;
}

}  // namespace frugal
