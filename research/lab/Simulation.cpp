#include "lab/Simulation.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace frugal::order {

Instance paperInstance(std::mt19937_64& rng, int rssCount, int states, int costly, double probability) {
    Instance instance;
    std::uniform_int_distribution<int> cost(1, 10);
    for (int s = 0; s < states; ++s) instance.costs.push_back(double(cost(rng) + (s < costly ? 20 : 0)));
    std::shuffle(instance.costs.begin(), instance.costs.end(), rng);
    std::bernoulli_distribution sets(probability);
    for (int i = 0; i < rssCount; ++i) {
        Rss rss(std::size_t(states), 0);
        for (std::uint32_t& value : rss) value = sets(rng) ? 1u : 0u;
        instance.sets.push_back(std::move(rss));
    }
    return instance;
}

const char* methodName(Method method) {
    switch (method) {
        case Method::Submit:
            return "submit";
        case Method::Paper:
            return "paper";
        case Method::Key:
            return "key";
        case Method::Greedy:
            return "greedy";
        case Method::Lookahead:
            return "lookahead";
        case Method::Best:
            return "best";
    }
    return "?";
}

InstanceCosts runMethods(const Instance& instance, CostRule rule, int hcsSize, int window, bool exactWhenSmall) {
    const Transitions t(instance.sets, instance.costs, rule);
    const std::vector<int> hcs = highCostSet(instance.costs, thresholdForSize(instance.costs, hcsSize));
    const std::vector<std::vector<int>> others{submitOrder(t.size()), paperOrder(instance.sets, hcs),
                                               keyOrder(instance.sets), greedyOrder(t), lookaheadOrder(t, window)};
    InstanceCosts out;
    std::size_t cheapest = 0;
    for (std::size_t m = 0; m < others.size(); ++m) {
        out.cost[m] = t.pathCost(others[m]);
        if (out.cost[m] < out.cost[cheapest]) cheapest = m;
    }
    const std::size_t best = others.size();
    if (rule == CostRule::EverySet) {
        // Every RSS pays for all it sets whatever comes before: every order costs the same.
        out.cost[best] = out.cost[0];
        out.bound = out.cost[0];
        out.exact = true;
        return out;
    }
    // The optimum of the distinct RSSs is that of all (DistinctSets): 5 kinds give at most 32 of them.
    const DistinctSets distinct = distinctSets(instance.sets);
    const Transitions d(distinct.sets, instance.costs, rule);
    const std::vector<std::vector<int>> starts{classOrder(distinct, others[cheapest])};
    const BestOrder found = exactWhenSmall ? bestOrder(d, starts) : searchOrder(d, starts);
    out.cost[best] = t.pathCost(expandOrder(distinct, found.order));
    out.exact = found.exact;
    out.bound = std::max(incomingBound(d), assignmentBound(d));
    return out;
}

MeanCi meanCi(const std::vector<double>& values) {
    MeanCi out;
    if (values.empty()) return out;
    double sum = 0.0;
    for (double v : values) sum += v;
    out.mean = sum / double(values.size());
    if (values.size() < 2) return out;
    double squares = 0.0;
    for (double v : values) squares += (v - out.mean) * (v - out.mean);
    const double sd = std::sqrt(squares / double(values.size() - 1));
    out.ci95 = 1.96 * sd / std::sqrt(double(values.size()));
    return out;
}

}  // namespace frugal::order
