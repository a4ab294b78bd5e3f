// Shared last step of every loader: make a Mesh safe and fast to draw.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <frugal/Scene.h>

namespace frugal {

// Every component finite (no NaN, no infinity): what a vertex must be to be drawn.
template <int N>
bool isFinite(const glm::vec<N, float>& v) {
    for (int k = 0; k < N; ++k)
        if (!std::isfinite(v[k])) return false;
    return true;
}

struct MeshBuildStats {
    std::size_t droppedNonFinite = 0;  // primitives with a NaN/Inf position (never passed to GL)
};

// Requires indices.size() to be a multiple of verticesPerPrimitive(topology), every index <
// positions.size(), and normals/colors/uvs either empty or as long as positions (loaders validate
// this before calling).
// - drops primitives that touch a non-finite position, and counts them;
// - fills `triangleSource` with 0..n-1 if the loader left it empty;
// - triangles: computes area-weighted vertex normals when `normals` is empty, and replaces
//   non-finite or zero normals by the face normal; segments and points: normalises the normals
//   there are (a broken one becomes +z) and computes none;
// - normalises tangents, and replaces broken ones by a perpendicular of the normal;
// - reorders triangles for the post-transform vertex cache (meshoptimizer) when `optimizeOrder`,
//   carrying `triangleSource` along.
MeshBuildStats finalizeMesh(Mesh& mesh, bool optimizeOrder);

// Fills `tangents` (Scene.h) from the positions, normals (unit) and uvs: per vertex, the directions
// of increasing u of the triangles around it, each projected on the vertex's tangent plane, weighted
// by the corner's angle, summed and normalised; w = +1 where the directions of decreasing v turn the
// same way as cross(normal, tangent), else −1. That is MikkTSpace's result (which the Khronos glTF
// Sample Renderer computes for a mesh without tangents) wherever the triangles around a vertex agree
// on handedness; MikkTSpace splits a vertex where they do not, this keeps the majority. A vertex
// with no usable triangle, or a mesh without uvs, gets a perpendicular of its normal and w = +1.
void generateTangents(Mesh& mesh);

// The seam before upload: puts the mesh's triangles in a new order, `order[newT] = oldT` (a
// permutation of 0..triangleCount-1), carrying `triangleSource` along so that ids stay stable.
// Vertices are untouched. Culling pre-processing (cull/) calls it so that every bin of its map is one
// contiguous index range; it must run before SceneRenderer uploads the mesh.
void reorderTriangles(Mesh& mesh, const std::vector<std::uint32_t>& order);

}  // namespace frugal
