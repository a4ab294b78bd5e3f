// Geometry that culling pre-processing needs from CGAL: the minimal enclosing sphere and the convex
// hull of a point set. This header is CGAL-free; cull/Hull.cpp is the only file in the project that
// includes CGAL (it is header-only and slow to compile), so nothing else ever recompiles it.
//
// Both functions take points in one object space, ignore non-finite points, and never throw: CGAL's
// precondition failures and exceptions are caught inside and turned into the stated fallbacks.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace frugal {

struct Sphere {
    glm::dvec3 center{0.0};
    double radius = 0.0;  // 0 for no points or one distinct point
};

// The smallest sphere that encloses every finite point (CGAL Min_sphere_of_spheres_d, exact up to
// double rounding); the radius is then grown by a few ulps so that every input point, as float,
// lies inside by a plain double distance test. No finite points: centre 0, radius 0.
Sphere minimalSphere(std::span<const glm::vec3> points);

// What the hull of a point set degenerates to. Solid: a 3-D polytope (CGAL convex_hull_3).
enum class HullKind { Empty, Point, Segment, Planar, Solid };

const char* hullKindName(HullKind kind);  // "empty", "point", "segment", "planar", "solid"

struct Hull {
    HullKind kind = HullKind::Empty;
    // The hull's vertices (each once): Solid — the polytope's vertices; Planar — the vertices of the
    // 2-D hull in the points' plane; Segment — its two end points; Point — the point.
    std::vector<glm::vec3> vertices;
    std::size_t faces = 0;  // Solid: triangular faces of the polytope; Planar: 1; otherwise 0
    std::string note;       // why a fallback was taken (empty for a solid hull built normally)
};

// The convex hull of the finite points. Degenerate sets never throw and never crash: fewer than 4
// affinely independent points give Empty/Point/Segment/Planar as stated above.
Hull convexHull(std::span<const glm::vec3> points);

}  // namespace frugal
