#include "lab/BackendPair.h"

#include "lab/SceneInfo.h"

#include <utility>

namespace frugal {

BackendPair::BackendPair(const Scene& scene, const Settings& settings, std::vector<Stage> stages, OrderCosts costs)
    : scene_(&scene), settings_(settings), stages_(std::move(stages)), costs_(std::move(costs)) {
    if (settings.hsr != Hsr::ZBuffer) planner_.emplace(scene);
}

Result<BackendPair> BackendPair::open(const Scene& scene, const Settings& settings,
                                      const std::function<void(const std::string&)>& progress) {
    Settings reference = settings;
    reference.backend = BackendKind::Software;
    std::vector<Stage> stages;
    for (const Settings* s : std::array<const Settings*, 2>{&settings, &reference}) {
        Result<Stage> stage = Stage::open(*s);
        if (!stage) return stage.error();
        stages.push_back(std::move(*stage));
    }
    progress("backend: " + describe(stages[0].backend()));
    progress("reference: " + describe(stages[1].backend()));
    for (Stage& stage : stages)
        if (Result<bool> uploaded = stage.upload(scene); !uploaded) return uploaded.error();
    Result<OrderCosts> costs = OrderCosts::start(settings.order, stages[0].backend(), 0);
    if (!costs)
        return Error{std::string("order ") + toString(settings.order) + ": " + costs.error().message, ErrorKind::BadInput, true};
    if (const std::optional<StateCosts> measured = costs->report())
        progress(stateCostsLine(settings.order, stages[0].backend().name(), *measured));
    return BackendPair(scene, settings, std::move(stages), std::move(*costs));
}

std::array<Buffers, 2> BackendPair::render(const FrameSetup& setup) {
    const Settings& s = settings_;
    const DrawList ordered = orderFrameDraws(*scene_, stages_[0].renderer().fullList(), s.order, costs_.costsUs());
    const DrawList list = planner_ ? planner_->plan(s.hsr, setup.params, setup.world, ordered, s.width, s.height)
                                   : ordered;
    std::array<Buffers, 2> images;
    for (std::size_t k = 0; k < 2; ++k) {
        Stage& stage = stages_[k];
        stage.renderer().renderFrame(stage.target(), s.width, s.height, setup.params, setup.world, s.background, list);
        images[k] = stage.backend().readBack(stage.target());
    }
    return images;
}

}  // namespace frugal
