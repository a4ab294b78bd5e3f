// Extreme cases for culling, each judged like every frame (CullRenderSupport.h): the methods that
// must never miss do not miss, and their plans render the full image byte for byte. Cameras inside
// the bounding sphere, on the map's poles, near and far planes cutting the object, tiny and huge
// coordinates, degenerate meshes, non-finite vertices that reach the mesh, orthographic cameras.
#include <iostream>
#include <limits>
#include <map>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "CullRenderSupport.h"
#include "TestSupport.h"
#include "lab/Views.h"

namespace frugal {
namespace {

using test::CullBench;
using test::Tallies;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

void expectSeen(Tallies& tallies) {
    EXPECT_GT(tallies.rendered, 0u) << tallies.summary();
    EXPECT_GT(tallies.of(Cull::Conservative).rvs, 0u) << "nothing visible: " << tallies.summary();
}

// Both materials of a mesh, one bench each.
template <class Check>
void forBothSides(const Mesh& mesh, Check check) {
    for (bool doubleSided : {false, true}) {
        SCOPED_TRACE(doubleSided ? "double-sided" : "single-sided");
        CullBench bench(test::singleMeshScene(mesh, doubleSided), 96, 72);
        ASSERT_TRUE(bench.canRender()) << bench.uploadError;
        check(bench, std::string(doubleSided ? "double-sided" : "single-sided"));
    }
}

TEST(CullExtremesTest, CameraInsideTheBoundingSphere) {
    const glm::vec3 looks[] = {{0, 0, -1}, {0, 0, 1}, {1, 0, 0}, {0.3f, -0.8f, 0.2f}, {0, 1, 0}, {-1, -1, -1}};
    // A closed blob wound inward (its inside is its front), an ordinary one, and a soup.
    for (const Mesh& mesh : {test::finished(test::blobMesh(3, 14, 24, true)), test::finished(test::blobMesh(4)),
                             test::finished(test::soupMesh(5, 300))}) {
        forBothSides(mesh, [&](CullBench& bench, const std::string& side) {
            Tallies tallies;
            for (const glm::vec3& eye : {glm::vec3(0.0f), glm::vec3(0.2f, -0.3f, 0.1f), glm::vec3(0.0f, 0.0f, 0.7f)})
                for (const glm::vec3& look : looks) {
                    Camera spec =
                        test::lookAt(eye, eye + look,
                                     std::abs(glm::normalize(look).y) > 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
                    spec.znear = 0.01f;
                    tallies.add(test::checkFrame(bench, spec, mesh.name + " " + side + " from inside"));
                }
            // The report views' "inside" class too.
            Tallies views = test::checkReportViews(bench, 12, mesh.name + " " + side);
            if (mesh.name != "blob4" || side == "double-sided") expectSeen(tallies);
            expectSeen(views);
        });
    }
    std::optional<Scene> bunny = test::loadBunny(false);
    if (!bunny) return;
    CullBench bench(std::move(*bunny), 96, 72);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    const Bounds bounds = bench.scene.bounds(0.0);
    const glm::vec3 c = bounds.center();
    const float r = bounds.radius();
    Tallies tallies;
    for (const glm::vec3& look : looks) {
        Camera spec = test::lookAt(c + glm::vec3(0.0f, 0.0f, 0.6f * r), c + glm::vec3(0.0f, 0.0f, 0.6f * r) + look,
                                   std::abs(glm::normalize(look).y) > 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
        tallies.add(test::checkFrame(bench, spec, "bunny from inside its sphere"));
    }
    expectSeen(tallies);
}

TEST(CullExtremesTest, ViewAxisThroughThePoles) {
    // Untransformed meshes: the view axis along ±z through the map's centre passes through θ = 0 and
    // θ = 180°, from outside and from the centre.
    for (const Mesh& mesh : {test::finished(test::blobMesh(7, 16, 32)), test::finished(test::soupMesh(8, 400))}) {
        forBothSides(mesh, [&](CullBench& bench, const std::string& side) {
            const glm::dvec3 centre = bench.culler.maps()[0].sphere.center;
            const glm::vec3 c(centre);
            const float r = float(bench.culler.maps()[0].sphere.radius);
            Tallies tallies;
            for (float sign : {1.0f, -1.0f}) {
                for (float distance : {3.0f * r, 1.5f * r})
                    tallies.add(test::checkFrame(bench, test::lookAt(c + glm::vec3(0, 0, sign * distance), c),
                                                 mesh.name + " " + side + " pole " + std::to_string(sign)));
                Camera fromCentre = test::lookAt(c, c + glm::vec3(0, 0, sign));
                fromCentre.znear = 0.01f * r;
                tallies.add(test::checkFrame(bench, fromCentre, mesh.name + " " + side + " from the centre along z"));
            }
            expectSeen(tallies);
        });
    }
}

TEST(CullExtremesTest, ObjectStraddlingTheNearPlane) {
    forBothSides(test::finished(test::blobMesh(9, 16, 28)), [](CullBench& bench, const std::string& side) {
        Tallies tallies;
        for (float znear : {3.0f, 2.5f, 3.6f, 2.05f}) {
            Camera spec = test::lookAt({0.0f, 0.0f, 3.0f}, glm::vec3(0.0f));
            spec.znear = znear;
            spec.zfar = 10.0f;
            tallies.add(test::checkFrame(bench, spec, side + " near " + std::to_string(znear)));
            // Oblique: the near plane cuts the object off-centre.
            Camera oblique = test::lookAt({1.2f, 0.5f, 2.6f}, {0.3f, 0.0f, 0.0f});
            oblique.znear = znear;
            oblique.zfar = 0.0f;  // infinite far plane
            tallies.add(test::checkFrame(bench, oblique, side + " oblique near " + std::to_string(znear)));
        }
        expectSeen(tallies);
    });
}

TEST(CullExtremesTest, ObjectStraddlingTheFarPlane) {
    forBothSides(test::finished(test::blobMesh(10, 16, 28)), [](CullBench& bench, const std::string& side) {
        Tallies tallies;
        for (float zfar : {3.0f, 2.5f, 3.7f, 2.02f}) {
            Camera spec = test::lookAt({0.0f, 0.0f, 3.0f}, glm::vec3(0.0f));
            spec.znear = 0.1f;
            spec.zfar = zfar;
            tallies.add(test::checkFrame(bench, spec, side + " far " + std::to_string(zfar)));
            Camera oblique = test::lookAt({-1.5f, 1.0f, 2.4f}, {0.2f, -0.1f, 0.0f});
            oblique.znear = 0.1f;
            oblique.zfar = zfar;
            tallies.add(test::checkFrame(bench, oblique, side + " oblique far " + std::to_string(zfar)));
        }
        expectSeen(tallies);
    });
}

// Coordinates scaled by `factor`: in the mesh itself, or by the instance's transform.
void checkScaled(float factor) {
    const Mesh unit = test::finished(test::blobMesh(11, 14, 24));
    const Mesh soup = test::finished(test::soupMesh(12, 200));
    for (const Mesh* base : {&unit, &soup}) {
        for (bool inMesh : {true, false}) {
            for (bool doubleSided : {false, true}) {
                Scene scene = test::singleMeshScene(inMesh ? test::scaledMesh(*base, factor) : *base, doubleSided);
                if (!inMesh) {
                    scene.nodes[0].scale = glm::vec3(factor);
                    scene.buildInstances();  // the envelope follows the node (Scene.h)
                }
                const std::string label = base->name + (inMesh ? " mesh" : " node") + " scaled by " +
                                          std::to_string(factor) + (doubleSided ? " double" : " single");
                CullBench bench(std::move(scene), 96, 72);
                ASSERT_TRUE(bench.canRender()) << bench.uploadError;
                Tallies tallies;
                tallies.add(test::checkFrame(bench, {}, label + ", fitted camera"));
                tallies.add(test::checkFrame(bench, test::lookAt(glm::vec3(0.3f, 0.2f, 3.0f) * factor, glm::vec3(0.0f)),
                                             label + ", outside"));
                Camera inside =
                    test::lookAt(glm::vec3(0.1f, 0.0f, 0.2f) * factor, glm::vec3(0.0f, 0.0f, -1.0f) * factor);
                inside.znear = 0.01f * factor;
                inside.zfar = 10.0f * factor;
                tallies.add(test::checkFrame(bench, inside, label + ", inside"));
                for (const ReportView& view : reportViews(glm::vec3(0.0f), 1.1f * factor * (base == &soup ? 1.6f : 1.0f), 6))
                    tallies.add(test::checkFrame(bench, view.camera, label + ", " + view.viewClass));
                expectSeen(tallies);
            }
        }
    }
}

TEST(CullExtremesTest, TinyCoordinates) { checkScaled(1e-6f); }
TEST(CullExtremesTest, HugeCoordinates) { checkScaled(1e6f); }

Mesh handMesh(const std::string& name, std::vector<glm::vec3> positions, std::vector<std::uint32_t> indices) {
    Mesh mesh;
    mesh.name = name;
    mesh.positions = std::move(positions);
    mesh.indices = std::move(indices);
    mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f, 0.0f, 1.0f));
    return mesh;
}

// Cameras all around a small object at the origin, plus one at its centre.
std::vector<Camera> aroundTheOrigin(float distance) {
    std::vector<Camera> views;
    const glm::vec3 eyes[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0.6f, 0.5f, 0.62f}, {-0.3f, -0.9f, 0.3f}, {0, 1, 0.001f}};
    for (const glm::vec3& e : eyes) views.push_back(test::lookAt(distance * glm::normalize(e), glm::vec3(0.0f)));
    Camera centre = test::lookAt(glm::vec3(0.01f, 0.02f, 0.0f), glm::vec3(0.5f, 0.3f, -1.0f));
    centre.znear = 0.001f;
    views.push_back(centre);
    return views;
}

void checkAround(const Mesh& mesh, bool expectVisible) {
    forBothSides(mesh, [&](CullBench& bench, const std::string& side) {
        Tallies tallies;
        for (const Camera& view : aroundTheOrigin(3.0f))
            tallies.add(test::checkFrame(bench, view, mesh.name + " " + side));
        tallies.add(test::checkFrame(bench, {}, mesh.name + " " + side + " fitted"));
        if (expectVisible) expectSeen(tallies);
    });
}

TEST(CullExtremesTest, PlanarMesh) {
    std::vector<glm::vec3> grid;
    std::vector<std::uint32_t> indices;
    for (int i = 0; i <= 12; ++i)
        for (int j = 0; j <= 12; ++j) grid.emplace_back(float(i) / 6.0f - 1.0f, float(j) / 6.0f - 1.0f, 0.0f);
    for (std::uint32_t i = 0; i < 12; ++i)
        for (std::uint32_t j = 0; j < 12; ++j) {
            const std::uint32_t a = i * 13 + j;
            indices.insert(indices.end(), {a, a + 13, a + 14, a, a + 14, a + 1});
        }
    checkAround(handMesh("planar grid", grid, indices), true);
}

TEST(CullExtremesTest, CollinearMesh) {
    std::vector<glm::vec3> line;
    std::vector<std::uint32_t> indices;
    for (int i = 0; i < 30; ++i) line.emplace_back(float(i) / 15.0f - 1.0f, 0.5f * (float(i) / 15.0f - 1.0f), 0.0f);
    for (std::uint32_t i = 0; i + 2 < 30; ++i) indices.insert(indices.end(), {i, i + 1, i + 2});
    checkAround(handMesh("collinear", line, indices), false);  // zero area: nothing to see, nothing to miss
}

TEST(CullExtremesTest, FewerThanFourVertices) {
    checkAround(handMesh("three vertices", {{-1, -1, 0}, {1, -0.5f, 0.2f}, {0, 1, -0.1f}}, {0, 1, 2, 2, 1, 0, 0, 2, 1}),
                true);
    checkAround(handMesh("two vertices", {{-1, -1, 0}, {1, 1, 0}}, {0, 1, 1}), false);
    checkAround(handMesh("one vertex", {{0.5f, 0.5f, 0.5f}}, {0, 0, 0}), false);
}

TEST(CullExtremesTest, OneTriangle) {
    checkAround(handMesh("one triangle", {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {0, 1, 2}), true);
    // Edge-on: the eye in the triangle's plane (undecided facing must be kept, nothing to see).
    CullBench bench(test::singleMeshScene(handMesh("edge-on", {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {0, 1, 2}), false),
                    96, 72);
    ASSERT_TRUE(bench.canRender());
    const glm::vec3 c(0.0f, -1.0f / 3.0f, 0.0f);
    test::checkFrame(bench, test::lookAt({0.0f, -0.3f, 4.0f}, c), "front");
    const test::FrameResult edge = test::checkFrame(bench, test::lookAt({4.0f, 0.0f, 0.0f}, c), "edge-on");
    const test::FrameResult back = test::checkFrame(bench, test::lookAt({0.0f, -0.3f, -4.0f}, c), "back");
    ASSERT_NE(back.list(Cull::Backface), nullptr);
    EXPECT_TRUE(back.list(Cull::Backface)->empty()) << "a single-sided triangle seen from behind";
    EXPECT_TRUE(back.list(Cull::Conservative)->empty()) << "a single-sided triangle seen from behind";
    EXPECT_FALSE(edge.list(Cull::Conservative)->empty()) << "edge-on is undecided: kept";
}

TEST(CullExtremesTest, AllBarycentersAtTheCentre) {
    // Pairs of triangles point-symmetric about the origin, each with its barycenter at the origin
    // (a, b, −a−b): R = 0 for every barycenter, all in bin 0, yet they cover the whole view.
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> indices;
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int t = 0; t < 40; ++t) {
        const glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
        const auto base = std::uint32_t(positions.size());
        // With its mirror image, so that the vertex set (and its bounding sphere) is centred at 0.
        positions.insert(positions.end(), {a, b, -a - b, -a, -b, a + b});
        indices.insert(indices.end(), {base, base + 1, base + 2, base + 3, base + 4, base + 5});
    }
    Mesh mesh = handMesh("centred barycenters", positions, indices);
    mesh = test::finished(std::move(mesh), false);
    // Most barycenters are exactly at the centre as the map sees them.
    {
        std::vector<std::uint32_t> order;
        const MeshMap map = buildMeshMap(mesh, {}, order);
        std::size_t zero = 0;
        for (const MapEntry& e : map.entries) zero += e.r < 1e-5f * float(map.sphere.radius);
        EXPECT_EQ(zero, mesh.triangleCount());
    }
    checkAround(mesh, true);
}

// A blob with non-finite vertices and triangles using them, built by hand (loaders drop those).
Mesh blobWithNonFinite() {
    Mesh mesh = test::finished(test::blobMesh(13, 12, 20), false);
    const auto nan = std::uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(),
                          {glm::vec3(kNaN, 0, 0), glm::vec3(0, kInf, 0), glm::vec3(-kInf, 1, kNaN)});
    mesh.normals.resize(mesh.positions.size(), glm::vec3(0, 0, 1));
    const std::size_t finiteTriangles = mesh.triangleCount();
    // Non-finite triangles among the finite ones: in front, in the middle and at the end.
    const std::uint32_t extra[] = {nan, 0, 1, 5, nan + 1, 6, nan, nan + 1, nan + 2, 40, 41, nan + 2};
    mesh.indices.insert(mesh.indices.begin(), extra, extra + 3);
    mesh.indices.insert(mesh.indices.begin() + 3 * std::ptrdiff_t(finiteTriangles / 2), extra + 3, extra + 9);
    mesh.indices.insert(mesh.indices.end(), extra + 9, extra + 12);
    mesh.triangleSource.resize(mesh.triangleCount());
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) mesh.triangleSource[t] = std::uint32_t(t);
    return mesh;
}

bool triangleFinite(const Mesh& mesh, std::size_t t) {
    for (int k = 0; k < 3; ++k) {
        const glm::vec3 p = mesh.positions[mesh.indices[3 * t + std::size_t(k)]];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
    }
    return true;
}

TEST(CullExtremesTest, NonFiniteVerticesReachingTheMesh) {
    const Mesh mesh = blobWithNonFinite();
    for (bool doubleSided : {false, true}) {
        SCOPED_TRACE(doubleSided ? "double-sided" : "single-sided");
        CullBench bench(test::singleMeshScene(mesh, doubleSided), 96, 72);
        const Mesh& reordered = bench.scene.meshes[0];
        // Reference without the non-finite triangles: the same (reordered) mesh minus them, same ids.
        Scene finiteScene = bench.scene;
        {
            Mesh& m = finiteScene.meshes[0];
            std::vector<std::uint32_t> indices, sources;
            for (std::size_t t = 0; t < m.triangleCount(); ++t)
                if (triangleFinite(m, t)) {
                    indices.insert(indices.end(), m.indices.begin() + std::ptrdiff_t(3 * t),
                                   m.indices.begin() + std::ptrdiff_t(3 * t + 3));
                    sources.push_back(m.triangleSource[t]);
                }
            m.indices = std::move(indices);
            m.triangleSource = std::move(sources);
            finiteScene.buildInstances();
        }
        ASSERT_EQ(finiteScene.meshes[0].triangleCount() + 4, reordered.triangleCount());
        std::map<std::uint32_t, std::size_t> bySource;  // source → triangle of the reordered mesh
        for (std::size_t t = 0; t < reordered.triangleCount(); ++t) bySource[reordered.triangleSource[t]] = t;

        std::unique_ptr<Backend> backend = makeSoftwareBackend();
        const TargetHandle target = backend->createTarget(96, 72);
        Result<SceneRenderer> finiteRenderer = SceneRenderer::create(*backend, finiteScene);
        ASSERT_TRUE(finiteRenderer) << finiteRenderer.error().message;

        std::vector<Camera> views = aroundTheOrigin(3.0f);
        for (const ReportView& view : reportViews(glm::vec3(0.0f), 1.2f, 8)) views.push_back(view.camera);
        std::size_t seen = 0;
        for (std::size_t k = 0; k < views.size(); ++k) {
            const std::string label = "view " + std::to_string(k);
            SCOPED_TRACE(label);
            Result<FrameSetup> setup = setUpFrame(finiteScene, views[k], 0.0, 96, 72, true);
            ASSERT_TRUE(setup) << setup.error().message;
            // Culling the mesh with the non-finite triangles: plans well-formed, and when the backend
            // took the mesh, rendered and compared as usual.
            const test::FrameResult result = test::checkSetup(bench, *setup, label);
            // Every finite triangle visible without the non-finite ones is kept by the never-miss methods.
            finiteRenderer->renderFrame(target, 96, 72, setup->params, setup->world, test::kBackground);
            Result<TriangleSet> rvs = visibleSet(finiteScene, backend->readBack(target));
            ASSERT_TRUE(rvs) << rvs.error().message;
            seen += rvs->count;
            for (Cull method : test::kNeverMiss) {
                const DrawList* list = result.list(method);
                ASSERT_NE(list, nullptr);
                const TriangleSet pvs = drawnSet(bench.scene, *list);
                std::size_t missed = 0;
                for (std::size_t t = 0; t < rvs->perInstance[0].size(); ++t)
                    if (rvs->perInstance[0][t] && !pvs.perInstance[0][bySource.at(finiteScene.meshes[0].triangleSource[t])])
                        ++missed;
                EXPECT_EQ(missed, 0u) << toString(method) << " dropped finite visible triangles";
                // The non-finite triangles are undecided: the triangle-level methods keep them when
                // the frustum cannot rule them out (never required; reported for the record).
            }
        }
        EXPECT_GT(seen, 0u);
        if (!bench.canRender()) std::cout << "[ info ] the software backend refused the mesh: " << bench.uploadError << "\n";
        backend->destroyTarget(target);
    }
}

// An orthographic scene camera (Camera::perspective = false on a camera node).
Scene orthoScene(const glm::vec3& cameraPosition, const glm::quat& cameraRotation, float znear, float zfar) {
    Scene scene = test::singleMeshScene(test::finished(test::blobMesh(14, 14, 24)), false);
    // Two more instances: mirrored, and double-sided-by-material through a second mesh.
    test::addMeshNode(scene, 0, {2.2f, 0.3f, -0.5f}, glm::angleAxis(0.7f, glm::vec3(0, 1, 0)), {-1.0f, 1.2f, 0.8f});
    Mesh soup = test::finished(test::soupMesh(15, 150));
    soup.material = 1;
    scene.meshes.push_back(std::move(soup));
    test::addMeshNode(scene, 1, {-2.0f, -0.2f, 0.4f});
    SceneCamera camera;
    camera.name = "ortho";
    camera.perspective = false;
    camera.xmag = 3.2f;
    camera.ymag = 2.4f;
    camera.znear = znear;
    camera.zfar = zfar;
    const int index = test::addCameraNode(scene, camera, cameraPosition);
    scene.nodes[std::size_t(scene.cameras[std::size_t(index)].node)].rotation = cameraRotation;
    scene.buildInstances();
    return scene;
}

TEST(CullExtremesTest, OrthographicCamera) {
    struct Case {
        glm::vec3 position;
        glm::quat rotation;
        float znear, zfar;
        const char* what;
    };
    const Case cases[] = {
        {{0, 0, 6}, {1, 0, 0, 0}, 0.1f, 20.0f, "front"},
        {{0, 0, 6}, {1, 0, 0, 0}, 5.5f, 6.5f, "near and far planes cutting the objects"},
        {{4, 1, 4}, glm::angleAxis(0.785f, glm::vec3(0, 1, 0)), 0.1f, 20.0f, "rotated"},
        {{0, 0, 0.3f}, {1, 0, 0, 0}, 0.01f, 5.0f, "from inside the first blob"},
        {{0, -6, 0}, glm::angleAxis(1.5708f, glm::vec3(1, 0, 0)), 0.1f, 20.0f, "from below"},
    };
    Tallies tallies;
    for (const Case& c : cases) {
        CullBench bench(orthoScene(c.position, c.rotation, c.znear, c.zfar), 96, 72);
        ASSERT_TRUE(bench.canRender()) << bench.uploadError;
        Camera spec;
        spec.sceneCamera = 0;
        const test::FrameResult frame = test::checkFrame(bench, spec, c.what);
        tallies.add(frame);
        Result<FrameSetup> setup = setUpFrame(bench.scene, spec, 0.0, 96, 72, true);
        ASSERT_TRUE(setup);
        EXPECT_FALSE(setup->view.perspective);
    }
    expectSeen(tallies);
    // Single-sided blobs seen orthographically: facing culls some triangles.
    EXPECT_LT(tallies.of(Cull::Backface).pvs, tallies.of(Cull::Backface).tos) << tallies.summary();
}

}  // namespace
}  // namespace frugal

namespace frugal {
namespace {

// A single-sided mesh scaled by 1e-12 (or 1e-20), seen from a camera exactly at the object-space
// origin. At that scale meshoptimizer's float area test (meshopt_computeClusterBounds: the squared
// cross product underflows) calls every triangle degenerate and returns all-zero bounds (centre 0,
// radius 0, cone axis 0, cutoff 0). Before SphereMap.cpp grew the cluster radius over the vertices,
// InstanceView::coneAway read such a cluster as facing away from an eye at the origin
// (0 >= 0·0 + 0 + kPlaneMargin·0) and cones/conservative dropped every visible triangle.
TEST(CullExtremesTest, TinyTrianglesSeenFromTheObjectOrigin) {
    for (float factor : {1e-12f, 1e-20f}) {
        for (float offset : {0.0f, 0.05f}) {
            Mesh mesh = test::scaledMesh(test::finished(test::blobMesh(31, 14, 24, true)), factor);
            CullBench bench(test::singleMeshScene(mesh, false), 96, 72);
            ASSERT_TRUE(bench.canRender()) << bench.uploadError;
            Tallies tallies;
            for (const glm::vec3& look : {glm::vec3(0, 0, -1), glm::vec3(1, 0.2f, 0), glm::vec3(0.3f, 0.1f, 1)}) {
                Camera spec = test::lookAt(glm::vec3(offset * factor), glm::vec3(offset * factor) + look);
                spec.znear = 1e-3f * factor;
                spec.zfar = 10.0f * factor;
                std::ostringstream label;
                label << "scale " << factor << ", eye " << offset << " x scale off the origin, looking " << look.x
                      << "," << look.y << "," << look.z;
                tallies.add(test::checkFrame(bench, spec, label.str()));
            }
            expectSeen(tallies);
        }
    }
}

}  // namespace
}  // namespace frugal
