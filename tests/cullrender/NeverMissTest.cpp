// The central property of culling: `conservative` (and sphere, backface, cones, conservative by
// construction) never drops a triangle that owns a pixel of the full render, and its plan renders
// the same image byte for byte. Judged on the software reference with the id image (RVS) of the
// full render of the same, reordered scene. `paper` may miss: its plans are only checked for shape.
#include <filesystem>
#include <iostream>
#include <random>

#include <gtest/gtest.h>

#include "CullRenderSupport.h"
#include "TestSupport.h"
#include "lab/Views.h"

namespace frugal {
namespace {

using test::CullBench;
using test::Tallies;

void expectSomethingSeen(Tallies& tallies) {
    std::cout << "[ tally    ] " << tallies.summary() << "\n";
    EXPECT_GT(tallies.rendered, 0u) << tallies.summary();
    EXPECT_GT(tallies.of(Cull::Conservative).rvs, 0u)
        << "nothing visible: the test proves nothing; " << tallies.summary();
}

TEST(NeverMissTest, BunnySingleSidedOverReportViews) {
    std::optional<Scene> bunny = test::loadBunny(false);
    if (!bunny) FRUGAL_SKIP_IF_MISSING(FRUGAL_BUNNY_OBJ << " (glmark2-data)");
    CullBench bench(std::move(*bunny), 128, 96);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    Tallies tallies = test::checkReportViews(bench, 12, "bunny single-sided");
    expectSomethingSeen(tallies);
    // Single-sided: backface and conservative drop about half of a closed mesh in every view.
    EXPECT_LT(tallies.of(Cull::Conservative).pvs, tallies.of(Cull::Conservative).tos * 7 / 10) << tallies.summary();
    EXPECT_LE(tallies.of(Cull::Conservative).pvs, tallies.of(Cull::Cones).pvs) << tallies.summary();
    EXPECT_LE(tallies.of(Cull::Backface).pvs, tallies.of(Cull::Conservative).pvs) << tallies.summary();
}

TEST(NeverMissTest, BunnyDoubleSidedOverReportViews) {
    std::optional<Scene> bunny = test::loadBunny(true);
    if (!bunny) FRUGAL_SKIP_IF_MISSING(FRUGAL_BUNNY_OBJ << " (glmark2-data)");
    CullBench bench(std::move(*bunny), 128, 96);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    Tallies tallies = test::checkReportViews(bench, 12, "bunny double-sided");
    expectSomethingSeen(tallies);
    // Double-sided: only the frustum culls, so partial and grazing views still drop something.
    EXPECT_LT(tallies.of(Cull::Conservative).pvs, tallies.of(Cull::Conservative).tos) << tallies.summary();
}

TEST(NeverMissTest, ThreeBunnies) {
    Result<Scene> scene = loadScene(std::string("builtin:copies?count=3&of=") + FRUGAL_BUNNY_OBJ,
                                    LoadOptions{true, false});
    if (!std::filesystem::exists(FRUGAL_BUNNY_OBJ)) FRUGAL_SKIP_IF_MISSING(FRUGAL_BUNNY_OBJ << " (glmark2-data)");
    ASSERT_TRUE(scene) << scene.error().message;
    ASSERT_EQ(scene->instances.size(), 3u);
    CullBench bench(std::move(*scene), 96, 72);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    EXPECT_EQ(bench.culler.maps().size(), bench.scene.meshes.size()) << "shared meshes are prepared once";
    Tallies tallies;
    tallies.add(test::checkFrame(bench, {}, "three bunnies, fitted camera"));
    // Close to the middle bunny: the outer ones are partly or wholly outside.
    const Bounds bounds = bench.scene.bounds(0.0);
    const glm::vec3 c = bounds.center();
    const float r = bounds.radius();
    tallies.add(test::checkFrame(bench, test::lookAt(c + glm::vec3(0.0f, 0.05f * r, 0.45f * r), c),
                                 "three bunnies, middle close up"));
    tallies.add(test::checkFrame(bench, test::lookAt(c + glm::vec3(1.5f * r, 0.2f * r, 0.0f), c),
                                 "three bunnies, along the row"));
    tallies.add(test::checkFrame(bench, test::lookAt(c, c + glm::vec3(0.0f, 0.0f, -1.0f)),
                                 "three bunnies, from the centre"));
    expectSomethingSeen(tallies);
}

// Back faces seen nearly edge-on: GL decides facing from window positions snapped to 1/256 pixel,
// so a triangle that faces away by a small angle may be drawn after all. Culling keeps every
// triangle within its snapping margin of edge-on (Culling.cpp, InstanceView).
TEST(NeverMissTest, BackFacesNearlyEdgeOnThatSnappingTurns) {
    // The view of three bunnies where conservative culling first missed such a triangle (one
    // pixel), at 800x600 as cull-report drew it.
    if (!std::filesystem::exists(FRUGAL_BUNNY_OBJ)) FRUGAL_SKIP_IF_MISSING(FRUGAL_BUNNY_OBJ << " (glmark2-data)");
    Result<Scene> three = loadScene(std::string("builtin:copies?count=3&of=") + FRUGAL_BUNNY_OBJ, LoadOptions{true, false});
    ASSERT_TRUE(three) << three.error().message;
    for (Material& m : three->materials) m.doubleSided = false;
    CullBench bunnies(std::move(*three), 800, 600);
    ASSERT_TRUE(bunnies.canRender()) << bunnies.uploadError;
    Tallies tallies;
    tallies.add(test::checkFrame(bunnies, test::lookAt({-5.78f, 2.0f, 10.0113f}, {0.0f, 0.0f, 0.0f}),
                                 "three bunnies, orbit view 44"));
    expectSomethingSeen(tallies);

    // Many small back faces, each turned away from edge-on by an angle from 1e-4 to 0.05 radians,
    // with edges of 0.5 to 4 pixels, single-sided, in front of a camera at the origin.
    constexpr int kWidth = 160, kHeight = 120, kTriangles = 40000;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    Mesh mesh;
    mesh.name = "edge-on";
    const float tanHalf = std::tan(glm::radians(20.0f));
    for (int i = 0; i < kTriangles; ++i) {
        const float z = 4.0f + 6.0f * unit(rng);
        const glm::vec3 centre((2.0f * unit(rng) - 1.0f) * 0.95f * tanHalf * z * float(kWidth) / float(kHeight),
                               (2.0f * unit(rng) - 1.0f) * 0.95f * tanHalf * z, -z);
        const glm::vec3 ray = glm::normalize(centre);
        glm::vec3 side = glm::cross(ray, glm::vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f));
        if (glm::length(side) < 1e-3f) continue;
        side = glm::normalize(side);
        const float angle = std::exp(std::log(1e-4f) + (std::log(0.05f) - std::log(1e-4f)) * unit(rng));
        // Edge-on the normal would be ray × side; turned towards the ray, it faces away.
        const glm::vec3 normal = glm::normalize(std::cos(angle) * glm::cross(ray, side) + std::sin(angle) * ray);
        const glm::vec3 other = glm::cross(normal, side);  // (side, other, normal) right-handed
        const float pixel = 2.0f * tanHalf * z / float(kHeight);
        const auto base = std::uint32_t(mesh.positions.size());
        for (int k = 0; k < 3; ++k) {
            const float phi = 2.0f * glm::pi<float>() * (float(k) + 0.6f * unit(rng)) / 3.0f;
            const float r = (0.25f + 1.75f * unit(rng)) * pixel;
            mesh.positions.push_back(centre + r * (std::cos(phi) * side + std::sin(phi) * other));
        }
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});  // counter-clockwise about `normal`
    }
    Scene slivers = test::singleMeshScene(test::finished(std::move(mesh), false), false);
    CullBench bench(std::move(slivers), kWidth, kHeight);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    const test::FrameResult frame =
        test::checkFrame(bench, test::lookAt({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}), "edge-on back faces");
    ASSERT_TRUE(frame.rendered);
    // Snapping turned some of them: they own pixels, and no method that never misses dropped them.
    EXPECT_GT(frame.rvs, 0u) << "no back face was drawn: the test proves nothing";
    EXPECT_LT(frame.count(Cull::Backface).pvs, frame.count(Cull::Backface).tos) << "nothing was dropped for facing";
}

TEST(NeverMissTest, DefaultDominoesOverTime) {
    Result<Scene> scene = loadScene("builtin:default");
    ASSERT_TRUE(scene) << scene.error().message;
    CullBench bench(std::move(*scene), 160, 120);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    Tallies tallies;
    const double duration = bench.scene.duration();
    for (double time : {0.0, 0.37 * duration, duration})
        tallies.add(test::checkFrame(bench, {}, "dominoes, scene camera, t = " + std::to_string(time), time));
    Tallies views = test::checkReportViews(bench, 8, "dominoes", 0.5 * duration);
    expectSomethingSeen(tallies);
    expectSomethingSeen(views);
}

// Morph targets: a morphing instance is drawn whole by every method (its map is of its rest pose)
// and is no occluder; the others are culled as always. Over weights from (−1, 10) to (10, 0.5).
TEST(NeverMissTest, MorphingSceneOverTime) {
    CullBench bench(test::morphingScene(), 160, 120);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    Tallies tallies;
    for (double time : {0.0, 0.5, 1.0, 1.7, 2.0, 2.6, 3.0, 3.5, 4.0})
        tallies.add(test::checkFrame(bench, {}, "morphing, t = " + std::to_string(time), time));
    Tallies views = test::checkReportViews(bench, 6, "morphing", 1.0);
    expectSomethingSeen(tallies);
    expectSomethingSeen(views);
}

// Skins: the skinned instance is drawn whole by every method, the static spheres culled as always,
// over a bend of 120 degrees and a joint scaled from 3 to 1 and back (and with weights that do not
// sum to 1).
TEST(NeverMissTest, SkinnedSceneOverTime) {
    for (const bool affine : {true, false}) {
        CullBench bench(test::skinnedScene(3.0f, affine), 160, 120);
        ASSERT_TRUE(bench.canRender()) << bench.uploadError;
        Tallies tallies;
        for (double time : {0.0, 0.7, 1.3, 2.0, 2.9, 3.6, 4.0})
            tallies.add(test::checkFrame(bench, {}, "skinned, t = " + std::to_string(time), time));
        Tallies views = test::checkReportViews(bench, 6, "skinned", 2.0);
        expectSomethingSeen(tallies);
        expectSomethingSeen(views);
    }
}

// Points and segments: drawn whole by every method (never culled, so never wrongly) and never
// occluders; the spheres around them culled as always.
TEST(NeverMissTest, PointsAndLinesOverTime) {
    CullBench bench(test::pointsLinesScene(), 160, 120);
    ASSERT_TRUE(bench.canRender()) << bench.uploadError;
    Tallies tallies;
    for (double time : {0.0, 0.9, 2.0, 3.1, 4.0})
        tallies.add(test::checkFrame(bench, {}, "points and lines, t = " + std::to_string(time), time));
    Tallies views = test::checkReportViews(bench, 6, "points and lines", 1.0);
    expectSomethingSeen(tallies);
    expectSomethingSeen(views);
}

// ---------------------------------------------------------------------------------------------
// Property: random meshes, random instances (mirrored, non-uniformly scaled, single- and
// double-sided) and random views, cameras inside the bounding sphere included.

struct RandomCase {
    Scene scene;
    std::string label;
};

RandomCase randomScene(unsigned seed) {
    std::mt19937 rng(seed * 7919u + 13u);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), unit(0.0f, 1.0f);
    RandomCase made;
    Scene& scene = made.scene;
    scene.materials.resize(2);
    scene.materials[0].baseColorFactor = {0.9f, 0.6f, 0.3f, 1.0f};
    scene.materials[1].baseColorFactor = {0.3f, 0.7f, 0.9f, 1.0f};
    scene.materials[1].doubleSided = true;
    const int kind = int(seed % 3);
    Mesh mesh;
    if (kind == 0) {
        mesh = test::soupMesh(seed, 150 + int(seed % 5) * 60);
        made.label = "soup";
    } else if (kind == 1) {
        mesh = test::blobMesh(seed, 10 + int(seed % 7), 16 + int(seed % 11));
        made.label = "blob";
    } else {
        // A blob with a soup inside and around it: occlusion and open parts in one mesh.
        Mesh blob = test::blobMesh(seed, 12, 20), soup = test::soupMesh(seed, 120);
        const auto base = std::uint32_t(blob.positions.size());
        for (glm::vec3& p : soup.positions) p *= 1.6f;
        blob.positions.insert(blob.positions.end(), soup.positions.begin(), soup.positions.end());
        for (std::uint32_t i : soup.indices) blob.indices.push_back(base + i);
        mesh = std::move(blob);
        made.label = "blob+soup";
    }
    mesh = test::finished(std::move(mesh), seed % 2 == 0);
    // Material: single-sided, double-sided, or the default material (-1, single-sided).
    const int materialChoice = int((seed / 3) % 3);
    mesh.material = materialChoice == 2 ? -1 : materialChoice;
    made.label += materialChoice == 1 ? " double-sided" : " single-sided";
    scene.meshes.push_back(std::move(mesh));

    const int instances = 1 + int(seed % 3);
    for (int k = 0; k < instances; ++k) {
        const glm::vec3 axis = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0.0f, 0.0f, 1e-3f));
        const glm::quat rotation = glm::angleAxis(3.14159f * u(rng), axis);
        glm::vec3 scale(1.0f);
        if ((seed + unsigned(k)) % 2 == 1) scale = glm::vec3(0.5f + unit(rng) * 1.5f, 0.5f + unit(rng) * 1.5f, 0.5f + unit(rng) * 1.5f);
        if ((seed + unsigned(k)) % 3 == 1) {
            scale.x = -scale.x;  // mirrored
            made.label += " mirrored";
        }
        if ((seed + unsigned(k)) % 5 == 4) scale = -scale;  // odd number of negative axes again
        test::addMeshNode(scene, 0, glm::vec3(float(k) * 2.5f, 0.3f * u(rng), 0.3f * u(rng)), rotation, scale);
    }
    scene.buildInstances();
    made.label += " x" + std::to_string(instances) + " (seed " + std::to_string(seed) + ")";
    return made;
}

// Random views of a scene: report views plus cameras inside the bounding sphere looking anywhere,
// and cameras outside with random near/far planes.
std::vector<Camera> randomViews(const Scene& scene, unsigned seed, int count) {
    std::mt19937 rng(seed * 31u + 5u);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), unit(0.0f, 1.0f);
    const Bounds bounds = scene.bounds(0.0);
    const glm::vec3 c = bounds.center();
    const float r = bounds.radius();
    std::vector<Camera> views;
    for (const ReportView& view : reportViews(c, r, 4, 40.0f, 4.0f / 3.0f)) views.push_back(view.camera);
    while (int(views.size()) < count) {
        const glm::vec3 dir = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(1e-3f));
        Camera spec;
        if (views.size() % 2 == 0) {
            // Inside the bounding sphere, looking in a random direction.
            const glm::vec3 eye = c + 0.8f * r * unit(rng) * dir;
            const glm::vec3 look = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0.0f, 0.0f, 1e-3f));
            spec = test::lookAt(eye, eye + look, std::abs(look.y) > 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
            spec.znear = 0.01f * r;
        } else {
            const glm::vec3 eye = c + (1.2f + 2.0f * unit(rng)) * r * dir;
            const glm::vec3 target = c + 0.7f * r * glm::vec3(u(rng), u(rng), u(rng));
            spec = test::lookAt(eye, target, std::abs(dir.y) > 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
            spec.yfovDegrees = 20.0f + 70.0f * unit(rng);
            if (unit(rng) < 0.5f) {
                const float distance = glm::length(c - eye);
                spec.znear = std::max(0.01f * r, distance - r * unit(rng));
                spec.zfar = *spec.znear + 2.0f * r * unit(rng) + 0.01f * r;
            }
        }
        views.push_back(spec);
    }
    return views;
}

void checkRandomScenes(unsigned firstSeed, unsigned lastSeed) {
    Tallies all;
    for (unsigned seed = firstSeed; seed <= lastSeed; ++seed) {
        RandomCase made = randomScene(seed);
        const std::string label = made.label;
        CullBench bench(std::move(made.scene), 96, 72);
        ASSERT_TRUE(bench.canRender()) << label << ": " << bench.uploadError;
        const std::vector<Camera> views = randomViews(bench.scene, seed, 8);
        for (std::size_t k = 0; k < views.size(); ++k)
            all.add(test::checkFrame(bench, views[k], label + ", view " + std::to_string(k)));
    }
    expectSomethingSeen(all);
    EXPECT_EQ(all.rendered, all.frames) << all.summary();
}

TEST(NeverMissTest, RandomScenes1To10) { checkRandomScenes(1, 10); }
TEST(NeverMissTest, RandomScenes11To20) { checkRandomScenes(11, 20); }
TEST(NeverMissTest, RandomScenes21To30) { checkRandomScenes(21, 30); }

// Coarse and fine maps: the plans must not depend on the bin layout for their correctness.
TEST(NeverMissTest, OtherMapParams) {
    for (const MapParams& params : {MapParams{1, 1}, MapParams{3, 7}, MapParams{64, 128}}) {
        RandomCase made = randomScene(100 + unsigned(params.thetaBins));
        const std::string label = made.label + " bins " + std::to_string(params.thetaBins) + "x" +
                                  std::to_string(params.phiBins);
        CullBench bench(std::move(made.scene), 96, 72, params);
        ASSERT_TRUE(bench.canRender()) << bench.uploadError;
        Tallies tallies;
        const std::vector<Camera> views = randomViews(bench.scene, 77, 6);
        for (std::size_t k = 0; k < views.size(); ++k)
            tallies.add(test::checkFrame(bench, views[k], label + ", view " + std::to_string(k)));
        expectSomethingSeen(tallies);
    }
}

}  // namespace
}  // namespace frugal
