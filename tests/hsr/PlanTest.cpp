// Polygons (src/hsr/Polygons.h) and the hidden-surface plans (src/hsr/Plan.h): the grouping on the
// built-in scenes and on hand-made cases, and each case of Plan.h's argument for when adaptive equals
// the z-buffer, rendered on the software reference: the paper's cubes and the dominoes,
// interpenetrating polygons (depthsort wrong, adaptive right), a polygon crossing the eye plane
// (everything flagged), and exact depth ties (where the runs' submission order keeps adaptive equal).
#include <algorithm>
#include <iostream>
#include <set>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "TestSupport.h"
#include "hsr/Flags.h"
#include "hsr/Order.h"
#include "hsr/Plan.h"
#include "pipeline/Frame.h"
#include "pipeline/SceneRenderer.h"
#include "scene/Load.h"
#include "software/SoftwareBackend.h"

namespace frugal::test {
namespace {

using hsr::Mode;

// A mesh from positions and triangles (indices into the positions), normals +z.
Mesh indexedMesh(std::vector<glm::vec3> positions, std::vector<std::uint32_t> indices) {
    Mesh mesh;
    mesh.normals.assign(positions.size(), glm::vec3(0, 0, 1));
    mesh.positions = std::move(positions);
    mesh.indices = std::move(indices);
    for (std::uint32_t t = 0; t < mesh.indices.size() / 3; ++t) mesh.triangleSource.push_back(t);
    return mesh;
}

TEST(HsrPolygons, CubesAreSixQuadsEach) {
    for (const char* name : {"builtin:cubes", "builtin:dominoes?polygons=120"}) {
        Result<Scene> scene = loadScene(name);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        const hsr::Planner planner(*scene);
        EXPECT_EQ(planner.polygonCount(), 3 * scene->triangleCount() / 6) << name;  // two triangles a quad
        for (std::size_t m = 0; m < scene->meshes.size(); ++m)
            EXPECT_EQ(planner.polygons(int(m)).count, scene->meshes[m].triangleCount() / 2) << name << " mesh " << m;
    }
    Result<Scene> cubes = loadScene("builtin:cubes");
    ASSERT_TRUE(cubes.ok());
    EXPECT_EQ(hsr::Planner(*cubes).polygonCount(), 168u);  // the paper's 28 cubes
}

TEST(HsrPolygons, ConvexFanIsOnePolygon) {
    // A regular hexagon as a fan of 4 triangles, with the corners duplicated per triangle (as a mesh
    // with flat normals or seams has them): one polygon.
    std::vector<glm::vec3> corners;
    for (int k = 0; k < 6; ++k) corners.emplace_back(std::cos(float(k) * 1.0471976f), std::sin(float(k) * 1.0471976f), 0.0f);
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> indices;
    for (int t = 0; t < 4; ++t)
        for (const glm::vec3& p : {corners[0], corners[std::size_t(t + 1)], corners[std::size_t(t + 2)]}) {
            indices.push_back(std::uint32_t(positions.size()));
            positions.push_back(p);
        }
    const hsr::MeshPolygons polygons = hsr::groupPolygons(indexedMesh(positions, indices));
    EXPECT_EQ(polygons.count, 1u);
    EXPECT_EQ(polygons.polygonOf, std::vector<std::uint32_t>(4, 0));
}

TEST(HsrPolygons, WhatIsNotOneConvexPlanarTilingFallsApart) {
    // An L: a 2×1 rectangle of three triangles and a triangle on its top left edge, all coplanar and
    // joined: not convex (hull area 3, triangles 2.5), so four polygons; the rectangle alone is one.
    const std::vector<glm::vec3> l{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, {1, 1, 0}, {1, 2, 0}};
    EXPECT_EQ(hsr::groupPolygons(indexedMesh(l, {0, 1, 2, 0, 2, 4, 0, 4, 3, 3, 4, 5})).count, 4u);
    EXPECT_EQ(hsr::groupPolygons(indexedMesh(l, {0, 1, 2, 0, 2, 4, 0, 4, 3})).count, 1u);
    // Two triangles on a shared edge at a right angle: two polygons.
    EXPECT_EQ(hsr::groupPolygons(indexedMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, -1}}, {0, 1, 2, 1, 0, 3})).count, 2u);
    // Two coplanar triangles on a shared edge, folded onto one side (opposite facing): two polygons.
    EXPECT_EQ(hsr::groupPolygons(indexedMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5f, 1, 0}}, {0, 1, 2, 1, 0, 3})).count, 2u);
    // A square: one polygon; the same square nearly flat but bent by 1e-3: two.
    EXPECT_EQ(hsr::groupPolygons(indexedMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {0, 1, 2, 0, 2, 3})).count, 1u);
    EXPECT_EQ(hsr::groupPolygons(indexedMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 1e-3f}}, {0, 1, 2, 0, 2, 3})).count, 2u);
}

// A box from its 8 corners as 12 triangles, counter-clockwise seen from outside; `dent` pushes the
// +z face's centre in by that much (then 4 triangles a face there: not convex when dent > 0).
Mesh box(float dent = 0.0f) {
    std::vector<glm::vec3> p;
    for (int i = 0; i < 8; ++i) p.emplace_back(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f);
    std::vector<std::uint32_t> quads{0, 2, 3, 1,  4, 5, 7, 6,  0, 1, 5, 4,  2, 6, 7, 3,  0, 4, 6, 2,  1, 3, 7, 5};
    std::vector<std::uint32_t> indices;
    for (std::size_t q = 0; q < quads.size(); q += 4) {
        const std::uint32_t a = quads[q], b = quads[q + 1], c = quads[q + 2], d = quads[q + 3];
        if (q == 4 && dent != 0.0f) {  // the +z face as a fan around a centre pushed inwards
            p.emplace_back(0.0f, 0.0f, 1.0f - dent);
            const std::uint32_t m = std::uint32_t(p.size() - 1);
            for (const auto& [u, v] : {std::pair{a, b}, {b, c}, {c, d}, {d, a}}) indices.insert(indices.end(), {u, v, m});
        } else {
            indices.insert(indices.end(), {a, b, c, a, c, d});
        }
    }
    return indexedMesh(p, indices);
}

TEST(HsrPolygons, ConvexSolids) {
    EXPECT_TRUE(hsr::groupPolygons(box()).convexSolid);
    EXPECT_FALSE(hsr::groupPolygons(box(0.1f)).convexSolid);     // dented
    EXPECT_TRUE(hsr::groupPolygons(box(-0.0f)).convexSolid);
    Mesh open = box();
    open.indices.resize(open.indices.size() - 6);                 // one face missing
    open.triangleSource.resize(open.indices.size() / 3);
    EXPECT_FALSE(hsr::groupPolygons(open).convexSolid);
    Mesh two = box();                                             // two boxes in one mesh, apart
    const Mesh other = box();
    const std::uint32_t base = std::uint32_t(two.positions.size());
    for (const glm::vec3& q : other.positions) two.positions.push_back(q + glm::vec3(5, 0, 0));
    for (std::uint32_t i : other.indices) two.indices.push_back(base + i);
    two.normals.resize(two.positions.size(), glm::vec3(0, 0, 1));
    two.triangleSource.resize(two.indices.size() / 3);
    EXPECT_FALSE(hsr::groupPolygons(two).convexSolid);
    for (const char* name : {"builtin:cubes", "builtin:dominoes?polygons=60"}) {
        Result<Scene> scene = loadScene(name);
        ASSERT_TRUE(scene.ok());
        for (const Mesh& mesh : scene->meshes) {
            if (mesh.triangleCount() != 12) continue;  // the dominoes' floor is not a solid
            EXPECT_TRUE(hsr::groupPolygons(mesh).convexSolid) << name << " " << mesh.name;
        }
    }
    Result<Scene> bunny = loadScene(FRUGAL_BUNNY_OBJ);
    ASSERT_TRUE(bunny.ok()) << bunny.error().message;
    EXPECT_FALSE(hsr::groupPolygons(bunny->meshes[0]).convexSolid);
}

// Renders `list` (or the full list) on the software backend with ids.
struct Rendered {
    Buffers zbuffer, depthsort, adaptive;
    hsr::PlanStats stats[3];
};

Rendered renderModes(const Scene& scene, const FrameParams& params, const std::vector<glm::mat4>& world, int width,
                     int height) {
    Rendered out;
    std::unique_ptr<Backend> backend = makeSoftwareBackend();
    const TargetHandle target = backend->createTarget(width, height);
    Result<SceneRenderer> renderer = SceneRenderer::create(*backend, scene);
    EXPECT_TRUE(renderer.ok());
    if (!renderer) return out;
    const hsr::Planner planner(scene);
    Buffers* images[3] = {&out.zbuffer, &out.depthsort, &out.adaptive};
    const Mode modes[3] = {Mode::ZBuffer, Mode::DepthSort, Mode::Adaptive};
    for (int m = 0; m < 3; ++m) {
        const DrawList list = planner.plan(modes[m], params, world, renderer->fullList(), width, height, &out.stats[m]);
        renderer->renderFrame(target, width, height, params, world, glm::vec4(0.0f), list);
        *images[m] = backend->readBack(target);
    }
    return out;
}

std::size_t differingPixels(const Buffers& a, const Buffers& b) {
    std::size_t count = 0;
    for (std::size_t p = 0; p < a.ids.size(); ++p)
        count += (a.ids[p] != b.ids[p] || !std::equal(a.rgba.begin() + std::ptrdiff_t(4 * p),
                                                       a.rgba.begin() + std::ptrdiff_t(4 * p + 4),
                                                       b.rgba.begin() + std::ptrdiff_t(4 * p)))
                     ? 1
                     : 0;
    return count;
}

TEST(HsrPlan, AdaptiveEqualsTheZBufferOnThePapersCubesAndTheDominoes) {
    for (const char* name : {"builtin:cubes", "builtin:dominoes?polygons=804"}) {
        Result<Scene> scene = loadScene(name);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        for (const double time : {0.0, 0.7, 1.9, 4.2}) {
            Result<FrameSetup> setup = setUpFrame(*scene, {}, time, 240, 320, true);
            ASSERT_TRUE(setup.ok()) << setup.error().message;
            const Rendered r = renderModes(*scene, setup->params, setup->world, 240, 320);
            EXPECT_EQ(differingPixels(r.adaptive, r.zbuffer), 0u) << name << " t=" << time;
            EXPECT_EQ(r.adaptive.ids, r.zbuffer.ids) << name << " t=" << time;
            EXPECT_GT(r.stats[2].polygons, 0u);
            EXPECT_LE(r.stats[2].flagged, r.stats[2].polygons);
            EXPECT_EQ(r.stats[1].flagged, 0u);
        }
    }
}

// Blended surfaces are drawn last with the z-buffer, and every polygon that meets one is flagged
// (Plan.h): adaptive still equals the z-buffer; masked ones change nothing in the argument.
TEST(HsrPlan, AdaptiveEqualsTheZBufferWithBlendedAndMaskedSurfaces) {
    for (const char* name : {"builtin:cubes", "builtin:dominoes?polygons=804"}) {
        Result<Scene> scene = loadScene(name);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        test::addAlpha(*scene);
        for (const double time : {0.0, 1.9}) {
            Result<FrameSetup> setup = setUpFrame(*scene, {}, time, 240, 320, true);
            ASSERT_TRUE(setup.ok()) << setup.error().message;
            const Rendered r = renderModes(*scene, setup->params, setup->world, 240, 320);
            EXPECT_EQ(differingPixels(r.adaptive, r.zbuffer), 0u) << name << " t=" << time;
            EXPECT_EQ(r.adaptive.ids, r.zbuffer.ids) << name << " t=" << time;
            // depthsort z-buffers what meets a blended polygon, and nothing else.
            EXPECT_GT(r.stats[1].flagged, 0u) << name;
            EXPECT_LT(r.stats[1].flagged, r.stats[1].polygons) << name;
        }
    }
    // A small opaque quad well in front of a blended one: their z ranges are apart, yet the opaque
    // one must write its depth, or the blend, drawn last, would cover it.
    Scene scene;
    Mesh quad;
    quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    Material glass;
    glass.alphaMode = AlphaMode::Blend;
    glass.baseColorFactor = {0.2f, 0.4f, 0.9f, 0.5f};
    for (const Material& material : {Material{}, glass}) {
        quad.material = *scene.addMaterial(material);
        (void)scene.addMesh(quad);
    }
    (void)scene.addInstance(0, glm::scale(glm::mat4(1.0f), glm::vec3(0.5f)));
    (void)scene.addInstance(1, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -2)));
    scene.buildInstances();
    Camera camera;
    camera.eye = glm::vec3(0.2f, 0.1f, 4.0f);
    camera.target = glm::vec3(0.0f);
    Result<FrameSetup> setup = setUpFrame(scene, camera, 0.0, 64, 48, true);
    ASSERT_TRUE(setup.ok()) << setup.error().message;
    const Rendered r = renderModes(scene, setup->params, setup->world, 64, 48);
    EXPECT_EQ(differingPixels(r.adaptive, r.zbuffer), 0u);
    EXPECT_EQ(differingPixels(r.depthsort, r.zbuffer), 0u);
    EXPECT_EQ(r.stats[2].flagged, r.stats[2].polygons) << "every polygon meets the blended one";
}

// The list drawn backwards, triangle by triangle: where it and the list disagree, two fragments tie
// for the nearest depth (with ids on, a unique nearest fragment wins in every order).
DrawList reversed(const DrawList& list) {
    DrawList out;
    for (auto command = list.rbegin(); command != list.rend(); ++command) {
        DrawCommand back{command->instance, {}, command->depth};
        for (auto range = command->ranges.rbegin(); range != command->ranges.rend(); ++range)
            for (std::uint32_t t = range->firstTriangle + range->triangleCount; t-- > range->firstTriangle;)
                back.ranges.push_back(IndexRange{t, 1});
        out.push_back(std::move(back));
    }
    return out;
}

TEST(HsrPlan, AdaptiveDiffersFromTheZBufferOnlyAtDepthTies) {
    // Plan.h: both adaptive modes equal the z-buffer wherever the nearest fragment is unique. Over
    // 30 frames of the paper's cubes (which interpenetrate), every pixel where they differ from the
    // z-buffer is one where the z-buffer itself depends on the order (a tie).
    Result<Scene> scene = loadScene("builtin:cubes");
    ASSERT_TRUE(scene.ok());
    std::unique_ptr<Backend> backend = makeSoftwareBackend();
    const int width = 240, height = 320;
    const TargetHandle target = backend->createTarget(width, height);
    Result<SceneRenderer> renderer = SceneRenderer::create(*backend, *scene);
    ASSERT_TRUE(renderer.ok());
    const hsr::Planner planner(*scene);
    std::size_t ties = 0, differing = 0;
    for (int frame = 0; frame < 30; ++frame) {
        Result<FrameSetup> setup = setUpFrame(*scene, {}, frame / 30.0, width, height, true);
        ASSERT_TRUE(setup.ok());
        const auto draw = [&](const DrawList& list) {
            renderer->renderFrame(target, width, height, setup->params, setup->world, glm::vec4(0.0f), list);
            return backend->readBack(target);
        };
        const Buffers forward = draw(renderer->fullList()), backward = draw(reversed(renderer->fullList()));
        for (Mode mode : {Mode::Adaptive, Mode::AdaptiveConvex}) {
            const Buffers image = draw(planner.plan(mode, setup->params, setup->world, renderer->fullList(), width, height));
            for (std::size_t p = 0; p < image.ids.size(); ++p) {
                ties += forward.ids[p] != backward.ids[p] ? 1 : 0;
                if (image.ids[p] == forward.ids[p]) continue;
                ++differing;
                EXPECT_NE(forward.ids[p], backward.ids[p]) << toString(mode) << " frame " << frame << " pixel " << p;
            }
        }
    }
    std::cout << "builtin:cubes, 30 frames: " << ties / 2 << " tie pixels, " << differing
              << " pixels where an adaptive mode differs from the z-buffer\n";
}

// Two triangles meeting at an angle and crossing each other (each in front of the other on one
// side of the line where they meet), seen from +z by an orthographic camera.
Scene crossingTriangles() {
    return oneMeshScene(looseTriangles({{-1, -1, -1.5f}, {1, -1, -0.5f}, {0, 1, -1.0f},    // leans back to the left
                                        {-1, -1, -0.5f}, {1, -1, -1.5f}, {0, 0.8f, -1.0f}}),  // leans back to the right
                        Material{"", glm::vec4(1.0f), -1, true});
}

FrameParams orthoFrame() {
    FrameParams params;
    params.projection = glm::ortho(-1.2f, 1.2f, -1.2f, 1.2f, 0.1f, 4.0f);
    params.writeIds = true;
    return params;
}

TEST(HsrPlan, InterpenetratingPolygonsAreFlaggedAndZBuffered) {
    const Scene scene = crossingTriangles();
    const std::vector<glm::mat4> world = scene.worldTransforms(0.0);
    const Rendered r = renderModes(scene, orthoFrame(), world, 96, 96);
    EXPECT_EQ(r.stats[2].flagged, 2u);                              // both flagged
    EXPECT_EQ(differingPixels(r.adaptive, r.zbuffer), 0u);          // so exact
    EXPECT_GT(differingPixels(r.depthsort, r.zbuffer), 100u);       // the painter cannot be
}

TEST(HsrPlan, ApartPolygonsAreDrawnWithoutTheDepthTest) {
    // Three quads one behind another, each smaller than the one behind, submitted front first:
    // boxes overlap but depth ranges are apart, so nothing is flagged, the order is back to front
    // and the image equals the z-buffer's; the depth image holds nothing (no depth written).
    std::vector<glm::vec3> positions;
    for (int k = 0; k < 3; ++k) {
        const float s = 0.4f + 0.3f * float(k), z = -1.0f - 0.5f * float(k);
        for (const glm::vec3& p : {glm::vec3(-s, -s, z), glm::vec3(s, -s, z), glm::vec3(s, s, z), glm::vec3(-s, -s, z),
                                   glm::vec3(s, s, z), glm::vec3(-s, s, z)})
            positions.push_back(p);
    }
    Scene scene = oneMeshScene(looseTriangles(positions));
    const std::vector<glm::mat4> world = scene.worldTransforms(0.0);
    const Rendered r = renderModes(scene, orthoFrame(), world, 64, 64);
    EXPECT_EQ(r.stats[2].polygons, 3u);  // the halves of a quad are joined through their positions
    EXPECT_EQ(r.stats[2].flagged, 0u);
    EXPECT_EQ(differingPixels(r.adaptive, r.zbuffer), 0u);
    EXPECT_EQ(differingPixels(r.depthsort, r.zbuffer), 0u);
    const std::uint32_t far = 0xFFFFFFu;
    EXPECT_TRUE(std::all_of(r.depthsort.depth.begin(), r.depthsort.depth.end(), [&](std::uint32_t d) { return d == far; }));
}

TEST(HsrPlan, APolygonCrossingTheEyePlaneFlagsEverything) {
    // A perspective camera; one triangle reaches behind the eye, the others stand apart in front.
    Scene scene = oneMeshScene(looseTriangles({{-2, -2, -3}, {-1, -2, -3}, {-1.5f, -1, -3},          // apart
                                               {1, 1, -6}, {2, 1, -6}, {1.5f, 2, -6},                // apart
                                               {-0.5f, -0.5f, 1}, {0.5f, -0.5f, -4}, {0, 0.5f, -4}}),  // behind the eye
                               Material{"", glm::vec4(1.0f), -1, true});
    FrameParams params;
    params.projection = glm::perspective(1.2f, 1.0f, 0.1f, 20.0f);
    params.writeIds = true;
    const std::vector<glm::mat4> world = scene.worldTransforms(0.0);
    const Rendered r = renderModes(scene, params, world, 64, 64);
    EXPECT_EQ(r.stats[2].polygons, 3u);
    EXPECT_EQ(r.stats[2].flagged, 3u);
    EXPECT_EQ(differingPixels(r.adaptive, r.zbuffer), 0u);
}

TEST(HsrPlan, DepthTiesResolveInSubmissionOrderWithinARunOfFlaggedPolygons) {
    // Two coplanar triangles facing the camera at one depth, overlapping; the first submitted has
    // the larger extent. They tie at every shared pixel: the z-buffer keeps the first submitted.
    // Both are flagged and form one run, drawn in submission order: adaptive keeps it too. Depth
    // sort draws the later one over the earlier (equal average depth, stable order), so it differs
    // exactly at the shared pixels.
    const Scene scene = oneMeshScene(looseTriangles({{-1, -1, -2}, {1, -1, -2}, {0, 1, -2},  //
                                                     {-0.5f, -0.8f, -2}, {0.6f, -0.8f, -2}, {0, 0.4f, -2}}));
    const std::vector<glm::mat4> world = scene.worldTransforms(0.0);
    const Rendered r = renderModes(scene, orthoFrame(), world, 64, 64);
    EXPECT_EQ(r.stats[2].flagged, 2u);
    EXPECT_EQ(differingPixels(r.adaptive, r.zbuffer), 0u);
    std::size_t second = 0;
    for (std::uint32_t id : r.zbuffer.ids) second += id == 2 ? 1 : 0;
    EXPECT_EQ(second, 0u);  // the second triangle lies inside the first: hidden by the tie
    std::size_t shown = 0;
    for (std::uint32_t id : r.depthsort.ids) shown += id == 2 ? 1 : 0;
    EXPECT_GT(shown, 0u);
    EXPECT_EQ(differingPixels(r.depthsort, r.zbuffer), shown);
}

TEST(HsrPlan, ZBufferModeIsTheListItself) {
    Result<Scene> scene = loadScene("builtin:cubes");
    ASSERT_TRUE(scene.ok());
    Result<FrameSetup> setup = setUpFrame(*scene, {}, 0.0, 240, 320, false);
    ASSERT_TRUE(setup.ok());
    const hsr::Planner planner(*scene);
    const DrawList full = fullDrawList(*scene);
    const DrawList same = planner.plan(Mode::ZBuffer, setup->params, setup->world, full, 240, 320);
    ASSERT_EQ(same.size(), full.size());
    for (std::size_t i = 0; i < full.size(); ++i) {
        EXPECT_EQ(same[i].instance, full[i].instance);
        EXPECT_EQ(same[i].depth, DepthMode::Test);
    }
    // depthsort lists every listed triangle once, all without the depth test.
    hsr::PlanStats stats;
    const DrawList sorted = planner.plan(Mode::DepthSort, setup->params, setup->world, full, 240, 320, &stats);
    std::set<std::pair<int, std::uint32_t>> seen;
    for (const DrawCommand& command : sorted) {
        EXPECT_EQ(command.depth, DepthMode::Off);
        for (const IndexRange& range : command.ranges)
            for (std::uint32_t t = range.firstTriangle; t < range.firstTriangle + range.triangleCount; ++t)
                EXPECT_TRUE(seen.insert({command.instance, t}).second);
    }
    EXPECT_EQ(seen.size(), hsr::screenTriangles(*scene, setup->params, setup->world, full, 240, 320).size());
    EXPECT_EQ(stats.draws, sorted.size());
}

TEST(HsrPlan, ModeNames) {
    for (Mode mode : {Mode::ZBuffer, Mode::DepthSort, Mode::Adaptive})
        EXPECT_EQ(fromString(toString(mode), kHsrs), mode);
    EXPECT_FALSE(fromString("zbuf", kHsrs).has_value());
    EXPECT_FALSE(fromString("", kHsrs).has_value());
}

}  // namespace
}  // namespace frugal::test
