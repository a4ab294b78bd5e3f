#include "app/CullSupport.h"

#include <ostream>

namespace frugal {

bool parseCullOption(const std::string& flag, ArgCursor& cursor, CullOptions& options, bool withMethod) {
    if (withMethod && flag == "--cull") {
        const std::optional<std::string> value = cursor.value(flag);
        if (!value) return true;
        const std::optional<Cull> method = fromString(*value, kCulls);
        if (!method)
            cursor.fail("--cull " + *value + ": unknown method (methods: " + namesOf(kCulls) + ")");
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

std::string cullPreparedLine(const Scene& scene, const Renderer::CullPreparation& prep) {
    std::size_t triangles = 0;
    for (const Mesh& mesh : scene.meshes) triangles += mesh.triangleCount();
    std::string line = "cull: " + std::to_string(scene.meshes.size()) +
                       (scene.meshes.size() == 1 ? " mesh, " : " meshes, ") + std::to_string(triangles) +
                       " triangles prepared in " + fmt(prep.totalMs) + " ms (sphere " + fmt(prep.sphereMs) + ", map " +
                       fmt(prep.mapMs) + ", clusters " + fmt(prep.clusterMs);
    if (prep.hull) line += ", hull " + fmt(prep.hullMs);
    return line + ")";
}

SceneCuller prepareCulling(Scene& scene, const MapParams& bins, std::ostream& err, bool quiet) {
    SceneCuller culler = SceneCuller::prepare(scene, bins);
    if (!quiet) {
        const PrepStats stats = culler.totals();
        err << cullPreparedLine(
                   scene, {stats.sphereMs, stats.mapMs, stats.clusterMs, stats.hullMs, stats.totalMs(), bins.hull})
            << "\n";
    }
    return culler;
}

std::optional<SceneCuller> prepareCullOption(Scene& scene, const CullOptions& options, std::ostream& err, bool quiet) {
    const Cull method = options.method.value_or(Cull::None);
    if (method == Cull::None) return std::nullopt;
    MapParams bins = options.bins;
    bins.hull = method == Cull::Paper;
    return prepareCulling(scene, bins, err, quiet);
}

}  // namespace frugal
