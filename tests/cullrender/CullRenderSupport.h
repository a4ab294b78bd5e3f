// Culling judged by renders on the software reference: a scene prepared for culling (its meshes
// reordered by SceneCuller::prepare before upload), a frame rendered whole with ids (the RVS), and
// every method's plan checked against it. Header-only; only frugal_cull_render_tests includes it.
//
// What a frame check proves, for each method:
//   none, oracle                  the plan is fullDrawList;
//   sphere, backface, cones,      misses == 0 (RVS ⊆ PVS), and the plan rendered is the full render,
//   conservative, occlusion,      colour, depth and ids byte for byte (occlusion runs on every frame here:
//   occlusion-ahead
//                                 target(), not its pays-or-skips policy);
//   paper                         the plan is well-formed (PVS ⊆ TOS); misses are counted, not judged.
// Every plan: instances in scene order, each once, ranges non-empty, ascending, disjoint and inside
// the instance's mesh; submittedTriangles agrees with the drawn set.
#pragma once

#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "cull/Culling.h"
#include "lab/Views.h"
#include "pipeline/Frame.h"
#include "pipeline/SceneRenderer.h"
#include "cull/VisibleSet.h"
#include "scene/Load.h"
#include "scene/MeshBuild.h"
#include "software/SoftwareBackend.h"

namespace frugal::test {

// The methods that must never miss a visible triangle.
inline constexpr Cull kNeverMiss[] = {Cull::Sphere, Cull::Backface, Cull::Cones, Cull::Conservative, Cull::Occlusion};

inline const glm::vec4 kBackground{0.1f, 0.15f, 0.2f, 1.0f};

// A scene prepared for culling and uploaded to its own software backend, with one target. Not
// movable: the renderer keeps a pointer to `scene`.
class CullBench {
public:
    CullBench(Scene s, int w, int h, const MapParams& params = {}, DepthFormat format = DepthFormat::D24)
        : scene(std::move(s)), width(w), height(h), depthFormat(format) {
        culler = SceneCuller::prepare(scene, params);  // reorders the meshes: before the upload
        backend = makeSoftwareBackend();
        target = backend->createTarget(width, height, format);
        EXPECT_NE(target, kNoHandle);
        Result<SceneRenderer> made = SceneRenderer::create(*backend, scene);
        if (made)
            renderer.emplace(std::move(*made));
        else
            uploadError = made.error().message;
    }
    ~CullBench() {
        renderer.reset();
        if (target != kNoHandle) backend->destroyTarget(target);
    }
    CullBench(const CullBench&) = delete;
    CullBench& operator=(const CullBench&) = delete;

    bool canRender() const { return renderer.has_value() && target != kNoHandle; }

    // The occlusion pass's target: the software backend's rules, run on every frame.
    OcclusionTarget occlusionTarget() const {
        Settings settings;
        settings.width = width;
        settings.height = height;
        OcclusionTarget t = frugal::occlusionTarget(*backend, settings);
        t.adaptive = false;
        return t;
    }

    Scene scene;
    SceneCuller culler;
    std::unique_ptr<Backend> backend;
    TargetHandle target = kNoHandle;
    std::optional<SceneRenderer> renderer;
    std::string uploadError;
    int width, height;
    DepthFormat depthFormat;
};

// What one method did over the frames checked.
struct MethodTally {
    std::size_t frames = 0, pvs = 0, rvs = 0, tos = 0, misses = 0, waste = 0;
    void add(const SetCounts& c) {
        ++frames;
        pvs += c.pvs;
        rvs += c.rvs;
        tos += c.tos;
        misses += c.misses;
        waste += c.waste;
    }
};

struct FrameResult {
    bool rendered = false;                   // the full frame was rendered and its RVS measured
    std::size_t rvs = 0, tos = 0;
    std::vector<std::pair<Cull, DrawList>> lists;    // every method's plan
    std::vector<std::pair<Cull, SetCounts>> counts;  // with a rendered frame
    const DrawList* list(Cull method) const {
        for (const auto& [m, l] : lists)
            if (m == method) return &l;
        return nullptr;
    }
    SetCounts count(Cull method) const {
        for (const auto& [m, c] : counts)
            if (m == method) return c;
        return {};
    }
};

struct Tallies {
    std::vector<std::pair<Cull, MethodTally>> perMethod;
    std::size_t frames = 0, rendered = 0;
    MethodTally& of(Cull method) {
        for (auto& [m, t] : perMethod)
            if (m == method) return t;
        perMethod.emplace_back(method, MethodTally{});
        return perMethod.back().second;
    }
    void add(const FrameResult& frame) {
        ++frames;
        rendered += frame.rendered;
        for (const auto& [m, c] : frame.counts) of(m).add(c);
    }
    std::string summary() {
        std::ostringstream out;
        out << frames << " frames (" << rendered << " rendered)";
        for (auto& [m, t] : perMethod)
            out << "; " << toString(m) << ": pvs " << t.pvs << "/" << t.tos << " rvs " << t.rvs << " misses "
                << t.misses;
        return out.str();
    }
};

inline bool isNeverMiss(Cull method) {
    for (Cull m : kNeverMiss)
        if (m == method) return true;
    return false;
}

// The plan is well-formed: instances in scene order (each at most once, valid), ranges non-empty,
// ascending, disjoint and inside the mesh.
inline void expectWellFormed(const Scene& scene, const DrawList& list, const std::string& what) {
    int previous = -1;
    std::size_t total = 0;
    for (const DrawCommand& command : list) {
        EXPECT_GT(command.instance, previous) << what << ": instances out of scene order";
        previous = command.instance;
        ASSERT_GE(command.instance, 0) << what;
        ASSERT_LT(std::size_t(command.instance), scene.instances.size()) << what;
        const std::size_t triangles =
            scene.meshes[std::size_t(scene.instances[std::size_t(command.instance)].mesh)].primitiveCount();
        EXPECT_FALSE(command.ranges.empty()) << what << ": instance " << command.instance << " with no range";
        std::uint64_t end = 0;
        for (const IndexRange& range : command.ranges) {
            EXPECT_GT(range.triangleCount, 0u) << what << ": empty range in instance " << command.instance;
            EXPECT_GE(std::uint64_t(range.firstTriangle), end)
                << what << ": ranges of instance " << command.instance << " overlap or go backwards";
            end = std::uint64_t(range.firstTriangle) + range.triangleCount;
            EXPECT_LE(end, triangles) << what << ": range past the end of instance " << command.instance;
            total += range.triangleCount;
        }
    }
    EXPECT_EQ(submittedTriangles(scene, list), total) << what;
}

inline bool sameList(const DrawList& a, const DrawList& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t k = 0; k < a.size(); ++k) {
        if (a[k].instance != b[k].instance || a[k].ranges.size() != b[k].ranges.size()) return false;
        for (std::size_t r = 0; r < a[k].ranges.size(); ++r)
            if (a[k].ranges[r].firstTriangle != b[k].ranges[r].firstTriangle ||
                a[k].ranges[r].triangleCount != b[k].ranges[r].triangleCount)
                return false;
    }
    return true;
}

// Names the first few triangles of `rvs` that `pvs` lacks.
inline std::string describeMisses(const Scene& scene, const TriangleSet& pvs, const TriangleSet& rvs) {
    std::ostringstream out;
    int shown = 0;
    for (std::size_t i = 0; i < rvs.perInstance.size() && shown < 8; ++i)
        for (std::size_t t = 0; t < rvs.perInstance[i].size() && shown < 8; ++t)
            if (rvs.perInstance[i][t] && !pvs.perInstance[i][t]) {
                const Mesh& mesh = scene.meshes[std::size_t(scene.instances[i].mesh)];
                out << " (instance " << i << ", triangle " << t;
                if (t < mesh.triangleSource.size()) out << ", source " << mesh.triangleSource[t];
                out << ")";
                ++shown;
            }
    return out.str();
}

inline std::size_t differingPixels(const Buffers& a, const Buffers& b, std::string& first) {
    std::size_t differ = 0;
    const std::size_t pixels = std::min(a.pixelCount(), b.pixelCount());
    for (std::size_t p = 0; p < pixels; ++p) {
        bool same = a.ids.size() != pixels || b.ids.size() != pixels || a.ids[p] == b.ids[p];
        same = same && (a.depth.size() != pixels || b.depth.size() != pixels || a.depth[p] == b.depth[p]);
        for (int k = 0; k < 4; ++k) same = same && a.rgba[4 * p + std::size_t(k)] == b.rgba[4 * p + std::size_t(k)];
        if (!same && differ++ == 0) {
            std::ostringstream out;
            out << "first at (" << p % std::size_t(a.width) << ", " << p / std::size_t(a.width) << "): id "
                << (a.ids.size() == pixels ? a.ids[p] : 0) << " vs " << (b.ids.size() == pixels ? b.ids[p] : 0);
            first = out.str();
        }
    }
    return differ;
}

// Checks every method on one frame (see the top of the file). Renders when the scene could be
// uploaded; without a renderer only the plans' shapes and the full lists are checked.
inline FrameResult checkSetup(CullBench& bench, const FrameSetup& setup, const std::string& label) {
    SCOPED_TRACE(label);
    FrameResult result;
    const Scene& scene = bench.scene;
    const DrawList full = fullDrawList(scene);
    for (Cull method : kCulls) {
        DrawList list;
        EXPECT_NO_THROW(list = bench.culler.cull(method, scene, setup.world, setup.view, bench.occlusionTarget()))
            << toString(method);
        expectWellFormed(scene, list, std::string(toString(method)) + " plan");
        if (method == Cull::None || method == Cull::Oracle) {
            EXPECT_TRUE(sameList(list, full)) << toString(method) << " must give the full list";
        }
        result.lists.emplace_back(method, std::move(list));
    }
    if (!bench.canRender()) return result;

    FrameParams params = setup.params;
    params.writeIds = true;
    bench.renderer->renderFrame(bench.target, bench.width, bench.height, params, setup.world, kBackground);
    const Buffers reference = bench.backend->readBack(bench.target);
    Result<TriangleSet> rvs = visibleSet(scene, reference);
    EXPECT_TRUE(rvs) << rvs.error().message;
    if (!rvs) return result;
    result.rendered = true;
    result.rvs = rvs->count;

    for (const auto& [method, list] : result.lists) {
        const TriangleSet pvs = drawnSet(scene, list);
        const SetCounts counts = compareSets(scene, pvs, *rvs);
        result.tos = counts.tos;
        result.counts.emplace_back(method, counts);
        EXPECT_LE(counts.pvs, counts.tos) << toString(method);
        // Judged by its images: every exact method that plans (none draws the full list; the oracle's
        // list is the full one, its visible set comes from an id pass; a method that is not exact misses).
        if (!traitsOf(method).exact || !traitsOf(method).prepares || traitsOf(method).idPass) continue;
        EXPECT_EQ(counts.misses, 0u) << toString(method)
                                     << " dropped visible triangles:" << describeMisses(scene, pvs, *rvs);
        bench.renderer->renderFrame(bench.target, bench.width, bench.height, params, setup.world, kBackground, list);
        const Buffers culled = bench.backend->readBack(bench.target);
        EXPECT_EQ(culled.rgba.size(), reference.rgba.size());
        std::string first;
        const std::size_t differ = differingPixels(reference, culled, first);
        EXPECT_EQ(differ, 0u) << toString(method) << ": the culled render differs from the full one in " << differ
                              << " pixels, " << first;
    }
    return result;
}

inline FrameResult checkFrame(CullBench& bench, const Camera& camera, const std::string& label, double time = 0.0) {
    Result<FrameSetup> setup =
        setUpFrame(bench.scene, camera, time, bench.width, bench.height, true, bench.depthFormat);
    EXPECT_TRUE(setup) << label << ": " << setup.error().message;
    if (!setup) return {};
    return checkSetup(bench, *setup, label);
}

// Every view of reportViews around the scene's bounds at `time`, checked; the tallies returned.
inline Tallies checkReportViews(CullBench& bench, int count, const std::string& label, double time = 0.0) {
    const Bounds bounds = bench.scene.bounds(time);
    const float aspect = float(bench.width) / float(bench.height);
    Tallies tallies;
    const std::vector<ReportView> views = reportViews(bounds.center(), bounds.radius(), count, 40.0f, aspect);
    for (std::size_t k = 0; k < views.size(); ++k)
        tallies.add(checkFrame(bench, views[k].camera, label + " view " + std::to_string(k) + " (" +
                                                           views[k].viewClass + ")",
                               time));
    return tallies;
}

// ---------------------------------------------------------------------------------------------
// Scenes.

inline Camera lookAt(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up = {0.0f, 1.0f, 0.0f}) {
    Camera spec;
    spec.eye = eye;
    spec.target = target;
    spec.up = up;
    return spec;
}

// Normals, ids and (optionally) the vertex-cache order, as a loader would leave the mesh.
inline Mesh finished(Mesh mesh, bool optimizeOrder = true) {
    mesh.normals.clear();
    finalizeMesh(mesh, optimizeOrder);
    return mesh;
}

// A closed blob: a UV sphere of radius ~1 with smooth bumps, counter-clockwise outside (inside
// when `inward`). Its poles have degenerate triangles, its seam duplicated vertices.
inline Mesh blobMesh(unsigned seed, int rings = 14, int segments = 24, bool inward = false) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 6.283f);
    const float a = u(rng), b = u(rng), amp = 0.1f + 0.05f * float(seed % 5);
    const int ka = 1 + int(seed % 4), kb = 2 + int(seed % 3);
    Mesh mesh;
    mesh.name = "blob" + std::to_string(seed);
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segments; ++j) {
            const float theta = 3.14159265f * float(i) / float(rings), phi = 6.2831853f * float(j) / float(segments);
            const float r = 1.0f + amp * std::sin(float(ka) * theta + a) * std::cos(float(kb) * phi + b);
            mesh.positions.push_back(r * glm::vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                                   std::cos(theta)));
        }
    const auto at = [segments](int i, int j) { return std::uint32_t(i * (segments + 1) + j); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            std::uint32_t q[6] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)};
            if (inward) std::swap(q[1], q[2]), std::swap(q[4], q[5]);
            mesh.indices.insert(mesh.indices.end(), q, q + 6);
        }
    return mesh;
}

// `count` random triangles of random size in [-1, 1]^3.
inline Mesh soupMesh(unsigned seed, int count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), size(0.05f, 0.6f);
    Mesh mesh;
    mesh.name = "soup" + std::to_string(seed);
    for (int t = 0; t < count; ++t) {
        const glm::vec3 c(u(rng), u(rng), u(rng));
        const float s = size(rng);
        const auto base = std::uint32_t(mesh.positions.size());
        for (int k = 0; k < 3; ++k) mesh.positions.push_back(c + s * glm::vec3(u(rng), u(rng), u(rng)));
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
    }
    return mesh;
}

// A node drawing `mesh` with a TRS transform; returns the node index.
inline int addMeshNode(Scene& scene, int mesh, const glm::vec3& translation, const glm::quat& rotation = {1, 0, 0, 0},
                       const glm::vec3& scale = glm::vec3(1.0f)) {
    Node node;
    node.meshes = {mesh};
    node.translation = translation;
    node.rotation = rotation;
    node.scale = scale;
    scene.roots.push_back(int(scene.nodes.size()));
    scene.nodes.push_back(node);
    return int(scene.nodes.size()) - 1;
}

// Materials 0 (single-sided) and 1 (double-sided) and one mesh drawn once at the origin.
inline Scene singleMeshScene(Mesh mesh, bool doubleSided) {
    Scene scene;
    scene.source = "test:" + mesh.name;
    scene.materials.resize(2);
    scene.materials[0].name = "single";
    scene.materials[1].name = "double";
    scene.materials[1].doubleSided = true;
    scene.materials[0].baseColorFactor = {0.9f, 0.6f, 0.3f, 1.0f};
    scene.materials[1].baseColorFactor = {0.3f, 0.7f, 0.9f, 1.0f};
    mesh.material = doubleSided ? 1 : 0;
    scene.meshes.push_back(std::move(mesh));
    addMeshNode(scene, 0, glm::vec3(0.0f));
    scene.buildInstances();
    return scene;
}

inline Mesh scaledMesh(Mesh mesh, float factor) {
    for (glm::vec3& p : mesh.positions) p *= factor;
    return mesh;
}

// The bunny as a loader gives it, or nothing (the test is skipped then).
inline std::optional<Scene> loadBunny(bool doubleSided) {
    LoadOptions options;
    options.objDoubleSided = doubleSided;
    Result<Scene> scene = loadScene(FRUGAL_BUNNY_OBJ, options);
    if (!scene) return std::nullopt;
    return std::move(*scene);
}

}  // namespace frugal::test
