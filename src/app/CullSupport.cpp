#include "app/CullSupport.h"

#include <chrono>
#include <ostream>

namespace frugal {

bool parseCullOption(const std::string& flag, ArgCursor& cursor, CullOptions& options, bool withMethod) {
    if (withMethod && flag == "--cull") {
        const std::optional<std::string> value = cursor.value(flag);
        if (!value) return true;
        const std::optional<CullMethod> method = parseCullMethod(*value);
        if (!method) cursor.fail("--cull " + *value + ": unknown method (methods: " + cullMethodNames() + ")");
        else options.method = *method;
        return true;
    }
    if (flag == "--cull-bins") {
        const std::optional<std::string> value = cursor.value(flag);
        if (!value) return true;
        int t = 0, p = 0;
        if (!parseIntPair(*value, t, p) || t < 1 || t > 1024 || p < 1 || p > 1024)
            cursor.fail("--cull-bins " + *value + ": expected THETAxPHI, each 1 to 1024 (default 16x32)");
        else
            options.bins = MapParams{t, p};
        return true;
    }
    return false;
}

SceneCuller prepareCulling(Scene& scene, const MapParams& bins, std::ostream& err, bool quiet) {
    SceneCuller culler = SceneCuller::prepare(scene, bins);
    if (!quiet) {
        const PrepStats stats = culler.totals();
        std::size_t triangles = 0;
        for (const Mesh& mesh : scene.meshes) triangles += mesh.triangleCount();
        err << "cull: " << scene.meshes.size() << (scene.meshes.size() == 1 ? " mesh, " : " meshes, ") << triangles
            << " triangles prepared in " << fmt(stats.totalMs()) << " ms (sphere " << fmt(stats.sphereMs) << ", map "
            << fmt(stats.mapMs) << ", clusters " << fmt(stats.clusterMs);
        if (bins.hull) err << ", hull " << fmt(stats.hullMs);
        err << ")\n";
    }
    return culler;
}

std::optional<SceneCuller> prepareCullOption(Scene& scene, const CullOptions& options, std::ostream& err, bool quiet) {
    const CullMethod method = options.method.value_or(CullMethod::None);
    if (method == CullMethod::None) return std::nullopt;
    MapParams bins = options.bins;
    bins.hull = method == CullMethod::Paper;
    return prepareCulling(scene, bins, err, quiet);
}

Result<Oracle> makeOracle(SceneRenderer& full, TargetHandle target, int width, int height, FrameParams frame,
                          const std::vector<glm::mat4>& world, const glm::vec4& background) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    frame.writeIds = true;
    full.renderFrame(target, width, height, frame, world, background);
    Result<TriangleSet> rvs = visibleSet(full.scene(), full.backend().readBack(target));
    if (!rvs) return Error{rvs.error()};
    Oracle oracle;
    oracle.rvs = std::move(*rvs);
    oracle.scene = std::make_unique<Scene>(oracleScene(full.scene(), oracle.rvs));
    oracle.ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    Result<SceneRenderer> renderer = SceneRenderer::create(full.backend(), *oracle.scene);
    if (!renderer) return Error{"oracle: " + renderer.error()};
    oracle.renderer.emplace(std::move(*renderer));
    return oracle;
}

}  // namespace frugal
