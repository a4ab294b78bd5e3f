#include "scene/MeshBuild.h"

#include <algorithm>
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

// A unit vector perpendicular to unit n (Duff et al. 2017, "Building an orthonormal basis, revisited").
glm::vec3 perpendicular(const glm::vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    return {1.0f + sign * n.x * n.x * a, sign * n.x * n.y * a, -sign * n.x};
}

// A file's tangents made drawable: a zero or non-finite direction becomes a perpendicular of the
// normal, and w its sign (+1 when it has none).
void repairTangents(Mesh& mesh) {
    for (std::size_t v = 0; v < mesh.tangents.size(); ++v) {
        glm::vec4& t = mesh.tangents[v];
        const float w = t.w < 0.0f ? -1.0f : 1.0f;
        const float length = glm::length(glm::vec3(t));
        t = std::isfinite(length) && length > 0.0f ? glm::vec4(glm::vec3(t) / length, w)
                                                   : glm::vec4(perpendicular(mesh.normals[v]), w);
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
    const std::size_t corners = verticesPerPrimitive(mesh.topology);
    assert(mesh.indices.size() % corners == 0);
    MeshBuildStats stats;
    if (mesh.triangleSource.empty()) {
        mesh.triangleSource.resize(mesh.primitiveCount());
        for (std::size_t t = 0; t < mesh.triangleSource.size(); ++t) mesh.triangleSource[t] = std::uint32_t(t);
    }
    assert(mesh.triangleSource.size() == mesh.primitiveCount());

    // Drop primitives that touch a NaN/Inf position: GL behaviour for them is undefined.
    std::size_t kept = 0;
    for (std::size_t t = 0; t < mesh.primitiveCount(); ++t) {
        const std::uint32_t* primitive = &mesh.indices[corners * t];
        bool finite = true;
        for (std::size_t k = 0; k < corners; ++k) {
            assert(primitive[k] < mesh.positions.size());
            finite = finite && isFinite(mesh.positions[primitive[k]]);
        }
        if (!finite) {
            ++stats.droppedNonFinite;
            continue;
        }
        for (std::size_t k = 0; k < corners; ++k) mesh.indices[corners * kept + k] = primitive[k];
        mesh.triangleSource[kept] = mesh.triangleSource[t];
        ++kept;
    }
    mesh.indices.resize(corners * kept);
    mesh.triangleSource.resize(kept);
    // Unused non-finite positions stay in the vertex buffer; make them harmless zeros.
    for (glm::vec3& p : mesh.positions)
        if (!isFinite(p)) p = glm::vec3(0.0f);
    // Non-finite colours or texture coordinates would reach the shader as NaN: neutral values instead.
    for (glm::vec4& c : mesh.colors)
        if (!isFinite(c)) c = glm::vec4(1.0f);
    for (glm::vec2& uv : mesh.uvs)
        if (!isFinite(uv)) uv = glm::vec2(0.0f);
    for (glm::vec4& t : mesh.tangents)
        if (!isFinite(t)) t = glm::vec4(0.0f);  // repaired with the normals below

    if (mesh.triangles()) {
        computeMissingNormals(mesh);
    } else {
        // Segments and points have no face to take a normal from: a broken normal becomes +z, and
        // without normals there is no tangent basis to read.
        for (glm::vec3& n : mesh.normals) {
            const float length = glm::length(n);
            n = std::isfinite(length) && length > 0.0f ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
        }
        if (mesh.normals.empty()) mesh.tangents.clear();
    }
    repairTangents(mesh);
    // Segments and points keep the file's order: it is their draw order, and no vertex cache gains.
    if (optimizeOrderFlag && kept > 0 && mesh.triangles()) optimizeOrder(mesh);
    return stats;
}

void generateTangents(Mesh& mesh) {
    const std::size_t n = mesh.positions.size();
    mesh.tangents.assign(n, glm::vec4(0.0f));
    if (mesh.uvs.size() != n || mesh.normals.size() != n) {
        for (std::size_t v = 0; v < n; ++v) {
            const glm::vec3 normal = mesh.normals.size() == n ? mesh.normals[v] : glm::vec3(0.0f, 0.0f, 1.0f);
            mesh.tangents[v] = glm::vec4(perpendicular(normal), 1.0f);
        }
        return;
    }
    // Per corner: the triangle's directions of increasing u and of decreasing v, each projected on
    // the vertex's tangent plane and normalised, weighted by the corner's angle (as MikkTSpace).
    std::vector<glm::vec3> up(n, glm::vec3(0.0f));
    std::vector<glm::vec3> along(n, glm::vec3(0.0f));
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t* corner = &mesh.indices[3 * t];
        const glm::vec3 p[3] = {mesh.positions[corner[0]], mesh.positions[corner[1]], mesh.positions[corner[2]]};
        const glm::vec2 uv[3] = {mesh.uvs[corner[0]], mesh.uvs[corner[1]], mesh.uvs[corner[2]]};
        const glm::vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
        const glm::vec2 d1 = uv[1] - uv[0], d2 = uv[2] - uv[0];
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (!std::isfinite(det) || det == 0.0f) continue;  // no u or v direction on this triangle
        const glm::vec3 dPdu = (e1 * d2.y - e2 * d1.y) / det;
        const glm::vec3 dPdv = (e2 * d1.x - e1 * d2.x) / det;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
            const float la = glm::length(a), lb = glm::length(b);
            if (!(la > 0.0f && lb > 0.0f)) continue;
            const float angle = std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0f, 1.0f));
            const glm::vec3 normal = mesh.normals[corner[k]];
            const auto onPlane = [&normal](const glm::vec3& d) {
                const glm::vec3 q = d - normal * glm::dot(normal, d);
                const float length = glm::length(q);
                return std::isfinite(length) && length > 0.0f ? q / length : glm::vec3(0.0f);
            };
            along[corner[k]] += onPlane(dPdu) * angle;
            up[corner[k]] -= onPlane(dPdv) * angle;
        }
    }
    for (std::size_t v = 0; v < n; ++v) {
        const glm::vec3 normal = mesh.normals[v];
        glm::vec3 t = along[v] - normal * glm::dot(normal, along[v]);
        const float length = glm::length(t);
        t = std::isfinite(length) && length > 1e-20f ? t / length : perpendicular(normal);
        mesh.tangents[v] = glm::vec4(t, glm::dot(glm::cross(normal, t), up[v]) < 0.0f ? -1.0f : 1.0f);
    }
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
