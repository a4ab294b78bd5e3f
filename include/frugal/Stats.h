// What a frame cost and did, as a Renderer reports it for each frame (frugal/Renderer.h), and as
// `frugal render --json` writes it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <frugal/Settings.h>

namespace frugal {

// The state changes a backend issued, by kind (a frame's are a difference of two readings): for
// the GL backend the calls its state cache let through (a repeat of the current state is not a
// change), for the software backend, which keeps no such state, the draws alone.
struct StateChanges {
    std::uint64_t draws = 0;     // draw calls (glDraw*, glMultiDraw*)
    std::uint64_t programs = 0;  // program binds (a shader variant)
    std::uint64_t meshes = 0;    // vertex array binds
    std::uint64_t textures = 0;  // texture binds
    std::uint64_t toggles = 0;   // glEnable / glDisable: face culling, depth test, scissor
    std::uint64_t uniforms = 0;  // uniform uploads: transforms, material, lighting, first id

    // The changes between two readings (a frame's: after − before).
    StateChanges operator-(const StateChanges& before) const {
        return {draws - before.draws,       programs - before.programs, meshes - before.meshes,
                textures - before.textures, toggles - before.toggles,   uniforms - before.uniforms};
    }
};

// Culling in one frame.
// The occlusion pass of one frame (cull occlusion): whether it ran (it skips itself where it does not
// pay), its time (within CullStats::ms) and the triangles of the conservative plan it dropped.
// cull occlusion-ahead: `ahead`, the plan was made while the frame before drew (its pass's time is
// then not within CullStats::ms); aheadWaitMs, what this frame waited after its draw for the next
// frame's plan (within FrameStats::renderMs).
struct OcclusionFrameStats {
    bool ran = false;
    double ms = 0.0;
    std::size_t trianglesHidden = 0;
    bool ahead = false;
    double aheadWaitMs = 0.0;
};

struct CullStats {
    std::size_t tos = 0;     // the scene's triangles (and its segments and points: Mesh::topology)
    std::size_t pvs = 0;     // the triangles submitted (the oracle: its visible set), segments and points too
    double ms = 0.0;         // culling (the oracle: its id pass, read-back and scene; not in renderMs)
    std::size_t ranges = 0;  // index ranges submitted (none for the oracle)
    std::optional<OcclusionFrameStats> occlusion;  // cull occlusion and occlusion-ahead only
};

// Temporal reuse in one frame (paper 000): the mode, its reason, and what was copied, cleared and
// drawn again.
enum class ReuseMode : std::uint8_t { Full, Rebuild, Reuse };
inline const char* toString(ReuseMode v) {
    constexpr const char* names[] = {"full", "rebuild", "reuse"};
    return names[std::size_t(v)];
}
// Instances, or their triangles, by how they moved between the frame before and this one.
struct ReuseCounts {
    std::uint64_t dd = 0;  // dynamic then and now
    std::uint64_t ds = 0;  // dynamic then, static now
    std::uint64_t sd = 0;  // static then, dynamic now
    std::uint64_t ss = 0;  // static then and now
    bool operator==(const ReuseCounts&) const = default;
};

struct ReuseStats {
    ReuseMode mode = ReuseMode::Full;
    std::string reason;                        // why this mode: "camera moved", "first still frame", ...
    ReuseCounts instances;
    ReuseCounts triangles;  // the instances' mesh triangles
    std::uint64_t copiedPx = 0;           // static → render (step 1) and render → static (step 5 or the rebuild)
    std::uint64_t clearedPx = 0;          // step 2 (and the whole target on full and rebuild frames)
    std::uint64_t redrawnTris = 0;        // every triangle this frame drew (all of them on full frames)
    std::uint64_t staticRedrawnTris = 0;  // of those, static ones drawn again (steps 3 + 4; all on a rebuild)
    std::uint64_t drawnTris = 0;          // what a full render of this frame draws
    std::uint64_t rects = 0;              // clear and copy rectangles issued
    double planMs = 0.0;                  // the whole plan: classification, extents, ⊗ tests, rectangles
    double extentMs = 0.0;                // extents of the instances that moved
    double overlapMs = 0.0;               // grid marking and the ⊗ tests
};

// A hidden-surface mode's plan in one frame (paper 003).
struct HsrStats {
    std::size_t polygons = 0;  // listed polygons (in view, not clearly back-facing)
    std::size_t flagged = 0;   // adaptive: polygons drawn with the z-buffer
    std::size_t draws = 0;     // draw commands in the plan
    double ms = 0.0;           // extents + sort + flags + the list, on the calling thread
    // The share of polygons drawn with the depth test: 1 for zbuffer, 0 for depthsort.
    double zbufferedShare(Hsr mode) const {
        if (mode == Hsr::ZBuffer) return 1.0;
        if (mode == Hsr::DepthSort || polygons == 0) return 0.0;
        return double(flagged) / double(polygons);
    }
    // The polygons drawn with the depth test.
    std::size_t zbuffered(Hsr mode) const { return mode == Hsr::ZBuffer ? polygons : flagged; }
};

// The software backend's span interpolator in one frame (DepthInterp other than Exact).
struct InterpStats {
    std::uint64_t spans = 0;        // span::fillSpan calls: one per covered run of a triangle's row per tile
    std::uint64_t pixels = 0;       // of those, the tile's pixels (the depths that met the depth test)
    std::uint64_t overflow = 0;     // calls that reported an overflow: their values were clamped (or the
                                    // span zeroed), never wrapped. A call fills its run from the run's
                                    // first column, so a run across several tiles may count once per tile.
};

// One frame.
struct FrameStats {
    double time = 0.0;                  // scene time, seconds
    double renderMs = 0.0;              // culling, planning and drawing until the backend finished
    double readbackMs = 0.0;            // reading the images back
    std::optional<CullStats> cull;      // with a Cull other than None
    std::optional<ReuseStats> reuse;    // with reuse
    std::optional<HsrStats> hsr;        // with an Hsr other than ZBuffer
    StateChanges stateChanges;          // what the backend issued for this frame
    std::optional<InterpStats> interp;  // with a DepthInterp other than Exact (software backend)
    // With Order paper, greedy or best and refineCosts > 0: the cost round run after the frame
    // before this one (between the two frames, outside every timing), and the costs it gave.
    std::optional<std::vector<double>> refinedCostsUs;
    double refineMs = 0.0;
    // What the backend was asked to do, as a hash (taken after the clock stops): the clears, copies
    // and draws in order, each draw's instance, depth mode and triangles (adjacent ranges of one
    // instance count as one run), and the interpolator. Two frames with one fingerprint drew the same
    // triangles in the same order with the same state. 0: not recorded (cull oracle, which draws
    // its own scene).
    std::uint64_t drawFingerprint = 0;
    // The same for the frame the cull's list alone would have been (the whole scene's without a
    // cull): a full clear, the list as culled, the exact interpolator. Equal to drawFingerprint when
    // what comes after the cull (order, hidden-surface planning, reuse, interpolator) changed nothing.
    std::uint64_t culledFingerprint = 0;
};

// The state-change costs a cost-driven order uses (Order paper, greedy, best), measured on the
// backend when the renderer was made and refined between frames, per kind of state.
struct StateCosts {
    std::vector<std::string> kinds;  // "program", "mesh", "texture", "material", "culling", "depth"
    std::vector<double> startUs;     // the first measurement (5 rounds of 200 draws a kind)
    std::vector<double> us;          // now: the interquartile mean of the last 32 rounds
    std::size_t rounds = 0;
    int refineEvery = 0;
};

}  // namespace frugal
