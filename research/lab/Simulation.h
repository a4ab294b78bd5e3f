// The simulation of paper 004, section 4.2: random render-state sets with a few costly states, every
// order of order/Order.h run on the same instance. Reproducible: an instance is a function of the
// generator's state, and the generator is std::mt19937_64 (libstdc++'s distributions).
#pragma once

#include <array>
#include <random>
#include <vector>

#include "renderer/Research.h"

namespace frugal::order {

// One simulated frame: costs per state kind and the RSSs in submission order.
struct Instance {
    std::vector<double> costs;
    std::vector<Rss> sets;
};

// The paper's parameters: `costly` kinds cost a uniform integer 21–30 (1–10 plus 20), the others
// 1–10; which kinds are costly is random, so a cost-blind key does not sort by cost by accident. Each
// RSS sets each kind (value 1) with probability `probability`, independently; an RSS may set none.
Instance paperInstance(std::mt19937_64& rng, int rssCount, int states, int costly = 3, double probability = 0.5);

enum class Method { Submit, Paper, Key, Greedy, Lookahead, Best };
constexpr std::array<Method, 6> kMethods{Method::Submit, Method::Paper,     Method::Key,
                                         Method::Greedy, Method::Lookahead, Method::Best};
const char* methodName(Method method);  // "submit", "paper", "key", "greedy", "lookahead", "best"

// Every method's total change cost on one instance under `rule`, and the lower bound.
struct InstanceCosts {
    std::array<double, kMethods.size()> cost{};  // indexed like kMethods
    double bound = 0.0;                          // max(incomingBound, assignmentBound) of the distinct RSSs
    bool exact = false;                          // best is the optimum (Held–Karp, or EverySet)
};
// The paper's sort with |HCS| = hcsSize (t = thresholdForSize), lookahead with `window`; best starts its
// local search from greedy and from the cheapest of the other orders, so it is never above any of them;
// it and the bound work on the distinct RSSs (DistinctSets). Under EverySet, best and the bound are the
// one cost every order has.
// With exactWhenSmall false, best searches even when Held–Karp could give the optimum (to measure the search).
InstanceCosts runMethods(const Instance& instance, CostRule rule, int hcsSize = 3, int window = 4,
                         bool exactWhenSmall = true);

// A sample's mean and the half-width of its 95 % confidence interval, 1.96 · sd / √n (sd with n − 1;
// 0 for fewer than two values).
struct MeanCi {
    double mean = 0.0, ci95 = 0.0;
};
MeanCi meanCi(const std::vector<double>& values);

}  // namespace frugal::order
