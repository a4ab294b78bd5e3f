// Occlusion culling (cull/Occlusion.h) on the cases where a depth bound goes wrong first: objects
// exactly touching, coplanar occluder and occludee, an occluder through the near plane, orthographic
// cameras, tiny and huge coordinates, both depth formats, and a thousand random scenes of boxes
// behind boxes. Every frame is checked by checkFrame (CullRenderSupport.h): no visible triangle
// missed, and the culled render equal to the full one in colour, depth and ids. Each test also
// asserts that occlusion removed something, so that it cannot pass by culling nothing.
#include <random>

#include <glm/gtc/quaternion.hpp>

#include "CullRenderSupport.h"
#include "cull/OcclusionKernels.h"
#include "TestSupport.h"

namespace frugal {
namespace {

using test::CullBench;
using test::Tallies;

// An axis-aligned box of size 2·half around the origin, each face split into n × n quads,
// counter-clockwise outside.
Mesh boxMesh(const glm::vec3& half, int n = 2) {
    Mesh mesh;
    mesh.name = "box";
    for (int axis = 0; axis < 3; ++axis)
        for (int sign = -1; sign <= 1; sign += 2) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const auto base = std::uint32_t(mesh.positions.size());
            for (int i = 0; i <= n; ++i)
                for (int j = 0; j <= n; ++j) {
                    glm::vec3 p(0.0f);
                    p[axis] = float(sign) * half[axis];
                    p[u] = (-1.0f + 2.0f * float(i) / float(n)) * half[u];
                    p[v] = (-1.0f + 2.0f * float(j) / float(n)) * half[v];
                    mesh.positions.push_back(p);
                }
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    const std::uint32_t a = base + std::uint32_t(i * (n + 1) + j), b = a + std::uint32_t(n + 1);
                    // (u, v, axis) is right-handed: u × v points along +axis.
                    if (sign > 0)
                        mesh.indices.insert(mesh.indices.end(), {a, b, b + 1, a, b + 1, a + 1});
                    else
                        mesh.indices.insert(mesh.indices.end(), {a, a + 1, b + 1, a, b + 1, b});
                }
        }
    return test::finished(std::move(mesh));
}

// A scene of materials 0 (single-sided) and 1 (double-sided), no meshes yet.
Scene emptyScene(const std::string& name) {
    Scene scene = test::singleMeshScene(boxMesh(glm::vec3(0.5f)), false);
    scene.source = "test:" + name;
    scene.meshes.clear();
    scene.nodes.clear();
    scene.roots.clear();
    return scene;
}

int addBox(Scene& scene, const glm::vec3& half, const glm::vec3& at, int material = 0, int n = 2,
           const glm::quat& rotation = {1, 0, 0, 0}, const glm::vec3& scale = glm::vec3(1.0f)) {
    Mesh mesh = boxMesh(half, n);
    mesh.material = material;
    scene.meshes.push_back(std::move(mesh));
    return test::addMeshNode(scene, int(scene.meshes.size()) - 1, at, rotation, scale);
}

// Checks the frame and returns what occlusion submitted against conservative.
struct Culled {
    std::size_t conservative = 0, occlusion = 0;
};
Culled check(CullBench& bench, const Camera& camera, const std::string& label) {
    const test::FrameResult frame = test::checkFrame(bench, camera, label);
    EXPECT_TRUE(frame.rendered) << label;
    return {frame.count(Cull::Conservative).pvs, frame.count(Cull::Occlusion).pvs};
}

TEST(OcclusionTest, ABoxBehindABoxIsCulledAndTheImageIsTheSame) {
    Scene scene = emptyScene("behind");
    addBox(scene, glm::vec3(1.0f), {0, 0, 0});
    addBox(scene, glm::vec3(0.5f), {0, 0, -4});  // hidden whole from +z
    scene.buildInstances();
    CullBench bench(std::move(scene), 96, 72);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    const Culled c = check(bench, test::lookAt({0, 0, 6}, {0, 0, 0}), "from the front");
    EXPECT_LT(c.occlusion, c.conservative) << "the box behind is culled";
    EXPECT_TRUE(bench.culler.occlusion().stats().ran);
    EXPECT_GE(bench.culler.occlusion().stats().clustersHidden, 1u);
}

// A masked or blended box in front hides nothing: the box behind shows through its holes, or
// through the blend, so it is kept, and the image is the full render's (check()). An opaque box
// in front of both still hides it.
TEST(OcclusionTest, MaskedAndBlendedSurfacesHideNothing) {
    for (const AlphaMode mode : {AlphaMode::Mask, AlphaMode::Blend}) {
        const std::string label = mode == AlphaMode::Mask ? "masked" : "blended";
        Scene scene = emptyScene(label);
        Material seeThrough = scene.materials[0];
        seeThrough.alphaMode = mode;
        seeThrough.baseColorFactor.a = mode == AlphaMode::Mask ? 1.0f : 0.5f;
        scene.materials.push_back(seeThrough);
        addBox(scene, glm::vec3(1.0f), {0, 0, 0}, 2, 4);
        Mesh& front = scene.meshes.back();
        front.colors.assign(front.positions.size(), glm::vec4(1.0f));
        for (std::size_t v = 0; v < front.colors.size(); v += 3) front.colors[v].a = 0.0f;  // holes (mask)
        addBox(scene, glm::vec3(0.5f), {0, 0, -4});
        scene.buildInstances();
        CullBench bench(std::move(scene), 96, 72);
        ASSERT_TRUE(bench.canRender()) << bench.uploadError;
        const Culled seen = check(bench, test::lookAt({0, 0, 6}, {0, 0, 0}), label);
        EXPECT_EQ(seen.occlusion, seen.conservative) << label << ": the box behind is kept";

        Scene covered = emptyScene(label + " covered");
        covered.materials.push_back(seeThrough);
        addBox(covered, glm::vec3(1.5f), {0, 0, 2});  // opaque, in front of both
        addBox(covered, glm::vec3(1.0f), {0, 0, 0}, 2, 4);
        addBox(covered, glm::vec3(0.5f), {0, 0, -4});
        covered.buildInstances();
        CullBench behind(std::move(covered), 96, 72);
        const Culled hidden = check(behind, test::lookAt({0, 0, 8}, {0, 0, 0}), label + " covered");
        EXPECT_LT(hidden.occlusion, hidden.conservative) << label << ": the opaque box hides both";
    }
}

TEST(OcclusionTest, ObjectsExactlyTouching) {
    // Face to face (the back box's front face lies in the front box's back face), edge to edge,
    // and a box standing on another; seen from angles where the touching faces are and are not seen.
    Tallies tallies;
    for (int material : {0, 1}) {
        Scene scene = emptyScene("touching");
        addBox(scene, glm::vec3(1.0f), {0, 0, 0}, material, 4);
        addBox(scene, glm::vec3(1.0f), {0, 0, -2}, material, 4);     // face to face
        addBox(scene, glm::vec3(1.0f), {2, 0, -2}, material, 4);     // edge to edge with the first
        addBox(scene, glm::vec3(0.5f), {0, 1.5f, 0}, material, 4);   // on top of the first
        scene.buildInstances();
        CullBench bench(std::move(scene), 128, 96);
        ASSERT_TRUE(bench.canRender()) << bench.uploadError;
        const glm::vec3 eyes[] = {{0, 0, 8}, {0.01f, 0.02f, 8}, {3, 2, 7}, {-4, 0.5f, 5}, {0, 6, 0.5f}, {8, 0, -2}};
        std::size_t conservative = 0, occlusion = 0;
        for (const glm::vec3& eye : eyes) {
            const test::FrameResult f = test::checkFrame(bench, test::lookAt(eye, {0.5f, 0, -1}),
                                                         "material " + std::to_string(material));
            tallies.add(f);
            conservative += f.count(Cull::Conservative).pvs;
            occlusion += f.count(Cull::Occlusion).pvs;
        }
        EXPECT_LT(occlusion, conservative) << tallies.summary();
    }
    EXPECT_EQ(tallies.of(Cull::Occlusion).misses, 0u) << tallies.summary();
}

TEST(OcclusionTest, CoplanarOccluderAndOccludee) {
    // Two quads in one plane, overlapping (z-fighting: the first drawn keeps its pixels), and a box
    // whose front face lies in the plane of a wall in front of it: neither may hide the other.
    Scene scene = emptyScene("coplanar");
    addBox(scene, {1.0f, 1.0f, 0.0f}, {0, 0, 0}, 1, 6);
    addBox(scene, {1.0f, 1.0f, 0.0f}, {0.5f, 0.3f, 0}, 1, 6);
    addBox(scene, {2.0f, 2.0f, 0.1f}, {0, 0, -1.0f}, 0, 6);   // a wall behind, its front at z = -0.9
    addBox(scene, {0.4f, 0.4f, 0.4f}, {0, 0, -1.3f}, 0, 6);   // front face at -0.9: coplanar with the wall
    scene.buildInstances();
    for (DepthFormat format : {DepthFormat::D24, DepthFormat::D32F}) {
        Scene copy = scene;
        CullBench bench(std::move(copy), 128, 96, {}, format);
        ASSERT_TRUE(bench.canRender()) << bench.uploadError;
        Tallies tallies;
        for (const glm::vec3& eye : {glm::vec3(0, 0, 5), glm::vec3(1, 1, 4), glm::vec3(-2, 0.5f, 3)})
            tallies.add(test::checkFrame(bench, test::lookAt(eye, {0, 0, -0.5f}), toString(format)));
        EXPECT_EQ(tallies.of(Cull::Occlusion).misses, 0u) << tallies.summary();
        EXPECT_LT(tallies.of(Cull::Occlusion).pvs, tallies.of(Cull::Conservative).pvs) << tallies.summary();
    }
}

TEST(OcclusionTest, OccluderThroughTheNearPlane) {
    // A wall that the near plane cuts, in front of boxes: its clipped triangles hide nothing, its
    // others do; boxes seen through the gap beside it stay.
    Scene scene = emptyScene("near");
    addBox(scene, {1.5f, 3.0f, 0.2f}, {-0.8f, 0, 0.3f}, 0, 8);
    for (int i = 0; i < 5; ++i) addBox(scene, glm::vec3(0.3f), {-1.5f + 0.8f * float(i), 0, -3.0f}, 0, 3);
    scene.buildInstances();
    CullBench bench(std::move(scene), 128, 96);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    Camera camera = test::lookAt({0, 0, 0.6f}, {0, 0, -3});
    camera.znear = 0.2f;  // the wall spans z ∈ [0.1, 0.5]: the near plane at z = 0.4 cuts it
    camera.zfar = 10.0f;
    const Culled c = check(bench, camera, "wall through the near plane");
    EXPECT_LT(c.occlusion, c.conservative);
}

TEST(OcclusionTest, OrthographicCamera) {
    // A row of boxes along the view axis: the first hides the rest.
    Scene scene = emptyScene("ortho");
    for (int i = 0; i < 6; ++i) addBox(scene, glm::vec3(0.8f), {0.05f * float(i), 0, -2.0f * float(i)}, i % 2, 3);
    SceneCamera camera;
    camera.name = "ortho";
    camera.perspective = false;
    camera.xmag = 2.0f;
    camera.ymag = 1.5f;
    camera.znear = 0.1f;
    camera.zfar = 30.0f;
    test::addCameraNode(scene, camera, {0, 0, 5});
    scene.buildInstances();
    for (DepthFormat format : {DepthFormat::D24, DepthFormat::D32F}) {
        Scene copy = scene;
        CullBench bench(std::move(copy), 128, 96, {}, format);
        ASSERT_TRUE(bench.canRender()) << bench.uploadError;
        Camera spec;
        spec.sceneCamera = 0;
        const Culled c = check(bench, spec, std::string("orthographic, ") + toString(format));
        EXPECT_LT(c.occlusion * 2, c.conservative) << "most of the row is hidden";
    }
}

// Boxes behind boxes scaled by `factor`, as mesh coordinates and as node scales.
void checkScale(float factor) {
    for (bool inNode : {false, true}) {
        Scene scene = emptyScene("scaled");
        for (int i = 0; i < 4; ++i) {
            const glm::vec3 half = glm::vec3(0.6f - 0.1f * float(i)) * (inNode ? 1.0f : factor);
            const glm::vec3 at = glm::vec3(0.1f * float(i), 0.05f * float(i), -1.5f * float(i)) * factor;
            addBox(scene, half, at, 0, 3, {1, 0, 0, 0}, glm::vec3(inNode ? factor : 1.0f));
        }
        scene.buildInstances();
        CullBench bench(std::move(scene), 128, 96);
        ASSERT_TRUE(bench.canRender()) << bench.uploadError;
        Camera camera = test::lookAt(glm::vec3(0.2f, 0.3f, 4.0f) * factor, glm::vec3(0, 0, -2) * factor);
        const Culled c = check(bench, camera, (inNode ? "node scaled by " : "mesh scaled by ") + std::to_string(factor));
        EXPECT_LT(c.occlusion, c.conservative);
    }
}

TEST(OcclusionTest, TinyCoordinates) { checkScale(1e-6f); }
TEST(OcclusionTest, HugeCoordinates) { checkScale(1e6f); }

TEST(OcclusionTest, FarFromTheOrigin) {
    // Small boxes a million units from the origin: the float transform loses most of its digits,
    // and the bounds must say so.
    Scene scene = emptyScene("far");
    const glm::vec3 origin(1e6f, -2e6f, 5e5f);
    for (int i = 0; i < 4; ++i) addBox(scene, glm::vec3(0.5f), origin + glm::vec3(0.02f * float(i), 0, -1.2f * float(i)), 0, 3);
    scene.buildInstances();
    CullBench bench(std::move(scene), 128, 96);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    check(bench, test::lookAt(origin + glm::vec3(0.1f, 0.2f, 3.0f), origin + glm::vec3(0, 0, -2)), "far from the origin");
}

// A random scene of boxes behind boxes: a few occluders in front of the camera and a crowd behind,
// random sizes, rotations, mirroring, materials, depth formats and target sizes.
struct RandomBoxes {
    Scene scene;
    Camera camera;
    DepthFormat format = DepthFormat::D24;
    int width = 0, height = 0;
};
RandomBoxes randomBoxes(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    RandomBoxes r;
    r.scene = emptyScene("boxes" + std::to_string(seed));
    const int occluders = 1 + int(seed % 3), crowd = 2 + int(seed % 7);
    for (int i = 0; i < occluders + crowd; ++i) {
        const bool front = i < occluders;
        const glm::vec3 half = front ? glm::vec3(0.6f + 0.8f * unit(rng), 0.6f + 0.8f * unit(rng), 0.1f + 0.5f * unit(rng))
                                     : glm::vec3(0.1f + 0.4f * unit(rng));
        const glm::vec3 at = front ? glm::vec3(0.8f * u(rng), 0.8f * u(rng), 1.0f * u(rng))
                                   : glm::vec3(1.5f * u(rng), 1.5f * u(rng), -2.0f - 3.0f * unit(rng));
        const glm::quat rotation = glm::angleAxis(0.6f * u(rng), glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + 1e-3f));
        glm::vec3 scale(1.0f);
        if (unit(rng) < 0.2f) scale.x = -1.0f;  // mirrored: the other winding is the front
        addBox(r.scene, half, at, unit(rng) < 0.3f ? 1 : 0, 1 + int(seed % 3), rotation, scale);
    }
    r.scene.buildInstances();
    r.format = seed % 4 == 3 ? DepthFormat::D32F : DepthFormat::D24;
    r.width = 48 + int(seed % 5) * 16;
    r.height = 36 + int(seed % 3) * 12;
    r.camera = test::lookAt(glm::vec3(0.8f * u(rng), 0.8f * u(rng), 4.0f + 3.0f * unit(rng)),
                            glm::vec3(0.3f * u(rng), 0.3f * u(rng), -2.0f));
    r.camera.yfovDegrees = 30.0f + 40.0f * unit(rng);
    return r;
}

void checkRandomBoxes(unsigned first, unsigned last) {
    std::size_t conservative = 0, occlusion = 0, frames = 0;
    Tallies tallies;
    for (unsigned seed = first; seed <= last; ++seed) {
        RandomBoxes r = randomBoxes(seed);
        CullBench bench(std::move(r.scene), r.width, r.height, {}, r.format);
        ASSERT_TRUE(bench.canRender()) << bench.uploadError;
        const test::FrameResult f = test::checkFrame(bench, r.camera, "boxes " + std::to_string(seed));
        tallies.add(f);
        conservative += f.count(Cull::Conservative).pvs;
        occlusion += f.count(Cull::Occlusion).pvs;
        ++frames;
        if (::testing::Test::HasFailure()) break;  // the first failing scene says enough
    }
    EXPECT_EQ(tallies.rendered, frames);
    EXPECT_EQ(tallies.of(Cull::Occlusion).misses, 0u) << tallies.summary();
    EXPECT_LT(occlusion * 10, conservative * 9) << "occlusion culls at least a tenth over the scenes";
}

TEST(OcclusionTest, RandomBoxesBehindBoxes1To250) { checkRandomBoxes(1, 250); }
TEST(OcclusionTest, RandomBoxesBehindBoxes251To500) { checkRandomBoxes(251, 500); }
TEST(OcclusionTest, RandomBoxesBehindBoxes501To750) { checkRandomBoxes(501, 750); }
TEST(OcclusionTest, RandomBoxesBehindBoxes751To1000) { checkRandomBoxes(751, 1000); }

TEST(OcclusionTest, ThreeBunniesComeCloseToTheVisibleSet) {
    std::optional<Scene> bunny = test::loadBunny(false);
    if (!bunny) GTEST_SKIP() << "no bunny (glmark2-data)";
    Result<Scene> three = makeBuiltin("copies?count=3&of=/usr/share/glmark2/models/bunny.obj");
    ASSERT_TRUE(three) << three.error().message;
    for (Material& m : three->materials) m.doubleSided = false;
    CullBench bench(std::move(*three), 400, 300);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    const test::FrameResult f = test::checkFrame(bench, {}, "three bunnies");
    ASSERT_TRUE(f.rendered);
    // The plan is within a tenth of the visible set, where conservative is far above it.
    EXPECT_LT(double(f.count(Cull::Occlusion).pvs), 1.1 * double(f.rvs));
    EXPECT_GT(double(f.count(Cull::Conservative).pvs), 2.0 * double(f.rvs));
}

TEST(OcclusionTest, BandsOfRowsGiveWhatOneWalkGives) {
    // The walk split into 1, 2, 3 and 7 bands (threads) gives the same plan, on three bunnies and on
    // random boxes.
    std::vector<Scene> scenes;
    if (test::loadBunny(false)) {
        Result<Scene> three = makeBuiltin("copies?count=3&of=/usr/share/glmark2/models/bunny.obj");
        ASSERT_TRUE(three) << three.error().message;
        for (Material& m : three->materials) m.doubleSided = false;
        scenes.push_back(std::move(*three));
    }
    Scene boxes = emptyScene("bands");
    for (int i = 0; i < 12; ++i)
        addBox(boxes, glm::vec3(0.3f + 0.05f * float(i % 4)), {0.4f * float(i % 5) - 1.0f, 0.3f * float(i % 3), -0.7f * float(i)},
               i % 2, 6);
    boxes.buildInstances();
    scenes.push_back(std::move(boxes));
    for (Scene& scene : scenes) {
        CullBench bench(std::move(scene), 200, 150);
        Result<FrameSetup> setup = setUpFrame(bench.scene, {}, 0.0, 200, 150, true);
        ASSERT_TRUE(setup) << setup.error().message;
        OcclusionTarget target = bench.occlusionTarget();
        target.threads = 1;
        const DrawList one = bench.culler.cull(Cull::Occlusion, bench.scene, setup->world, setup->view, target);
        const std::size_t conservative =
            submittedTriangles(bench.scene, bench.culler.cull(Cull::Conservative, bench.scene, setup->world, setup->view));
        EXPECT_LT(submittedTriangles(bench.scene, one), conservative) << bench.scene.source;
        for (int threads : {2, 3, 7}) {
            target.threads = threads;
            EXPECT_TRUE(test::sameList(one, bench.culler.cull(Cull::Occlusion, bench.scene, setup->world, setup->view,
                                                               target)))
                << bench.scene.source << ", " << threads << " bands";
        }
    }
}

TEST(OcclusionTest, TheAvx2LoopsGiveTheScalarPlan) {
    // The vertex transform and the quick triangle test eight at a time (cull/OcclusionKernels.h),
    // with the corners gathered (AVX2) and looked up (AVX-512, where the CPU has it), give the plan
    // of the scalar loops: on three bunnies from far away (a few pixels a triangle), near
    // (triangles tens of pixels wide, many clipped) and from inside, in both depth formats, and on
    // 200 scenes of random boxes.
    if (!occlusion::cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2 and FMA: only the scalar loops run";
    std::size_t compared = 0;
    const auto compare = [&compared](CullBench& bench, const Camera& camera, const std::string& label) {
        Result<FrameSetup> setup = setUpFrame(bench.scene, camera, 0.0, bench.width, bench.height, true);
        ASSERT_TRUE(setup) << setup.error().message;
        OcclusionTarget target = bench.occlusionTarget();
        target.simd = false;
        const DrawList scalar = bench.culler.cull(Cull::Occlusion, bench.scene, setup->world, setup->view, target);
        target.simd = true;
        target.avx512 = false;
        const DrawList gathers = bench.culler.cull(Cull::Occlusion, bench.scene, setup->world, setup->view, target);
        EXPECT_TRUE(test::sameList(scalar, gathers)) << label << ": AVX2";
        if (occlusion::cpuHasAvx512()) {
            target.avx512 = true;
            const DrawList lookups = bench.culler.cull(Cull::Occlusion, bench.scene, setup->world, setup->view, target);
            EXPECT_TRUE(test::sameList(scalar, lookups)) << label << ": AVX-512 lookups";
        }
        ++compared;
    };
    if (test::loadBunny(false)) {
        for (const DepthFormat format : {DepthFormat::D24, DepthFormat::D32F}) {
            Result<Scene> three = makeBuiltin("copies?count=3&of=/usr/share/glmark2/models/bunny.obj");
            ASSERT_TRUE(three) << three.error().message;
            for (Material& m : three->materials) m.doubleSided = false;
            CullBench bench(std::move(*three), 320, 240, {}, format);
            const Bounds bounds = bench.scene.bounds(0.0);
            const glm::vec3 centre = bounds.center();
            const float radius = bounds.radius();
            for (const glm::vec3& eye : {centre + glm::vec3(0, 0.4f, 3.0f) * radius, centre + glm::vec3(0.6f, 0.2f, 0.7f) * radius,
                                         centre + glm::vec3(-0.4f, 0.1f, 0.2f) * radius, centre})
                compare(bench, test::lookAt(eye, centre + glm::vec3(0.01f, 0, -0.1f) * radius), "three bunnies");
        }
    }
    for (unsigned seed = 1; seed <= 200 && !::testing::Test::HasFailure(); ++seed) {
        RandomBoxes r = randomBoxes(seed);
        CullBench bench(std::move(r.scene), r.width, r.height, {}, r.format);
        compare(bench, r.camera, "boxes " + std::to_string(seed));
    }
    EXPECT_GE(compared, 200u);
}

TEST(OcclusionTest, WithoutLlvmpipesRulesOnlyWholeClustersAreDropped) {
    // A GPU's rasterizer is not llvmpipe's: no triangle is dropped for its pixels, only clusters
    // hidden whole, with their margins.
    Scene scene = emptyScene("gpu");
    addBox(scene, glm::vec3(1.0f), {0, 0, 0}, 0, 6);
    addBox(scene, glm::vec3(0.5f), {0, 0, -4}, 0, 6);
    scene.buildInstances();
    CullBench bench(std::move(scene), 96, 72);
    ASSERT_TRUE(bench.canRender());
    Result<FrameSetup> setup = setUpFrame(bench.scene, test::lookAt({0, 0, 6}, {0, 0, 0}), 0.0, 96, 72, true);
    ASSERT_TRUE(setup);
    OcclusionTarget gpu = bench.occlusionTarget();
    gpu.exactRules = false;
    const DrawList whole = bench.culler.cull(Cull::Occlusion, bench.scene, setup->world, setup->view, gpu);
    const DrawList exact =
        bench.culler.cull(Cull::Occlusion, bench.scene, setup->world, setup->view, bench.occlusionTarget());
    const DrawList conservative = bench.culler.cull(Cull::Conservative, bench.scene, setup->world, setup->view);
    // The hidden box goes in both; triangle by triangle only on llvmpipe's rules.
    for (const DrawList* list : {&whole, &exact}) {
        ASSERT_FALSE(list->empty());
        EXPECT_EQ(list->back().instance, 0) << "instance 1 is hidden whole";
    }
    EXPECT_LE(submittedTriangles(bench.scene, exact), submittedTriangles(bench.scene, whole));
    EXPECT_EQ(submittedTriangles(bench.scene, whole), submittedTriangles(bench.scene, conservative) -
                                                          submittedTriangles(bench.scene, {conservative.back()}));
}

TEST(OcclusionTest, ItSkipsItselfWhereItDoesNotPay) {
    Scene scene = emptyScene("pays");
    addBox(scene, glm::vec3(1.0f), {0, 0, 0}, 0, 40);  // 19,200 triangles, 9,600 facing any eye at most
    addBox(scene, glm::vec3(0.5f), {0, 0, -4}, 0, 40);
    scene.buildInstances();
    const Scene copy = scene;
    CullBench bench(std::move(scene), 96, 72);
    Result<FrameSetup> setup = setUpFrame(bench.scene, test::lookAt({0, 0, 6}, {0, 0, 0}), 0.0, 96, 72, true);
    ASSERT_TRUE(setup);
    const DrawList conservative = bench.culler.cull(Cull::Conservative, bench.scene, setup->world, setup->view);
    OcclusionTarget target = bench.occlusionTarget();
    target.adaptive = true;
    const OcclusionStats& stats = bench.culler.occlusion().stats();

    // It pays when a dropped triangle saves more than the pass costs a triangle...
    target.drawNsPerTriangle = 1e6;
    DrawList list = bench.culler.cull(Cull::Occlusion, bench.scene, setup->world, setup->view, target);
    EXPECT_TRUE(stats.ran);
    EXPECT_GT(stats.trianglesHidden, 0u);
    EXPECT_LT(submittedTriangles(bench.scene, list), submittedTriangles(bench.scene, conservative));
    // ...and not when a triangle costs the draw nothing: then the next call skips the pass and
    // gives conservative's plan, the one after runs it again, then two are skipped.
    target.drawNsPerTriangle = 0.0;
    std::vector<bool> ran;
    for (int call = 0; call < 6; ++call) {
        list = bench.culler.cull(Cull::Occlusion, bench.scene, setup->world, setup->view, target);
        ran.push_back(stats.ran);
        if (!stats.ran) {
            EXPECT_TRUE(test::sameList(list, conservative));
        }
    }
    EXPECT_EQ(ran, (std::vector<bool>{true, false, true, false, false, true}));

    // The draws it saves count too: with triangles free and draws dear it runs on every call
    // (the box behind is a draw the plan no longer makes), with both free it backs off (each
    // from a culler of its own: none has backed off before).
    target.drawNsPerTriangle = 0.0;
    target.gathering = {1, 1u << 30};  // an instance's ranges one draw (the front box's, split, too)
    for (const double drawNs : {1e12, 0.0}) {  // a draw dearer than any pass, even under a sanitizer
        target.drawNsPerDraw = drawNs;
        CullBench fresh(Scene(copy), 96, 72);
        ran.clear();
        for (int call = 0; call < 3; ++call) {
            fresh.culler.cull(Cull::Occlusion, fresh.scene, setup->world, setup->view, target);
            ran.push_back(fresh.culler.occlusion().stats().ran);
        }
        EXPECT_EQ(ran, drawNs > 0.0 ? (std::vector<bool>{true, true, true}) : (std::vector<bool>{true, false, true}))
            << drawNs << " ns a draw";
    }

    // A plan of a few triangles is never worth the pass.
    Scene small = emptyScene("small");
    addBox(small, glm::vec3(1.0f), {0, 0, 0});
    small.buildInstances();
    CullBench smallBench(std::move(small), 96, 72);
    target.drawNsPerTriangle = 1e6;
    Result<FrameSetup> smallSetup = setUpFrame(smallBench.scene, test::lookAt({0, 0, 6}, {0, 0, 0}), 0.0, 96, 72, true);
    ASSERT_TRUE(smallSetup);
    smallBench.culler.cull(Cull::Occlusion, smallBench.scene, smallSetup->world, smallSetup->view, target);
    EXPECT_FALSE(smallBench.culler.occlusion().stats().ran);
}

TEST(OcclusionTest, TheDrawsItSavesAreTheDrawsThePlansMake) {
    // A wall in front of a row of small boxes (12 triangles each, a draw each): the ones behind it
    // go whole, the ones beside it stay; a box half behind the wall's edge loses some faces. What
    // the pass counts as saved is, for every way a backend may draw an instance's ranges, the
    // draws of the conservative plan less those of its own, as the draw lists give them.
    Scene scene = emptyScene("draws");
    addBox(scene, {1.5f, 1.0f, 0.2f}, {0, 0, 0}, 0, 12);
    for (int i = 0; i < 9; ++i) addBox(scene, glm::vec3(0.25f), {-2.6f + 0.65f * float(i), 0.1f * float(i % 3), -2.0f}, 0, 1);
    scene.buildInstances();
    CullBench bench(std::move(scene), 160, 120);
    Result<FrameSetup> setup = setUpFrame(bench.scene, test::lookAt({0.3f, 0.4f, 5}, {0, 0, -1}), 0.0, 160, 120, true);
    ASSERT_TRUE(setup);
    const DrawList conservative = bench.culler.cull(Cull::Conservative, bench.scene, setup->world, setup->view);
    const auto drawsOf = [&](const DrawList& list, const RangeGathering& g) {
        std::int64_t draws = 0;
        for (const DrawCommand& command : list) {
            std::uint64_t triangles = 0;
            for (const IndexRange& r : command.ranges) triangles += r.triangleCount;
            draws += std::int64_t(g.drawsOf(command.ranges.size(), triangles));
        }
        return draws;
    };
    for (const RangeGathering& g : {RangeGathering{}, RangeGathering{1, 1u << 30}, RangeGathering{2, 3}}) {
        OcclusionTarget target = bench.occlusionTarget();
        target.gathering = g;
        const DrawList occlusion = bench.culler.cull(Cull::Occlusion, bench.scene, setup->world, setup->view, target);
        const OcclusionStats& stats = bench.culler.occlusion().stats();
        ASSERT_TRUE(stats.ran);
        ASSERT_LT(occlusion.size(), conservative.size()) << "boxes behind the wall go whole";
        EXPECT_EQ(stats.drawsSaved, drawsOf(conservative, g) - drawsOf(occlusion, g)) << g.minRuns << " " << g.maxAverageRun;
        if (g.minRuns == 1) {
            EXPECT_EQ(stats.drawsSaved, std::int64_t(conservative.size() - occlusion.size())) << "a draw an instance";
        }
    }
}

}  // namespace
}  // namespace frugal
