// FrameStats::drawFingerprint (renderer/DrawFingerprint.h), which `frugal report` compares with the
// plain render's to find no-ops: the same triangles in the same order with the same state give the
// same fingerprint however the ranges are split; any other draw, order, depth mode, clear, copy or
// interpolator gives another. Then on real frames (software backend): an order of a single draw and
// a cull that keeps everything draw the plain render's draws; a cull that drops triangles does not.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include <frugal/Renderer.h>
#include <frugal/Scene.h>

#include "renderer/DrawFingerprint.h"

namespace frugal {
namespace {

DrawCommand command(int instance, std::vector<IndexRange> ranges, DepthMode depth = DepthMode::Test) {
    return DrawCommand{instance, std::move(ranges), depth};
}

std::uint64_t usual(const DrawList& list, std::uint64_t seed = 0) { return drawFingerprint(list, 64, 48, seed); }

TEST(DrawFingerprintTest, TheSameTrianglesInTheSameOrderWithTheSameStateMatch) {
    const DrawList whole{command(0, {{0, 20}}), command(1, {{0, 8}})};
    EXPECT_EQ(usual(whole), usual(DrawList{command(0, {{0, 20}}), command(1, {{0, 8}})}));
    EXPECT_EQ(usual(whole), usual(DrawList{command(0, {{0, 5}, {5, 15}}), command(1, {{0, 8}})}))
        << "one run split in two ranges";
    EXPECT_EQ(usual(whole), usual(DrawList{command(0, {{0, 5}}), command(0, {{5, 15}}), command(1, {{0, 8}, {8, 0}})}))
        << "one run in two commands, and an empty range";
    EXPECT_NE(usual(whole), 0u);

    EXPECT_NE(usual(whole), usual(DrawList{command(1, {{0, 8}}), command(0, {{0, 20}})})) << "another order";
    EXPECT_NE(usual(whole), usual(DrawList{command(0, {{0, 19}}), command(1, {{0, 8}})})) << "a triangle fewer";
    EXPECT_NE(usual(whole), usual(DrawList{command(0, {{0, 10}, {11, 9}}), command(1, {{0, 8}})})) << "a hole";
    EXPECT_NE(usual(whole), usual(DrawList{command(0, {{10, 10}, {0, 10}}), command(1, {{0, 8}})}))
        << "the same triangles, in another order";
    EXPECT_NE(usual(whole), usual(DrawList{command(0, {{0, 20}}, DepthMode::Off), command(1, {{0, 8}})}))
        << "another depth mode";
    EXPECT_NE(usual(whole), usual(DrawList{command(0, {{0, 20}}), command(2, {{0, 8}})})) << "another instance";
    EXPECT_NE(usual(whole), usual(whole, 1)) << "another interpolator";
    EXPECT_NE(usual(whole), drawFingerprint(whole, 64, 47, 0)) << "another clear";
}

TEST(DrawFingerprintTest, TheUsualFrameIsItsTwoStepPlan) {
    const DrawList list{command(0, {{0, 20}}), command(1, {{0, 8}})};
    FramePlan plan;
    plan.push_back({PlanStep::Op::Clear, PlanTarget::Render, PlanTarget::Render, {Rect{0, 0, 64, 48}}, {}});
    plan.push_back({PlanStep::Op::Draw, PlanTarget::Render, PlanTarget::Render, {}, list});
    EXPECT_EQ(drawFingerprint(plan, 0), usual(list)) << "reuse's full frame is the plain render's";
    plan[1].draws.clear();
    plan[1].list = &list;
    EXPECT_EQ(drawFingerprint(plan, 0), usual(list)) << "a step's list by pointer";

    FramePlan copied = plan;
    copied.push_back({PlanStep::Op::Copy, PlanTarget::Render, PlanTarget::Static, {Rect{0, 0, 64, 48}}, {}});
    EXPECT_NE(drawFingerprint(copied, 0), usual(list)) << "one copy more";
    FramePlan reused;
    reused.push_back({PlanStep::Op::Copy, PlanTarget::Static, PlanTarget::Render, {Rect{0, 0, 64, 48}}, {}});
    reused.push_back({PlanStep::Op::Draw, PlanTarget::Render, PlanTarget::Render, {}, list});
    EXPECT_NE(drawFingerprint(reused, 0), usual(list)) << "a copy where the plain render clears";
}

const Camera kFacing = Camera::lookAt({1.5f, 1.2f, 2.5f}, {0, 0, 0});
const Camera kAway = Camera::lookAt({1.5f, 1.2f, 2.5f}, {3.0f, 2.4f, 5.0f});  // the scene behind it

// The stats of a frame of `scene` by `camera` with `change` applied to the software backend's
// default settings.
FrameStats frameStats(const std::string& scene, const std::function<void(Settings&)>& change,
                      const Camera& camera = kFacing) {
    Result<Scene> loaded = loadScene(scene);
    EXPECT_TRUE(loaded) << loaded.error().message;
    if (!loaded) return {};
    Settings settings;
    settings.width = 64;
    settings.height = 48;
    settings.backend = BackendKind::Software;
    change(settings);
    Result<Renderer> renderer = Renderer::create(std::move(*loaded), settings);
    EXPECT_TRUE(renderer) << renderer.error().message;
    if (!renderer) return {};
    Result<Frame> frame = renderer->render(camera, 0.0);
    EXPECT_TRUE(frame) << frame.error().message;
    return frame ? frame->stats : FrameStats{};
}
std::uint64_t frameFingerprint(const std::string& scene, const std::function<void(Settings&)>& change,
                               const Camera& camera = kFacing) {
    return frameStats(scene, change, camera).drawFingerprint;
}

// Whether what comes after the cull (order, hidden-surface plan, interpolator) changed the frame.
bool changedAfterTheCull(const std::string& scene, const std::function<void(Settings&)>& change) {
    const FrameStats stats = frameStats(scene, change);
    EXPECT_NE(stats.culledFingerprint, 0u);
    return stats.drawFingerprint != stats.culledFingerprint;
}

TEST(DrawFingerprintTest, WhatTheCullGaveIsKeptBesideWhatWasDrawn) {
    const std::string cube = "builtin:cubes?count=1";
    EXPECT_FALSE(changedAfterTheCull(cube, [](Settings&) {}));
    EXPECT_FALSE(changedAfterTheCull(cube, [](Settings& s) { s.cull = Cull::Conservative; }));
    EXPECT_FALSE(changedAfterTheCull(cube, [](Settings& s) {
        s.cull = Cull::Conservative;
        s.order = Order::Key;
    })) << "an order of one draw";
    EXPECT_TRUE(changedAfterTheCull(cube, [](Settings& s) {
        s.cull = Cull::Conservative;
        s.hsr = Hsr::DepthSort;
    })) << "the hidden-surface plan draws polygons of its own";
    EXPECT_TRUE(changedAfterTheCull(cube, [](Settings& s) { s.interp = DepthInterp::Span; }));
    EXPECT_TRUE(changedAfterTheCull("builtin:dominoes", [](Settings& s) { s.order = Order::Key; }))
        << "the dominoes' draws sorted by their states";
}

TEST(DrawFingerprintTest, AnOrderOfOneDrawAndACullThatKeepsEverythingDrawThePlainRendersDraws) {
    const std::string cube = "builtin:cubes?count=1";  // one mesh, one instance, in view
    const std::uint64_t plain = frameFingerprint(cube, [](Settings&) {});
    ASSERT_NE(plain, 0u);
    EXPECT_EQ(frameFingerprint(cube, [](Settings& s) { s.order = Order::Key; }), plain);
    EXPECT_EQ(frameFingerprint(cube, [](Settings& s) { s.order = Order::Greedy; }), plain);
    EXPECT_EQ(frameFingerprint(cube, [](Settings& s) { s.cull = Cull::Sphere; }), plain) << "the cube is in view";
    const std::uint64_t sphere = frameFingerprint(cube, [](Settings& s) { s.cull = Cull::Sphere; }, kAway);
    EXPECT_NE(sphere, frameFingerprint(cube, [](Settings&) {}, kAway)) << "the cube culled when out of view";
    EXPECT_NE(sphere, 0u);
    EXPECT_NE(frameFingerprint(cube, [](Settings& s) { s.interp = DepthInterp::Span; }), plain);
    EXPECT_EQ(frameFingerprint(cube, [](Settings& s) { s.cull = Cull::Oracle; }), 0u) << "the oracle's own scene";
}

}  // namespace
}  // namespace frugal
