// Temporal reuse (paper 000, the temporal-coherence z-buffer: its steps, Fig. 5, and its cost model,
// eq. 1 and 2, are restated below): with the camera still, a frame redraws only what changed,
// reusing the colour, depth and ids of static instances from a static pair (a second target that
// holds what the static instances alone render to). Plans only: this module never touches a
// backend; SceneRenderer::execute runs the FramePlan it makes on either one.
//
// Dynamic: an instance whose world matrix, material (any member of it), pose (morph weights and
// joint matrices, Scene::deforms: extents are then of the posed positions) or drawn ranges differ
// from the previous frame,
// compared exactly: bit for bit (so -0 and +0 differ,
// and a NaN pose that stays the same bits is static: it draws the same nothing); appearing (drawn
// now, not before) and disappearing count as changes. An instance of a blended material
// (AlphaMode::Blend) is dynamic in every frame: a blend must come after every opaque surface behind
// it, dynamic ones too, so it is drawn last each frame (SceneRenderer::draw) and never reused. The four states
// pair the previous frame's state with this one: P_dd, P_ds, P_sd, P_ss.
//
// A reuse frame (camera, light, background and size as in the previous frame; static pair valid)
// runs the paper's Fig. 5, with every region a set of cells of a CellGrid (the ⊗ tests are
// O(n + k), not the paper's all pairs) and every redraw in draw-list order:
//   1. copy static → render over the cells of the previous extents of P_dd (minus those of step 2);
//   2. clear the cells of the previous extents of P_sd in the render target;
//   3+4. redraw the groups of P_ss whose extent meets a cleared cell and the groups of P_ds whose
//      extent meets a copied or cleared cell (one pass, so two static instances tie as they do in
//      a full render);
//   5. copy render → static over the cleared cells and the cells of P_ds's extents;
//   6. draw P_sd ∪ P_dd as they are now.
// Why it equals a full render: outside the cells of steps 1–2 the render target still holds the
// previous frame, in which only instances static now (P_ss, and P_ds, unmoved) own pixels there;
// in a copied cell the static pair holds the previous frame's static instances (P_ss, and P_sd
// whose cells step 2 clears), missing only P_ds, redrawn where it meets such a cell; in a cleared
// cell every static instance that can own a pixel there is redrawn (its extent meets the cell).
// Step 5 makes the static pair this frame's static instances again, step 6 adds the dynamic ones.
// Depth ties: a full render resolves an exact tie by draw order; reuse draws the dynamic instances
// after the static ones, so a tie between a static and a dynamic triangle can go the other way in
// that frame (reuse-bench counts such pixels, tie_px). With the paper's steps a P_ds instance keeps
// the pixels it was drawn with while dynamic, so a tie it lost then stays lost, in the render target
// and, through step 5, in the static pair, until something redraws that place.
//
// ReuseOptions::paperSteps = false (`--exact-static`) keeps the static pair exact instead: "cleared"
// = the previous extents of P_sd and the extents of P_ds, "copied" = those and P_dd's, and
//   a. clear the cleared cells of the static pair; b. redraw there, in draw order, the static groups
//   (P_ss, P_ds) whose extent meets a cleared cell; c. copy static → render over the copied cells;
//   d. draw P_sd ∪ P_dd (step 6).
// The static pair is then exactly what the static instances render to after every frame, so no tie
// outlives its frame; it costs the redraw of the static instances around each one that comes to
// rest (slower on the dominoes; the figures are in docs/reuse/README.md).
//
// Other frames: the camera (or light, background) changed → a full render, static pair invalid;
// the first frame with the camera still → rebuild: render the static instances, copy the whole
// target to the static pair, draw the dynamic ones. A frame with no previous one counts everything
// static. When a reuse frame would cost more than a full render by the cost model below, or a
// rebuild would be followed by frames that are mostly dynamic, the frame is a full render; the
// decision and its reason are in the frame's stats.
//
// Cost model (the paper's eq. 1 and 2, in triangle-equivalents, with what its t_r hides on a
// modern rasterizer spelled out; ReuseCosts): a full render costs its triangles, its draw calls and
// one clear of the whole target; a reuse frame its triangles, draw calls, pixels cleared and copied,
// rectangles and, when it redraws static instances, one more pass. Reuse runs when it is cheaper.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <frugal/Settings.h>
#include <frugal/Stats.h>

#include "pipeline/Plan.h"
#include "reuse/CellGrid.h"

namespace frugal {

// An instance's state between the frame before and this one, as the planner numbers them: dynamic
// then and now, dynamic then and static now, static then and dynamic now, static both.
enum ReuseState : int { kDD = 0, kDS = 1, kSD = 2, kSS = 3 };
// The count of `state` among `counts` (frugal/Stats.h ReuseCounts).
inline std::uint64_t& countOf(ReuseCounts& counts, int state) {
    std::uint64_t* const each[] = {&counts.dd, &counts.ds, &counts.sd, &counts.ss};
    return *each[state];
}
inline std::uint64_t countOf(const ReuseCounts& counts, int state) {
    const std::uint64_t each[] = {counts.dd, counts.ds, counts.sd, counts.ss};
    return each[state];
}

// The fallback's cost model, in units of one triangle drawn. The defaults are rough fits to
// llvmpipe and the software backend (the timings they come from: docs/gl/README.md, "Outside the GL
// backend"): a draw call costs tens of triangles before any of its own, a pixel copied (read one
// target, write another) about four times a pixel cleared, and each rectangle is a blit on llvmpipe.
struct ReuseCosts {
    double draw = 24.0;
    double pixelCleared = 1.0 / 256.0;
    double pixelCopied = 1.0 / 64.0;
    double rect = 32.0;
    double pass = 64.0;
};

struct ReuseOptions {
    // Triangles per extent: consecutive triangles of a mesh's index buffer share one rectangle.
    // 1 = per triangle (the paper), 0 = one extent per instance.
    int grain = 16;
    int cell = 16;  // grid cell side in pixels
    ReuseCosts costs;
    bool fallback = true;  // false: never fall back to a full render while the camera is still
    bool paperSteps = true;  // false: steps a–d, the static pair kept exact (see above)
};

// The options of the renderer's settings (frugal/Settings.h), the costs left at their defaults.
ReuseOptions reuseOptionsFrom(const ReuseSettings& settings);

using ReuseFrameStats = ReuseStats;  // frugal/Stats.h

class TemporalReuse {
public:
    // `scene` must outlive the planner; width × height is the target's size.
    TemporalReuse(const Scene& scene, int width, int height, ReuseOptions options = {});

    // The plan of one frame. `list` is what a full render of the frame draws, in its order (the full
    // draw list, or a culled one: at most one entry per instance). `frame` and `background` are
    // the frame's camera, light and clear colour; `world` its node matrices.
    FramePlan plan(const FrameParams& frame, const std::vector<glm::mat4>& world, const DrawList& list,
                   const glm::vec4& background);
    // The same for the whole scene (fullDrawList): faster, as no instance's ranges need comparing.
    // Its plan may point to the planner's own list (PlanStep::list): execute it while the planner lives.
    FramePlan plan(const FrameParams& frame, const std::vector<glm::mat4>& world, const glm::vec4& background);
    const ReuseFrameStats& stats() const { return stats_; }

    // Forget the static pair and the render target's content (someone else drew into them).
    void invalidate() { staticValid_ = false; }
    bool staticValid() const { return staticValid_; }
    const ReuseOptions& options() const { return options_; }
    // After plan(): whether `instance` is dynamic in that frame (changed since the previous one;
    // false on a first frame, and for an index out of range).
    bool dynamicNow(int instance) const {
        // plan() leaves this frame's flags in wasDynamic_, ready for the next frame.
        return instance >= 0 && std::size_t(instance) < wasDynamic_.size() && wasDynamic_[std::size_t(instance)] != 0;
    }

private:
    struct InstanceInfo {
        int node = -1;
        int material = -1;  // -1: the default material
        std::uint32_t triangles = 0;
    };
    struct Record {
        bool drawn = false;
        std::vector<IndexRange> ranges;  // normalised, as drawn in the previous frame
        std::uint64_t drawnTris = 0;
        std::uint32_t firstGroup = 0, groups = 0;
    };

    void computeExtents(int instance, const glm::mat4& viewProjection, const std::vector<glm::mat4>& world);
    std::uint32_t groupSize(int instance) const;
    // What changed this frame, drawn now.
    struct Changes {
        std::uint64_t triangles = 0;
        std::uint64_t draws = 0;
    };

    FramePlan makePlan(const FrameParams& frame, const std::vector<glm::mat4>& world, const DrawList& list,
                       const glm::vec4& background, bool wholeScene);
    // Fills nowDynamic_, the records, and the frame's state counts; false (and only drawnTris
    // counted) when `list` names an instance twice or one the scene does not have.
    bool classify(const DrawList& list, const std::vector<glm::mat4>& world, bool first, bool wholeAgain,
                  Changes& changes);
    FramePlan rebuildPlan(const DrawList& list, const std::vector<glm::mat4>& world, const glm::mat4& viewProjection,
                          bool first, const Changes& changes);
    FramePlan reusePlan(const DrawList& list, const std::vector<glm::mat4>& world, const glm::mat4& viewProjection,
                        double fullCost, const Changes& changes);
    FramePlan fullPlan(const DrawList& list, const char* reason);

    const Scene* scene_;
    int width_, height_;
    ReuseOptions options_;
    std::vector<InstanceInfo> info_;
    std::vector<Record> records_;
    std::vector<glm::mat4> models_;                // per instance, as drawn in the previous frame
    // Deforming instances (Scene::deforms): this frame's morph weights per node, and per instance
    // the weights and joint matrices it was drawn with last and its posed positions (what its
    // extents are made of).
    std::vector<std::vector<float>> frameWeights_;
    std::vector<std::vector<float>> weights_;
    std::vector<std::vector<glm::mat4>> joints_;
    std::vector<std::vector<glm::vec3>> posed_;
    PosedVertices poseScratch_;                    // poseVertices' output, its memory kept from frame to frame
    std::vector<Material> materialKeys_;           // per material + 1 (0: the default material)
    std::vector<std::uint8_t> materialChanged_;
    DrawList fullList_;
    std::vector<reuse::Box> extents_;  // per group, as last drawn
    std::vector<reuse::Box> instanceBoxes_;
    reuse::ExtentBuilder builder_;
    reuse::CellGrid grid_;
    bool history_ = false;       // a previous frame was planned
    bool lastWhole_ = false;     // ... and it drew the whole scene
    bool staticValid_ = false;
    FrameParams lastFrame_;
    glm::vec4 lastBackground_{0.0f};
    ReuseFrameStats stats_;
    std::vector<std::uint8_t> nowDynamic_;  // per instance: changed since the previous frame
    std::vector<std::uint8_t> wasDynamic_;  // the same one frame earlier
};

}  // namespace frugal
