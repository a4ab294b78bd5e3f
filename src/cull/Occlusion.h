// Occlusion culling on the CPU (`--cull occlusion`): of the clusters the conservative plan keeps,
// drop those hidden behind others that are drawn anyway. After the masked software occlusion
// culling of Hasselgren, Andersson and Akenine-Möller (HPG 2016), with frugal's own rasterizer in
// place of its coarse one: occluders are rasterized with llvmpipe's exact coverage (software/
// Rasterizer.h), so the buffer never claims a pixel the GL draw leaves open.
//
// The occlusion buffer holds, per pixel, an upper bound on the depth the frame's z-buffer ends with
// there: the nearest occluder's depth plane at the pixel plus the bound of its float rounding (or
// "open" where no occluder covers the pixel), and per 8 × 8 block the farthest of those. Clusters are
// visited nearest first (by the nearest corner of their box; an instance of a small mesh is taken
// whole, under the box of its kept clusters); each is tested, and when it may be seen it is kept
// and rasterized into the buffer as an occluder. A cluster is hidden when every
// pixel its box can reach (its screen rectangle, grown by one pixel and by the bound of the float
// vertex transform) holds an occluder strictly nearer than the box's nearest point (less a margin
// for rounding and the 24-bit quantization). Then each of its fragments fails the depth test
// against a fragment that is drawn, in whatever order they are drawn: the image, depth and ids are
// the same as the conservative plan's.
//
// Masked and blended surfaces (AlphaMode::Mask, Blend) are tested like any other but never
// occlude: a fragment they discard, or blend, leaves what is behind it visible.
// Occluders are only triangles the GL draw does not clip (clip mask 0): a clipped triangle's new
// vertices are rounded, and the buffer must not depend on them. A box that reaches the near plane,
// or whose numbers are not finite, is never tested (kept). The vertex transform and setup are
// llvmpipe's (bit for bit on llvmpipe and the software backend, checked by tests); on another GL
// driver the one-pixel and depth margins are what is left, untested here.
//
// Every triangle of a cluster that is not hidden whole is set up on the CPU: on llvmpipe's rules,
// one that owns no pixel centre (most of a dense mesh far away) or whose pixels all hold something
// nearer is dropped, and so the plan comes close to the oracle's. The walk is split into bands of
// rows, one per core; each band sees exactly what one walk over the whole screen sees there. The
// rest (the conservative plan, the boxes, gathering the plan) is done in pieces side by side on the
// same threads, woken before the conservative plan is made (prepare), and joined in order.
//
// It pays for itself or turns itself off: a pass is skipped when the conservative plan submits
// fewer than a few thousand triangles, and after a pass whose saved draw (the triangles it dropped
// and the draws the plan no longer makes, by what each costs the target) was less than its own
// time, the next 1, 2, 4, ... 16 calls skip it, unless their plan is more than 1.25 times as large
// (another kind of view). A skipped pass leaves the conservative plan as it is.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Image.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>

#include "cull/SphereMap.h"
#include "pipeline/Backend.h"
#include "pipeline/Camera.h"

namespace frugal {

// What occlusion culling did in one view.
struct OcclusionStats {
    bool ran = false;                   // false: skipped (too little to gain, or it did not pay lately)
    std::size_t clustersTested = 0;     // kept by the conservative plan, with a box in front of the eye
    std::size_t clustersHidden = 0;     // dropped
    std::size_t trianglesHidden = 0;    // of the conservative plan's: dropped with the clusters, or alone
    double ms = 0.0;                    // the pass: ordering, rasterizing and testing
    std::int64_t drawsSaved = 0;        // draws the plan no longer makes (OcclusionTarget::gathering)
    double savedMs = 0.0;               // estimated: trianglesHidden and drawsSaved by the target's costs
};

// One cluster that the conservative plan keeps, with the ranges of it that the plan submits.
struct KeptCluster {
    std::uint32_t instance = 0;                   // index into scene.instances
    std::uint32_t cluster = 0;                    // index into its mesh map's clusters
    std::uint32_t firstRange = 0, rangeCount = 0;  // into the plan's ranges
};

// The target the plan is drawn into.
struct OcclusionTarget {
    int width = 0, height = 0;
    // The draw follows llvmpipe's rasterization rules (llvmpipe, or the software backend): clusters
    // are then also tested triangle by triangle, and a triangle that owns no pixel centre is dropped.
    // Otherwise (a GPU's driver) only whole clusters are tested, with their margins.
    bool exactRules = true;
    double drawNsPerTriangle = 110.0;  // what a submitted triangle costs the draw (llvmpipe's, 2 cores)
    double drawNsPerDraw = 0.0;        // and what each draw costs it, besides its triangles
    RangeGathering gathering{};        // how the backend draws an instance's ranges: which draws it makes
    // false: the pass runs on every call, however little it gains (tests, and measuring it).
    bool adaptive = true;
    int threads = 0;  // the walk's threads; 0: every core
    // The vertex transform and the quick triangle test eight at a time (AVX2) where the CPU has it;
    // false: the scalar loops (the tests compare the two plans).
    bool simd = true;
    // With simd, the quick test looks up each corner with AVX-512 permutes where the CPU has them;
    // false: it gathers them with AVX2 (the tests compare the plans).
    bool avx512 = true;
};

// The target of `backend` for frames of `settings` (size, threads): its rules, and its cost of a
// triangle.
OcclusionTarget occlusionTarget(const Backend& backend, const Settings& settings);

class OcclusionCuller {
public:
    OcclusionCuller();
    ~OcclusionCuller();
    OcclusionCuller(OcclusionCuller&&) noexcept;
    OcclusionCuller& operator=(OcclusionCuller&&) noexcept;

    // What is left of each of `kept` (result[k]: the same cluster, its ranges in `out`; none when
    // it is hidden), for `target`, whose depth buffer has `view.depthFormat`. `maps` are the scene's
    // mesh maps, `ranges` the plan's.
    void run(const Scene& scene, const std::vector<MeshMap>& maps, const std::vector<glm::mat4>& world,
             const View& view, const OcclusionTarget& target, const std::vector<KeptCluster>& kept,
             const std::vector<IndexRange>& ranges, std::vector<KeptCluster>& result, std::vector<IndexRange>& out);

    // Called before the conservative plan that run() will get is made: wakes the pass's threads,
    // so that their wake-up (a tenth of a millisecond in a virtual machine) overlaps making it, and
    // they wait for the pass spinning until run() ends. Not when the next run() is likely to skip
    // the pass (the last plan was small, or it is backing off).
    // Returns whether it woke them.
    bool prepare(const OcclusionTarget& target);

    // fn(i, worker) for i in [0, count), in any order: for making the plan run() gets. On the pass's
    // threads side by side when prepare() woke them; otherwise on the caller in order (waking
    // sleeping threads would cost more than a small plan).
    // `worker` is in [0, threads(target)): the thread's number.
    void parallel(const OcclusionTarget& target, std::size_t count, const std::function<void(std::size_t, int)>& fn);
    int threads(const OcclusionTarget& target);

    const OcclusionStats& stats() const;

    // Memory it keeps between calls: the buffer, the clusters' vertices side by side, the bands'
    // flags (0 before the first pass that ran).
    std::uint64_t bytes() const;

    // The last run's buffer as an RGBA8 image (top row first): open pixels blue, covered pixels
    // grey, lighter the nearer. Empty when the last run was skipped.
    std::vector<std::uint8_t> image(int& width, int& height) const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace frugal
