// A frame's plan made while the frame before it draws (`--cull occlusion-ahead`).
//
// On a sequence the next frame's camera and time are known before the current frame is drawn. The
// occlusion pass of that next frame can then run on a thread of its own while the current frame's
// draw keeps the rasterizer busy, and the next render() takes the finished plan instead of making
// it: the pass leaves the frame's critical path wherever the draw leaves a core some time.
//
// The plan is exactly the one SceneCuller::cull gives for that frame: it is made with the frame's
// own transforms and view, and taken only when the frame to draw has exactly those (and the same
// target); any other frame is culled as usual. So the images are the same as `occlusion`'s, byte
// for byte, whether or not the guess was right.
//
// The culler is not safe to use from two threads: while a plan is being made ahead, nothing else may
// call the SceneCuller, or change the scene it reads. take() and settle() wait for it.
#pragma once

#include <future>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Scene.h>
#include <frugal/Settings.h>

#include "cull/Culling.h"

namespace frugal {

class CullAhead {
public:
    CullAhead() = default;
    ~CullAhead() { settle(); }
    CullAhead(const CullAhead&) = delete;
    CullAhead& operator=(const CullAhead&) = delete;

    // Starts making `method`'s plan for a frame with node transforms `world` and camera `view` on a
    // thread of its own (after waiting for and dropping any plan started before). `culler` and
    // `scene` must stay alive and unchanged until take() or settle().
    void start(const SceneCuller& culler, Cull method, const Scene& scene, std::vector<glm::mat4> world,
               const View& view, const OcclusionTarget& target);

    // The plan made ahead, when it was started for exactly this frame: `method`, `world`, `view` and
    // `target` equal to start()'s (bit for bit; a NaN never equals). Waits for it. Otherwise (nothing
    // started, or another frame) nullopt, and what was started is waited for and dropped.
    std::optional<DrawList> take(Cull method, const std::vector<glm::mat4>& world, const View& view,
                                 const OcclusionTarget& target);

    // Waits until the plan started is made, and keeps it for take().
    void wait() const {
        if (plan_.valid()) plan_.wait();
    }

    // Waits for what is running and drops it. After it, the culler and the scene are free.
    void settle();

    bool pending() const { return plan_.valid(); }

private:
    struct Key {
        Cull method = Cull::None;
        std::vector<glm::mat4> world;
        View view;
        OcclusionTarget target;
    };
    Key key_;
    std::future<DrawList> plan_;
};

// The target a plan made ahead uses: `target` with one thread for its walk. Run beside a draw, the
// pass's own threads would take the cores the rasterizer draws with (measured in docs/occlusion.md).
OcclusionTarget aheadTarget(OcclusionTarget target);

}  // namespace frugal
