#include "app/OrderSupport.h"

#include <algorithm>
#include <ostream>

#include <nlohmann/json.hpp>

#include "base/Format.h"

namespace frugal {

std::vector<order::Rss> drawStates(const Scene& scene, const DrawList& list, bool cullAllBackFaces) {
    std::vector<order::Rss> sets;
    sets.reserve(list.size());
    for (const DrawCommand& command : list) {
        const int meshIndex = scene.instances[std::size_t(command.instance)].mesh;
        const Mesh& mesh = scene.meshes[std::size_t(meshIndex)];
        const Material* material = mesh.material >= 0 ? &scene.materials[std::size_t(mesh.material)] : nullptr;
        const bool textured = material && material->baseColorTexture >= 0;
        const bool doubleSided = material && material->doubleSided && !cullAllBackFaces;
        sets.push_back({std::uint32_t(1 + (textured ? 1 : 0) + (mesh.colors.empty() ? 0 : 2)),
                        std::uint32_t(1 + meshIndex),
                        textured ? std::uint32_t(1 + material->baseColorTexture) : 0u,
                        std::uint32_t(2 + mesh.material),
                        doubleSided ? 2u : 1u,
                        command.depth == DepthMode::Test ? 1u : 2u});
    }
    return sets;
}

std::vector<double> stateCostsUs(const StateCostReport& report) {
    std::vector<double> costs;
    for (const StateCost& cost : report.costs) costs.push_back(std::max(cost.us, 0.01));
    return costs;
}

DrawList orderFrameDraws(const Scene& scene, const DrawList& list, DrawOrder drawOrder, const std::vector<double>& costs) {
    if (drawOrder == DrawOrder::Submit || drawOrder == DrawOrder::Key || list.size() < 2)
        return orderDraws(scene, list, drawOrder);
    const order::DistinctSets distinct = order::distinctSets(drawStates(scene, list));
    const order::Transitions transitions(distinct.sets, costs, order::CostRule::SetNotHeld);
    std::vector<int> classes;
    if (drawOrder == DrawOrder::Paper)
        classes = order::paperOrder(distinct.sets, order::highCostSet(costs, order::thresholdForSize(costs, 3)));
    else if (drawOrder == DrawOrder::Greedy)
        classes = order::greedyOrder(transitions);
    else
        classes = order::bestOrder(transitions, {order::greedyOrder(transitions)}).order;
    DrawList out;
    out.reserve(list.size());
    for (int index : order::expandOrder(distinct, classes)) out.push_back(list[std::size_t(index)]);
    return out;
}

nlohmann::json stateChangesJson(const StateChanges& c) {
    return {{"draws", c.draws}, {"programs", c.programs}, {"meshes", c.meshes},
            {"textures", c.textures}, {"toggles", c.toggles}, {"uniforms", c.uniforms}};
}

Result<std::vector<double>> costsForOrder(DrawOrder order, Backend& backend, std::ostream& err, bool quiet) {
    if (order == DrawOrder::Submit || order == DrawOrder::Key) return std::vector<double>{};
    Result<StateCostReport> measured = measureStateCosts(backend, 5, 200);
    if (!measured) return Error{measured.error()};
    const std::vector<double> costs = stateCostsUs(*measured);
    if (!quiet) {
        err << "order " << drawOrderName(order) << ": state costs on " << backend.name() << " (us):";
        for (std::size_t k = 0; k < costs.size(); ++k)
            err << (k ? ", " : " ") << measured->costs[k].kind << " " << fmt(costs[k]);
        err << "\n";
    }
    return costs;
}

}  // namespace frugal
