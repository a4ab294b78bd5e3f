// Per-mesh pre-processing for culling (paper 002, "spherical-coordinate visible sets with a convex
// hull"): the bounding sphere, every triangle's barycenter in spherical coordinates, the barycenter
// map binned by (θ, φ), the memory-access map (the triangles reordered once, before upload, so that a
// bin is one contiguous index range), clusters inside each bin, and the convex hull.
//
// Conventions (object space of the mesh; the paper's equation 1):
//   d = p − c for a point p and the bounding sphere's centre c;
//   R = |d|;  θ = acos(d.z / R) ∈ [0, π], the polar angle from +z (θ = 0 is the "north" pole);
//   φ = atan2(d.y, d.x) wrapped into [0, 2π), the azimuth from +x towards +y.
//   At the poles (d.x = d.y = 0) φ = 0; at the centre (R = 0) θ = φ = 0. Both are ordinary values:
//   such barycenters land in bin 0 of their row, nothing divides by R.
// Bins: thetaBins × phiBins cells uniform in θ and φ; bin (i, j), index i·phiBins + j, holds
//   θ ∈ [iπ/T, (i+1)π/T) and φ ∈ [2πj/P, 2π(j+1)/P); θ = π belongs to the last row.
// Order of the index buffer after reordering: bin by bin (index order); inside a bin, cluster by
//   cluster (meshoptimizer meshlets of at most kClusterTriangles triangles), and inside a cluster the
//   vertex-cache order (meshoptimizer). The barycenter map (`entries`) lists each bin's triangles
//   sorted by R, farthest first, with their position in that index buffer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Scene.h>

#include "cull/Geometry.h"

namespace frugal {

struct MapParams {
    int thetaBins = 16;  // 1..1024
    int phiBins = 32;    // 1..1024
    bool hull = true;    // build the convex hull; only the paper method reads it (without: it keeps
                         // every bin of an instance wholly in view)
};

inline constexpr std::uint32_t kClusterTriangles = 124;  // meshoptimizer's meshlet limit
inline constexpr std::uint32_t kClusterVertices = 64;

// A run of triangles of one bin with the bounds culling tests (object space).
struct Cluster {
    std::uint32_t first = 0, count = 0;  // triangles, in the reordered index buffer
    glm::vec3 boxMin{0.0f}, boxMax{0.0f};
    glm::vec3 center{0.0f};               // bounding sphere of its vertices (meshoptimizer)
    float radius = 0.0f;
    // Normal cone (meshoptimizer's): coneCutoff = sin α, α the largest angle between a face normal
    // and coneAxis, so every triangle faces away from an eye e when
    // dot(center − e, coneAxis) ≥ coneCutoff·|center − e| + radius. A cone too wide to be of use
    // (meshoptimizer: α ≳ 84°) has coneCutoff = 1, which no eye passes.
    glm::vec3 coneAxis{0.0f, 0.0f, 1.0f};
    float coneCutoff = 1.0f;
    // Some triangle has zero area in object space (its plane is 0). meshoptimizer leaves such
    // triangles out of the cone, but after GL's float transform and snapping one may still own a
    // pixel: conservative culling never drops this cluster on its cone alone.
    bool hasDegenerate = false;
    // The largest facingSlack (MeshMap) of its triangles: how near edge-on a triangle of it may be
    // seen and still be drawn front-facing after GL's rounding and snapping (Culling.cpp).
    glm::vec2 slack{0.0f};
};

struct Bin {
    std::uint32_t first = 0, count = 0;                // triangles, contiguous in the index buffer
    std::uint32_t firstCluster = 0, clusterCount = 0;  // into MeshMap::clusters
    float rMin = 0.0f, rMax = 0.0f;                    // barycenter distances from the centre
};

// One barycenter of the map: its spherical coordinates and where its triangle sits after reordering.
struct MapEntry {
    float r = 0.0f, theta = 0.0f, phi = 0.0f;
    std::uint32_t triangle = 0;
};

struct PrepStats {
    double sphereMs = 0.0, mapMs = 0.0, clusterMs = 0.0, hullMs = 0.0;
    std::size_t mapBytes = 0;     // barycenter map (entries)
    std::size_t accessBytes = 0;  // memory-access map (bins, clusters, planes)
    std::size_t hullBytes = 0;    // the hull's vertices (when built)
    double totalMs() const { return sphereMs + mapMs + clusterMs + hullMs; }
};

// Every cluster's vertices side by side, for the work done per vertex of a cluster (conservative's
// clip outcodes, the occlusion pass's transform): a cluster's triangles then read a few hundred
// bytes in a row, not vertices scattered over the mesh. Structure of arrays, each padded with 8
// zeros (the AVX2 loops read 8 at a time). A cluster has at most kClusterVertices vertices.
struct ClusterVertices {
    std::vector<float> x, y, z;              // positions, cluster by cluster
    std::vector<std::uint32_t> firstVertex;  // per cluster, and one past the last
    std::uint32_t maxVertices = 0;           // of a cluster
    std::vector<std::uint16_t> c0, c1, c2;   // per triangle (and 8 more): its corners among its cluster's vertices
};

struct MeshMap {
    MapParams params;
    Sphere sphere;                   // object space; minimal enclosing sphere of the used vertices
    std::vector<Bin> bins;           // thetaBins × phiBins
    std::vector<Cluster> clusters;   // bin by bin
    std::vector<MapEntry> entries;   // bin by bin, R descending inside a bin
    // Per triangle of the reordered buffer: unit face normal n and n · (first vertex), for exact
    // facing tests; a degenerate (zero-area) triangle has n = 0.
    std::vector<glm::vec4> planes;
    // Per triangle of the reordered buffer, in object units: (its two shorter edges' lengths ÷ twice
    // the area, 1 ÷ twice the area); +inf for zero area. The facing margin of a triangle is K1·x + K2·y (Culling.cpp),
    // K1 and K2 from the view.
    std::vector<glm::vec2> facingSlack;
    ClusterVertices vertices;        // of `clusters`
    Hull hull;                       // of the used vertices
    PrepStats stats;

    int binIndex(int thetaBin, int phiBin) const { return thetaBin * params.phiBins + phiBin; }
};

// Spherical coordinates of `d` (conventions above).
struct Spherical {
    float r = 0.0f, theta = 0.0f, phi = 0.0f;
};
Spherical toSpherical(const glm::dvec3& d);
// The bin of a direction given as spherical coordinates.
int binOf(const MapParams& params, float theta, float phi);

// Builds the map of `mesh` and the triangle order it needs: order[newT] = oldT. The caller applies
// the order with reorderTriangles (scene/MeshBuild.h) before upload; the map refers to the new order.
// Triangles are those of the mesh as given (finite positions: loaders drop the others; a non-finite
// vertex that reaches this function still gets a bin and never a NaN bound, see the .cpp).
MeshMap buildMeshMap(const Mesh& mesh, const MapParams& params, std::vector<std::uint32_t>& order);

}  // namespace frugal
