#include "cull/SphereMap.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <meshoptimizer.h>

#include "scene/MeshBuild.h"

namespace frugal {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The vertices of each cluster of `clusters` (triangles of the reordered index buffer `indices`)
// side by side.
void buildClusterVertices(const Mesh& mesh, const std::vector<std::uint32_t>& indices,
                          const std::vector<Cluster>& clusters, ClusterVertices& cv) {
    std::vector<std::uint32_t> local(mesh.positions.size(), UINT32_MAX);  // vertex → its index in the cluster
    const std::size_t triangles = indices.size() / 3;
    for (auto* c : {&cv.c0, &cv.c1, &cv.c2}) c->assign(triangles + 8, 0);
    cv.firstVertex.clear();
    for (const Cluster& c : clusters) {
        const auto first = std::uint32_t(cv.x.size());
        cv.firstVertex.push_back(first);
        for (std::size_t t = c.first; t < std::size_t(c.first) + c.count; ++t)
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t v = indices[3 * t + std::size_t(k)];
                if (local[v] == UINT32_MAX) {
                    local[v] = std::uint32_t(cv.x.size()) - first;
                    cv.x.push_back(mesh.positions[v].x);
                    cv.y.push_back(mesh.positions[v].y);
                    cv.z.push_back(mesh.positions[v].z);
                }
                (k == 0 ? cv.c0 : k == 1 ? cv.c1 : cv.c2)[t] = std::uint16_t(local[v]);  // below kClusterVertices
            }
        for (std::size_t i = 3 * std::size_t(c.first); i < 3 * (std::size_t(c.first) + c.count); ++i)
            local[indices[i]] = UINT32_MAX;
        cv.maxVertices = std::max(cv.maxVertices, std::uint32_t(cv.x.size()) - first);
        // meshoptimizer's limit, which culling's per-cluster arrays rely on.
        if (cv.maxVertices > kClusterVertices)
            throw std::logic_error("a cluster of " + std::to_string(cv.maxVertices) + " vertices, more than " +
                                   std::to_string(kClusterVertices));
    }
    cv.firstVertex.push_back(std::uint32_t(cv.x.size()));
    for (auto* a : {&cv.x, &cv.y, &cv.z}) a->resize(a->size() + 8, 0.0f);
}

// Splits one bin's triangles (consecutive in `indices`, vertex-cache order) into meshoptimizer
// meshlets by scanning (meshopt_buildMeshletsScan keeps the order: each meshlet is a run of the
// input), and appends a Cluster with meshoptimizer's bounds for each run.
void clusterBin(const Mesh& mesh, const std::vector<glm::vec4>& planes, const std::vector<glm::vec2>& slack,
                const std::uint32_t* indices,
                std::uint32_t first, std::uint32_t count, std::vector<std::uint32_t>& localIndex, std::vector<std::uint32_t>& scratch,
                std::vector<Cluster>& clusters) {
    // Bin-local vertex numbering keeps meshoptimizer's per-vertex tables as small as the bin.
    scratch.clear();
    std::vector<std::uint32_t> local(std::size_t(count) * 3);
    for (std::size_t i = 0; i < local.size(); ++i) {
        const std::uint32_t v = indices[i];
        if (localIndex[v] == UINT32_MAX) {
            localIndex[v] = std::uint32_t(scratch.size());
            scratch.push_back(v);
        }
        local[i] = localIndex[v];
    }
    for (std::uint32_t v : scratch) localIndex[v] = UINT32_MAX;

    const std::size_t maxMeshlets = meshopt_buildMeshletsBound(local.size(), kClusterVertices, kClusterTriangles);
    std::vector<meshopt_Meshlet> meshlets(maxMeshlets);
    std::vector<unsigned int> meshletVertices(maxMeshlets * kClusterVertices);
    std::vector<unsigned char> meshletTriangles(maxMeshlets * kClusterTriangles * 3);
    const std::size_t made = meshopt_buildMeshletsScan(meshlets.data(), meshletVertices.data(), meshletTriangles.data(),
                                                       local.data(), local.size(), scratch.size(), kClusterVertices,
                                                       kClusterTriangles);
    std::uint32_t at = first;
    for (std::size_t m = 0; m < made; ++m) {
        Cluster cluster;
        cluster.first = at;
        cluster.count = meshlets[m].triangle_count;
        at += cluster.count;
        const std::uint32_t* tri = indices + 3 * std::size_t(cluster.first - first);
        bool allFinite = true;
        cluster.boxMin = glm::vec3(INFINITY);
        cluster.boxMax = glm::vec3(-INFINITY);
        for (std::size_t i = 0; i < std::size_t(cluster.count) * 3; ++i) {
            const glm::vec3& p = mesh.positions[tri[i]];
            allFinite = allFinite && isFinite(p);
            cluster.boxMin = glm::min(cluster.boxMin, p);
            cluster.boxMax = glm::max(cluster.boxMax, p);
        }
        for (std::uint32_t t = cluster.first; t < cluster.first + cluster.count; ++t) {
            cluster.hasDegenerate = cluster.hasDegenerate || planes[t] == glm::vec4(0.0f);
            cluster.slack = glm::max(cluster.slack, slack[t]);
        }
        if (allFinite) {
            const meshopt_Bounds bounds = meshopt_computeClusterBounds(
                tri, std::size_t(cluster.count) * 3, &mesh.positions[0].x, mesh.positions.size(), sizeof(glm::vec3));
            cluster.center = {bounds.center[0], bounds.center[1], bounds.center[2]};
            // meshoptimizer's sphere is approximate (Ritter) and rounded: grow it until it holds every
            // vertex by a plain float test, since cone tests rely on it.
            float radius = bounds.radius;
            for (std::size_t i = 0; i < std::size_t(cluster.count) * 3; ++i)
                radius = std::max(radius, glm::length(mesh.positions[tri[i]] - cluster.center));
            cluster.radius = radius * (1.0f + 1e-5f);
            cluster.coneAxis = {bounds.cone_axis[0], bounds.cone_axis[1], bounds.cone_axis[2]};
            cluster.coneCutoff = bounds.cone_cutoff;
        } else {
            // A vertex that is not a number: no bound holds, so the cluster is never culled whole.
            cluster.boxMin = glm::vec3(-INFINITY);
            cluster.boxMax = glm::vec3(INFINITY);
            cluster.center = glm::vec3(0.0f);
            cluster.radius = INFINITY;
            cluster.coneCutoff = 1.0f;
        }
        clusters.push_back(cluster);
    }
}

}  // namespace

Spherical toSpherical(const glm::dvec3& d) {
    Spherical s;
    const double r = glm::length(d);
    if (!(r > 0.0) || !std::isfinite(r)) return s;  // the centre, or not a number: bin 0
    s.r = float(r);
    s.theta = float(std::acos(std::clamp(d.z / r, -1.0, 1.0)));
    if (d.x != 0.0 || d.y != 0.0) {
        double phi = std::atan2(d.y, d.x);
        if (phi < 0.0) phi += 2.0 * std::numbers::pi;
        s.phi = float(phi);
        if (s.phi >= float(2.0 * std::numbers::pi)) s.phi = 0.0f;  // rounding up to 2π wraps to 0
    }
    return s;
}

int binOf(const MapParams& params, float theta, float phi) {
    const double pi = std::numbers::pi;
    const int i = std::clamp(int(double(theta) / pi * params.thetaBins), 0, params.thetaBins - 1);
    const int j = std::clamp(int(double(phi) / (2.0 * pi) * params.phiBins), 0, params.phiBins - 1);
    return i * params.phiBins + j;
}

MeshMap buildMeshMap(const Mesh& mesh, const MapParams& params, std::vector<std::uint32_t>& order) {
    MeshMap map;
    map.params = params;
    const std::size_t triangles = mesh.triangleCount();
    const std::uint32_t* indices = mesh.indices.data();

    // Bounding sphere and hull of the vertices the triangles use.
    auto start = Clock::now();
    std::vector<std::uint8_t> used(mesh.positions.size(), 0);
    for (std::uint32_t v : mesh.indices) used[v] = 1;
    std::vector<glm::vec3> points;
    points.reserve(mesh.positions.size());
    for (std::size_t v = 0; v < used.size(); ++v)
        if (used[v]) points.push_back(mesh.positions[v]);
    map.sphere = minimalSphere(points);
    map.stats.sphereMs = msSince(start);

    if (params.hull) {
        start = Clock::now();
        map.hull = convexHull(points);
        map.stats.hullMs = msSince(start);
    } else {
        map.hull.note = "not built (no method that reads it was asked for)";
    }

    // Barycenters, their bins, and the order: bin by bin, the mesh's order (vertex cache) inside.
    start = Clock::now();
    const int binCount = params.thetaBins * params.phiBins;
    std::vector<Spherical> spherical(triangles);
    std::vector<int> binOfTriangle(triangles);
    std::vector<std::uint32_t> binStart(std::size_t(binCount) + 1, 0);
    for (std::size_t t = 0; t < triangles; ++t) {
        const glm::dvec3 a(mesh.positions[indices[3 * t]]), b(mesh.positions[indices[3 * t + 1]]),
            c(mesh.positions[indices[3 * t + 2]]);
        spherical[t] = toSpherical((a + b + c) / 3.0 - map.sphere.center);
        binOfTriangle[t] = binOf(params, spherical[t].theta, spherical[t].phi);
        ++binStart[std::size_t(binOfTriangle[t]) + 1];
    }
    for (int b = 0; b < binCount; ++b) binStart[std::size_t(b) + 1] += binStart[std::size_t(b)];
    order.assign(triangles, 0);
    {
        std::vector<std::uint32_t> fill(binStart.begin(), binStart.end() - 1);
        for (std::size_t t = 0; t < triangles; ++t) order[fill[std::size_t(binOfTriangle[t])]++] = std::uint32_t(t);
    }
    std::vector<std::uint32_t> reordered(triangles * 3);
    for (std::size_t t = 0; t < triangles; ++t)
        for (int k = 0; k < 3; ++k) reordered[3 * t + k] = indices[3 * std::size_t(order[t]) + k];

    map.bins.resize(std::size_t(binCount));
    map.entries.resize(triangles);
    for (int b = 0; b < binCount; ++b) {
        Bin& bin = map.bins[std::size_t(b)];
        bin.first = binStart[std::size_t(b)];
        bin.count = binStart[std::size_t(b) + 1] - bin.first;
        bin.rMin = INFINITY;
        bin.rMax = 0.0f;
        for (std::uint32_t t = bin.first; t < bin.first + bin.count; ++t) {
            const Spherical& s = spherical[order[t]];
            map.entries[t] = MapEntry{s.r, s.theta, s.phi, t};
            bin.rMin = std::min(bin.rMin, s.r);
            bin.rMax = std::max(bin.rMax, s.r);
        }
        if (bin.count == 0) bin.rMin = 0.0f;
        std::sort(map.entries.begin() + bin.first, map.entries.begin() + bin.first + bin.count,
                  [](const MapEntry& x, const MapEntry& y) { return x.r > y.r || (x.r == y.r && x.triangle < y.triangle); });
    }
    map.planes.resize(triangles);
    map.facingSlack.assign(triangles, glm::vec2(INFINITY));
    for (std::size_t t = 0; t < triangles; ++t) {
        const glm::vec3 a = mesh.positions[reordered[3 * t]], b = mesh.positions[reordered[3 * t + 1]],
                        c = mesh.positions[reordered[3 * t + 2]];
        const glm::dvec3 n = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
        const double length = glm::length(n);
        // Zero area, or not a number: plane 0, which every facing test reads as "undecided" (kept).
        if (!(length > 0.0) || !std::isfinite(length)) continue;
        const glm::dvec3 unit = n / length;
        map.planes[t] = glm::vec4(glm::vec3(unit), float(glm::dot(unit, glm::dvec3(a))));
        // The two shorter edges: twice the area is their cross product (from the vertex between them).
        const double ab = glm::length(glm::dvec3(b) - glm::dvec3(a)), bc = glm::length(glm::dvec3(c) - glm::dvec3(b)),
                     ca = glm::length(glm::dvec3(a) - glm::dvec3(c));
        const double shorter = ab + bc + ca - std::max({ab, bc, ca});
        // Rounded up to float (a margin may only grow): an area too small for a float stays +inf.
        const auto up = [](double x) {
            const float f = float(x);
            return double(f) >= x ? f : std::nextafter(f, INFINITY);
        };
        map.facingSlack[t] = glm::vec2(up(shorter / length), up(1.0 / length));
    }
    map.stats.mapMs = msSince(start);

    // Clusters inside each bin.
    start = Clock::now();
    std::vector<std::uint32_t> localIndex(mesh.positions.size(), UINT32_MAX), scratch;
    for (Bin& bin : map.bins) {
        bin.firstCluster = std::uint32_t(map.clusters.size());
        if (bin.count > 0)
            clusterBin(mesh, map.planes, map.facingSlack, reordered.data() + 3 * std::size_t(bin.first), bin.first, bin.count,
                       localIndex, scratch, map.clusters);
        bin.clusterCount = std::uint32_t(map.clusters.size()) - bin.firstCluster;
    }
    buildClusterVertices(mesh, reordered, map.clusters, map.vertices);
    map.stats.clusterMs = msSince(start);

    map.stats.mapBytes = map.entries.size() * sizeof(MapEntry);
    const ClusterVertices& cv = map.vertices;
    map.stats.accessBytes = map.bins.size() * sizeof(Bin) + map.clusters.size() * sizeof(Cluster) +
                            map.planes.size() * sizeof(glm::vec4) + map.facingSlack.size() * sizeof(glm::vec2) +
                            (cv.x.size() + cv.y.size() + cv.z.size()) * sizeof(float) +
                            cv.firstVertex.size() * sizeof(std::uint32_t) +
                            (cv.c0.size() + cv.c1.size() + cv.c2.size()) * sizeof(std::uint16_t);
    map.stats.hullBytes = map.hull.vertices.size() * sizeof(glm::vec3);
    return map;
}

}  // namespace frugal
