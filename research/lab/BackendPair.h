// `frugal diff`'s two stages: a GL backend and the software reference drawing the same frames from
// the same draw list (ordered, then planned in the hidden-surface mode), so that their images can
// be compared pixel by pixel. The GL image is the "actual", the software image the "reference".
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>

#include "renderer/Research.h"

namespace frugal {

class BackendPair {
public:
    // Opens settings.backend (a GL kind, or Auto) and the software reference, each with a target of
    // the settings' size and `scene` uploaded (the scene must outlive the pair). paper, greedy and
    // best (settings.order) order by the GL backend's measured costs; both draw that list, in
    // settings.hsr. `progress` receives "backend: NAME (...)", "reference: software (...)" and the
    // state-cost line. Errors: Stage::open's; "order best: <why>" (about a setting).
    static Result<BackendPair> open(const Scene& scene, const Settings& settings,
                                    const std::function<void(const std::string&)>& progress);

    // The frame drawn on both and read back: [0] the GL backend's, [1] the reference's.
    std::array<Buffers, 2> render(const FrameSetup& setup);

    const Stage& actual() const { return stages_[0]; }
    const Stage& reference() const { return stages_[1]; }

private:
    BackendPair(const Scene& scene, const Settings& settings, std::vector<Stage> stages, OrderCosts costs);

    const Scene* scene_;
    Settings settings_;
    std::vector<Stage> stages_;  // the GL backend's, the reference's
    OrderCosts costs_;
    std::optional<hsr::Planner> planner_;
};

}  // namespace frugal
