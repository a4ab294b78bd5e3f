// Minimal enclosing sphere and convex hull of a point set, with CGAL. This is the only translation
// unit in the project that includes CGAL (see Geometry.h).
//
// Kernel: Exact_predicates_inexact_constructions_kernel (EPICK). Every decision below (duplicates,
// collinear, coplanar, hull facets) is made by an exact predicate on the input coordinates, and the
// hull constructs no point: its vertices are input points (only a -0 coordinate may come back as +0).
// The points come in as float, so double holds them exactly, and no product of degree up to 4 that
// the code forms can overflow ((2 FLT_MAX)^4 < DBL_MAX).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Min_sphere_of_spheres_d.h>
#include <CGAL/Min_sphere_of_spheres_d_traits_3.h>
#include <CGAL/Projection_traits_xy_3.h>
#include <CGAL/Projection_traits_xz_3.h>
#include <CGAL/Projection_traits_yz_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/exceptions.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <exception>
#include <iterator>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "cull/Geometry.h"

namespace frugal {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = K::Point_3;

// The distinct finite points of the input, in input order (first occurrences).
struct CleanPoints {
    std::vector<glm::vec3> points;
    std::size_t finite = 0;     // finite input points, duplicates included
    std::size_t nonFinite = 0;  // input points dropped for NaN/Inf coordinates
};

// Duplicates are removed with a small open-addressing hash set rather than sort + unique: the hull
// is cheaper on points in their original (mesh) order than on sorted ones, and the sort costs time of
// its own (figures on the bunny: docs/gl/README.md, "Outside the GL backend").
CleanPoints cleanPoints(std::span<const glm::vec3> input) {
    CleanPoints clean;
    clean.points.reserve(input.size());
    std::size_t capacity = 16;
    while (capacity < 2 * input.size()) capacity *= 2;
    std::vector<std::size_t> slots(capacity, 0);  // index + 1 into clean.points; 0 = free
    for (const glm::vec3& in : input) {
        if (!std::isfinite(in.x) || !std::isfinite(in.y) || !std::isfinite(in.z)) {
            ++clean.nonFinite;
            continue;
        }
        ++clean.finite;
        // -0 + 0 = +0: equal coordinates get equal bits, so bit patterns can be hashed and compared.
        const glm::vec3 p(in.x + 0.0f, in.y + 0.0f, in.z + 0.0f);
        const std::uint64_t bx = std::bit_cast<std::uint32_t>(p.x), by = std::bit_cast<std::uint32_t>(p.y),
                            bz = std::bit_cast<std::uint32_t>(p.z);
        std::uint64_t h = (bx | by << 32) * 0x9E3779B97F4A7C15ull ^ bz * 0xC2B2AE3D27D4EB4Full;
        h ^= h >> 29;
        for (std::size_t i = h & (capacity - 1);; i = (i + 1) & (capacity - 1)) {
            if (slots[i] == 0) {
                clean.points.push_back(p);
                slots[i] = clean.points.size();
                break;
            }
            if (clean.points[slots[i] - 1] == p) break;  // a duplicate
        }
    }
    return clean;
}

Point3 toCgal(const glm::vec3& p) { return {p.x, p.y, p.z}; }

// Exact back to float: every point handled here came from a float.
glm::vec3 toVec3(const Point3& p) {
    return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

std::string count(std::size_t n, const char* noun) { return std::to_string(n) + " " + noun + (n == 1 ? "" : "s"); }

// " (ignored N non-finite points)" when any were dropped, else "".
std::string ignoredSuffix(const CleanPoints& clean) {
    if (clean.nonFinite == 0) return {};
    return " (ignored " + count(clean.nonFinite, "non-finite point") + ")";
}

// ---------------------------------------------------------------------------------------------------
// Degeneracy: the affine dimension of the point set, decided as quickhull chooses its initial simplex
// (farthest pair among the axis extremes, farthest point from their line, farthest from their plane).
// The "farthest" choices use plain double arithmetic and only pick candidates; each verdict is an exact
// CGAL predicate, and a degenerate verdict is confirmed against every point before it is trusted, so
// the result never depends on rounding or on the coordinates' scale.

struct Simplex {
    int dimension = 0;              // 0 point, 1 segment, 2 planar, 3 solid
    std::array<Point3, 4> corners;  // the first dimension+1 are affinely independent
};

Simplex initialSimplex(const std::vector<Point3>& pts) {
    Simplex s;
    s.corners.fill(pts.front());
    if (pts.size() == 1) return s;

    // Farthest pair among the six axis-extreme points. Distinct points differ on some axis, so that
    // axis' extremes are distinct and the chosen pair has a positive distance.
    std::array<std::size_t, 6> extreme{};
    for (std::size_t i = 1; i < pts.size(); ++i) {
        for (int axis = 0; axis < 3; ++axis) {
            if (pts[i][axis] < pts[extreme[2 * axis]][axis]) extreme[2 * axis] = i;
            if (pts[i][axis] > pts[extreme[2 * axis + 1]][axis]) extreme[2 * axis + 1] = i;
        }
    }
    double best = -1.0;
    for (std::size_t i = 0; i < 6; ++i) {
        for (std::size_t j = i + 1; j < 6; ++j) {
            double d = CGAL::to_double(CGAL::squared_distance(pts[extreme[i]], pts[extreme[j]]));
            if (d > best && pts[extreme[i]] != pts[extreme[j]]) {
                best = d;
                s.corners[0] = pts[extreme[i]];
                s.corners[1] = pts[extreme[j]];
            }
        }
    }
    const Point3& a = s.corners[0];
    const Point3& b = s.corners[1];
    s.dimension = 1;

    // Farthest from the line ab (|(p - a) x (b - a)|² is proportional to the squared distance).
    const K::Vector_3 ab = b - a;
    const Point3* c = nullptr;
    best = -1.0;
    for (const Point3& p : pts) {
        double d = CGAL::cross_product(p - a, ab).squared_length();
        if (d > best) {
            best = d;
            c = &p;
        }
    }
    if (CGAL::collinear(a, b, *c)) {
        // Rounding may have hidden a point that is off the line; confirm exactly.
        auto off = std::find_if(pts.begin(), pts.end(), [&](const Point3& p) { return !CGAL::collinear(a, b, p); });
        if (off == pts.end()) return s;
        c = &*off;
    }
    s.corners[2] = *c;
    s.dimension = 2;

    // Farthest from the plane abc.
    const K::Vector_3 normal = CGAL::cross_product(ab, *c - a);
    const Point3* d = nullptr;
    best = -1.0;
    for (const Point3& p : pts) {
        double h = std::abs((p - a) * normal);
        if (h > best) {
            best = h;
            d = &p;
        }
    }
    if (CGAL::coplanar(a, b, *c, *d)) {
        auto off = std::find_if(pts.begin(), pts.end(),
                                [&](const Point3& p) { return CGAL::orientation(a, b, *c, p) != CGAL::COPLANAR; });
        if (off == pts.end()) return s;
        d = &*off;
    }
    s.corners[3] = *d;
    s.dimension = 3;
    return s;
}

// ---------------------------------------------------------------------------------------------------
// Planar hull: exactly coplanar points are projected onto a coordinate plane the points' plane is not
// perpendicular to, which is an affine bijection of their plane (so the 2-D hull there is the hull),
// and needs no constructions: CGAL's projection traits just ignore one coordinate.

template <class Traits>
std::vector<Point3> hull2(const std::vector<Point3>& pts) {
    std::vector<Point3> out;
    out.reserve(16);
    CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(out), Traits());
    return out;
}

// Whether dropping coordinate `axis` keeps the non-collinear a, b, c non-collinear (exact).
bool projectionKeepsTriangle(int axis, const Point3& a, const Point3& b, const Point3& c) {
    switch (axis) {
        case 0:
            return CGAL::Projection_traits_yz_3<K>().orientation_2_object()(a, b, c) != CGAL::COLLINEAR;
        case 1:
            return CGAL::Projection_traits_xz_3<K>().orientation_2_object()(a, b, c) != CGAL::COLLINEAR;
        default:
            return CGAL::Projection_traits_xy_3<K>().orientation_2_object()(a, b, c) != CGAL::COLLINEAR;
    }
}

std::vector<Point3> planarHull(const std::vector<Point3>& pts, const Simplex& s) {
    const Point3& a = s.corners[0];
    const Point3& b = s.corners[1];
    const Point3& c = s.corners[2];
    // Try the axes from the plane normal's largest component down; the exact test guards against a
    // normal that is all rounding noise. Some axis always works, as the true normal is not zero.
    const K::Vector_3 n = CGAL::cross_product(b - a, c - a);
    std::array<int, 3> axes{0, 1, 2};
    std::sort(axes.begin(), axes.end(), [&](int i, int j) { return std::abs(n[i]) > std::abs(n[j]); });
    for (int axis : axes) {
        if (!projectionKeepsTriangle(axis, a, b, c)) continue;
        switch (axis) {
            case 0:
                return hull2<CGAL::Projection_traits_yz_3<K>>(pts);
            case 1:
                return hull2<CGAL::Projection_traits_xz_3<K>>(pts);
            default:
                return hull2<CGAL::Projection_traits_xy_3<K>>(pts);
        }
    }
    return {a, b, c};  // unreachable for exactly coplanar, non-collinear a, b, c
}

Hull solidHull(const std::vector<Point3>& pts) {
    CGAL::Surface_mesh<Point3> mesh;
    CGAL::convex_hull_3(pts.begin(), pts.end(), mesh);
    Hull hull;
    hull.kind = HullKind::Solid;
    hull.faces = mesh.number_of_faces();
    hull.vertices.reserve(mesh.number_of_vertices());
    for (auto v : mesh.vertices()) hull.vertices.push_back(toVec3(mesh.point(v)));
    return hull;
}

// `attempted` is set to the kind being built before CGAL is called, for the fallback in convexHull.
Hull computeHull(const CleanPoints& clean, const std::vector<Point3>& pts, HullKind& attempted) {
    Hull hull;
    const std::string ignored = ignoredSuffix(clean);
    const std::size_t n = pts.size();
    if (n == 0) {
        hull.note = clean.nonFinite == 0 ? "no points" : "no finite points" + ignored;
        return hull;
    }
    if (n == 1) {
        hull.kind = HullKind::Point;
        hull.vertices = {toVec3(pts.front())};
        hull.note =
            (clean.finite == 1 ? std::string("one point") : "all " + count(clean.finite, "point") + " are equal") +
            ignored;
        return hull;
    }

    const Simplex s = initialSimplex(pts);
    switch (s.dimension) {
        case 1: {
            // Along a line (exactly), lexicographic order is the order on the line: the lexicographic
            // extremes are the ends.
            const auto [lo, hi] = std::minmax_element(pts.begin(), pts.end());
            hull.kind = HullKind::Segment;
            hull.vertices = {toVec3(*lo), toVec3(*hi)};
            hull.note = "all " + count(n, "distinct point") + " are collinear: segment between the extremes" + ignored;
            return hull;
        }
        case 2:
            attempted = HullKind::Planar;
            hull.kind = HullKind::Planar;
            hull.faces = 1;
            for (const Point3& p : planarHull(pts, s)) hull.vertices.push_back(toVec3(p));
            hull.note = "all " + count(n, "distinct point") + " are coplanar: 2-D hull in their plane" + ignored;
            return hull;
        default:
            attempted = HullKind::Solid;
            hull = solidHull(pts);
            hull.note = ignored.empty() ? std::string() : ignored.substr(1);
            return hull;
    }
}

// ---------------------------------------------------------------------------------------------------
// Sphere.

// Grows `radius` until every point passes the plain double test `length(p - center) <= radius`,
// then adds a few ulps so that callers computing the distance slightly differently agree.
double coverAll(const std::vector<glm::dvec3>& pts, const glm::dvec3& center, double radius) {
    constexpr double eps = std::numeric_limits<double>::epsilon();
    // Absolute slack: a few ulps of the coordinates involved, for radii near zero.
    const double tiny = 4.0 * eps * std::max(glm::length(center), std::numeric_limits<double>::min());
    for (int round = 0; round < 64; ++round) {
        double worst = 0.0;
        for (const glm::dvec3& p : pts) worst = std::max(worst, glm::length(p - center));
        if (worst <= radius) break;
        radius = worst + 4.0 * eps * worst + tiny;
    }
    return radius > 0.0 ? radius * (1.0 + 4.0 * eps) : radius;
}

// Used if CGAL fails: the box centre and the farthest point from it (encloses, not minimal).
Sphere boxSphere(const std::vector<glm::dvec3>& pts) {
    glm::dvec3 lo = pts.front(), hi = pts.front();
    for (const glm::dvec3& p : pts) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    Sphere s;
    s.center = 0.5 * lo + 0.5 * hi;  // no overflow, unlike (lo + hi) / 2
    s.radius = coverAll(pts, s.center, 0.0);
    return s;
}

}  // namespace

const char* hullKindName(HullKind kind) {
    switch (kind) {
        case HullKind::Empty:
            return "empty";
        case HullKind::Point:
            return "point";
        case HullKind::Segment:
            return "segment";
        case HullKind::Planar:
            return "planar";
        case HullKind::Solid:
            return "solid";
    }
    return "unknown";
}

Sphere minimalSphere(std::span<const glm::vec3> points) {
    std::vector<glm::dvec3> pts;
    try {
        const CleanPoints clean = cleanPoints(points);
        pts.assign(clean.points.begin(), clean.points.end());
    } catch (...) {  // out of memory: nothing sensible to return but the empty sphere
        return {};
    }
    if (pts.empty()) return {};
    if (pts.size() == 1) return {pts.front(), 0.0};

    try {
        // Points are zero-radius spheres. Square roots are fine (and needed) with a double FT.
        using Traits = CGAL::Min_sphere_of_spheres_d_traits_3<K, double, CGAL::Tag_true>;
        std::vector<Traits::Sphere> spheres;
        spheres.reserve(pts.size());
        for (const glm::dvec3& p : pts) spheres.emplace_back(Point3(p.x, p.y, p.z), 0.0);
        CGAL::Min_sphere_of_spheres_d<Traits> ms(spheres.begin(), spheres.end());
        Sphere s;
        auto c = ms.center_cartesian_begin();
        s.center = {c[0], c[1], c[2]};
        s.radius = ms.radius();
        if (std::isfinite(s.center.x) && std::isfinite(s.center.y) && std::isfinite(s.center.z) &&
            std::isfinite(s.radius) && s.radius >= 0.0) {
            s.radius = coverAll(pts, s.center, s.radius);
            return s;
        }
    } catch (const CGAL::Failure_exception&) {
    } catch (const std::exception&) {
    } catch (...) {
    }
    try {
        return boxSphere(pts);
    } catch (...) {
        return {};
    }
}

Hull convexHull(std::span<const glm::vec3> points) {
    std::vector<Point3> pts;
    HullKind attempted = HullKind::Empty;
    std::string failure;
    // Records why the hull failed; called in the handlers below, where nothing may throw.
    auto fail = [&failure](const char* prefix, const char* what) noexcept {
        try {
            failure = std::string(prefix) + what;
            std::replace(failure.begin(), failure.end(), '\n', ' ');  // CGAL's messages span several lines
        } catch (...) {
        }
    };
    try {
        const CleanPoints clean = cleanPoints(points);
        pts.reserve(clean.points.size());
        for (const glm::vec3& p : clean.points) pts.push_back(toCgal(p));
        return computeHull(clean, pts, attempted);
    } catch (const CGAL::Failure_exception& e) {
        fail("CGAL failed: ", e.what());
    } catch (const std::exception& e) {
        fail("hull failed: ", e.what());
    } catch (...) {
        fail("hull failed: ", "unknown exception");
    }
    Hull hull;
    try {
        hull.note = failure;
        if (attempted == HullKind::Planar || attempted == HullKind::Solid) {
            // Conservative: every distinct point, a superset of the hull's vertices (faces unknown).
            hull.note += "; vertices are all distinct points";
            hull.kind = attempted;
            hull.vertices.reserve(pts.size());
            for (const Point3& p : pts) hull.vertices.push_back(toVec3(p));
        }
    } catch (...) {  // out of memory while falling back
        hull = Hull{};
    }
    return hull;
}

}  // namespace frugal
