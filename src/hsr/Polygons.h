// A mesh's polygons, the unit paper 003 sorts and flags: the paper's scenes are quads (its 28 cubes
// are 168 of them), ours are triangle lists, so each mesh's triangles are grouped back into the
// polygons they were cut from, once per scene.
//
// A polygon here is a set of triangles that tile one convex planar polygon without overlapping:
// triangles joined across an edge they share (the same two positions, in opposite directions:
// a consistently wound surface) when the fourth vertex lies in the first triangle's plane (exactly,
// in double: |orient3d| ≤ 1e-12 of the product of the edge lengths cubed, which axis-aligned and
// exactly representable faces meet and curved surfaces do not) and on the other side of the edge,
// then kept only if the group is convex and does not overlap itself: the sum of its triangles'
// areas equals the area of its vertices' convex hull in the plane (to 1e-9, relative). Otherwise
// each of its triangles is a polygon of its own.
//
// Why that matters (hsr/Plan.h): a polygon drawn without a depth test must draw each of its pixels
// once, whatever the order of its triangles. Triangles that tile a convex region share every inner
// edge, so the rasterizers' fill rule (src/raster/Rasterizer.h) gives each pixel centre to exactly
// one of them; an overlapping or folded group would not.
#pragma once

#include <cstdint>
#include <vector>

#include <frugal/Scene.h>

namespace frugal::hsr {

struct MeshPolygons {
    std::vector<std::uint32_t> polygonOf;  // per triangle of the mesh: its polygon, 0 .. count − 1
    std::uint32_t count = 0;
    // The mesh bounds a convex solid: it is connected and closed (every edge, by position, held by
    // exactly two triangles in opposite directions, none degenerate), and every vertex lies on or
    // behind every triangle's plane (within 1e-6 of the mesh's bounding-box diagonal). A ray from
    // outside enters such a solid once, so two of its front-facing triangles never cover one point
    // of the screen (hsr/Plan.h, adaptive-convex). Not checked above 10^8 vertex-plane tests: false.
    bool convexSolid = false;
};

// Polygons numbered in the order of their first triangle.
MeshPolygons groupPolygons(const Mesh& mesh);

}  // namespace frugal::hsr
