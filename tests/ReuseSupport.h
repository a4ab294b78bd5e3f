// Sequences rendered twice on one backend, fully and with temporal reuse, and compared frame by
// frame (colour, depth, ids). Header-only; the reuse suites include it (software in tests/reuse, GL
// in tests/gl), so it needs nothing but the reuse, report and render modules.
#pragma once

#include <cstring>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "cull/Culling.h"
#include "lab/ReuseCheck.h"
#include "pipeline/Frame.h"
#include "pipeline/SceneRenderer.h"
#include "reuse/Reuse.h"
#include "scene/Load.h"
#include "scene/MeshBuild.h"

namespace frugal::test {

inline const glm::vec4 kReuseBackground{0.1f, 0.15f, 0.2f, 1.0f};

// One frame of a sequence: its node matrices, camera and what a full render draws.
struct SequenceFrame {
    std::vector<glm::mat4> world;
    FrameParams params;
    DrawList list;
};

struct SequenceResult {
    std::vector<ReuseFrameStats> stats;
    std::vector<FrameMatch> matches;
    std::size_t errors = 0, ties = 0;
    std::size_t count(ReuseMode mode) const {
        std::size_t k = 0;
        for (const ReuseFrameStats& s : stats) k += s.mode == mode ? 1 : 0;
        return k;
    }
    // One letter a frame: R(ebuild), F(ull), U (reuse).
    std::string modes() const {
        std::string text;
        for (const ReuseFrameStats& s : stats)
            text += s.mode == ReuseMode::Full ? 'F' : s.mode == ReuseMode::Rebuild ? 'R' : 'U';
        return text;
    }
    // Per frame: mode, reason, differing pixels and ties (for failure messages).
    std::string describe() const {
        std::ostringstream out;
        for (std::size_t i = 0; i < stats.size(); ++i) {
            out << "\n  frame " << i << ": " << toString(stats[i].mode) << " (" << stats[i].reason << ")";
            if (i < matches.size()) out << ", " << matches[i].differing << " differ, " << matches[i].ties << " ties";
            out << ", redrawn " << stats[i].redrawnTris << "/" << stats[i].drawnTris << ", copied "
                << stats[i].copiedPx << ", cleared " << stats[i].clearedPx;
        }
        return out.str();
    }
};

// Called after each frame with both read-backs (reuse first, full second).
using FrameInspector = std::function<void(int frame, const Buffers& reuse, const Buffers& full, const ReuseFrameStats&)>;

// Renders frames 0..frames-1 (frame(i) describes frame i; it may change `scene`'s materials) on
// `backend` both ways and compares each pair. `scene` must stay alive and unmoved throughout.
// `wholeScene`: plan through TemporalReuse's whole-scene overload (the frames must draw fullDrawList).
// `color`: the targets' colour format (Rgba32F: linear colour, compared bit for bit as well).
inline SequenceResult runSequence(Backend& backend, const Scene& scene, int width, int height, int frames,
                                  const std::function<SequenceFrame(int)>& frame, const ReuseOptions& options = {},
                                  const FrameInspector& inspect = {}, bool wholeScene = false,
                                  ColorFormat color = ColorFormat::Rgba8) {
    SequenceResult result;
    Result<SceneRenderer> made = SceneRenderer::create(backend, scene);
    EXPECT_TRUE(made.ok()) << (made.ok() ? "" : made.error().message);
    if (!made) return result;
    SceneRenderer& renderer = *made;
    const TargetHandle full = backend.createTarget(width, height, DepthFormat::D24, 1, color);
    const TargetHandle render = backend.createTarget(width, height, DepthFormat::D24, 1, color);
    const TargetHandle stat = backend.createTarget(width, height, DepthFormat::D24, 1, color);
    EXPECT_TRUE(full != kNoHandle && render != kNoHandle && stat != kNoHandle);
    TemporalReuse reuse(scene, width, height, options);
    for (int i = 0; i < frames; ++i) {
        const SequenceFrame f = frame(i);
        renderer.renderFrame(full, width, height, f.params, f.world, kReuseBackground, f.list);
        const FramePlan plan = wholeScene ? reuse.plan(f.params, f.world, kReuseBackground)
                                          : reuse.plan(f.params, f.world, f.list, kReuseBackground);
        renderer.execute(plan, render, stat, f.params, f.world, kReuseBackground);
        const Buffers a = backend.readBack(render), b = backend.readBack(full);
        const FrameMatch match = matchFrames(a, b);
        result.stats.push_back(reuse.stats());
        result.matches.push_back(match);
        result.errors += match.errors();
        result.ties += match.ties;
        EXPECT_EQ(match.errors(), 0u) << "frame " << i << " (" << toString(reuse.stats().mode) << ", "
                                      << reuse.stats().reason << "): " << match.errors() << " pixels differ in depth";
        EXPECT_EQ(a.linear.size(), color == ColorFormat::Rgba32F ? a.pixelCount() * 4 : 0u);
        EXPECT_TRUE(a.linear.size() == b.linear.size() &&
                    std::memcmp(a.linear.data(), b.linear.data(), a.linear.size() * sizeof(float)) == 0)
            << "frame " << i << ": the linear colour differs";
        if (inspect) inspect(i, a, b, reuse.stats());
    }
    backend.destroyTarget(full);
    backend.destroyTarget(render);
    backend.destroyTarget(stat);
    return result;
}

// Frame `i` of `scene` at scene time `time` through `camera`, drawn whole.
inline SequenceFrame frameAt(const Scene& scene, const Camera& camera, double time, int width, int height) {
    Result<FrameSetup> setup = setUpFrame(scene, camera, time, width, height, true);
    EXPECT_TRUE(setup.ok()) << (setup.ok() ? "" : setup.error().message);
    SequenceFrame f;
    if (!setup) return f;
    f.world = std::move(setup->world);
    f.params = setup->params;
    f.list = fullDrawList(scene);
    return f;
}

// The usual sequence: the scene's animation at its fps, seen through `camera`, drawn whole.
inline std::function<SequenceFrame(int)> animated(const Scene& scene, const Camera& camera, int width, int height) {
    return [&scene, camera, width, height](int i) { return frameAt(scene, camera, frameTime(i, scene.fps), width, height); };
}

inline Scene loadOrFail(const std::string& spec) {
    Result<Scene> scene = loadScene(spec, LoadOptions{});
    EXPECT_TRUE(scene.ok()) << spec << ": " << (scene.ok() ? "" : scene.error().message);
    return scene ? std::move(*scene) : Scene{};
}

// A look-at camera with fixed clip planes (fitted ones follow the animated bounds, which would make
// every frame a camera change).
inline Camera eyeAt(const glm::vec3& eye, const glm::vec3& target, float fovDegrees = 50.0f, float znear = 0.1f,
                    float zfar = 200.0f) {
    Camera spec;
    spec.eye = eye;
    spec.target = target;
    spec.yfovDegrees = fovDegrees;
    spec.znear = znear;
    spec.zfar = zfar;
    return spec;
}

// ---------------------------------------------------------------------------------------------
// Scenes built in code.

// An axis-aligned box with flat faces (24 vertices, 12 triangles, counter-clockwise outside).
inline Mesh boxMesh(const glm::vec3& lo, const glm::vec3& hi, int material, const std::string& name = "box") {
    Mesh mesh;
    mesh.name = name;
    mesh.material = material;
    const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::vec3& n : normals) {
        const glm::vec3 u = std::abs(n.y) > 0.5f ? glm::vec3(0, 0, n.y) : glm::vec3(-n.z, 0, n.x);
        const glm::vec3 v = glm::cross(n, u);
        const auto base = std::uint32_t(mesh.positions.size());
        const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (const glm::vec2& c : corners) mesh.positions.push_back(glm::mix(lo, hi, (n + c.x * u + c.y * v + 1.0f) * 0.5f));
        for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
    }
    finalizeMesh(mesh, false);
    return mesh;
}

// A quad in the plane z = `z` (facing +z), corners (x0, y0) .. (x1, y1), two triangles.
inline Mesh quadMesh(float x0, float y0, float x1, float y1, float z, int material, const std::string& name = "quad") {
    Mesh mesh;
    mesh.name = name;
    mesh.material = material;
    mesh.positions = {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    finalizeMesh(mesh, false);
    return mesh;
}

inline int addMaterial(Scene& scene, const glm::vec4& colour, bool doubleSided = false) {
    Material material;
    material.name = "m" + std::to_string(scene.materials.size());
    material.baseColorFactor = colour;
    material.doubleSided = doubleSided;
    scene.materials.push_back(material);
    return int(scene.materials.size()) - 1;
}

inline int addMesh(Scene& scene, Mesh mesh) {
    scene.meshes.push_back(std::move(mesh));
    return int(scene.meshes.size()) - 1;
}

// A root node drawing `mesh`, at `translation`; returns the node.
inline int addNodeWith(Scene& scene, int mesh, const glm::vec3& translation, const glm::vec3& scale = glm::vec3(1.0f)) {
    Node node;
    node.name = "n" + std::to_string(scene.nodes.size());
    if (mesh >= 0) node.meshes = {mesh};
    node.translation = translation;
    node.scale = scale;
    scene.roots.push_back(int(scene.nodes.size()));
    scene.nodes.push_back(node);
    return int(scene.nodes.size()) - 1;
}

// A linear translation (or scale) animation of `node` through `keys` (time, value) pairs.
inline void animate(Scene& scene, int node, AnimPath path, const std::vector<std::pair<float, glm::vec3>>& keys,
                    Interp interpolation = Interp::Linear) {
    AnimChannel channel;
    channel.node = node;
    channel.path = path;
    channel.interpolation = interpolation;
    for (const auto& [t, v] : keys) {
        channel.times.push_back(t);
        channel.values.push_back(glm::vec4(v, 0.0f));
    }
    Animation animation;
    animation.name = "a" + std::to_string(scene.animations.size());
    animation.channels.push_back(std::move(channel));
    scene.animations.push_back(std::move(animation));
}

// A static backdrop of `count` × `count` boxes on a floor plate, for the dynamic objects of a test
// to move over (the static instances come first in the draw order).
inline void addBackdrop(Scene& scene, int count = 4) {
    const int floorMaterial = addMaterial(scene, {0.8f, 0.8f, 0.75f, 1.0f});
    addNodeWith(scene, addMesh(scene, boxMesh({-6, -0.5f, -6}, {6, 0, 6}, floorMaterial, "plate")), glm::vec3(0.0f));
    for (int i = 0; i < count; ++i)
        for (int j = 0; j < count; ++j) {
            const int material = addMaterial(scene, {0.3f + 0.15f * float(i), 0.4f, 0.3f + 0.15f * float(j), 1.0f});
            const int mesh = addMesh(scene, boxMesh({-0.4f, 0, -0.4f}, {0.4f, 0.6f + 0.3f * float((i + j) % 3), 0.4f},
                                                    material, "pillar"));
            addNodeWith(scene, mesh, {-4.5f + 3.0f * float(i), 0.0f, -4.5f + 3.0f * float(j)});
        }
}

// ---------------------------------------------------------------------------------------------
// Sequences both suites run (software in tests/reuse, GL in tests/gl).

using Frames = std::function<SequenceFrame(int)>;

// `paper`: the paper's steps 1–6 (ReuseOptions::paperSteps) instead of steps a–d.
inline ReuseOptions reuseOptions(int grain = 16, int cell = 16, bool fallback = true, bool paper = false) {
    ReuseOptions o;
    o.grain = grain;
    o.cell = cell;
    o.fallback = fallback;
    o.paperSteps = paper;
    return o;
}

inline std::string describeOptions(const ReuseOptions& o) {
    return "grain " + std::to_string(o.grain) + ", cell " + std::to_string(o.cell) + (o.fallback ? "" : ", no fallback") +
           (o.paperSteps ? ", the paper's steps" : "");
}

// runSequence on `backend`, for a sequence that must come out exact: every frame run, no pixel
// differing in depth, and none at all unless `tiesAllowed` (the scenes made for depth ties).
inline SequenceResult expectExactOn(Backend& backend, const Scene& scene, int width, int height, int frames,
                                    const Frames& frame, const ReuseOptions& options = {}, bool tiesAllowed = false) {
    SCOPED_TRACE(describeOptions(options) + " on " + backend.name());
    SequenceResult r = runSequence(backend, scene, width, height, frames, frame, options);
    EXPECT_EQ(r.stats.size(), std::size_t(frames));
    EXPECT_EQ(r.errors, 0u) << r.describe();
    if (!tiesAllowed) {
        EXPECT_EQ(r.ties, 0u) << r.describe();
    }
    return r;
}

// A fixed camera and the scene's animation, with the frame's draw list edited by `edit`.
inline Frames withCamera(const Scene& scene, const Camera& camera, int width, int height,
                         std::function<void(int, SequenceFrame&)> edit = {}) {
    return [&scene, camera, width, height, edit](int i) {
        SequenceFrame f = frameAt(scene, camera, frameTime(i, scene.fps), width, height);
        if (edit) edit(i, f);
        return f;
    };
}

// Looking at the backdrop of addBackdrop from above and in front.
inline Camera overviewCamera() { return eyeAt({0.0f, 8.0f, 14.0f}, {0.0f, 0.0f, 0.0f}, 50.0f, 0.5f, 60.0f); }

// The backdrop and two boxes that pass the camera of overviewCamera(): one flies along the line of
// sight through the near plane and the eye to behind the camera (a vertex behind the eye: extents
// are the whole screen), the other comes up to the near plane and back.
inline Scene flyThroughScene() {
    Scene scene;
    addBackdrop(scene);
    const int green = addMaterial(scene, {0.1f, 0.8f, 0.2f, 1.0f}, true);
    const int cube = addMesh(scene, boxMesh(glm::vec3(-0.6f), glm::vec3(0.6f), green, "flyer"));
    const Camera camera = overviewCamera();
    const glm::vec3 eye = *camera.eye;
    const glm::vec3 back = glm::normalize(eye - *camera.target);  // from the scene towards the eye, and beyond
    const int flyer = addNodeWith(scene, cube, eye - 9.0f * back);
    animate(scene, flyer, AnimPath::Translation,
            {{0.0f, eye - 9.0f * back}, {0.6f, eye + 4.0f * back + glm::vec3(0.2f, 0.0f, 0.0f)}});
    const int visitor = addNodeWith(scene, cube, eye - 3.0f * back);
    animate(scene, visitor, AnimPath::Translation,
            {{0.0f, eye - 3.0f * back}, {0.3f, eye - 0.3f * back}, {0.6f, eye - 3.0f * back}});
    scene.buildInstances();
    return scene;
}

// The backdrop with every instance moving every frame.
inline Scene allDynamicScene() {
    Scene scene;
    addBackdrop(scene, 3);
    scene.buildInstances();
    for (const Instance& instance : scene.instances) {
        const glm::vec3 t = scene.nodes[std::size_t(instance.node)].translation;
        animate(scene, instance.node, AnimPath::Translation, {{0.0f, t}, {1.0f, t + glm::vec3(1.0f, 0.3f, -0.5f)}});
    }
    return scene;
}

// A camera that circles the scene: still, moving, still, moving, still (angle per frame; equal
// angles in a row are a still camera), with the modes the planner must choose.
struct CameraPath {
    std::vector<float> angle = {0, 0, 0, 0, 0, 0.05f, 0.1f, 0.15f, 0.2f, 0.2f, 0.2f, 0.2f, 0.2f, 0.2f,
                                0.25f, 0.3f, 0.3f, 0.3f, 0.3f, 0.35f, 0.35f};
    std::string modes = "RUUUUFFFFRUUUUFFRUUFR";
    int frames() const { return int(angle.size()); }
    // Frame i of `scene` (its animation runs on) from the path.
    Frames of(const Scene& scene, int width, int height) const {
        const Bounds bounds = scene.bounds(0.0);
        const float r = bounds.radius();
        return [&scene, angles = angle, bounds, r, width, height](int i) {
            const float a = angles[std::size_t(i)];
            const Camera camera = eyeAt(bounds.center() + glm::vec3(std::sin(a), 0.7f, std::cos(a)) * r * 1.4f,
                                        bounds.center(), 45.0f, 0.1f, r * 6.0f);
            return frameAt(scene, camera, frameTime(i, scene.fps), width, height);
        };
    }
};

// Close to a scene prepared with SceneCuller::prepare, so that culling drops part of it; still,
// moving, still. Each frame draws `method`'s list; `culled` counts the frames that drop something.
inline const std::vector<float> kCullAngles = {0, 0, 0, 0, 0, 0.3f, 0.6f, 0.6f, 0.6f, 0.6f, 0.6f, 0.6f};
inline const char* const kCullModes = "RUUUUFFRUUUU";
inline Frames culledFrames(const Scene& scene, const SceneCuller& culler, Cull method, int width, int height,
                           int& culled) {
    const Bounds bounds = scene.bounds(0.0);
    const float r = bounds.radius();
    return [&scene, &culler, method, bounds, r, width, height, &culled](int i) {
        const float a = kCullAngles[std::size_t(i)];
        const Camera camera = eyeAt(bounds.center() + glm::vec3(std::sin(a) * 0.4f, 0.35f, std::cos(a) * 0.5f) * r,
                                    bounds.center() + glm::vec3(0.2f * r, 0.0f, 0.0f), 50.0f, 0.05f, r * 6.0f);
        Result<FrameSetup> setup = setUpFrame(scene, camera, frameTime(i, scene.fps), width, height, true);
        EXPECT_TRUE(setup) << (setup ? "" : setup.error().message);
        SequenceFrame f;
        if (!setup) return f;
        f.world = setup->world;
        f.params = setup->params;
        f.list = culler.cull(method, scene, setup->world, setup->view);
        culled += submittedTriangles(scene, f.list) < scene.primitiveCount() ? 1 : 0;
        return f;
    };
}

// Two quads in one plane facing a camera at the origin (every pixel of both has exactly the same
// depth), the dynamic one first in the draw order; it slides in its plane in frames 1..8, then
// rests. Instance 0 is the dynamic quad, instance 1 the static one.
inline Scene coplanarQuadsScene() {
    Scene scene;
    const int orange = addMaterial(scene, {0.9f, 0.5f, 0.1f, 1.0f});
    const int teal = addMaterial(scene, {0.1f, 0.6f, 0.6f, 1.0f});
    const int dyn = addNodeWith(scene, addMesh(scene, quadMesh(-1.0f, -0.8f, 1.0f, 0.8f, -6.0f, orange, "dynamic")),
                                {-0.6f, 0.0f, 0.0f});
    addNodeWith(scene, addMesh(scene, quadMesh(-1.2f, -1.0f, 1.2f, 1.0f, -6.0f, teal, "static")), {0.7f, 0.1f, 0.0f});
    // Keys end between frames 7 and 8, so frame 8 is the last that changes.
    animate(scene, dyn, AnimPath::Translation, {{0.0f, {-0.6f, 0.0f, 0.0f}}, {7.5f / 30.0f, {0.3f, -0.4f, 0.0f}}});
    scene.buildInstances();
    return scene;
}
inline Camera coplanarQuadsCamera() { return eyeAt({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 50.0f, 0.5f, 20.0f); }

}  // namespace frugal::test
