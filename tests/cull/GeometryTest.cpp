// minimalSphere, convexHull and hullKindName (cull/Hull.cpp, the CGAL wrapper). The checks here are
// brute force and CGAL-free: hull vertices must be input points, every input point must lie inside
// the hull and the sphere, and the sphere must be minimal (points on its boundary, known radii).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "TestSupport.h"
#include "cull/Geometry.h"

namespace frugal {
namespace {

using Points = std::vector<glm::vec3>;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

struct Vec3Less {
    bool operator()(const glm::vec3& a, const glm::vec3& b) const {
        return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
    }
};
using PointSet = std::set<glm::vec3, Vec3Less>;

PointSet asSet(const Points& points) { return PointSet(points.begin(), points.end()); }

Points scaled(Points points, float factor) {
    for (glm::vec3& p : points) p *= factor;
    return points;
}

// The 8 corners of the box [lo, hi].
Points boxCorners(const glm::vec3& lo, const glm::vec3& hi) {
    Points corners;
    for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    return corners;
}

// Cube corners [0.5, 1.5]x[1.5, 2.5]x[2.5, 3.5] (centre (1, 2, 3)) followed by `interior` points
// strictly inside, in a fixed pseudo-random order.
Points cubeWithInterior(int interior, unsigned seed = 1) {
    Points points = boxCorners({0.5f, 1.5f, 2.5f}, {1.5f, 2.5f, 3.5f});
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-0.49f, 0.49f);
    for (int i = 0; i < interior; ++i) points.emplace_back(1.0f + u(rng), 2.0f + u(rng), 3.0f + u(rng));
    std::shuffle(points.begin(), points.end(), rng);
    return points;
}

// `n` points on the unit sphere (as float): every one is a vertex of their hull.
Points sphereSurface(int n, unsigned seed = 7) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g;
    Points points;
    while (static_cast<int>(points.size()) < n) {
        glm::dvec3 d(g(rng), g(rng), g(rng));
        if (glm::length(d) < 1e-3) continue;
        points.emplace_back(glm::normalize(d));
    }
    return points;
}

// Every vertex is an input point, and no vertex is listed twice.
void expectVerticesAreInputPoints(const Hull& hull, const Points& input) {
    const PointSet in = asSet(input);
    for (const glm::vec3& v : hull.vertices) {
        EXPECT_TRUE(in.count(v)) << "hull vertex (" << v.x << ", " << v.y << ", " << v.z << ") is not an input point";
    }
    EXPECT_EQ(asSet(hull.vertices).size(), hull.vertices.size()) << "a hull vertex is listed twice";
}

// Every finite input point passes the plain double test the header promises.
void expectSphereEncloses(const Sphere& s, const Points& input) {
    ASSERT_TRUE(std::isfinite(s.radius));
    for (const glm::vec3& p : input) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
        const double d = glm::length(glm::dvec3(p) - s.center);
        ASSERT_LE(d, s.radius) << "point (" << p.x << ", " << p.y << ", " << p.z << ") is outside the sphere";
    }
}

// A closed triangulated surface of genus 0 has F = 2V - 4 (Euler: V - E + F = 2, 3F = 2E).
void expectEuler(const Hull& hull) {
    ASSERT_EQ(hull.kind, HullKind::Solid);
    EXPECT_EQ(hull.faces, 2 * hull.vertices.size() - 4);
}

// The support function of the hull's vertices equals that of the input in `directions` random
// directions: no extreme point is missing from the hull.
void expectSameSupport(const Hull& hull, const Points& input, int directions = 200) {
    std::mt19937 rng(99);
    std::normal_distribution<double> g;
    for (int i = 0; i < directions; ++i) {
        const glm::dvec3 d(g(rng), g(rng), g(rng));
        double inMax = -std::numeric_limits<double>::infinity(), hullMax = inMax;
        for (const glm::vec3& p : input) inMax = std::max(inMax, glm::dot(d, glm::dvec3(p)));
        for (const glm::vec3& p : hull.vertices) hullMax = std::max(hullMax, glm::dot(d, glm::dvec3(p)));
        ASSERT_EQ(hullMax, inMax) << "direction " << i;
    }
}

// Brute-force facets of the hull's vertices (for points in general position): the triangles of
// vertices with every other vertex on one side. Checks that their number is hull.faces, that every
// vertex is on one (so it is extreme), and that every input point is inside all of them.
void expectInsideBruteForceHull(const Hull& hull, const Points& input, double tolerance) {
    const std::vector<glm::dvec3> v(hull.vertices.begin(), hull.vertices.end());
    const std::size_t n = v.size();
    std::vector<bool> onFacet(n, false);
    std::size_t facets = 0;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = i + 1; j < n; ++j) {
            for (std::size_t k = j + 1; k < n; ++k) {
                glm::dvec3 normal = glm::cross(v[j] - v[i], v[k] - v[i]);
                int below = 0, above = 0;
                for (std::size_t m = 0; m < n; ++m) {
                    const double h = glm::dot(v[m] - v[i], normal);
                    below += h < -tolerance;
                    above += h > tolerance;
                }
                if (below != 0 && above != 0) continue;
                if (above != 0) normal = -normal;  // outward
                ++facets;
                onFacet[i] = onFacet[j] = onFacet[k] = true;
                for (const glm::vec3& p : input) {
                    ASSERT_LE(glm::dot(glm::dvec3(p) - v[i], normal), tolerance)
                        << "input point (" << p.x << ", " << p.y << ", " << p.z << ") is outside the hull";
                }
            }
        }
    }
    EXPECT_EQ(facets, hull.faces);
    for (std::size_t i = 0; i < n; ++i) EXPECT_TRUE(onFacet[i]) << "hull vertex " << i << " is not extreme";
}

TEST(GeometryTest, HullKindNames) {
    EXPECT_STREQ(hullKindName(HullKind::Empty), "empty");
    EXPECT_STREQ(hullKindName(HullKind::Point), "point");
    EXPECT_STREQ(hullKindName(HullKind::Segment), "segment");
    EXPECT_STREQ(hullKindName(HullKind::Planar), "planar");
    EXPECT_STREQ(hullKindName(HullKind::Solid), "solid");
}

TEST(GeometryTest, CubeWithInteriorPoints) {
    const Points points = cubeWithInterior(200);
    const Hull hull = convexHull(points);
    EXPECT_EQ(hull.kind, HullKind::Solid);
    EXPECT_EQ(hull.faces, 12u);
    EXPECT_EQ(asSet(hull.vertices), asSet(boxCorners({0.5f, 1.5f, 2.5f}, {1.5f, 2.5f, 3.5f})));
    EXPECT_EQ(hull.vertices.size(), 8u);
    EXPECT_EQ(hull.note, "");

    const Sphere s = minimalSphere(points);
    EXPECT_NEAR(s.center.x, 1.0, 1e-12);
    EXPECT_NEAR(s.center.y, 2.0, 1e-12);
    EXPECT_NEAR(s.center.z, 3.0, 1e-12);
    const double halfDiagonal = 0.5 * std::sqrt(3.0);
    EXPECT_NEAR(s.radius, halfDiagonal, 1e-9 * halfDiagonal);
    expectSphereEncloses(s, points);
}

TEST(GeometryTest, RandomCloud) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Points points;
    for (int i = 0; i < 400; ++i) points.emplace_back(u(rng), 3.0f * u(rng) + 10.0f, 0.5f * u(rng));

    const Hull hull = convexHull(points);
    ASSERT_EQ(hull.kind, HullKind::Solid);
    EXPECT_GT(hull.vertices.size(), 8u);
    EXPECT_LT(hull.vertices.size(), points.size());
    expectVerticesAreInputPoints(hull, points);
    expectEuler(hull);
    expectSameSupport(hull, points);
    expectInsideBruteForceHull(hull, points, 1e-12);

    const Sphere s = minimalSphere(points);
    expectSphereEncloses(s, points);
    // Diameter D (farthest pair): a minimal sphere has D/2 <= r <= D*sqrt(3/8) (Jung's theorem).
    double diameter = 0.0;
    for (const glm::vec3& p : points) {
        for (const glm::vec3& q : points) diameter = std::max(diameter, glm::length(glm::dvec3(p) - glm::dvec3(q)));
    }
    EXPECT_GE(s.radius, 0.5 * diameter * (1.0 - 1e-12));
    EXPECT_LE(s.radius, diameter * std::sqrt(3.0 / 8.0));
    // Minimal: at least two input points lie on its boundary (relative 1e-9).
    int onBoundary = 0;
    for (const glm::vec3& p : points) onBoundary += glm::length(glm::dvec3(p) - s.center) >= s.radius * (1.0 - 1e-9);
    EXPECT_GE(onBoundary, 2);
}

TEST(GeometryTest, PointsOnASphereAreAllHullVertices) {
    const Points points = sphereSurface(300);
    const Hull hull = convexHull(points);
    ASSERT_EQ(hull.kind, HullKind::Solid);
    EXPECT_EQ(asSet(hull.vertices), asSet(points));
    expectEuler(hull);
    EXPECT_EQ(hull.faces, 596u);

    // The points surround the centre, so the minimal sphere is the unit sphere (up to float rounding).
    const Sphere s = minimalSphere(points);
    EXPECT_NEAR(glm::length(s.center), 0.0, 1e-6);
    EXPECT_NEAR(s.radius, 1.0, 1e-6);
    expectSphereEncloses(s, points);
}

TEST(GeometryTest, EmptyInput) {
    const Hull hull = convexHull({});
    EXPECT_EQ(hull.kind, HullKind::Empty);
    EXPECT_TRUE(hull.vertices.empty());
    EXPECT_EQ(hull.faces, 0u);
    EXPECT_FALSE(hull.note.empty());

    const Sphere s = minimalSphere({});
    EXPECT_EQ(s.center, glm::dvec3(0.0));
    EXPECT_EQ(s.radius, 0.0);
}

TEST(GeometryTest, OnePoint) {
    const Points points{{1.5f, -2.0f, 1e6f}};
    const Hull hull = convexHull(points);
    EXPECT_EQ(hull.kind, HullKind::Point);
    EXPECT_EQ(hull.vertices, points);
    EXPECT_EQ(hull.faces, 0u);

    const Sphere s = minimalSphere(points);
    EXPECT_EQ(s.center, glm::dvec3(points[0]));
    EXPECT_EQ(s.radius, 0.0);
}

TEST(GeometryTest, AllEqualPoints) {
    const Points points(7, glm::vec3(0.1f, 0.2f, 0.3f));
    const Hull hull = convexHull(points);
    EXPECT_EQ(hull.kind, HullKind::Point);
    EXPECT_EQ(hull.vertices, Points{points[0]});
    EXPECT_EQ(hull.faces, 0u);
    EXPECT_FALSE(hull.note.empty());

    const Sphere s = minimalSphere(points);
    EXPECT_EQ(s.center, glm::dvec3(points[0]));
    EXPECT_EQ(s.radius, 0.0);
    expectSphereEncloses(s, points);
}

TEST(GeometryTest, TwoPoints) {
    const Points points{{1.0f, 2.0f, 3.0f}, {4.0f, 6.0f, 3.0f}};
    const Hull hull = convexHull(points);
    EXPECT_EQ(hull.kind, HullKind::Segment);
    EXPECT_EQ(asSet(hull.vertices), asSet(points));
    EXPECT_EQ(hull.faces, 0u);

    const Sphere s = minimalSphere(points);
    EXPECT_NEAR(s.center.x, 2.5, 1e-12);
    EXPECT_NEAR(s.center.y, 4.0, 1e-12);
    EXPECT_NEAR(s.center.z, 3.0, 1e-12);
    EXPECT_NEAR(s.radius, 2.5, 2.5e-9);
    expectSphereEncloses(s, points);
}

// Exactly collinear in float: integer points a + t*d, in scrambled order, with duplicates.
Points collinearPoints() {
    Points points;
    for (int t : {3, 0, 7, 10, 3, 5, 1, 9, 10, 2}) points.emplace_back(5 + t, 5 - 2 * t, 5 + 3 * t);
    return points;
}

TEST(GeometryTest, CollinearPoints) {
    const Points points = collinearPoints();
    const Hull hull = convexHull(points);
    EXPECT_EQ(hull.kind, HullKind::Segment);
    EXPECT_EQ(asSet(hull.vertices), (PointSet{{5.0f, 5.0f, 5.0f}, {15.0f, -15.0f, 35.0f}}));
    EXPECT_EQ(hull.vertices.size(), 2u);
    EXPECT_EQ(hull.faces, 0u);
    EXPECT_NE(hull.note.find("collinear"), std::string::npos) << hull.note;

    const Sphere s = minimalSphere(points);
    EXPECT_NEAR(s.center.x, 10.0, 1e-9);
    EXPECT_NEAR(s.center.y, -5.0, 1e-9);
    EXPECT_NEAR(s.center.z, 20.0, 1e-9);
    const double half = 0.5 * std::sqrt(100.0 + 400.0 + 900.0);
    EXPECT_NEAR(s.radius, half, 1e-9 * half);
    expectSphereEncloses(s, points);
}

// Exactly coplanar in float: a square in the tilted plane z = x + 2y, with interior points and
// edge midpoints (which are not vertices).
Points coplanarSquare() {
    Points points;
    auto at = [&](int x, int y) { points.emplace_back(x, y, x + 2 * y); };
    for (int x = 0; x <= 8; ++x) {
        for (int y = 0; y <= 8; ++y) at(x, y);
    }
    std::shuffle(points.begin(), points.end(), std::mt19937(3));
    return points;
}

TEST(GeometryTest, CoplanarPoints) {
    const Points points = coplanarSquare();
    const Hull hull = convexHull(points);
    EXPECT_EQ(hull.kind, HullKind::Planar);
    EXPECT_EQ(asSet(hull.vertices), (PointSet{{0, 0, 0}, {8, 0, 8}, {0, 8, 16}, {8, 8, 24}}));
    EXPECT_EQ(hull.vertices.size(), 4u);
    EXPECT_EQ(hull.faces, 1u);
    EXPECT_NE(hull.note.find("coplanar"), std::string::npos) << hull.note;

    const Sphere s = minimalSphere(points);
    EXPECT_NEAR(s.center.x, 4.0, 1e-9);
    EXPECT_NEAR(s.center.y, 4.0, 1e-9);
    EXPECT_NEAR(s.center.z, 12.0, 1e-9);
    expectSphereEncloses(s, points);
}

TEST(GeometryTest, VerticalPlane) {
    // A rectangle with its interior in the plane x = 2, which projects onto a line in the xy and xz
    // planes: only the yz projection keeps it 2-D.
    Points points;
    for (int y = -3; y <= 3; ++y) {
        for (int z = 0; z <= 2; ++z) points.emplace_back(2.0f, float(y), float(z));
    }
    const Hull hull = convexHull(points);
    EXPECT_EQ(hull.kind, HullKind::Planar);
    EXPECT_EQ(asSet(hull.vertices), (PointSet{{2, -3, 0}, {2, 3, 0}, {2, -3, 2}, {2, 3, 2}}));
}

TEST(GeometryTest, ThreePoints) {
    const Points points{{0, 0, 0}, {1, 0, 0}, {0, 1, 1}};
    const Hull hull = convexHull(points);
    EXPECT_EQ(hull.kind, HullKind::Planar);
    EXPECT_EQ(asSet(hull.vertices), asSet(points));
    EXPECT_EQ(hull.vertices.size(), 3u);
    EXPECT_EQ(hull.faces, 1u);
    expectSphereEncloses(minimalSphere(points), points);
}

TEST(GeometryTest, Tetrahedron) {
    const Points points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const Hull hull = convexHull(points);
    EXPECT_EQ(hull.kind, HullKind::Solid);
    EXPECT_EQ(asSet(hull.vertices), asSet(points));
    EXPECT_EQ(hull.vertices.size(), 4u);
    EXPECT_EQ(hull.faces, 4u);
    EXPECT_EQ(hull.note, "");

    // Not the circumsphere (radius sqrt(3)/2): the sphere on the circumcircle of the face opposite
    // the origin is smaller and holds the origin too.
    const Sphere s = minimalSphere(points);
    const double r = std::sqrt(2.0 / 3.0);  // circumradius of the equilateral triangle with side sqrt(2)
    EXPECT_NEAR(s.radius, r, 1e-9 * r);
    EXPECT_NEAR(s.center.x, 1.0 / 3.0, 1e-9);
    expectSphereEncloses(s, points);
}

TEST(GeometryTest, NonFinitePointsAreIgnored) {
    Points points = cubeWithInterior(50);
    const Hull clean = convexHull(points);
    const Sphere cleanSphere = minimalSphere(points);
    for (const glm::vec3& bad : {glm::vec3(kNaN, 0, 0), glm::vec3(0, kInf, 0), glm::vec3(0, 0, -kInf),
                                 glm::vec3(kNaN, kNaN, kNaN), glm::vec3(1e30f, -kInf, kNaN)}) {
        points.insert(points.begin() + 3, bad);
        points.push_back(bad);
    }
    const Hull hull = convexHull(points);
    EXPECT_EQ(hull.kind, HullKind::Solid);
    EXPECT_EQ(asSet(hull.vertices), asSet(clean.vertices));
    EXPECT_EQ(hull.faces, 12u);
    EXPECT_NE(hull.note.find("non-finite"), std::string::npos) << hull.note;

    const Sphere s = minimalSphere(points);
    EXPECT_TRUE(std::isfinite(s.center.x) && std::isfinite(s.center.y) && std::isfinite(s.center.z));
    EXPECT_EQ(s.center, cleanSphere.center);
    EXPECT_EQ(s.radius, cleanSphere.radius);
    expectSphereEncloses(s, points);

    // Nothing finite at all: empty.
    const Points allBad{{kNaN, 0, 0}, {kInf, 1, 2}};
    EXPECT_EQ(convexHull(allBad).kind, HullKind::Empty);
    EXPECT_EQ(minimalSphere(allBad).radius, 0.0);
    EXPECT_EQ(minimalSphere(allBad).center, glm::dvec3(0.0));
    // One finite point among them: a point.
    const Points oneGood{{kNaN, 0, 0}, {4, 5, 6}, {kInf, 1, 2}};
    EXPECT_EQ(convexHull(oneGood).kind, HullKind::Point);
    EXPECT_EQ(convexHull(oneGood).vertices, Points{glm::vec3(4, 5, 6)});
}

TEST(GeometryTest, TinyAndHugeCoordinates) {
    // General position sets keep their hull under scaling by 1e-6 and 1e6 (not exact in float).
    for (float factor : {1e-6f, 1e6f}) {
        SCOPED_TRACE(factor);
        const Points cube = scaled(cubeWithInterior(100), factor);
        const Hull cubeHull = convexHull(cube);
        EXPECT_EQ(cubeHull.kind, HullKind::Solid);
        EXPECT_EQ(cubeHull.vertices.size(), 8u);
        EXPECT_EQ(cubeHull.faces, 12u);
        expectVerticesAreInputPoints(cubeHull, cube);
        const Sphere cubeSphere = minimalSphere(cube);
        EXPECT_NEAR(cubeSphere.radius, 0.5 * std::sqrt(3.0) * factor, 1e-6 * factor);
        expectSphereEncloses(cubeSphere, cube);

        const Points sphere = scaled(sphereSurface(200), factor);
        const Hull sphereHull = convexHull(sphere);
        EXPECT_EQ(sphereHull.vertices.size(), 200u);
        expectEuler(sphereHull);
        expectVerticesAreInputPoints(sphereHull, sphere);
        expectSphereEncloses(minimalSphere(sphere), sphere);
    }
    // Degenerate sets stay exactly degenerate only under power-of-two scaling (2^-20 ≈ 1e-6, 2^20 ≈ 1e6).
    for (float factor : {std::ldexp(1.0f, -20), std::ldexp(1.0f, 20)}) {
        SCOPED_TRACE(factor);
        const Hull segment = convexHull(scaled(collinearPoints(), factor));
        EXPECT_EQ(segment.kind, HullKind::Segment);
        EXPECT_EQ(segment.vertices.size(), 2u);
        const Hull planar = convexHull(scaled(coplanarSquare(), factor));
        EXPECT_EQ(planar.kind, HullKind::Planar);
        EXPECT_EQ(planar.vertices.size(), 4u);
        const Points two = scaled({{1, 2, 3}, {1, 2, 4}}, factor);
        EXPECT_EQ(convexHull(two).kind, HullKind::Segment);
        expectSphereEncloses(minimalSphere(two), two);
    }
}

TEST(GeometryTest, NearlyCoplanarPointsDoNotBreak) {
    // A 1 x 1 grid in z = 0 with a few points lifted by 1e-12 (relative to the extent): exact
    // predicates see a very thin solid; either verdict is fine, but it must be consistent.
    for (float lift : {1e-12f, -1e-12f}) {
        Points points;
        for (int x = 0; x <= 10; ++x) {
            for (int y = 0; y <= 10; ++y) points.emplace_back(0.1f * float(x), 0.1f * float(y), 0.0f);
        }
        points[17].z = lift;
        points[60].z = -lift * 0.5f;
        const Hull hull = convexHull(points);
        ASSERT_TRUE(hull.kind == HullKind::Planar || hull.kind == HullKind::Solid) << hullKindName(hull.kind);
        expectVerticesAreInputPoints(hull, points);
        if (hull.kind == HullKind::Solid) expectEuler(hull);
        EXPECT_GE(hull.vertices.size(), 4u);
        expectSphereEncloses(minimalSphere(points), points);
    }
    // A tilted plane with one point nudged off it by one float ulp.
    Points points = coplanarSquare();
    points[10].z = std::nextafter(points[10].z, 1e9f);
    points[40].z = std::nextafter(points[40].z, -1e9f);
    const Hull hull = convexHull(points);
    ASSERT_TRUE(hull.kind == HullKind::Planar || hull.kind == HullKind::Solid) << hullKindName(hull.kind);
    expectVerticesAreInputPoints(hull, points);
    if (hull.kind == HullKind::Solid) expectEuler(hull);
    expectSphereEncloses(minimalSphere(points), points);
    // Nearly collinear: a segment with one point off the line by a float ulp.
    Points line = collinearPoints();
    line[2].y = std::nextafter(line[2].y, 1e9f);
    const Hull thin = convexHull(line);
    ASSERT_TRUE(thin.kind == HullKind::Planar || thin.kind == HullKind::Segment) << hullKindName(thin.kind);
    expectVerticesAreInputPoints(thin, line);
}

TEST(GeometryTest, DuplicatesDoNotMatter) {
    Points points = cubeWithInterior(30);
    const Hull once = convexHull(points);
    const Points copy = points;
    points.insert(points.end(), copy.begin(), copy.end());
    points.insert(points.end(), copy.rbegin(), copy.rend());
    const Hull thrice = convexHull(points);
    EXPECT_EQ(asSet(thrice.vertices), asSet(once.vertices));
    EXPECT_EQ(thrice.vertices.size(), 8u);
    EXPECT_EQ(thrice.faces, once.faces);
    // -0 and +0 are one point.
    const Hull zeros = convexHull(Points{{0.0f, 0.0f, 0.0f}, {-0.0f, 0.0f, -0.0f}});
    EXPECT_EQ(zeros.kind, HullKind::Point);
}

// The Stanford bunny's vertices (glmark2-data), read directly from the OBJ's "v" lines.
Points bunnyVertices() {
    std::ifstream in(FRUGAL_BUNNY_OBJ);
    Points points;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("v ", 0) != 0) continue;
        std::istringstream fields(line.substr(2));
        glm::vec3 p;
        if (fields >> p.x >> p.y >> p.z) points.push_back(p);
    }
    return points;
}

TEST(GeometryTest, StanfordBunny) {
    const Points points = bunnyVertices();
    if (points.empty()) FRUGAL_SKIP_IF_MISSING(FRUGAL_BUNNY_OBJ << " (glmark2-data)");
    ASSERT_EQ(points.size(), 34835u);

    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    const Hull hull = convexHull(points);
    const auto t1 = Clock::now();
    const Sphere s = minimalSphere(points);
    const auto t2 = Clock::now();
    std::printf("bunny: %zu points: convexHull %.2f ms (%zu vertices, %zu faces), minimalSphere %.2f ms\n",
                points.size(), std::chrono::duration<double, std::milli>(t1 - t0).count(), hull.vertices.size(),
                hull.faces, std::chrono::duration<double, std::milli>(t2 - t1).count());

    ASSERT_EQ(hull.kind, HullKind::Solid);
    EXPECT_GT(hull.vertices.size(), 100u);
    expectVerticesAreInputPoints(hull, points);
    expectEuler(hull);
    expectSameSupport(hull, points, 500);
    expectSphereEncloses(s, points);
    int onBoundary = 0;
    for (const glm::vec3& p : points) onBoundary += glm::length(glm::dvec3(p) - s.center) >= s.radius * (1.0 - 1e-9);
    EXPECT_GE(onBoundary, 2);
}

}  // namespace
}  // namespace frugal
