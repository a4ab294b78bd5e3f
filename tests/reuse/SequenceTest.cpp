// Temporal reuse on the software reference: every frame of every sequence equals the full render of
// that frame in colour, depth and ids (ties aside, counted; none in these scenes but the one made
// for them). Scenes: the paper's dominoes, the cubes, builtin:default, a camera path that moves,
// stops and moves again, objects that leave the screen, fly through the camera or appear, nothing
// dynamic, everything dynamic, every grain × cell, culled draw lists, glTF files with node
// animation, NaN matrices, material changes, and a scene made for exact depth ties.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "ReuseSupport.h"
#include "TestSupport.h"
#include "cull/Culling.h"
#include "software/SoftwareBackend.h"

namespace frugal::test {
namespace {

namespace fs = std::filesystem;

// The sequence on a fresh software backend, exact (expectExactOn).
SequenceResult expectExact(const Scene& scene, int width, int height, int frames, const Frames& frame,
                           const ReuseOptions& options = {}, bool tiesAllowed = false) {
    auto backend = makeSoftwareBackend();
    return expectExactOn(*backend, scene, width, height, frames, frame, options, tiesAllowed);
}

// The same with and without the fallback (which hides the reuse path on expensive frames), each
// with steps a–d and with the paper's steps: results [0] fallback, [1] fallback + paper, [2] no
// fallback, [3] no fallback + paper.
std::vector<SequenceResult> expectExactEveryWay(const Scene& scene, int width, int height, int frames, const Frames& frame,
                                                int grain = 16, int cell = 16) {
    std::vector<SequenceResult> results;
    for (bool fallback : {true, false})
        for (bool paper : {false, true})
            results.push_back(expectExact(scene, width, height, frames, frame, reuseOptions(grain, cell, fallback, paper)));
    return results;
}

// ---------------------------------------------------------------------------------------------
// Built-in scenes.

TEST(ReuseSequence, DominoesAtThePapersSizesMatchTheFullRender) {
    for (const char* spec : {"builtin:dominoes?polygons=804&static=0.5544", "builtin:dominoes?polygons=1404&static=0.9866"}) {
        SCOPED_TRACE(spec);
        const Scene scene = loadOrFail(spec);
        const SequenceResult r = expectExact(scene, 200, 150, 20, animated(scene, {}, 200, 150));
        EXPECT_EQ(r.modes(), "RUUUUUUUUUUUUUUUUUUU") << r.describe();
        // Reuse redraws less than a full render on every reuse frame.
        for (std::size_t i = 1; i < r.stats.size(); ++i) EXPECT_LT(r.stats[i].redrawnTris, r.stats[i].drawnTris) << i;
        expectExactEveryWay(scene, 200, 150, 20, animated(scene, {}, 200, 150));
    }
}

// Blended instances are dynamic in every frame and drawn after the rest (Reuse.h); masked ones are
// reused like any other: the sequence still matches the full render, pixel for pixel.
TEST(ReuseSequence, BlendedAndMaskedSurfacesMatchTheFullRender) {
    Scene scene = loadOrFail("builtin:dominoes?polygons=804&static=0.5544");
    test::addAlpha(scene);
    std::uint64_t blended = 0;
    for (int i = 0; i < int(scene.instances.size()); ++i) blended += blendedInstance(scene, i) ? 1 : 0;
    ASSERT_GT(blended, 0u);
    const std::vector<SequenceResult> results = expectExactEveryWay(scene, 200, 150, 20, animated(scene, {}, 200, 150));
    for (const SequenceResult& r : results)
        for (std::size_t i = 0; i < r.stats.size(); ++i)
            EXPECT_GE(r.stats[i].instances.sd + r.stats[i].instances.dd, blended) << "frame " << i << ": " << r.describe();
}

// The same in linear colour (a float target): blended surfaces mix in float, and the static pair's
// copies and the redrawn parts still give the full render's floats, bit for bit.
TEST(ReuseSequence, BlendedAndMaskedSurfacesInLinearColourMatchTheFullRender) {
    Scene scene = loadOrFail("builtin:dominoes?polygons=804&static=0.5544");
    test::addAlpha(scene);
    auto backend = makeSoftwareBackend();
    for (bool fallback : {true, false}) {
        const SequenceResult r = runSequence(*backend, scene, 200, 150, 20, animated(scene, {}, 200, 150),
                                             reuseOptions(16, 16, fallback), {}, false, ColorFormat::Rgba32F);
        EXPECT_EQ(r.errors, 0u) << r.describe();
        EXPECT_EQ(r.modes().find('U') != std::string::npos, true) << r.describe();
    }
}

// A morphing instance is dynamic in the frames its weights change, and its extents are of its posed
// positions: the still spheres are reused around it, and every frame is the full render's.
TEST(ReuseSequence, MorphTargetsMatchTheFullRender) {
    const Scene scene = test::morphingScene();
    const Camera camera = eyeAt({0.5f, 1.0f, 6.0f}, {0.5f, 0.0f, 0.0f});
    const std::vector<SequenceResult> results =
        expectExactEveryWay(scene, 200, 150, 40, animated(scene, camera, 200, 150));
    const std::string modes = results[2].modes();  // no fallback: the reuse path on every frame it can take
    EXPECT_NE(modes.find('U'), std::string::npos) << results[2].describe();
}

// A skinned instance is dynamic in the frames its joints move; the static spheres are reused.
TEST(ReuseSequence, SkinsMatchTheFullRender) {
    const Scene scene = test::skinnedScene(3.0f);
    const Camera camera = eyeAt({0.5f, 1.0f, 7.0f}, {0.5f, 0.5f, 0.0f});
    const std::vector<SequenceResult> results =
        expectExactEveryWay(scene, 200, 150, 40, animated(scene, camera, 200, 150));
    EXPECT_NE(results[2].modes().find('U'), std::string::npos) << results[2].describe();
}

// A moving ring of segments is dynamic (its boxes one pixel wider than a triangle's: its pixels
// reach half a pixel past it); the still points, strip and spheres are reused around it.
TEST(ReuseSequence, PointsAndLinesMatchTheFullRender) {
    const Scene scene = test::pointsLinesScene();
    const Camera camera = eyeAt({0.5f, 1.0f, 7.0f}, {0.0f, 0.0f, 0.0f});
    const std::vector<SequenceResult> results =
        expectExactEveryWay(scene, 200, 150, 40, animated(scene, camera, 200, 150));
    EXPECT_NE(results[2].modes().find('U'), std::string::npos) << results[2].describe();
}

TEST(ReuseSequence, CubesEverythingDynamicFallsBackAndStillMatches) {
    const Scene scene = loadOrFail("builtin:cubes");
    // Every cube spins: from the second frame on, everything is dynamic.
    const SequenceResult r = expectExact(scene, 160, 120, 12, animated(scene, {}, 160, 120));
    EXPECT_EQ(r.modes(), "RFFFFFFFFFFF") << r.describe();
    for (std::size_t i = 1; i < r.stats.size(); ++i) {
        EXPECT_EQ(r.stats[i].instances.sd + r.stats[i].instances.dd, scene.instances.size()) << i;
        EXPECT_FALSE(r.stats[i].reason.empty());
    }
    // Without the fallback the reuse path runs on every frame, and is exact too.
    const SequenceResult forced = expectExact(scene, 160, 120, 12, animated(scene, {}, 160, 120), reuseOptions(16, 16, false));
    EXPECT_EQ(forced.modes(), "RUUUUUUUUUUU") << forced.describe();
    expectExactEveryWay(scene, 160, 120, 12, animated(scene, {}, 160, 120), 1, 8);
}

TEST(ReuseSequence, DefaultSceneWholeAnimationMatchesExactly) {
    // The dominoes on the textured floor, every frame of the animation (the last domino comes to
    // rest at frame dominoes + moving), at a small size: not one pixel differs.
    const Scene scene = loadOrFail("builtin:default");
    ASSERT_FALSE(scene.textures.empty());
    const int frames = int(std::ceil(scene.duration() * scene.fps)) + 3;
    ASSERT_GT(frames, 150);
    for (bool paper : {false, true}) {
        const SequenceResult r = expectExact(scene, 200, 150, frames, animated(scene, {}, 200, 150), reuseOptions(16, 16, true, paper));
        EXPECT_EQ(r.modes(), "R" + std::string(std::size_t(frames - 1), 'U')) << r.describe();
        EXPECT_EQ(r.stats.back().instances.ss, scene.instances.size()) << "everything at rest at the end";
    }
}

// At 800×600 builtin:default has exact depth ties: a falling domino's front face (box face +z,
// triangle source 9) meets the floor along the domino's pivot edge, and at a pixel whose centre lies
// on that line both planes round to the same 24-bit depth. The full render keeps the domino (drawn
// before the floor); reuse draws the static floor first and keeps it. Every tie found must be that:
// reuse shows the floor, the full render a domino that moved in this frame, and the floor and that
// domino drawn alone give the pixel the same depth.
TEST(ReuseSequence, DefaultSceneTiesAreExactFloorDominoTies) {
    const Scene scene = loadOrFail("builtin:default");
    const int w = 800, h = 600, first = 40, frames = 13;
    const int floorInstance = int(scene.instances.size()) - 1;
    const std::uint32_t floorFirst = scene.instances[std::size_t(floorInstance)].firstId;
    const Frames sequence = [&scene](int i) { return frameAt(scene, {}, frameTime(first + i, scene.fps), w, h); };
    auto backend = makeSoftwareBackend();
    Result<SceneRenderer> made = SceneRenderer::create(*backend, scene);
    ASSERT_TRUE(made) << made.error().message;
    const TargetHandle alone = backend->createTarget(w, h);
    const auto instanceOf = [&scene](std::uint32_t id) {
        int found = -1;
        for (std::size_t k = 0; k < scene.instances.size(); ++k)
            if (id >= scene.instances[k].firstId) found = int(k);
        return found;
    };
    for (bool paper : {false, true}) {
        SCOPED_TRACE(paper ? "the paper's steps" : "steps a-d");
        std::size_t checked = 0;
        std::ostringstream perFrame;
        const SequenceResult r = runSequence(
            *backend, scene, w, h, frames, sequence, reuseOptions(16, 16, true, paper),
            [&](int i, const Buffers& a, const Buffers& b, const ReuseFrameStats&) {
                const SequenceFrame f = sequence(i), before = sequence(std::max(i - 1, 0));
                std::size_t k = 0;
                for (std::size_t p = 0; p < a.ids.size(); ++p) {
                    if (a.depth[p] != b.depth[p] || (a.ids[p] == b.ids[p] && std::memcmp(&a.rgba[4 * p], &b.rgba[4 * p], 4) == 0))
                        continue;
                    ++k;
                    const std::string where = "frame " + std::to_string(first + i) + " pixel (" + std::to_string(p % w) + ", " +
                                              std::to_string(p / w) + ")";
                    EXPECT_GE(a.ids[p], floorFirst) << where << ": reuse shows the floor";
                    const int domino = instanceOf(b.ids[p]);
                    ASSERT_GE(domino, 0);
                    EXPECT_LT(domino, floorInstance) << where << ": the full render shows a domino";
                    const std::size_t node = std::size_t(scene.instances[std::size_t(domino)].node);
                    EXPECT_TRUE(i > 0 && f.world[node] != before.world[node]) << where << ": the domino moved in this frame";
                    for (int instance : {floorInstance, domino}) {
                        made->renderFrame(alone, w, h, f.params, f.world, kReuseBackground, DrawList{f.list[std::size_t(instance)]});
                        const Buffers one = backend->readBack(alone);
                        EXPECT_EQ(one.depth[p], a.depth[p]) << where << ": instance " << instance << " alone";
                        EXPECT_NE(one.ids[p], 0u) << where << ": instance " << instance << " alone";
                    }
                    ++checked;
                }
                perFrame << " " << k;
            });
        EXPECT_EQ(r.errors, 0u) << r.describe();
        EXPECT_EQ(checked, r.ties);
        std::cout << "[ builtin:default 800x600 frames " << first << ".." << first + frames - 1 << ", "
                  << (paper ? "the paper's steps" : "steps a-d") << " ] tie_px " << r.ties << " per frame:" << perFrame.str()
                  << "\n";
    }
    backend->destroyTarget(alone);
}

// ---------------------------------------------------------------------------------------------
// Cameras.

TEST(ReuseSequence, CameraPathMovesStopsMovesAgain) {
    const Scene scene = loadOrFail("builtin:dominoes?polygons=1404&static=0.9866");
    const CameraPath path;
    const Frames frames = path.of(scene, 200, 150);
    for (bool paper : {false, true}) {
        const SequenceResult res = expectExact(scene, 200, 150, path.frames(), frames, reuseOptions(16, 16, true, paper));
        EXPECT_EQ(res.modes(), path.modes) << res.describe();
        for (std::size_t i = 0; i < res.stats.size(); ++i) {
            if (path.modes[i] == 'F') {
                EXPECT_EQ(res.stats[i].reason, "camera, light or background changed") << i;
            }
            if (path.modes[i] == 'R') {
                EXPECT_EQ(res.stats[i].reason, i == 0 ? "first frame" : "first still frame") << i;
            }
        }
    }
    // Without the fallback: the same modes (a moving camera is always a full render).
    const SequenceResult forced = expectExact(scene, 200, 150, path.frames(), frames, reuseOptions(16, 16, false));
    EXPECT_EQ(forced.modes(), path.modes) << forced.describe();
}

// ---------------------------------------------------------------------------------------------
// Scenes built here: a static backdrop (plate and pillars, drawn first) and dynamic objects.

const Camera kOverview = overviewCamera();

TEST(ReuseSequence, ObjectsLeaveTheScreenAndComeBack) {
    Scene scene;
    addBackdrop(scene);
    const int red = addMaterial(scene, {0.9f, 0.1f, 0.1f, 1.0f});
    const int cube = addMesh(scene, boxMesh(glm::vec3(-0.7f), glm::vec3(0.7f), red, "cube"));
    const int a = addNodeWith(scene, cube, {0.0f, 1.0f, 0.0f});
    const int b = addNodeWith(scene, cube, {-2.0f, 1.0f, 2.0f});
    // a: out to the right over frames 0..15, off screen until frame 24, back by frame 30.
    animate(scene, a, AnimPath::Translation, {{0.0f, {0, 1, 0}}, {0.5f, {40, 1, 0}}, {0.8f, {40, 1, 0}}, {1.0f, {0, 1, 2}}});
    // b: up and out of the top, and stays there.
    animate(scene, b, AnimPath::Translation, {{0.0f, {-2, 1, 2}}, {0.4f, {-2, 30, 2}}});
    scene.buildInstances();
    const std::vector<SequenceResult> results = expectExactEveryWay(scene, 160, 120, 34, withCamera(scene, kOverview, 160, 120));
    const SequenceResult& r = results.front();
    // Off screen and at rest (frames 16..23): nothing to do at all.
    for (int i = 17; i < 24; ++i) {
        EXPECT_EQ(r.stats[std::size_t(i)].mode, ReuseMode::Reuse) << i;
        EXPECT_EQ(r.stats[std::size_t(i)].redrawnTris, 0u) << i;
        EXPECT_EQ(r.stats[std::size_t(i)].copiedPx + r.stats[std::size_t(i)].clearedPx, 0u) << i;
    }
}

TEST(ReuseSequence, AnObjectFliesThroughTheCamera) {
    const Scene scene = flyThroughScene();
    const std::vector<SequenceResult> results = expectExactEveryWay(scene, 160, 120, 22, withCamera(scene, kOverview, 160, 120));
    // Without the fallback, the reuse path ran on every frame after the first, including those
    // with a vertex behind the eye (whole-screen extents).
    const SequenceResult& forced = results[2];
    EXPECT_EQ(forced.count(ReuseMode::Reuse), 21u) << forced.describe();
}

TEST(ReuseSequence, ObjectsAppear) {
    Scene scene;
    addBackdrop(scene);
    const int blue = addMaterial(scene, {0.2f, 0.3f, 0.9f, 1.0f});
    const int cube = addMesh(scene, boxMesh(glm::vec3(-0.8f), glm::vec3(0.8f), blue, "grower"));
    const int grower = addNodeWith(scene, cube, {1.5f, 1.0f, 1.0f}, glm::vec3(0.0f));
    animate(scene, grower, AnimPath::Scale, {{0.0f, glm::vec3(0.0f)}, {0.2f, glm::vec3(0.0f)}, {0.4f, glm::vec3(1.0f)}});
    const int popper = addNodeWith(scene, cube, {-1.5f, 1.0f, -1.0f}, glm::vec3(0.0f));
    animate(scene, popper, AnimPath::Scale, {{0.0f, glm::vec3(0.0f)}, {0.3f, glm::vec3(1.0f)}}, Interp::Step);
    const int listed = addNodeWith(scene, cube, {0.0f, 2.5f, 3.0f});
    scene.buildInstances();
    // `listed` is drawn only in frames 6..13 (added to the draw list, then taken out).
    int listedInstance = -1;
    for (std::size_t i = 0; i < scene.instances.size(); ++i)
        if (scene.instances[i].node == listed) listedInstance = int(i);
    ASSERT_GE(listedInstance, 0);
    const Frames frames = withCamera(scene, kOverview, 160, 120, [listedInstance](int i, SequenceFrame& f) {
        if (i < 6 || i > 13) std::erase_if(f.list, [listedInstance](const DrawCommand& c) { return c.instance == listedInstance; });
    });
    const std::vector<SequenceResult> results = expectExactEveryWay(scene, 160, 120, 18, frames);
    const SequenceResult& r = results.front();
    EXPECT_EQ(r.stats[6].instances.sd, 1u) << "the added instance is dynamic when it appears";
    EXPECT_EQ(r.stats[14].instances.sd, 1u) << "and when it leaves";
}

TEST(ReuseSequence, NothingDynamic) {
    const Scene scene = loadOrFail("builtin:dominoes?polygons=804&static=0.5544");
    const Frames still = [&scene](int) { return frameAt(scene, {}, 0.5, 160, 120); };
    const SequenceResult r = expectExact(scene, 160, 120, 8, still);
    EXPECT_EQ(r.modes(), "RUUUUUUU") << r.describe();
    for (std::size_t i = 1; i < r.stats.size(); ++i) {
        EXPECT_EQ(r.stats[i].redrawnTris, 0u) << i;
        EXPECT_EQ(r.stats[i].copiedPx + r.stats[i].clearedPx + r.stats[i].rects, 0u) << i;
        EXPECT_EQ(r.stats[i].instances.ss, scene.instances.size()) << i;
    }
    // A static scene built here too (no animation at all).
    Scene built;
    addBackdrop(built, 3);
    built.buildInstances();
    const SequenceResult b = expectExact(built, 96, 72, 5, withCamera(built, kOverview, 96, 72));
    EXPECT_EQ(b.modes(), "RUUUU");
}

TEST(ReuseSequence, EverythingDynamicBuilt) {
    // Every instance of a scene built here moves every frame, the backdrop included.
    const Scene scene = allDynamicScene();
    const std::vector<SequenceResult> results = expectExactEveryWay(scene, 120, 90, 10, withCamera(scene, kOverview, 120, 90));
    EXPECT_EQ(results[0].modes(), "RFFFFFFFFF") << results[0].describe();
    EXPECT_EQ(results[2].modes(), "RUUUUUUUUU") << results[2].describe();
}

TEST(ReuseSequence, ABurstOfMotionFallsBackThenReuseResumes) {
    // The dominoes fall as usual, but in frames 4..6 every domino is shifted (a different shift each
    // frame): the planner falls back to full renders, then rebuilds and reuses again.
    const Scene scene = loadOrFail("builtin:dominoes?polygons=804&static=0.5544");
    const Frames frames = [&scene](int i) {
        SequenceFrame f = frameAt(scene, {}, frameTime(i, scene.fps), 160, 120);
        if (i >= 4 && i <= 6)
            for (const Instance& instance : scene.instances) {
                glm::mat4& m = f.world[std::size_t(instance.node)];
                m = glm::translate(glm::mat4(1.0f), glm::vec3(0.05f * float(i - 3), 0.0f, 0.0f)) * m;
            }
        return f;
    };
    const SequenceResult r = expectExact(scene, 160, 120, 12, frames);
    EXPECT_EQ(r.modes(), "RUUUFFFFRUUU") << r.describe();
    expectExactEveryWay(scene, 160, 120, 12, frames);
}

TEST(ReuseSequence, MirroredAndDoubleSidedMovers) {
    // Negative scales swap the culled side; a double-sided box shows its inside when cut open by
    // the near plane. Both move over the backdrop.
    Scene scene;
    addBackdrop(scene);
    const int single = addMaterial(scene, {0.8f, 0.8f, 0.2f, 1.0f});
    const int twoSided = addMaterial(scene, {0.7f, 0.2f, 0.8f, 1.0f}, true);
    const int mirrored = addNodeWith(scene, addMesh(scene, boxMesh(glm::vec3(-0.5f), glm::vec3(0.5f), single, "mirrored")),
                                     {-1.0f, 1.0f, 1.0f}, {-1.0f, 1.0f, 1.0f});
    animate(scene, mirrored, AnimPath::Scale, {{0.0f, {-1.0f, 1.0f, 1.0f}}, {0.3f, {1.5f, -1.0f, 1.0f}}});
    const int open = addNodeWith(scene, addMesh(scene, boxMesh(glm::vec3(-0.5f), glm::vec3(0.5f), twoSided, "open")),
                                 {1.0f, 1.0f, 1.0f});
    animate(scene, open, AnimPath::Translation, {{0.0f, {1.0f, 1.0f, 1.0f}}, {0.3f, {1.0f, 5.0f, 9.5f}}});
    scene.buildInstances();
    expectExactEveryWay(scene, 160, 120, 12, withCamera(scene, overviewCamera(), 160, 120));
}

TEST(ReuseSequence, WithoutIdsAndThroughTheWholeSceneOverload) {
    const Scene scene = loadOrFail("builtin:default");
    // Ids not written: the id attachment stays as cleared in both renders.
    const Frames noIds = [&scene](int i) {
        SequenceFrame f = frameAt(scene, {}, frameTime(i, scene.fps), 160, 120);
        f.params.writeIds = false;
        return f;
    };
    const SequenceResult r = expectExact(scene, 160, 120, 10, noIds);
    EXPECT_EQ(r.modes(), "RUUUUUUUUU");
    // plan(frame, world, background): the planner's own full list.
    for (bool paper : {false, true}) {
        auto backend = makeSoftwareBackend();
        const SequenceResult whole = runSequence(*backend, scene, 160, 120, 12, animated(scene, {}, 160, 120),
                                                 reuseOptions(16, 16, true, paper), {}, true);
        EXPECT_EQ(whole.errors + whole.ties, 0u) << whole.describe();
        EXPECT_EQ(whole.modes(), "RUUUUUUUUUUU") << whole.describe();
    }
}

TEST(ReuseSequence, LargeMeshesMoving) {
    // Two bunnies (69,666 triangles each, in meshoptimizer's order): the second one slides. Groups
    // of 16 triangles make the redraws partial index ranges of a large mesh.
    if (!fs::exists(FRUGAL_BUNNY_OBJ)) FRUGAL_SKIP_IF_MISSING(FRUGAL_BUNNY_OBJ << " (glmark2-data)");
    Scene scene = loadOrFail(std::string("builtin:copies?count=2&of=") + FRUGAL_BUNNY_OBJ);
    ASSERT_GE(scene.roots.size(), 2u);
    const int second = scene.roots[1];
    const glm::vec3 t = scene.nodes[std::size_t(second)].translation;
    animate(scene, second, AnimPath::Translation, {{0.0f, t}, {0.2f, t + glm::vec3(0.0f, 0.02f, 0.03f)}});
    const Bounds bounds = scene.bounds(0.0);
    const Camera camera = eyeAt(bounds.center() + glm::vec3(0.0f, 0.3f, 2.2f) * bounds.radius(), bounds.center(), 40.0f,
                                bounds.radius() * 0.1f, bounds.radius() * 10.0f);
    const SequenceResult r = expectExact(scene, 160, 120, 8, withCamera(scene, camera, 160, 120), reuseOptions(16, 16, false));
    EXPECT_EQ(r.modes(), "RUUUUUUU") << r.describe();
    EXPECT_LT(r.stats[3].staticRedrawnTris, r.stats[3].drawnTris / 2) << "a partial redraw of the static bunny";
    expectExact(scene, 160, 120, 8, withCamera(scene, camera, 160, 120), reuseOptions(1, 8, false, false));
}

TEST(ReuseSequence, RandomScenesAndEvents) {
    // Seeded random sequences: floating boxes (none touches another surface, so no exact ties) that
    // move, stop, change colour or sidedness, leave and rejoin the draw list, with a camera that
    // sometimes moves, at random grains and cells, both step variants, with and without fallback.
    int busyReuseFrames = 0;
    std::string modes;
    for (unsigned seed = 1; seed <= 40; ++seed) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        std::mt19937 rng(seed);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        Scene scene;
        addBackdrop(scene, 2);
        const int boxes = 3 + int(seed % 6);
        for (int b = 0; b < boxes; ++b) {
            const int material = addMaterial(scene, {u(rng), u(rng), u(rng), 1.0f}, u(rng) < 0.3f);
            const float size = 0.3f + 0.8f * u(rng);
            addNodeWith(scene, addMesh(scene, boxMesh(glm::vec3(-size), glm::vec3(size), material, "box")),
                        {6.0f * u(rng) - 3.0f, 1.2f + 2.0f * u(rng), 6.0f * u(rng) - 3.0f});
        }
        scene.buildInstances();
        const int frames = 12;
        // Per frame and box: an offset (held when the box rests), a colour change, list membership.
        struct Event {
            glm::vec3 offset{0.0f};
            bool recolour = false, listed = true;
        };
        std::vector<std::vector<Event>> events(std::size_t(frames), std::vector<Event>(std::size_t(boxes), Event{}));
        for (int b = 0; b < boxes; ++b) {
            glm::vec3 at(0.0f);
            for (int f = 1; f < frames; ++f) {
                if (u(rng) < 0.5f) at += glm::vec3(u(rng) - 0.5f, 0.3f * (u(rng) - 0.5f), u(rng) - 0.5f);
                events[std::size_t(f)][std::size_t(b)] = {at, u(rng) < 0.1f, u(rng) > 0.1f};
            }
        }
        std::vector<float> angle(std::size_t(frames), 0.0f);
        for (int f = 1; f < frames; ++f) angle[std::size_t(f)] = angle[std::size_t(f - 1)] + (u(rng) < 0.2f ? 0.1f : 0.0f);
        const std::size_t firstBox = scene.instances.size() - std::size_t(boxes);
        Scene* edited = &scene;
        const Frames sequence = [edited, events, angle, firstBox](int i) {
            Scene& s = *edited;
            const float a = angle[std::size_t(i)];
            const Camera camera =
                eyeAt({8.0f * std::sin(a), 7.0f, 12.0f * std::cos(a)}, {0.0f, 0.5f, 0.0f}, 55.0f, 0.5f, 60.0f);
            SequenceFrame f = frameAt(s, camera, 0.0, 96, 72);
            DrawList list;
            for (const DrawCommand& c : f.list) {
                if (std::size_t(c.instance) < firstBox) {
                    list.push_back(c);
                    continue;
                }
                const Event& e = events[std::size_t(i)][std::size_t(c.instance) - firstBox];
                const Instance& instance = s.instances[std::size_t(c.instance)];
                f.world[std::size_t(instance.node)] = glm::translate(glm::mat4(1.0f), e.offset) * f.world[std::size_t(instance.node)];
                glm::vec4& colour = s.materials[std::size_t(s.meshes[std::size_t(instance.mesh)].material)].baseColorFactor;
                if (e.recolour) colour = glm::vec4(1.0f) - glm::vec4(glm::vec3(colour), 0.0f);
                if (e.listed) list.push_back(c);
            }
            f.list = std::move(list);
            return f;
        };
        const int grains[] = {0, 1, 5, 16};
        const int cells[] = {1, 7, 16, 40};
        const ReuseOptions options = reuseOptions(grains[seed % 4], cells[(seed / 4) % 4], seed % 4 == 0, seed % 3 == 0);
        // The colours are edited by the frames: each run starts from the same materials.
        const std::vector<Material> materials = scene.materials;
        const SequenceResult r = expectExact(scene, 96, 72, frames, sequence, options);
        scene.materials = materials;
        for (const ReuseFrameStats& st : r.stats) busyReuseFrames += st.mode == ReuseMode::Reuse && st.redrawnTris > 0 ? 1 : 0;
        modes += " " + r.modes();
    }
    // The sequences did run the reuse path with something to redraw, often.
    EXPECT_GT(busyReuseFrames, 150) << modes;
}

// ---------------------------------------------------------------------------------------------
// Options.

TEST(ReuseSequence, EveryGrainAndCellOnDominoes) {
    const Scene scene = loadOrFail("builtin:dominoes?polygons=804&static=0.5544");
    for (int grain : {0, 1, 16, 256})
        for (int cell : {1, 8, 16, 64})
            for (bool paper : {false, true}) {
                SCOPED_TRACE("grain " + std::to_string(grain) + " cell " + std::to_string(cell));
                const SequenceResult r =
                    expectExact(scene, 120, 90, 10, animated(scene, {}, 120, 90), reuseOptions(grain, cell, false, paper));
                EXPECT_EQ(r.modes(), "RUUUUUUUUU");
            }
}

TEST(ReuseSequence, OddTargetSizes) {
    const Scene scene = loadOrFail("builtin:default");
    for (const auto& [w, h] : {std::pair{97, 61}, std::pair{1, 1}, std::pair{3, 200}, std::pair{250, 7}}) {
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
        expectExact(scene, w, h, 8, animated(scene, {}, w, h), reuseOptions(16, 16, false), true);
        expectExact(scene, w, h, 8, animated(scene, {}, w, h), reuseOptions(1, 7, false), true);
    }
}

// ---------------------------------------------------------------------------------------------
// Culled draw lists.

TEST(ReuseSequence, CulledDrawLists) {
    for (const char* spec : {"builtin:default", "builtin:dominoes?polygons=1404&static=0.9866", "builtin:cubes"}) {
        for (Cull method : {Cull::Sphere, Cull::Conservative}) {
            SCOPED_TRACE(std::string(spec) + " " + toString(method));
            Scene scene = loadOrFail(spec);
            const SceneCuller culler = SceneCuller::prepare(scene);  // reorders the meshes: before any upload
            int culled = 0;
            const Frames frames = culledFrames(scene, culler, method, 160, 120, culled);
            const std::vector<SequenceResult> results = expectExactEveryWay(scene, 160, 120, int(kCullAngles.size()), frames);
            EXPECT_GT(culled, 0) << "culling drops something in some frames";
            EXPECT_EQ(results[2].modes(), kCullModes) << results[2].describe();
        }
    }
}

// ---------------------------------------------------------------------------------------------
// glTF files with node animation.

// A glTF 2.0 file with a static ground, a translating cube, a rotating cube with a child (so the
// child is dynamic through the hierarchy), a cube scaled in steps and a cubic-spline translation.
std::string animatedGltf() {
    std::vector<std::uint8_t> buffer;
    const auto put = [&buffer](const void* data, std::size_t size) {
        const auto* p = static_cast<const std::uint8_t*>(data);
        buffer.insert(buffer.end(), p, p + size);
        while (buffer.size() % 4) buffer.push_back(0);
    };
    const Mesh box = boxMesh(glm::vec3(-0.5f), glm::vec3(0.5f), 0);
    std::vector<float> positions;
    for (const glm::vec3& p : box.positions) positions.insert(positions.end(), {p.x, p.y, p.z});
    std::vector<std::uint16_t> indices(box.indices.begin(), box.indices.end());
    const std::vector<float> times = {0.0f, 0.5f, 1.0f};
    const std::vector<float> translations = {-2.5f, 0.5f, 0.0f, 0.0f, 1.5f, 0.0f, 2.5f, 0.5f, 1.0f};
    const glm::quat q0 = glm::angleAxis(0.0f, glm::vec3(0, 1, 0)), q1 = glm::angleAxis(1.5f, glm::vec3(0, 1, 0)),
                    q2 = glm::angleAxis(3.0f, glm::vec3(0, 1, 0));
    const std::vector<float> rotations = {q0.x, q0.y, q0.z, q0.w, q1.x, q1.y, q1.z, q1.w, q2.x, q2.y, q2.z, q2.w};
    const std::vector<float> scales = {1, 1, 1, 1.6f, 0.6f, 1.6f, 0.4f, 0.4f, 0.4f};
    // Cubic spline: (in-tangent, value, out-tangent) per key.
    const std::vector<float> spline = {0, 0, 0, 0, 0.5f, -2, 0, 2, 0, 0, 2, 0, 0, 1.5f, -2, 0, 0, 0, 0, 0, 0, 0, 0.5f, -2, 0, 0, 0};
    const std::size_t posOffset = buffer.size();
    put(positions.data(), positions.size() * 4);
    const std::size_t idxOffset = buffer.size();
    put(indices.data(), indices.size() * 2);
    const std::size_t timeOffset = buffer.size();
    put(times.data(), times.size() * 4);
    const std::size_t tOffset = buffer.size();
    put(translations.data(), translations.size() * 4);
    const std::size_t rOffset = buffer.size();
    put(rotations.data(), rotations.size() * 4);
    const std::size_t sOffset = buffer.size();
    put(scales.data(), scales.size() * 4);
    const std::size_t cOffset = buffer.size();
    put(spline.data(), spline.size() * 4);

    std::ostringstream j;
    const auto view = [&j](std::size_t offset, std::size_t length, bool last = false) {
        j << "{\"buffer\":0,\"byteOffset\":" << offset << ",\"byteLength\":" << length << "}" << (last ? "" : ",");
    };
    j << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1,2,4,5]}],)";
    j << R"("nodes":[{"name":"ground","mesh":1,"scale":[8,0.2,8],"translation":[0,-0.1,0]},)"
      << R"({"name":"mover","mesh":0,"translation":[-2.5,0.5,0]},)"
      << R"({"name":"spinner","mesh":0,"translation":[0,0.5,-2],"children":[3]},)"
      << R"({"name":"child","mesh":0,"translation":[1.2,0.6,0],"scale":[0.5,0.5,0.5]},)"
      << R"({"name":"stepper","mesh":0,"translation":[2,0.5,-1]},)"
      << R"({"name":"spline","mesh":0,"translation":[0,0.5,2]}],)";
    j << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]},)"
      << R"({"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":1}]}],)";
    j << R"("materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.9,0.4,0.2,1]}},)"
      << R"({"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.6,0.7,1]}}],)";
    j << R"("animations":[{"samplers":[{"input":2,"output":3,"interpolation":"LINEAR"},)"
      << R"({"input":2,"output":4,"interpolation":"LINEAR"},{"input":2,"output":5,"interpolation":"STEP"},)"
      << R"({"input":2,"output":6,"interpolation":"CUBICSPLINE"}],)"
      << R"("channels":[{"sampler":0,"target":{"node":1,"path":"translation"}},)"
      << R"({"sampler":1,"target":{"node":2,"path":"rotation"}},{"sampler":2,"target":{"node":4,"path":"scale"}},)"
      << R"({"sampler":3,"target":{"node":5,"path":"translation"}}]}],)";
    j << R"("accessors":[)"
      << R"({"bufferView":0,"componentType":5126,"count":24,"type":"VEC3","min":[-0.5,-0.5,-0.5],"max":[0.5,0.5,0.5]},)"
      << R"({"bufferView":1,"componentType":5123,"count":36,"type":"SCALAR"},)"
      << R"({"bufferView":2,"componentType":5126,"count":3,"type":"SCALAR","min":[0],"max":[1]},)"
      << R"({"bufferView":3,"componentType":5126,"count":3,"type":"VEC3"},)"
      << R"({"bufferView":4,"componentType":5126,"count":3,"type":"VEC4"},)"
      << R"({"bufferView":5,"componentType":5126,"count":3,"type":"VEC3"},)"
      << R"({"bufferView":6,"componentType":5126,"count":9,"type":"VEC3"}],)";
    j << R"("bufferViews":[)";
    view(posOffset, positions.size() * 4);
    view(idxOffset, indices.size() * 2);
    view(timeOffset, times.size() * 4);
    view(tOffset, translations.size() * 4);
    view(rOffset, rotations.size() * 4);
    view(sOffset, scales.size() * 4);
    view(cOffset, spline.size() * 4, true);
    j << R"(],"buffers":[{"byteLength":)" << buffer.size() << R"(,"uri":"data:application/octet-stream;base64,)"
      << test::base64(std::string(buffer.begin(), buffer.end())) << R"("}]})";
    return j.str();
}

TEST(ReuseSequence, GltfWithNodeAnimation) {
    const fs::path path = freshDir("ReuseGltf") / "animated.gltf";
    writeFile(path, animatedGltf());
    const Scene scene = loadOrFail(path.string());
    ASSERT_EQ(scene.animations.size(), 1u);
    ASSERT_EQ(scene.instances.size(), 6u);
    const Camera camera = eyeAt({0.0f, 6.0f, 9.0f}, {0.0f, 0.0f, 0.0f}, 50.0f, 0.5f, 50.0f);
    const std::vector<SequenceResult> results = expectExactEveryWay(scene, 160, 120, 36, withCamera(scene, camera, 160, 120));
    // While the animation runs (frames 1..30), the four animated nodes and the child are dynamic
    // (the stepped scale only on its key frames); afterwards nothing is.
    const SequenceResult& r = results[2];
    EXPECT_EQ(r.modes(), "R" + std::string(35, 'U')) << r.describe();
    EXPECT_EQ(r.stats[5].instances.dd + r.stats[5].instances.sd, 4u) << r.describe();
    EXPECT_EQ(r.stats[35].instances.ss, 6u);
}

// Real files that carry animations (assimp-testmodels), when installed: what they animate may be
// unsupported (skins, morph weights), but the sequence must match the full render all the same.
TEST(ReuseSequence, InstalledGltfFilesWithAnimations) {
    const fs::path root = FRUGAL_ASSIMP_GLTF2_DIR;
    const std::vector<fs::path> candidates = {root / "simple_skin/simple_skin.gltf",
                                              root / "glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf",
                                              root / "glTF-Sample-Models/BoxAnimated-glTF/BoxAnimated.gltf",
                                              root / "BoxAnimated-glTF-Binary/BoxAnimated.glb"};
    int ran = 0;
    for (const fs::path& file : candidates) {
        if (!fs::exists(file)) continue;
        SCOPED_TRACE(file.string());
        Result<Scene> loaded = loadScene(file.string());
        ASSERT_TRUE(loaded) << loaded.error().message;
        const Scene& scene = *loaded;
        if (scene.animations.empty() || scene.instances.empty()) continue;
        // One camera for the whole sequence: fitted at time 0, then held.
        Result<FrameSetup> setup0 = setUpFrame(scene, {}, 0.0, 128, 96, true);
        ASSERT_TRUE(setup0) << setup0.error().message;
        const FrameParams params = setup0->params;
        const double duration = std::max(scene.duration(), 0.1);
        const Frames frames = [&scene, params, duration](int i) {
            SequenceFrame f;
            f.world = scene.worldTransforms(duration * double(i) / 15.0);
            f.params = params;
            f.list = fullDrawList(scene);
            return f;
        };
        expectExactEveryWay(scene, 128, 96, 16, frames);
        ++ran;
    }
    if (ran == 0) FRUGAL_SKIP_IF_MISSING("no animated glTF file of assimp-testmodels under " << root);
}

// ---------------------------------------------------------------------------------------------
// Odd changes.

TEST(ReuseSequence, NotANumberMatrixAndMaterialChanges) {
    Scene scene = loadOrFail("builtin:dominoes?polygons=804&static=0.5544");
    Scene* mutableScene = &scene;
    const Frames frames = [mutableScene](int i) {
        Scene& s = *mutableScene;
        SequenceFrame f = frameAt(s, {}, frameTime(i, s.fps), 160, 120);
        // Instance 50's node is NaN from frame 3 to 6; material 2 changes colour at frames 4 and 9,
        // material 5 becomes double-sided at frame 7.
        if (i >= 3 && i <= 6) f.world[std::size_t(s.instances[50].node)][3][0] = std::numeric_limits<float>::quiet_NaN();
        s.materials[2].baseColorFactor = i >= 4 && i < 9 ? glm::vec4(0.2f, 0.9f, 0.9f, 1.0f) : glm::vec4(0.9f, 0.2f, 0.2f, 1.0f);
        s.materials[5].doubleSided = i >= 7;
        return f;
    };
    expectExactEveryWay(scene, 160, 120, 12, frames);
}

// ---------------------------------------------------------------------------------------------
// The scene made for ties: two quads in one plane facing the camera (so every pixel of both has
// the same depth, exactly), the dynamic one first in the draw order. In a full render it wins the
// overlap (first drawn); reuse draws it after the static one, which keeps the overlap. Every such
// pixel is a tie (same depth, other id), none is an error.

TEST(ReuseSequence, CoplanarStaticAndDynamicQuadsTie) {
    const Scene scene = coplanarQuadsScene();
    ASSERT_EQ(scene.instances.size(), 2u);
    const std::uint32_t dynamicFirst = scene.instances[0].firstId, staticFirst = scene.instances[1].firstId;
    const Camera camera = coplanarQuadsCamera();

    auto backend = makeSoftwareBackend();
    Result<SceneRenderer> made = SceneRenderer::create(*backend, scene);
    ASSERT_TRUE(made) << made.error().message;
    const int w = 160, h = 120;
    const TargetHandle alone = backend->createTarget(w, h);
    // The pixels each quad covers when drawn alone, at frame i.
    const auto coverage = [&](int i, int instance) {
        SequenceFrame f = frameAt(scene, camera, frameTime(i, scene.fps), w, h);
        const DrawList list{f.list[std::size_t(instance)]};
        made->renderFrame(alone, w, h, f.params, f.world, kReuseBackground, list);
        return backend->readBack(alone);
    };

    for (bool paper : {false, true}) {
        SCOPED_TRACE(paper ? "the paper's steps" : "steps a-d");
        std::vector<std::size_t> expected, overlap;
        const SequenceResult r = runSequence(
            *backend, scene, w, h, 14, withCamera(scene, camera, w, h), reuseOptions(16, 16, false, paper),
            [&](int i, const Buffers& reuse, const Buffers& full, const ReuseFrameStats&) {
                const Buffers a = coverage(i, 0), b = coverage(i, 1);
                std::size_t both = 0, fullShowsDynamic = 0, reuseShowsStatic = 0;
                for (std::size_t p = 0; p < a.ids.size(); ++p) {
                    if (a.ids[p] == 0 || b.ids[p] == 0) continue;
                    ++both;
                    EXPECT_EQ(a.depth[p], b.depth[p]) << "the quads are coplanar: same depth at pixel " << p;
                    fullShowsDynamic += full.ids[p] >= dynamicFirst && full.ids[p] < staticFirst ? 1 : 0;
                    reuseShowsStatic += reuse.ids[p] >= staticFirst ? 1 : 0;
                }
                EXPECT_EQ(fullShowsDynamic, both) << "frame " << i << ": the full render keeps the first drawn";
                overlap.push_back(both);
                // Frame 0 draws both as static, in list order; frames 1..8 draw the moving quad after
                // the static one; from frame 9 on it rests: steps a-d redraw the static pair in list
                // order where it lies, and the ties end; the paper's steps keep them.
                const bool tied = (i >= 1 && i <= 8) || (paper && i > 8);
                expected.push_back(tied ? both : 0);
                if (tied) {
                    EXPECT_EQ(reuseShowsStatic, both) << "frame " << i;
                }
            });
        EXPECT_EQ(r.errors, 0u) << r.describe();
        EXPECT_EQ(r.modes(), "RUUUUUUUUUUUUU") << r.describe();
        ASSERT_EQ(r.matches.size(), expected.size());
        for (std::size_t i = 0; i < expected.size(); ++i) {
            EXPECT_GT(overlap[i], 500u) << "frame " << i << ": the quads overlap";
            EXPECT_EQ(r.matches[i].ties, expected[i]) << "frame " << i;
            EXPECT_EQ(r.matches[i].differing, r.matches[i].ties) << "frame " << i;
        }
        EXPECT_GT(r.ties, 0u);
    }
    backend->destroyTarget(alone);
}

}  // namespace
}  // namespace frugal::test
