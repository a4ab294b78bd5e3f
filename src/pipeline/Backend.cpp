#include "pipeline/Backend.h"

namespace frugal {

bool isUploadable(const Mesh& mesh) {
    const std::size_t vertices = mesh.positions.size();
    if (std::size_t(mesh.topology) >= std::size(kTopologyNames)) return false;
    const std::size_t corners = verticesPerPrimitive(mesh.topology);
    const std::size_t triangles = mesh.indices.size() / corners;
    const auto fits = [vertices](std::size_t n) { return n == 0 || n == vertices; };
    if (mesh.indices.size() % corners != 0 || !fits(mesh.normals.size()) || !fits(mesh.colors.size()) ||
        !fits(mesh.uvs.size()) || !fits(mesh.tangents.size()) || vertices > 0xFFFFFFFFu ||
        triangles > 0x7FFFFFFFu / 3 || (!mesh.triangleSource.empty() && mesh.triangleSource.size() != triangles))
        return false;
    for (std::uint32_t index : mesh.indices)
        if (index >= vertices) return false;
    return true;
}

void Backend::drawInstances(const DrawParams& params, std::span<const InstanceParams> instances, IndexRange range) {
    DrawParams one = params;
    for (const InstanceParams& instance : instances) {
        one.model = instance.model;
        one.firstId = instance.firstId;
        draw(one, {&range, 1});
    }
}

}  // namespace frugal
