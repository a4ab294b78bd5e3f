// The per-mesh culling map (cull/SphereMap.h) and the report views (cull/Views.h): spherical
// conventions, bins, the triangle order with its invariants (bins contiguous, clusters tiling bins,
// entries sorted, planes, ids carried along), degenerate and non-finite meshes, and the classes of
// the views measured against their own frustum.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "cull/SphereMap.h"
#include "lab/Views.h"
#include "pipeline/Camera.h"
#include "scene/MeshBuild.h"

namespace frugal {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// ---------------------------------------------------------------------------------------------
// Meshes.

Mesh fromTriangles(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices) {
    Mesh mesh;
    mesh.name = "test";
    mesh.positions = positions;
    mesh.normals.assign(positions.size(), glm::vec3(0.0f, 0.0f, 1.0f));
    mesh.indices = indices;
    return mesh;
}

// A triangulated UV sphere of radius `radius` about `center`, counter-clockwise outside.
Mesh uvSphere(int rings, int segments, float radius = 1.0f, const glm::vec3& center = glm::vec3(0.0f)) {
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> indices;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segments; ++j) {
            const double theta = kPi * i / rings, phi = 2.0 * kPi * j / segments;
            positions.push_back(center + radius * glm::vec3(float(std::sin(theta) * std::cos(phi)),
                                                            float(std::sin(theta) * std::sin(phi)),
                                                            float(std::cos(theta))));
        }
    const auto at = [segments](int i, int j) { return std::uint32_t(i * (segments + 1) + j); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            indices.insert(indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            indices.insert(indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return fromTriangles(positions, indices);
}

// `count` random triangles in the box [-1, 1]^3 (a soup, vertices shared at random).
Mesh randomSoup(int count, unsigned seed, int vertices = 0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const int v = vertices > 0 ? vertices : 3 * count;
    std::vector<glm::vec3> positions;
    for (int i = 0; i < v; ++i) positions.emplace_back(u(rng), u(rng), u(rng));
    std::uniform_int_distribution<std::uint32_t> pick(0, std::uint32_t(v - 1));
    std::vector<std::uint32_t> indices;
    for (int t = 0; t < count; ++t) indices.insert(indices.end(), {pick(rng), pick(rng), pick(rng)});
    return fromTriangles(positions, indices);
}

Mesh scaledMesh(Mesh mesh, float factor, const glm::vec3& offset = glm::vec3(0.0f)) {
    for (glm::vec3& p : mesh.positions) p = p * factor + offset;
    return mesh;
}

// ---------------------------------------------------------------------------------------------
// The invariants of a built map, checked against the mesh as given and the order.

std::uint32_t sourceOf(const Mesh& mesh, std::size_t t) {
    return mesh.triangleSource.empty() ? std::uint32_t(t) : mesh.triangleSource[t];
}

glm::dvec3 barycenter(const Mesh& mesh, std::size_t t) {
    const std::uint32_t* tri = &mesh.indices[3 * t];
    return (glm::dvec3(mesh.positions[tri[0]]) + glm::dvec3(mesh.positions[tri[1]]) +
            glm::dvec3(mesh.positions[tri[2]])) /
           3.0;
}

bool triangleFinite(const Mesh& mesh, std::size_t t) {
    for (int k = 0; k < 3; ++k)
        if (!finite3(mesh.positions[mesh.indices[3 * t + std::size_t(k)]])) return false;
    return true;
}

// meshoptimizer's own test (meshopt_computeClusterBounds): the float cross product has length 0.
bool zeroAreaInFloat(const Mesh& mesh, std::size_t t) {
    const glm::vec3 p0 = mesh.positions[mesh.indices[3 * t]], p1 = mesh.positions[mesh.indices[3 * t + 1]],
                    p2 = mesh.positions[mesh.indices[3 * t + 2]];
    const glm::vec3 a = p1 - p0, b = p2 - p0;
    const float x = a.y * b.z - a.z * b.y, y = a.z * b.x - a.x * b.z, z = a.x * b.y - a.y * b.x;
    return std::sqrt(x * x + y * y + z * z) == 0.0f;
}

// Builds the map of `given` with `params`, checks every invariant the header states, and returns the
// reordered mesh (through `out`) with the map.
MeshMap buildAndCheck(const Mesh& given, const MapParams& params, Mesh* out = nullptr, const std::string& label = "") {
    SCOPED_TRACE(label + " (" + std::to_string(params.thetaBins) + "x" + std::to_string(params.phiBins) + " bins, " +
                 std::to_string(given.triangleCount()) + " triangles)");
    std::vector<std::uint32_t> order;
    MeshMap map;
    EXPECT_NO_THROW(map = buildMeshMap(given, params, order));
    const std::size_t triangles = given.triangleCount();
    const int binCount = params.thetaBins * params.phiBins;

    // `order` is a permutation of 0..n-1.
    EXPECT_EQ(order.size(), triangles);
    {
        std::vector<std::uint32_t> sorted = order;
        std::sort(sorted.begin(), sorted.end());
        for (std::size_t t = 0; t < sorted.size(); ++t)
            if (sorted[t] != t) {
                ADD_FAILURE() << "order is not a permutation: sorted[" << t << "] = " << sorted[t];
                break;
            }
    }
    if (order.size() != triangles) return map;

    Mesh mesh = given;
    reorderTriangles(mesh, order);
    EXPECT_EQ(mesh.triangleSource.size(), triangles);
    // Ids stay stable: the multiset of (indices, source) is unchanged, and triangle t of the new order
    // is triangle order[t] of the old one.
    {
        using Key = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>;
        std::map<Key, int> before, after;
        for (std::size_t t = 0; t < triangles; ++t) {
            ++before[Key{given.indices[3 * t], given.indices[3 * t + 1], given.indices[3 * t + 2], sourceOf(given, t)}];
            ++after[Key{mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2], sourceOf(mesh, t)}];
            EXPECT_EQ(sourceOf(mesh, t), sourceOf(given, order[t])) << "triangle " << t;
        }
        EXPECT_EQ(before, after);
    }

    // The sphere encloses every finite vertex the triangles use.
    EXPECT_TRUE(std::isfinite(map.sphere.radius) && map.sphere.radius >= 0.0);
    EXPECT_TRUE(std::isfinite(map.sphere.center.x + map.sphere.center.y + map.sphere.center.z));
    for (std::uint32_t v : mesh.indices)
        if (finite3(mesh.positions[v])) {
            EXPECT_LE(glm::length(glm::dvec3(mesh.positions[v]) - map.sphere.center), map.sphere.radius)
                << "vertex " << v;
        }

    // Bins: thetaBins × phiBins, one contiguous range each, in index order, covering every triangle.
    EXPECT_EQ(map.bins.size(), std::size_t(binCount));
    EXPECT_EQ(map.params.thetaBins, params.thetaBins);
    EXPECT_EQ(map.params.phiBins, params.phiBins);
    std::uint32_t next = 0, nextCluster = 0;
    for (int b = 0; b < int(map.bins.size()); ++b) {
        const Bin& bin = map.bins[std::size_t(b)];
        EXPECT_EQ(bin.first, next) << "bin " << b;
        next = bin.first + bin.count;
        EXPECT_EQ(bin.firstCluster, nextCluster) << "bin " << b;
        nextCluster = bin.firstCluster + bin.clusterCount;
        if (bin.count == 0) {
            EXPECT_EQ(bin.clusterCount, 0u) << "bin " << b;
            EXPECT_EQ(bin.rMin, 0.0f);
            EXPECT_EQ(bin.rMax, 0.0f);
        } else {
            EXPECT_GE(bin.clusterCount, 1u) << "bin " << b;
        }
    }
    EXPECT_EQ(next, triangles);
    EXPECT_EQ(nextCluster, map.clusters.size());
    if (next != triangles || map.bins.size() != std::size_t(binCount)) return map;

    // Each triangle sits in the bin of its barycenter (exactly the rule toSpherical + binOf), and that
    // bin is the cell its direction points into (independently, with a margin for cell edges).
    for (int b = 0; b < binCount; ++b) {
        const Bin& bin = map.bins[std::size_t(b)];
        const int i = b / params.phiBins, j = b % params.phiBins;
        for (std::uint32_t t = bin.first; t < bin.first + bin.count; ++t) {
            const glm::dvec3 d = barycenter(mesh, t) - map.sphere.center;
            const Spherical s = toSpherical(d);
            EXPECT_EQ(binOf(params, s.theta, s.phi), b) << "triangle " << t;
            if (!triangleFinite(mesh, t) || !std::isfinite(glm::length(d))) {
                EXPECT_EQ(b, 0) << "a triangle that is not a number lands in bin 0, triangle " << t;
                continue;
            }
            const double r = glm::length(d);
            if (r <= 1e-9 * std::max(1.0, map.sphere.radius)) continue;  // direction undefined
            const double theta = std::acos(std::clamp(d.z / r, -1.0, 1.0));
            const double eps = 1e-4;
            EXPECT_GE(theta, kPi * i / params.thetaBins - eps) << "triangle " << t;
            EXPECT_LE(theta, kPi * (i + 1) / params.thetaBins + eps) << "triangle " << t;
            if (std::hypot(d.x, d.y) > 1e-6 * r) {
                double phi = std::atan2(d.y, d.x);
                if (phi < 0.0) phi += 2.0 * kPi;
                const double lo = 2.0 * kPi * j / params.phiBins - eps, hi = 2.0 * kPi * (j + 1) / params.phiBins + eps;
                // φ near 2π may wrap to 0 (column 0).
                const bool inCell = (phi >= lo && phi <= hi) || (j == 0 && phi >= 2.0 * kPi - eps);
                EXPECT_TRUE(inCell) << "triangle " << t << " phi " << phi << " in column " << j;
            }
        }
    }

    // Clusters tile each bin exactly: contiguous, no gaps, no overlaps, 1..kClusterTriangles each.
    for (int b = 0; b < binCount; ++b) {
        const Bin& bin = map.bins[std::size_t(b)];
        std::uint32_t at = bin.first;
        for (std::uint32_t c = bin.firstCluster; c < bin.firstCluster + bin.clusterCount && c < map.clusters.size(); ++c) {
            const Cluster& cluster = map.clusters[c];
            EXPECT_EQ(cluster.first, at) << "bin " << b << " cluster " << c;
            EXPECT_GE(cluster.count, 1u);
            EXPECT_LE(cluster.count, kClusterTriangles);
            at = cluster.first + cluster.count;
            bool allFinite = true, degenerate = false;
            for (std::uint32_t t = cluster.first; t < cluster.first + cluster.count && t < triangles; ++t) {
                allFinite = allFinite && triangleFinite(mesh, t);
                degenerate = degenerate || (t < map.planes.size() && map.planes[t] == glm::vec4(0.0f));
            }
            EXPECT_EQ(cluster.hasDegenerate, degenerate) << "cluster " << c << ": a triangle with plane 0";
            if (!allFinite) {
                EXPECT_EQ(cluster.boxMin, glm::vec3(-kInf)) << "cluster " << c;
                EXPECT_EQ(cluster.boxMax, glm::vec3(kInf)) << "cluster " << c;
                EXPECT_EQ(cluster.radius, kInf) << "cluster " << c;
                EXPECT_EQ(cluster.coneCutoff, 1.0f) << "cluster " << c;
                continue;
            }
            EXPECT_TRUE(finite3(cluster.boxMin) && finite3(cluster.boxMax) && finite3(cluster.center) &&
                        std::isfinite(cluster.radius) && finite3(cluster.coneAxis) && std::isfinite(cluster.coneCutoff))
                << "cluster " << c;
            const double scale = double(glm::length(cluster.center)) + double(cluster.radius);
            for (std::uint32_t t = cluster.first; t < cluster.first + cluster.count && t < triangles; ++t) {
                for (int k = 0; k < 3; ++k) {
                    const glm::vec3 p = mesh.positions[mesh.indices[3 * std::size_t(t) + std::size_t(k)]];
                    EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, cluster.boxMin)) &&
                                glm::all(glm::lessThanEqual(p, cluster.boxMax)))
                        << "cluster " << c << " box misses a vertex of triangle " << t;
                    EXPECT_LE(glm::length(glm::dvec3(p) - glm::dvec3(cluster.center)),
                              double(cluster.radius) * (1.0 + 1e-4) + 1e-6 * scale)
                        << "cluster " << c << " sphere misses a vertex of triangle " << t;
                }
                // The normal cone holds every face normal, but those meshoptimizer leaves out (zero
                // area in its float test).
                const glm::vec4 plane = t < map.planes.size() ? map.planes[t] : glm::vec4(0.0f);
                if (cluster.coneCutoff < 1.0f && glm::vec3(plane) != glm::vec3(0.0f) && !zeroAreaInFloat(mesh, t)) {
                    const double minDot = std::sqrt(std::max(0.0, 1.0 - double(cluster.coneCutoff) * cluster.coneCutoff));
                    EXPECT_GE(glm::dot(glm::dvec3(glm::vec3(plane)), glm::dvec3(cluster.coneAxis)), minDot - 2e-3)
                        << "cluster " << c << " cone misses the normal of triangle " << t ;
                }
            }
        }
        EXPECT_EQ(at, bin.first + bin.count) << "bin " << b;
    }

    // Entries: one per triangle, each bin's own triangles, R descending, the right coordinates.
    EXPECT_EQ(map.entries.size(), triangles);
    if (map.entries.size() == triangles) {
        for (int b = 0; b < binCount; ++b) {
            const Bin& bin = map.bins[std::size_t(b)];
            std::vector<std::uint32_t> seen;
            float rMin = kInf, rMax = 0.0f;
            for (std::uint32_t e = bin.first; e < bin.first + bin.count; ++e) {
                const MapEntry& entry = map.entries[e];
                seen.push_back(entry.triangle);
                if (e > bin.first) {
                    EXPECT_GE(map.entries[e - 1].r, entry.r) << "bin " << b << " entry " << e;
                }
                if (entry.triangle >= triangles) continue;
                const Spherical s = toSpherical(barycenter(mesh, entry.triangle) - map.sphere.center);
                EXPECT_EQ(entry.r, s.r) << "entry " << e;
                EXPECT_EQ(entry.theta, s.theta) << "entry " << e;
                EXPECT_EQ(entry.phi, s.phi) << "entry " << e;
                rMin = std::min(rMin, entry.r);
                rMax = std::max(rMax, entry.r);
            }
            std::sort(seen.begin(), seen.end());
            for (std::size_t k = 0; k < seen.size(); ++k)
                EXPECT_EQ(seen[k], bin.first + k) << "bin " << b << ": entries name the bin's own triangles";
            if (bin.count > 0) {
                EXPECT_EQ(bin.rMin, rMin) << "bin " << b;
                EXPECT_EQ(bin.rMax, rMax) << "bin " << b;
            }
        }
    }

    // Planes: a unit normal along (b − a) × (c − a) and w = n · a; zero for a degenerate triangle.
    EXPECT_EQ(map.planes.size(), triangles);
    for (std::size_t t = 0; t < map.planes.size() && t < triangles; ++t) {
        const glm::vec4 plane = map.planes[t];
        const glm::dvec3 n{glm::vec3(plane)};
        if (!triangleFinite(mesh, t)) {
            EXPECT_EQ(plane, glm::vec4(0.0f)) << "plane of non-finite triangle " << t;
            continue;
        }
        const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]),
            c(mesh.positions[mesh.indices[3 * t + 2]]);
        const glm::dvec3 cross = glm::cross(b - a, c - a);
        const double area2 = glm::length(cross);
        if (!(area2 > 0.0)) {
            EXPECT_EQ(plane, glm::vec4(0.0f)) << "plane of degenerate triangle " << t;
            continue;
        }
        EXPECT_NEAR(glm::length(n), 1.0, 1e-5) << "triangle " << t;
        EXPECT_GT(glm::dot(n, cross / area2), 1.0 - 1e-4) << "triangle " << t;
        EXPECT_NEAR(double(plane.w), glm::dot(n, a), 1e-5 * std::max(1.0, glm::length(a))) << "triangle " << t;
        // The facing slack: the two shorter edges over twice the area, and one over it, rounded up.
        const double ab = glm::length(b - a), bc = glm::length(c - b), ca = glm::length(a - c);
        const glm::vec2 slack = t < map.facingSlack.size() ? map.facingSlack[t] : glm::vec2(0.0f);
        EXPECT_GE(double(slack.x), (ab + bc + ca - std::max({ab, bc, ca})) / area2) << "triangle " << t;
        EXPECT_LE(double(slack.x), (ab + bc + ca - std::max({ab, bc, ca})) / area2 * (1.0 + 1e-6)) << "triangle " << t;
        EXPECT_GE(double(slack.y), 1.0 / area2) << "triangle " << t;
        EXPECT_LE(double(slack.y), 1.0 / area2 * (1.0 + 1e-6)) << "triangle " << t;
    }
    EXPECT_EQ(map.facingSlack.size(), map.planes.size());
    for (std::size_t t = 0; t < map.planes.size() && t < map.facingSlack.size(); ++t) {
        if (map.planes[t] == glm::vec4(0.0f)) {
            EXPECT_TRUE(std::isinf(map.facingSlack[t].x) && std::isinf(map.facingSlack[t].y))
                << "a triangle without a plane has no facing margin: " << t;
        }
    }
    for (const Cluster& cluster : map.clusters)
        for (std::uint32_t t = cluster.first; t < cluster.first + cluster.count && t < map.facingSlack.size(); ++t)
            EXPECT_TRUE(glm::all(glm::lessThanEqual(map.facingSlack[t], cluster.slack))) << "cluster's largest, " << t;

    // Each cluster's vertices side by side: every corner of its triangles, bit for bit (not-a-number
    // ones too), at most kClusterVertices of them, and the arrays padded with 8.
    const ClusterVertices& cv = map.vertices;
    const std::size_t triangleCount = mesh.indices.size() / 3;
    EXPECT_EQ(cv.firstVertex.size(), map.clusters.size() + 1);
    EXPECT_EQ(cv.c0.size(), triangleCount + 8);
    EXPECT_EQ(cv.c1.size(), triangleCount + 8);
    EXPECT_EQ(cv.c2.size(), triangleCount + 8);
    EXPECT_EQ(cv.y.size(), cv.x.size());
    EXPECT_EQ(cv.z.size(), cv.x.size());
    const bool sized = cv.firstVertex.size() == map.clusters.size() + 1 && cv.c0.size() == triangleCount + 8 &&
                       cv.c1.size() == cv.c0.size() && cv.c2.size() == cv.c0.size() && cv.y.size() == cv.x.size() &&
                       cv.z.size() == cv.x.size() && cv.x.size() == std::size_t(cv.firstVertex.back()) + 8;
    EXPECT_TRUE(sized) << "the cluster vertices' arrays";
    for (std::size_t c = 0; sized && c < map.clusters.size(); ++c) {
        const std::uint32_t first = cv.firstVertex[c], count = cv.firstVertex[c + 1] - first;
        EXPECT_LE(count, kClusterVertices) << "cluster " << c;
        EXPECT_LE(count, cv.maxVertices) << "cluster " << c;
        for (std::uint32_t t = map.clusters[c].first; t < map.clusters[c].first + map.clusters[c].count && t < triangleCount; ++t)
            for (int k = 0; k < 3; ++k) {
                const std::uint16_t local = (k == 0 ? cv.c0 : k == 1 ? cv.c1 : cv.c2)[t];
                EXPECT_LT(local, count) << "cluster " << c << ", triangle " << t;
                if (local >= count) continue;
                const glm::vec3 p = mesh.positions[mesh.indices[3 * std::size_t(t) + std::size_t(k)]];
                const float got[3] = {cv.x[first + local], cv.y[first + local], cv.z[first + local]};
                EXPECT_EQ(std::memcmp(got, &p.x, sizeof got), 0) << "cluster " << c << ", triangle " << t << ", corner " << k;
            }
    }

    // Stats.
    EXPECT_EQ(map.stats.mapBytes, map.entries.size() * sizeof(MapEntry));
    EXPECT_EQ(map.stats.accessBytes, map.bins.size() * sizeof(Bin) + map.clusters.size() * sizeof(Cluster) +
                                         map.planes.size() * sizeof(glm::vec4) +
                                         map.facingSlack.size() * sizeof(glm::vec2) +
                                         (cv.x.size() + cv.y.size() + cv.z.size()) * sizeof(float) +
                                         cv.firstVertex.size() * sizeof(std::uint32_t) +
                                         (cv.c0.size() + cv.c1.size() + cv.c2.size()) * sizeof(std::uint16_t));
    for (double ms : {map.stats.sphereMs, map.stats.mapMs, map.stats.clusterMs, map.stats.hullMs}) {
        EXPECT_TRUE(std::isfinite(ms));
        EXPECT_GE(ms, 0.0);
    }
    EXPECT_DOUBLE_EQ(map.stats.totalMs(),
                     map.stats.sphereMs + map.stats.mapMs + map.stats.clusterMs + map.stats.hullMs);

    if (out) *out = std::move(mesh);
    return map;
}

const MapParams kParamSets[] = {{16, 32}, {1, 1}, {3, 5}, {64, 128}};

// ---------------------------------------------------------------------------------------------
// toSpherical and binOf.

TEST(SphereMapTest, ToSphericalFollowsTheAxisConventions) {
    const float pi = float(kPi);
    struct Case {
        glm::dvec3 d;
        float r, theta, phi;
    };
    const Case cases[] = {
        {{0, 0, 1}, 1, 0, 0},                // +z: the north pole
        {{0, 0, -2}, 2, pi, 0},              // −z: the south pole
        {{3, 0, 0}, 3, pi / 2, 0},           // +x: φ = 0
        {{0, 1, 0}, 1, pi / 2, pi / 2},      // +y: φ = π/2
        {{-1, 0, 0}, 1, pi / 2, pi},         // −x: φ = π
        {{0, -1, 0}, 1, pi / 2, 1.5f * pi},  // −y: φ = 3π/2
        {{1, 1, std::sqrt(2.0)}, 2, pi / 4, pi / 4},
        {{1, -1, -std::sqrt(2.0)}, 2, 0.75f * pi, 1.75f * pi},
    };
    for (const Case& c : cases) {
        const Spherical s = toSpherical(c.d);
        SCOPED_TRACE(testing::Message() << "d = (" << c.d.x << ", " << c.d.y << ", " << c.d.z << ")");
        EXPECT_NEAR(s.r, c.r, 1e-6);
        EXPECT_NEAR(s.theta, c.theta, 1e-6);
        EXPECT_NEAR(s.phi, c.phi, 1e-6);
    }
}

TEST(SphereMapTest, ToSphericalStaysInItsRangesAndRoundTrips) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::uniform_real_distribution<double> e(-20.0, 20.0);
    for (int k = 0; k < 20000; ++k) {
        const glm::dvec3 d = glm::dvec3(u(rng), u(rng), u(rng)) * std::pow(10.0, e(rng));
        const Spherical s = toSpherical(d);
        ASSERT_GE(s.theta, 0.0f);
        ASSERT_LE(s.theta, float(kPi));
        ASSERT_GE(s.phi, 0.0f);
        ASSERT_LT(s.phi, float(2.0 * kPi));
        ASSERT_NEAR(double(s.r), glm::length(d), 1e-6 * glm::length(d));
        const glm::dvec3 back(std::sin(double(s.theta)) * std::cos(double(s.phi)),
                              std::sin(double(s.theta)) * std::sin(double(s.phi)), std::cos(double(s.theta)));
        ASSERT_NEAR(glm::length(back - d / glm::length(d)), 0.0, 1e-6) << k;
    }
    // Just below the positive x axis φ rounds up to 2π in float: it wraps to 0, never 2π.
    for (double y : {-1e-7, -1e-9, -1e-12, -1e-30}) {
        const Spherical s = toSpherical({1.0, y, 0.0});
        EXPECT_GE(s.phi, 0.0f) << y;
        EXPECT_LT(s.phi, float(2.0 * kPi)) << y;
        const int bin = binOf(MapParams{}, s.theta, s.phi);
        EXPECT_TRUE(bin % 32 == 0 || bin % 32 == 31) << y;
    }
}

TEST(SphereMapTest, ToSphericalPolesHaveAzimuthZero) {
    for (const glm::dvec3& d : {glm::dvec3(0, 0, 5), glm::dvec3(0, 0, -3), glm::dvec3(-0.0, -0.0, 1),
                                glm::dvec3(-0.0, 0.0, -1), glm::dvec3(0.0, -0.0, 1e-30)}) {
        const Spherical s = toSpherical(d);
        EXPECT_EQ(s.phi, 0.0f) << d.x << " " << d.y << " " << d.z;
        EXPECT_EQ(s.theta, d.z > 0 ? 0.0f : float(kPi));
        EXPECT_EQ(binOf(MapParams{}, s.theta, s.phi), d.z > 0 ? 0 : 15 * 32);
    }
}

TEST(SphereMapTest, ToSphericalOfTheCentreAndOfNonNumbersIsZero) {
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    for (const glm::dvec3& d : {glm::dvec3(0.0), glm::dvec3(-0.0, 0.0, -0.0), glm::dvec3(nan, 0, 0),
                                glm::dvec3(0, nan, 1), glm::dvec3(nan), glm::dvec3(inf, 0, 0), glm::dvec3(-inf, inf, 0),
                                glm::dvec3(1, 2, -inf)}) {
        const Spherical s = toSpherical(d);
        EXPECT_EQ(s.r, 0.0f) << d.x << " " << d.y << " " << d.z;
        EXPECT_EQ(s.theta, 0.0f) << d.x << " " << d.y << " " << d.z;
        EXPECT_EQ(s.phi, 0.0f) << d.x << " " << d.y << " " << d.z;
        EXPECT_EQ(binOf(MapParams{}, s.theta, s.phi), 0);
    }
}

TEST(SphereMapTest, BinOfPutsEdgesInTheStatedCells) {
    const float pi = float(kPi);
    const float twoPi = float(2.0 * kPi);
    for (const MapParams& params : kParamSets) {
        SCOPED_TRACE(std::to_string(params.thetaBins) + "x" + std::to_string(params.phiBins));
        const int T = params.thetaBins, P = params.phiBins;
        EXPECT_EQ(binOf(params, 0.0f, 0.0f), 0);
        // θ = π (as float, a little above π) belongs to the last row.
        EXPECT_EQ(binOf(params, pi, 0.0f), (T - 1) * P);
        EXPECT_EQ(binOf(params, float(std::nextafter(kPi, 0.0)), 0.0f), (T - 1) * P);
        // φ just below 2π is in the last column; 2π itself (never produced) clamps there too.
        EXPECT_EQ(binOf(params, 0.0f, std::nextafter(twoPi, 0.0f)), P - 1);
        EXPECT_EQ(binOf(params, pi, std::nextafter(twoPi, 0.0f)), T * P - 1);
        EXPECT_EQ(binOf(params, 0.0f, twoPi), P - 1);
        // Out-of-range values clamp to the border cells.
        EXPECT_EQ(binOf(params, -1.0f, -1.0f), 0);
        EXPECT_EQ(binOf(params, 10.0f, 10.0f), T * P - 1);
        // Cell middles and the inside of each lower edge.
        for (int i = 0; i < T; ++i)
            for (int j = 0; j < P; ++j) {
                const float theta = float(kPi * (i + 0.5) / T), phi = float(2.0 * kPi * (j + 0.5) / P);
                ASSERT_EQ(binOf(params, theta, phi), i * P + j) << i << " " << j;
                const float theta0 = float(kPi * (i + 1e-3) / T), phi0 = float(2.0 * kPi * (j + 1e-3) / P);
                ASSERT_EQ(binOf(params, theta0, phi0), i * P + j) << i << " " << j;
            }
    }
    MapParams params;
    EXPECT_EQ(params.thetaBins, 16);
    EXPECT_EQ(params.phiBins, 32);
    MeshMap map;
    map.params = {4, 6};
    EXPECT_EQ(map.binIndex(2, 3), 15);
}

// ---------------------------------------------------------------------------------------------
// buildMeshMap on ordinary meshes.

TEST(SphereMapTest, MapOfASphereMeshKeepsEveryInvariant) {
    const Mesh sphere = uvSphere(24, 48, 2.0f, glm::vec3(1.0f, -2.0f, 3.0f));
    for (const MapParams& params : kParamSets) {
        const MeshMap map = buildAndCheck(sphere, params, nullptr, "uv sphere");
        EXPECT_NEAR(map.sphere.radius, 2.0, 1e-4);
        EXPECT_NEAR(glm::length(map.sphere.center - glm::dvec3(1, -2, 3)), 0.0, 1e-4);
        EXPECT_EQ(map.hull.kind, HullKind::Solid);
    }
    // With the default bins, a sphere's triangles spread over every row and many cells.
    const MeshMap map = buildAndCheck(sphere, {}, nullptr, "uv sphere");
    int nonEmpty = 0;
    for (const Bin& bin : map.bins) nonEmpty += bin.count > 0;
    EXPECT_GT(nonEmpty, 16 * 32 / 2);
    EXPECT_GT(map.clusters.size(), std::size_t(nonEmpty) - 1);
}

TEST(SphereMapTest, MapOfRandomSoupsKeepsEveryInvariant) {
    for (unsigned seed = 1; seed <= 6; ++seed) {
        Mesh soup = randomSoup(int(200 * seed), seed, seed % 2 ? 0 : 50);
        // A loader's ids: a permutation of sources (as after finalizeMesh's vertex-cache order).
        soup.triangleSource.resize(soup.triangleCount());
        for (std::size_t t = 0; t < soup.triangleCount(); ++t) soup.triangleSource[t] = std::uint32_t(soup.triangleCount() - 1 - t);
        for (const MapParams& params : kParamSets) buildAndCheck(soup, params, nullptr, "soup " + std::to_string(seed));
    }
}

TEST(SphereMapTest, TheHullIsBuiltOnlyWhenAsked) {
    const Mesh sphere = uvSphere(12, 24);
    MapParams params;
    params.hull = false;
    const MeshMap without = buildAndCheck(sphere, params, nullptr, "no hull");
    EXPECT_EQ(without.hull.kind, HullKind::Empty);
    EXPECT_TRUE(without.hull.vertices.empty());
    EXPECT_FALSE(without.hull.note.empty());
    EXPECT_EQ(without.stats.hullMs, 0.0);
    const MeshMap with = buildAndCheck(sphere, {}, nullptr, "hull");
    EXPECT_EQ(with.hull.kind, HullKind::Solid);
    // Everything else is the same map.
    ASSERT_EQ(with.bins.size(), without.bins.size());
    for (std::size_t b = 0; b < with.bins.size(); ++b) EXPECT_EQ(with.bins[b].count, without.bins[b].count);
}

TEST(SphereMapTest, ManyTrianglesInOneBinAreSplitIntoClusters) {
    // A dense patch around +x: all in very few bins, so clusters must split each bin.
    Mesh patch;
    const int n = 60;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) patch.positions.emplace_back(1.0f, 0.01f * float(i) - 0.3f, 0.01f * float(j) - 0.3f);
    // One far point on the other side so the sphere's centre is away from the patch.
    patch.positions.emplace_back(-5.0f, 0.0f, 0.0f);
    const auto at = [&](int i, int j) { return std::uint32_t(i * (n + 1) + j); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            patch.indices.insert(patch.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            patch.indices.insert(patch.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    const auto far = std::uint32_t(patch.positions.size() - 1);
    patch.indices.insert(patch.indices.end(), {far, at(0, 0), at(n, n)});
    patch.normals.assign(patch.positions.size(), glm::vec3(1, 0, 0));
    const MeshMap map = buildAndCheck(patch, {4, 4}, nullptr, "dense patch");
    const Bin* biggest = &map.bins[0];
    for (const Bin& bin : map.bins)
        if (bin.count > biggest->count) biggest = &bin;
    EXPECT_GT(biggest->count, 2 * kClusterTriangles);
    EXPECT_GE(biggest->clusterCount, (biggest->count + kClusterTriangles - 1) / kClusterTriangles);
    EXPECT_LT(biggest->clusterCount, biggest->count / 8) << "clusters hold many triangles each";
    // A flat patch facing +x has a tight normal cone along +x.
    for (const Cluster& c : map.clusters)
        if (c.count > 10 && c.coneCutoff < 1.0f) {
            EXPECT_GT(c.coneAxis.x, 0.99f);
        }
}

// ---------------------------------------------------------------------------------------------
// Degenerate meshes: none may throw, crash or produce a non-number bound.

TEST(SphereMapTest, EmptyMeshGivesEmptyBins) {
    for (const Mesh& mesh : {Mesh{}, fromTriangles({{1, 2, 3}, {4, 5, 6}}, {})}) {
        for (const MapParams& params : kParamSets) {
            const MeshMap map = buildAndCheck(mesh, params, nullptr, "empty");
            EXPECT_TRUE(map.entries.empty());
            EXPECT_TRUE(map.clusters.empty());
            EXPECT_TRUE(map.planes.empty());
            for (const Bin& bin : map.bins) EXPECT_EQ(bin.count, 0u);
            EXPECT_EQ(map.hull.kind, HullKind::Empty);
        }
    }
}

TEST(SphereMapTest, OneTriangle) {
    const Mesh mesh = fromTriangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
    for (const MapParams& params : kParamSets) {
        const MeshMap map = buildAndCheck(mesh, params, nullptr, "one triangle");
        ASSERT_EQ(map.clusters.size(), 1u);
        EXPECT_EQ(map.clusters[0].count, 1u);
        ASSERT_EQ(map.planes.size(), 1u);
        EXPECT_NEAR(map.planes[0].z, 1.0f, 1e-6f);
        EXPECT_NEAR(map.planes[0].w, 0.0f, 1e-6f);
        EXPECT_EQ(map.hull.kind, HullKind::Planar);
    }
}

TEST(SphereMapTest, AllVerticesAtOnePointHaveRadiusZero) {
    std::vector<glm::vec3> positions(12, glm::vec3(0.5f, -1.25f, 3.0f));
    std::vector<std::uint32_t> indices;
    for (std::uint32_t t = 0; t < 10; ++t) indices.insert(indices.end(), {t, t + 1, t + 2});
    const Mesh mesh = fromTriangles(positions, indices);
    for (const MapParams& params : kParamSets) {
        const MeshMap map = buildAndCheck(mesh, params, nullptr, "one point");
        EXPECT_LE(map.sphere.radius, 1e-5);
        ASSERT_EQ(map.entries.size(), 10u);
        EXPECT_EQ(map.bins[0].count, 10u) << "R = 0: every barycenter in bin 0";
        for (const MapEntry& e : map.entries) {
            EXPECT_LE(e.r, 1e-5f);
            if (e.r == 0.0f) {
                EXPECT_EQ(e.theta, 0.0f);
            }
        }
        for (const glm::vec4& plane : map.planes) EXPECT_EQ(plane, glm::vec4(0.0f));
        EXPECT_EQ(map.hull.kind, HullKind::Point);
    }
}

TEST(SphereMapTest, BarycentersAtTheCentreLandInBinZero) {
    // Triangles symmetric about the origin: each barycenter is exactly the origin, the centre of the
    // bounding sphere of the (symmetric) vertex set.
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> indices;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int t = 0; t < 40; ++t) {
        const glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
        const auto base = std::uint32_t(positions.size());
        positions.insert(positions.end(), {a, b, -(a + b)});
        positions.insert(positions.end(), {-a, -b, a + b});
        indices.insert(indices.end(), {base, base + 1, base + 2, base + 3, base + 4, base + 5});
    }
    const Mesh mesh = fromTriangles(positions, indices);
    const MeshMap map = buildAndCheck(mesh, {}, nullptr, "centred barycenters");
    // Every barycenter is within rounding of the centre, so nearly all go to bin 0 (R = 0 exactly) or
    // wherever their rounding points; with the sphere centred within rounding at the origin.
    EXPECT_LE(glm::length(map.sphere.center), 1e-5 * map.sphere.radius + 1e-6);
    for (const MapEntry& e : map.entries) EXPECT_LE(e.r, 1e-5f * float(map.sphere.radius) + 1e-6f);
}

TEST(SphereMapTest, CollinearAndPlanarMeshes) {
    // Collinear: every triangle has zero area.
    std::vector<glm::vec3> line;
    for (int i = 0; i < 20; ++i) line.emplace_back(float(i) * 0.5f, float(i) * 0.25f, -float(i));
    std::vector<std::uint32_t> lineIndices;
    for (std::uint32_t t = 0; t + 2 < 20; ++t) lineIndices.insert(lineIndices.end(), {t, t + 2, t + 1});
    for (const MapParams& params : kParamSets) {
        const MeshMap map = buildAndCheck(fromTriangles(line, lineIndices), params, nullptr, "collinear");
        for (const glm::vec4& plane : map.planes) EXPECT_EQ(glm::vec3(plane), glm::vec3(0.0f));
        EXPECT_EQ(map.hull.kind, HullKind::Segment);
    }
    // Planar: a grid in z = 2; barycenters all on the sphere's equator band.
    std::vector<glm::vec3> grid;
    std::vector<std::uint32_t> gridIndices;
    for (int i = 0; i <= 10; ++i)
        for (int j = 0; j <= 10; ++j) grid.emplace_back(float(i), float(j), 2.0f);
    for (std::uint32_t i = 0; i < 10; ++i)
        for (std::uint32_t j = 0; j < 10; ++j) {
            const std::uint32_t a = i * 11 + j;
            gridIndices.insert(gridIndices.end(), {a, a + 11, a + 12, a, a + 12, a + 1});
        }
    for (const MapParams& params : kParamSets) {
        const MeshMap map = buildAndCheck(fromTriangles(grid, gridIndices), params, nullptr, "planar");
        EXPECT_EQ(map.hull.kind, HullKind::Planar);
        for (const glm::vec4& plane : map.planes) {
            EXPECT_NEAR(plane.z, 1.0f, 1e-6f);  // (b − a) × (c − a) = +z for this winding
            EXPECT_NEAR(plane.w, 2.0f, 1e-5f);
        }
    }
}

TEST(SphereMapTest, FewerThanFourVertices) {
    const std::vector<std::pair<std::vector<glm::vec3>, std::vector<std::uint32_t>>> cases = {
        {{{1, 1, 1}}, {0, 0, 0}},                         // one vertex
        {{{0, 0, 0}, {1, 0, 0}}, {0, 1, 1, 1, 0, 0}},     // two vertices
        {{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {0, 1, 2, 2, 1, 0, 0, 0, 1}},  // three: both sides and a sliver
    };
    for (const auto& [positions, indices] : cases)
        for (const MapParams& params : kParamSets)
            buildAndCheck(fromTriangles(positions, indices), params, nullptr,
                          std::to_string(positions.size()) + " vertices");
}

TEST(SphereMapTest, TinyAndHugeCoordinates) {
    const Mesh sphere = uvSphere(12, 24);
    const Mesh soup = randomSoup(300, 11);
    for (float factor : {1e-6f, 1e6f, 1e-12f}) {
        for (const Mesh* base : {&sphere, &soup}) {
            const Mesh mesh = scaledMesh(*base, factor, glm::vec3(3.0f * factor));
            const MeshMap map = buildAndCheck(mesh, {}, nullptr, "scaled " + std::to_string(factor));
            EXPECT_NEAR(map.sphere.center.x / double(factor), 3.0, 0.5);
            EXPECT_GT(map.sphere.radius, 0.5 * factor);
            EXPECT_LT(map.sphere.radius, 2.0 * factor);
        }
        // Same bins as the unscaled mesh for the sphere (directions do not depend on scale), up to
        // rounding at cell edges.
        std::vector<std::uint32_t> o1, o2;
        const MeshMap a = buildMeshMap(sphere, {}, o1), b = buildMeshMap(scaledMesh(sphere, factor), {}, o2);
        int differ = 0;
        for (std::size_t k = 0; k < a.bins.size(); ++k) differ += a.bins[k].count != b.bins[k].count;
        EXPECT_LE(differ, 8) << factor;
    }
}

TEST(SphereMapTest, NonFiniteVerticesGetBinZeroZeroPlanesAndUnboundedClusters) {
    Mesh mesh = uvSphere(8, 16);
    const auto finiteTriangles = mesh.triangleCount();
    const auto nanVertex = std::uint32_t(mesh.positions.size());
    mesh.positions.push_back(glm::vec3(kNaN, 0.0f, 0.0f));
    const auto infVertex = std::uint32_t(mesh.positions.size());
    mesh.positions.push_back(glm::vec3(0.0f, kInf, 0.0f));
    const auto negInfVertex = std::uint32_t(mesh.positions.size());
    mesh.positions.push_back(glm::vec3(-kInf, kNaN, kInf));
    mesh.normals.resize(mesh.positions.size(), glm::vec3(0, 0, 1));
    // Non-finite triangles spread among the finite ones.
    mesh.indices.insert(mesh.indices.begin() + 30, {nanVertex, 1, 2});
    mesh.indices.insert(mesh.indices.end(), {3, infVertex, 4, 5, 6, negInfVertex, nanVertex, infVertex, negInfVertex});
    const std::size_t triangles = mesh.triangleCount();
    ASSERT_EQ(triangles, finiteTriangles + 4);

    for (const MapParams& params : kParamSets) {
        Mesh reordered;
        const MeshMap map = buildAndCheck(mesh, params, &reordered, "non-finite");
        ASSERT_EQ(reordered.triangleCount(), triangles);
        // The sphere ignores them: the finite vertices' unit sphere.
        EXPECT_NEAR(map.sphere.radius, 1.0, 1e-4);
        int nonFinite = 0;
        for (std::size_t t = 0; t < triangles; ++t) {
            if (triangleFinite(reordered, t)) continue;
            ++nonFinite;
            EXPECT_LT(t, map.bins[0].count) << "triangle " << t << " is not in bin 0";
            EXPECT_EQ(map.planes[t], glm::vec4(0.0f));
            bool inUnbounded = false;
            for (const Cluster& c : map.clusters)
                if (t >= c.first && t < c.first + c.count)
                    inUnbounded = c.boxMin == glm::vec3(-kInf) && c.boxMax == glm::vec3(kInf) && c.radius == kInf;
            EXPECT_TRUE(inUnbounded) << "triangle " << t;
        }
        EXPECT_EQ(nonFinite, 4);
        for (const MapEntry& e : map.entries) {
            EXPECT_FALSE(std::isnan(e.r) || std::isnan(e.theta) || std::isnan(e.phi));
            if (!triangleFinite(reordered, e.triangle)) {
                EXPECT_EQ(e.r, 0.0f);
                EXPECT_EQ(e.theta, 0.0f);
                EXPECT_EQ(e.phi, 0.0f);
            }
        }
        for (const Bin& bin : map.bins) EXPECT_FALSE(std::isnan(bin.rMin) || std::isnan(bin.rMax));
    }
    // A mesh of nothing but non-finite vertices.
    const Mesh bad = fromTriangles({glm::vec3(kNaN), glm::vec3(kInf), glm::vec3(-kInf, 0, 0)}, {0, 1, 2, 2, 1, 0});
    const MeshMap map = buildAndCheck(bad, {}, nullptr, "all non-finite");
    EXPECT_EQ(map.bins[0].count, 2u);
    EXPECT_EQ(map.sphere.radius, 0.0);
    EXPECT_EQ(map.hull.kind, HullKind::Empty);
}

// ---------------------------------------------------------------------------------------------
// reportViews.

TEST(ViewsTest, CountAndDeterminism) {
    EXPECT_TRUE(reportViews(glm::vec3(0.0f), 1.0f, 0).empty());
    EXPECT_TRUE(reportViews(glm::vec3(0.0f), 1.0f, -3).empty());
    for (int count : {1, 2, 3, 7, 12, 40}) {
        const std::vector<ReportView> a = reportViews(glm::vec3(1, 2, 3), 2.5f, count);
        const std::vector<ReportView> b = reportViews(glm::vec3(1, 2, 3), 2.5f, count);
        ASSERT_EQ(a.size(), std::size_t(count));
        ASSERT_EQ(b.size(), a.size());
        for (std::size_t k = 0; k < a.size(); ++k) {
            EXPECT_EQ(a[k].viewClass, b[k].viewClass);
            EXPECT_EQ(*a[k].camera.eye, *b[k].camera.eye);
            EXPECT_EQ(*a[k].camera.target, *b[k].camera.target);
            EXPECT_EQ(a[k].camera.up, b[k].camera.up);
            EXPECT_EQ(a[k].camera.yfovDegrees, b[k].camera.yfovDegrees);
        }
    }
    // Only the first two are poles, and with one view there is no pole.
    EXPECT_NE(reportViews(glm::vec3(0.0f), 1.0f, 1)[0].viewClass, "pole");
    const std::vector<ReportView> many = reportViews(glm::vec3(0.0f), 1.0f, 30);
    std::map<std::string, int> classes;
    for (std::size_t k = 0; k < many.size(); ++k) {
        ++classes[many[k].viewClass];
        if (k >= 2) {
            EXPECT_NE(many[k].viewClass, "pole") << k;
        }
    }
    EXPECT_EQ(classes["pole"], 2);
    for (const char* name : {"whole", "partial", "grazing", "inside"}) EXPECT_GT(classes[name], 0) << name;
    EXPECT_EQ(classes.size(), 5u);
}

// Planes (unit normal, inside ≥ 0) of a view's frustum, from projection · view (Gribb & Hartmann).
std::vector<glm::dvec4> frustumPlanes(const View& view) {
    const glm::dmat4 m = glm::dmat4(view.projection) * glm::dmat4(view.view);
    auto row = [&m](int i) { return glm::dvec4(m[0][i], m[1][i], m[2][i], m[3][i]); };
    std::vector<glm::dvec4> planes;
    for (const glm::dvec4& p : {row(3) + row(0), row(3) - row(0), row(3) + row(1), row(3) - row(1), row(3) + row(2),
                                row(3) - row(2)})
        planes.push_back(p / glm::length(glm::dvec3(p)));
    return planes;
}

// A scene of one small triangle at `center` (resolveCamera only needs something to frame).
Scene tinyScene(const glm::vec3& center) {
    return test::oneMeshScene(
        fromTriangles({center, center + glm::vec3(1e-3f, 0, 0), center + glm::vec3(0, 1e-3f, 0)}, {0, 1, 2}));
}

// Across several counts, fields of view and aspects (portrait included), with the frustum of
// resolveCamera: whole views hold the sphere, partial and grazing views have its centre outside yet
// meet it, inside views put the eye inside it, poles sit on the ±z axis.
TEST(ViewsTest, ViewClassesHoldAgainstTheirFrustum) {
    struct Setup {
        glm::vec3 center;
        float radius, yfov;
        int width, height;
    };
    const Setup setups[] = {
        {{0, 0, 0}, 1.0f, 40.0f, 400, 300},
        {{10, -4, 2}, 0.03f, 40.0f, 400, 300},
        {{-1, 2, 3}, 250.0f, 60.0f, 300, 400},  // portrait: the narrow field is horizontal
        {{0, 0, 0}, 1.0f, 25.0f, 200, 150},
    };
    for (const Setup& s : setups)
      for (int count : {12, 24, 36}) {
        const float aspect = float(s.width) / float(s.height);
        const std::vector<ReportView> views = reportViews(s.center, s.radius, count, s.yfov, aspect);
        const Scene scene = tinyScene(s.center);
        const std::vector<glm::mat4> world = scene.worldTransforms(0.0);
        ASSERT_EQ(views.size(), std::size_t(count));
        for (std::size_t k = 0; k < views.size(); ++k) {
            const ReportView& rv = views[k];
            SCOPED_TRACE(testing::Message() << "view " << k << "/" << count << " (" << rv.viewClass << "), radius " << s.radius
                                            << ", fov " << s.yfov << ", aspect " << aspect);
            ASSERT_TRUE(rv.camera.eye && rv.camera.target);
            ASSERT_TRUE(rv.camera.yfovDegrees);
            EXPECT_EQ(*rv.camera.yfovDegrees, s.yfov);
            EXPECT_FALSE(rv.camera.sceneCamera);
            EXPECT_NEAR(glm::length(rv.camera.up), 1.0f, 1e-5f);
            const glm::vec3 eye = *rv.camera.eye, target = *rv.camera.target;
            const double distance = glm::length(glm::dvec3(eye) - glm::dvec3(s.center));
            Camera spec = rv.camera;
            spec.znear = s.radius * 1e-4f;
            spec.zfar = s.radius * 1e4f;
            spec.depthRange = DepthRange::File;  // the frustum around the report view's sphere, as given
            const Result<View> view = resolveCamera(scene, world, 0.0, spec, s.width, s.height);
            ASSERT_TRUE(view) << view.error().message;
            // Also resolvable with fitted near/far (the up vector is never parallel to the view).
            EXPECT_TRUE(resolveCamera(scene, world, 0.0, rv.camera, s.width, s.height));

            const std::vector<glm::dvec4> planes = frustumPlanes(*view);
            double minDistance = INFINITY;  // signed distance of the centre to the nearest plane
            for (const glm::dvec4& p : planes)
                minDistance = std::min(minDistance, glm::dot(glm::dvec3(p), glm::dvec3(s.center)) + p.w);
            const double r = s.radius;
            if (k < 2) {
                EXPECT_EQ(rv.viewClass, "pole");
                EXPECT_EQ(eye.x, s.center.x);
                EXPECT_EQ(eye.y, s.center.y);
                EXPECT_EQ(eye.z > s.center.z, k == 0);
                EXPECT_EQ(target, s.center);
                EXPECT_GE(minDistance, r * 0.999);  // the whole sphere is in view
            } else if (rv.viewClass == "whole") {
                EXPECT_GE(minDistance, r * (1.0 - 1e-4));
            } else if (rv.viewClass == "partial") {
                EXPECT_LT(minDistance, 0.0) << "the centre is outside the frustum";
                EXPECT_GT(minDistance, -r) << "the sphere meets the frustum";
                EXPECT_GT(distance, r) << "the eye is outside the sphere";
            } else if (rv.viewClass == "grazing") {
                EXPECT_LT(minDistance, 0.0) << "the centre is outside the frustum";
                EXPECT_GT(minDistance, -r) << "the sphere meets the frustum";
                // How deep: GrazingViewsAreLessThanTenPercentDeep.
            } else if (rv.viewClass == "inside") {
                EXPECT_LT(distance, r);
            } else {
                ADD_FAILURE() << "unknown class " << rv.viewClass;
            }
        }
    }
}

// Grazing: the sphere meets the frustum, less than 10% of its radius deep.
TEST(ViewsTest, GrazingViewsAreLessThanTenPercentDeep) {
    for (const float aspect : {4.0f / 3.0f, 0.75f}) {
        const int width = 400, height = int(std::lround(400.0f / aspect));
        const std::vector<ReportView> views = reportViews(glm::vec3(0.0f), 1.0f, 24, 40.0f, float(width) / float(height));
        const Scene scene = tinyScene(glm::vec3(0.0f));
        for (std::size_t k = 0; k < views.size(); ++k) {
            if (views[k].viewClass != "grazing") continue;
            Camera spec = views[k].camera;
            spec.znear = 1e-4f;
            spec.zfar = 1e4f;
            const Result<View> view = resolveCamera(scene, scene.worldTransforms(0.0), 0.0, spec, width, height);
            ASSERT_TRUE(view) << view.error().message;
            double minDistance = INFINITY;
            for (const glm::dvec4& p : frustumPlanes(*view)) minDistance = std::min(minDistance, p.w);
            EXPECT_GT(minDistance, -1.0) << "view " << k << ": the sphere meets the frustum";
            EXPECT_LT(minDistance + 1.0, 0.1) << "view " << k << " (aspect " << aspect
                                              << "): the sphere is this deep in the frustum, in radii";
        }
    }
}

}  // namespace
}  // namespace frugal
