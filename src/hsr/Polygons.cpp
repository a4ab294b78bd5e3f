#include "hsr/Polygons.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include <glm/glm.hpp>

namespace frugal::hsr {
namespace {

using Vec = glm::dvec3;

struct UnionFind {
    std::vector<std::uint32_t> parent;
    explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    std::uint32_t find(std::uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    void unite(std::uint32_t a, std::uint32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the root is the group's first triangle
    }
};

// Positions that are equal (bit for bit, −0 as +0) share one number: meshes duplicate a corner per
// face for flat normals or uvs, and the surface is joined through its positions.
std::vector<std::uint32_t> weldPositions(const Mesh& mesh) {
    const auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f + 0.0f); };
    struct Hash {
        std::size_t operator()(const glm::uvec3& k) const {
            return std::size_t(k.x) * 0x9E3779B97F4A7C15ull ^ std::size_t(k.y) * 0xC2B2AE3D27D4EB4Full ^ k.z;
        }
    };
    std::unordered_map<glm::uvec3, std::uint32_t, Hash> first;
    first.reserve(mesh.positions.size());
    std::vector<std::uint32_t> welded(mesh.positions.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3& p = mesh.positions[i];
        welded[i] = first.try_emplace(glm::uvec3(bits(p.x), bits(p.y), bits(p.z)), std::uint32_t(i)).first->second;
    }
    return welded;
}

// Area of the convex hull of 2-D points (Andrew's monotone chain).
double hullArea(std::vector<glm::dvec2> p) {
    std::sort(p.begin(), p.end(), [](const glm::dvec2& a, const glm::dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    p.erase(std::unique(p.begin(), p.end()), p.end());
    if (p.size() < 3) return 0.0;
    const auto cross = [](const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    std::vector<glm::dvec2> hull(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
        hull[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
        hull[k++] = p[i];
    }
    double area = 0.0;
    for (std::size_t i = 0; i + 1 < k; ++i) area += hull[i].x * hull[i + 1].y - hull[i + 1].x * hull[i].y;
    return 0.5 * std::abs(area);
}

// MeshPolygons::convexSolid, given the welded corners, the triangles' normals and the directed edges.
bool isConvexSolid(const Mesh& mesh, const std::vector<std::uint32_t>& welded, const std::vector<glm::dvec3>& normal,
                   const std::unordered_map<std::uint64_t, std::uint32_t>& edges) {
    const std::size_t n = mesh.triangleCount();
    if (n < 4) return false;
    const auto corner = [&](std::size_t t, int k) { return welded[mesh.indices[3 * t + std::size_t(k)]]; };
    // Closed, and connected through its edges.
    UnionFind parts(n);
    for (std::size_t t = 0; t < n; ++t) {
        if (!(glm::dot(normal[t], normal[t]) > 0.0)) return false;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t from = corner(t, k), to = corner(t, (k + 1) % 3);
            const auto it = edges.find(std::uint64_t(to) << 32 | from);
            if (it == edges.end() || it->second == ~0u) return false;
            const auto self = edges.find(std::uint64_t(from) << 32 | to);
            if (self == edges.end() || self->second == ~0u) return false;
            parts.unite(std::uint32_t(t), it->second);
        }
    }
    for (std::uint32_t t = 0; t < n; ++t)
        if (parts.find(t) != 0) return false;
    // Every vertex on or behind every plane.
    std::vector<std::uint32_t> vertices(welded.begin(), welded.end());
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    if (double(vertices.size()) * double(n) > 1e8) return false;
    glm::dvec3 lo(mesh.positions[vertices[0]]), hi = lo;
    for (std::uint32_t v : vertices) {
        lo = glm::min(lo, glm::dvec3(mesh.positions[v]));
        hi = glm::max(hi, glm::dvec3(mesh.positions[v]));
    }
    const double tolerance = 1e-6 * glm::length(hi - lo);
    for (std::size_t t = 0; t < n; ++t) {
        const glm::dvec3 unit = glm::normalize(normal[t]), a(mesh.positions[corner(t, 0)]);
        for (std::uint32_t v : vertices)
            if (glm::dot(unit, glm::dvec3(mesh.positions[v]) - a) > tolerance) return false;
    }
    return true;
}

}  // namespace

MeshPolygons groupPolygons(const Mesh& mesh) {
    const std::size_t n = mesh.triangleCount();
    MeshPolygons out;
    out.polygonOf.resize(n);
    if (n == 0) return out;
    const std::vector<std::uint32_t> welded = weldPositions(mesh);
    const auto corner = [&](std::size_t t, int k) { return welded[mesh.indices[3 * t + std::size_t(k)]]; };
    const auto position = [&](std::uint32_t v) { return Vec(mesh.positions[v]); };
    std::vector<Vec> normal(n);  // unnormalised: twice the area
    for (std::size_t t = 0; t < n; ++t) {
        const Vec a = position(corner(t, 0));
        normal[t] = glm::cross(position(corner(t, 1)) - a, position(corner(t, 2)) - a);
    }

    // Directed edge (from, to) → the triangle holding it; an edge held twice in one direction (a
    // non-manifold or inconsistently wound surface) joins nothing.
    constexpr std::uint32_t kShared = ~0u;
    std::unordered_map<std::uint64_t, std::uint32_t> edges;
    edges.reserve(3 * n);
    const auto key = [](std::uint32_t from, std::uint32_t to) { return std::uint64_t(from) << 32 | to; };
    for (std::size_t t = 0; t < n; ++t)
        for (int k = 0; k < 3; ++k) {
            auto [it, fresh] = edges.try_emplace(key(corner(t, k), corner(t, (k + 1) % 3)), std::uint32_t(t));
            if (!fresh) it->second = kShared;
        }

    UnionFind groups(n);
    for (std::size_t t = 0; t < n; ++t) {
        if (!(glm::dot(normal[t], normal[t]) > 0.0)) continue;  // degenerate: a polygon of its own
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t from = corner(t, k), to = corner(t, (k + 1) % 3);
            const auto it = edges.find(key(to, from));
            if (it == edges.end() || it->second == kShared || it->second <= t) continue;
            const std::uint32_t other = it->second;
            if (!(glm::dot(normal[t], normal[other]) > 0.0)) continue;  // folded back, or degenerate
            std::uint32_t fourth = corner(other, 0);
            for (int j = 0; j < 3; ++j)
                if (corner(other, j) != from && corner(other, j) != to) fourth = corner(other, j);
            const Vec a = position(from), u = position(to) - a, v = position(corner(t, (k + 2) % 3)) - a;
            const Vec d = position(fourth) - a;
            const double orient = glm::dot(glm::cross(u, v), d);
            if (std::abs(orient) <= 1e-12 * glm::length(u) * glm::length(v) * glm::length(d)) groups.unite(std::uint32_t(t), other);
        }
    }

    // Members of each group, then the convexity check: a group that is not one convex, non-overlapping
    // tiling falls apart into its triangles.
    std::vector<std::vector<std::uint32_t>> members(n);
    for (std::uint32_t t = 0; t < n; ++t) members[groups.find(t)].push_back(t);
    std::vector<std::uint8_t> single(n, 0);
    for (std::uint32_t root = 0; root < n; ++root) {
        const std::vector<std::uint32_t>& group = members[root];
        if (group.size() < 2) continue;
        const Vec axis = glm::normalize(normal[root]);
        const Vec e0 = glm::normalize(glm::abs(axis.x) < 0.9 ? glm::cross(axis, Vec(1, 0, 0)) : glm::cross(axis, Vec(0, 1, 0)));
        const Vec e1 = glm::cross(axis, e0);
        std::vector<glm::dvec2> points;
        double area = 0.0;
        for (std::uint32_t t : group) {
            area += 0.5 * glm::length(normal[t]);
            for (int k = 0; k < 3; ++k) {
                const Vec p = position(corner(t, k));
                points.emplace_back(glm::dot(p, e0), glm::dot(p, e1));
            }
        }
        const double hull = hullArea(std::move(points));
        if (!(std::abs(hull - area) <= 1e-9 * hull))
            for (std::uint32_t t : group) single[t] = 1;
    }

    out.convexSolid = isConvexSolid(mesh, welded, normal, edges);

    std::vector<std::uint32_t> number(n, ~0u);
    for (std::uint32_t t = 0; t < n; ++t) {
        const std::uint32_t root = single[t] ? t : groups.find(t);
        if (number[root] == ~0u) number[root] = out.count++;
        out.polygonOf[t] = number[root];
    }
    return out;
}

}  // namespace frugal::hsr
