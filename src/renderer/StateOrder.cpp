#include "renderer/StateOrder.h"

#include <algorithm>

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
        // The program: which inputs and maps the draw's shader variant reads.
        const std::uint32_t maps =
            material ? (material->metallicRoughnessTexture >= 0 ? 4u : 0u) |
                           (material->occlusionTexture >= 0 ? 8u : 0u) | (material->emissiveTexture >= 0 ? 16u : 0u) |
                           (material->normalTexture >= 0 ? 32u : 0u) | (material->specularGlossiness ? 64u : 0u) |
                           (material->specularGlossinessTexture >= 0 ? 128u : 0u) |
                           (std::uint32_t(material->alphaMode) << 8) | (material->clearcoat() ? 1024u : 0u) |
                           (material->clearcoatTexture >= 0 ? 2048u : 0u) |
                           (material->clearcoatRoughnessTexture >= 0 ? 4096u : 0u) |
                           (material->clearcoatNormalTexture >= 0 ? 8192u : 0u)
                     : 0u;
        sets.push_back({1 + ((textured ? 1u : 0u) | (mesh.colors.empty() ? 0u : 2u) | maps),
                        std::uint32_t(1 + meshIndex), textured ? std::uint32_t(1 + material->baseColorTexture) : 0u,
                        std::uint32_t(2 + mesh.material), doubleSided ? 2u : 1u,
                        command.depth == DepthMode::Test ? 1u : 2u});
    }
    return sets;
}

DrawList orderFrameDraws(const Scene& scene, const DrawList& list, Order drawOrder, const std::vector<double>& costs) {
    if (!traitsOf(drawOrder).measuresCosts || list.size() < 2)
        return orderDraws(scene, list, drawOrder);
    const order::DistinctSets distinct = order::distinctSets(drawStates(scene, list));
    const order::Transitions transitions(distinct.sets, costs, order::CostRule::SetNotHeld);
    std::vector<int> classes;
    if (drawOrder == Order::Paper)
        classes = order::paperOrder(distinct.sets, order::highCostSet(costs, order::thresholdForSize(costs, 3)));
    else if (drawOrder == Order::Greedy)
        classes = order::greedyOrder(transitions);
    else
        classes = order::bestOrder(transitions, {order::greedyOrder(transitions)}).order;
    DrawList out;
    out.reserve(list.size());
    for (int index : order::expandOrder(distinct, classes)) out.push_back(list[std::size_t(index)]);
    return out;
}

Result<OrderCosts> OrderCosts::start(Order order, Backend& backend, int refineEvery) {
    OrderCosts costs;
    if (!traitsOf(order).measuresCosts) return costs;
    Result<std::unique_ptr<StateCostProbe>> probe = StateCostProbe::create(backend);
    if (!probe) return Error{probe.error().message};
    costs.probe_ = std::move(*probe);
    for (int r = 0; r < 5; ++r) costs.running_.add(costs.probe_->round(200, r));
    costs.start_ = costs.costs_ = costs.running_.costsUs();
    costs.refineEvery_ = std::max(refineEvery, 0);
    return costs;
}

bool OrderCosts::refine(int framesDone) {
    if (!probe_ || refineEvery_ <= 0 || framesDone <= 0 || framesDone % refineEvery_ != 0) return false;
    running_.add(probe_->round(100, int(running_.rounds())));
    costs_ = running_.costsUs();
    return true;
}

std::optional<StateCosts> OrderCosts::report() const {
    if (!probe_) return std::nullopt;
    return StateCosts{std::vector<std::string>(kStateKindNames.begin(), kStateKindNames.end()), start_, costs_,
                      running_.rounds(), refineEvery_};
}


}  // namespace frugal
