#include "scene/MeshBuild.h"

#include <cassert>
#include <cmath>
#include <unordered_map>

#include <meshoptimizer.h>

namespace frugal {

namespace {


void computeMissingNormals(Mesh& mesh) {
    const bool had = !mesh.normals.empty();
    if (!had) mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
    std::vector<glm::vec3> accumulated(had ? mesh.positions.size() : 0, glm::vec3(0.0f));
    std::vector<glm::vec3>& target = had ? accumulated : mesh.normals;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1], c = mesh.indices[3 * t + 2];
        // Unnormalised cross product: area weighting for free.
        const glm::vec3 n = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
        if (!isFinite(n)) continue;
        target[a] += n;
        target[b] += n;
        target[c] += n;
    }
    for (std::size_t v = 0; v < mesh.normals.size(); ++v) {
        glm::vec3 n = mesh.normals[v];
        float len = glm::length(n);
        if (had && (!std::isfinite(len) || len == 0.0f)) {
            // A broken normal from the file: fall back to the computed one.
            n = accumulated[v];
            len = glm::length(n);
        }
        mesh.normals[v] = (std::isfinite(len) && len > 0.0f) ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
    }
}

// meshoptimizer returns a new index buffer but not the permutation; it copies each triangle's three
// indices unchanged, so the permutation is recovered by looking the triangles up.
void optimizeOrder(Mesh& mesh) {
    const std::size_t count = mesh.triangleCount();
    std::vector<std::uint32_t> optimized(mesh.indices.size());
    meshopt_optimizeVertexCache(optimized.data(), mesh.indices.data(), mesh.indices.size(), mesh.positions.size());

    struct Key {
        std::uint32_t a, b, c;
        bool operator==(const Key&) const = default;
    };
    struct Hash {
        std::size_t operator()(const Key& k) const {
            return (std::size_t(k.a) * 0x9E3779B1u) ^ (std::size_t(k.b) * 0x85EBCA77u) ^ (std::size_t(k.c) * 0xC2B2AE3Du);
        }
    };
    // Duplicated triangles are matched in their original order, so each source id is used once.
    std::unordered_map<Key, std::vector<std::uint32_t>, Hash> where;
    where.reserve(count);
    for (std::size_t t = count; t-- > 0;)
        where[{mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]}].push_back(std::uint32_t(t));

    std::vector<std::uint32_t> source(count);
    for (std::size_t t = 0; t < count; ++t) {
        std::vector<std::uint32_t>& slots = where[{optimized[3 * t], optimized[3 * t + 1], optimized[3 * t + 2]}];
        assert(!slots.empty());
        source[t] = mesh.triangleSource[slots.back()];
        slots.pop_back();
    }
    mesh.indices = std::move(optimized);
    mesh.triangleSource = std::move(source);
}

}  // namespace

MeshBuildStats finalizeMesh(Mesh& mesh, bool optimizeOrderFlag) {
    assert(mesh.indices.size() % 3 == 0);
    MeshBuildStats stats;
    if (mesh.triangleSource.empty()) {
        mesh.triangleSource.resize(mesh.triangleCount());
        for (std::size_t t = 0; t < mesh.triangleSource.size(); ++t) mesh.triangleSource[t] = std::uint32_t(t);
    }
    assert(mesh.triangleSource.size() == mesh.triangleCount());

    // Drop triangles that touch a NaN/Inf position: GL behaviour for them is undefined.
    std::size_t kept = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t* tri = &mesh.indices[3 * t];
        assert(tri[0] < mesh.positions.size() && tri[1] < mesh.positions.size() && tri[2] < mesh.positions.size());
        if (!isFinite(mesh.positions[tri[0]]) || !isFinite(mesh.positions[tri[1]]) || !isFinite(mesh.positions[tri[2]])) {
            ++stats.droppedNonFinite;
            continue;
        }
        for (int k = 0; k < 3; ++k) mesh.indices[3 * kept + k] = tri[k];
        mesh.triangleSource[kept] = mesh.triangleSource[t];
        ++kept;
    }
    mesh.indices.resize(3 * kept);
    mesh.triangleSource.resize(kept);
    // Unused non-finite positions stay in the vertex buffer; make them harmless zeros.
    for (glm::vec3& p : mesh.positions)
        if (!isFinite(p)) p = glm::vec3(0.0f);
    // Non-finite colours or texture coordinates would reach the shader as NaN: neutral values instead.
    for (glm::vec4& c : mesh.colors)
        if (!isFinite(c)) c = glm::vec4(1.0f);
    for (glm::vec2& uv : mesh.uvs)
        if (!isFinite(uv)) uv = glm::vec2(0.0f);

    computeMissingNormals(mesh);
    if (optimizeOrderFlag && kept > 0) optimizeOrder(mesh);
    return stats;
}

void reorderTriangles(Mesh& mesh, const std::vector<std::uint32_t>& order) {
    const std::size_t count = mesh.triangleCount();
    assert(order.size() == count);
    if (mesh.triangleSource.empty()) {
        mesh.triangleSource.resize(count);
        for (std::size_t t = 0; t < count; ++t) mesh.triangleSource[t] = std::uint32_t(t);
    }
    std::vector<std::uint32_t> indices(mesh.indices.size());
    std::vector<std::uint32_t> source(count);
    for (std::size_t t = 0; t < count; ++t) {
        const std::uint32_t from = order[t];
        assert(from < count);
        for (int k = 0; k < 3; ++k) indices[3 * t + k] = mesh.indices[3 * std::size_t(from) + k];
        source[t] = mesh.triangleSource[from];
    }
    mesh.indices = std::move(indices);
    mesh.triangleSource = std::move(source);
}

}  // namespace frugal
