// The draw orders of paper 004 (src/order/): the cost rules on hand-made sets, the paper's sort and its
// guarantee, every baseline a permutation, Held–Karp against brute force, and best and the bounds
// against every other order.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "lab/Simulation.h"
#include "order/Order.h"

namespace frugal::order {
namespace {

bool isPermutation(std::vector<int> order, int n) {
    std::sort(order.begin(), order.end());
    std::vector<int> expected(static_cast<std::size_t>(n));
    std::iota(expected.begin(), expected.end(), 0);
    return order == expected;
}

// The cheapest of all n! orders.
double bruteForce(const Transitions& t) {
    std::vector<int> order = submitOrder(t.size());
    double best = std::numeric_limits<double>::infinity();
    do {
        best = std::min(best, t.pathCost(order));
    } while (std::next_permutation(order.begin(), order.end()));
    return best;
}

// Random RSSs over `states` kinds with values 0..values, and random costs 1–30.
Instance randomInstance(std::mt19937_64& rng, int n, int states, std::uint32_t values) {
    Instance instance;
    std::uniform_int_distribution<int> cost(1, 30);
    std::uniform_int_distribution<std::uint32_t> value(0, values);
    for (int s = 0; s < states; ++s) instance.costs.push_back(double(cost(rng)));
    for (int i = 0; i < n; ++i) {
        Rss rss(static_cast<std::size_t>(states));
        for (std::uint32_t& v : rss) v = value(rng);
        instance.sets.push_back(rss);
    }
    return instance;
}

constexpr CostRule kRules[] = {CostRule::SetNotHeld, CostRule::EverySet, CostRule::SymmetricDifference};

TEST(OrderTest, TransitionCostFollowsEachRule) {
    const std::vector<double> costs{1, 10, 100, 1000};
    const Rss a{1, 1, 0, 2}, b{1, 0, 1, 3};
    // a → b: kind 0 held, kind 1 unset, kind 2 newly set, kind 3 changed value.
    EXPECT_EQ(transitionCost(a, b, costs, CostRule::SetNotHeld), 100 + 1000);
    EXPECT_EQ(transitionCost(a, b, costs, CostRule::EverySet), 1 + 100 + 1000);
    EXPECT_EQ(transitionCost(a, b, costs, CostRule::SymmetricDifference), 10 + 100 + 1000);
    // From the empty state every rule pays for what the RSS sets.
    for (CostRule rule : kRules) {
        EXPECT_EQ(transitionCost({}, a, costs, rule), 1 + 10 + 1000) << costRuleName(rule);
    }
    EXPECT_EQ(transitionCost(a, a, costs, CostRule::SetNotHeld), 0);
    EXPECT_EQ(transitionCost(a, a, costs, CostRule::SymmetricDifference), 0);
}

TEST(OrderTest, PathCostStartsFromTheEmptyState) {
    const std::vector<double> costs{5, 7};
    const std::vector<Rss> sets{{1, 0}, {1, 1}, {0, 1}};
    const Transitions t(sets, costs, CostRule::SetNotHeld);
    EXPECT_EQ(t.pathCost({0, 1, 2}), 5 + 7 + 0);
    EXPECT_EQ(t.pathCost({2, 0, 1}), 7 + 5 + 7);
    EXPECT_EQ(t.pathCost({}), 0);
}

TEST(OrderTest, HighCostSetStopsWhenTheRunningSumFirstPassesTheThreshold) {
    const std::vector<double> costs{3, 25, 8, 22, 30};
    EXPECT_EQ(highCostSet(costs, 40), (std::vector<int>{4, 1}));
    EXPECT_EQ(highCostSet(costs, 55), (std::vector<int>{4, 1, 3}));
    EXPECT_EQ(thresholdForSize(costs, 3), 55);
    EXPECT_EQ(highCostSet(costs, thresholdForSize(costs, 3)).size(), 3u);
    EXPECT_EQ(highCostSet(costs, 1000).size(), 5u);
}

TEST(OrderTest, PaperIdPutsTheCostliestStateInTheTopBit) {
    const std::vector<int> hcs{2, 0, 1};
    EXPECT_EQ(paperId({1, 1, 1, 1}, hcs), 7u);
    EXPECT_EQ(paperId({0, 0, 1, 0}, hcs), 4u);
    EXPECT_EQ(paperId({1, 0, 0, 1}, hcs), 2u);
    EXPECT_EQ(paperId({0, 1, 0, 1}, hcs), 1u);
    // The paper's example: ids 111, 100, 101, 110, 001, 010 sort to 111, 110, 101, 100, 010, 001.
    const std::vector<Rss> sets{{1, 1, 1}, {1, 0, 0}, {1, 0, 1}, {1, 1, 0}, {0, 0, 1}, {0, 1, 0}};
    EXPECT_EQ(paperOrder(sets, {0, 1, 2}), (std::vector<int>{0, 3, 2, 1, 5, 4}));
}

TEST(OrderTest, PaperSortChangesTheCostliestStateAtMostTwice) {
    std::mt19937_64 rng(7);
    for (int trial = 0; trial < 50; ++trial) {
        const Instance in = paperInstance(rng, 60, 6);
        const std::vector<int> hcs = highCostSet(in.costs, thresholdForSize(in.costs, 3));
        const std::vector<int> order = paperOrder(in.sets, hcs);
        const std::size_t top = std::size_t(hcs[0]);
        int changes = 0;
        std::uint32_t held = 0;  // the empty state
        for (int i : order) {
            changes += in.sets[std::size_t(i)][top] != held;
            held = in.sets[std::size_t(i)][top];
        }
        EXPECT_LE(changes, 2);
    }
}

TEST(OrderTest, KeySortsLexicographicallyAndStably) {
    const std::vector<Rss> sets{{1, 0}, {0, 2}, {1, 0}, {0, 1}};
    EXPECT_EQ(keyOrder(sets), (std::vector<int>{3, 1, 0, 2}));
}

TEST(OrderTest, GreedyAndLookaheadOnAHandMadeCase) {
    // Kind 0 costs 100, kind 1 costs 1. Submission alternates kind 0 on and off.
    const std::vector<double> costs{100, 1};
    const std::vector<Rss> sets{{1, 0}, {0, 1}, {1, 1}, {0, 0}, {1, 0}};
    const Transitions t(sets, costs, CostRule::SymmetricDifference);
    EXPECT_EQ(greedyOrder(t), (std::vector<int>{3, 1, 2, 0, 4}));  // 0 + 1 + 100 + 1 + 0
    EXPECT_EQ(t.pathCost(greedyOrder(t)), 102);
    EXPECT_EQ(lookaheadOrder(t, 1), submitOrder(5));
    // Window 2: {0,1} → 1 (cost 1); {0,2} → 2 (100); {0,3} → 0 (1); {3,4} → 4 (0); then 3 (100).
    EXPECT_EQ(lookaheadOrder(t, 2), (std::vector<int>{1, 2, 0, 4, 3}));
}

TEST(OrderTest, EveryOrderIsAPermutation) {
    std::mt19937_64 rng(11);
    for (int n : {0, 1, 2, 7, 16, 17, 40}) {
        const Instance in = randomInstance(rng, n, 5, 2);
        const Transitions t(in.sets, in.costs, CostRule::SetNotHeld);
        const std::vector<int> hcs = highCostSet(in.costs, thresholdForSize(in.costs, 3));
        const std::vector<std::vector<int>> orders{submitOrder(n),     paperOrder(in.sets, hcs),   keyOrder(in.sets),
                                                   greedyOrder(t),     lookaheadOrder(t, 4),        bestOrder(t).order,
                                                   searchOrder(t).order, improveOrder(t, submitOrder(n))};
        for (const std::vector<int>& order : orders) {
            EXPECT_TRUE(isPermutation(order, n)) << "n " << n;
        }
    }
}

TEST(OrderTest, HeldKarpEqualsBruteForce) {
    std::mt19937_64 rng(3);
    for (int trial = 0; trial < 40; ++trial) {
        const int n = 1 + trial % 8;
        const Instance in = randomInstance(rng, n, 4, trial % 2 == 0 ? 1 : 3);
        for (CostRule rule : kRules) {
            const Transitions t(in.sets, in.costs, rule);
            const std::vector<int> order = heldKarpOrder(t);
            ASSERT_TRUE(isPermutation(order, n));
            EXPECT_DOUBLE_EQ(t.pathCost(order), bruteForce(t)) << "trial " << trial << " " << costRuleName(rule);
        }
    }
}

TEST(OrderTest, BestIsNeverAboveAnotherMethodAndTheBoundsNeverAboveBest) {
    std::mt19937_64 rng(5);
    for (int n : {8, 16, 30, 60}) {
        for (int trial = 0; trial < 5; ++trial) {
            const Instance in = paperInstance(rng, n, trial % 2 == 0 ? 5 : 12);
            for (CostRule rule : {CostRule::SetNotHeld, CostRule::SymmetricDifference}) {
                SCOPED_TRACE(testing::Message() << "n " << n << " trial " << trial << " " << costRuleName(rule));
                const InstanceCosts costs = runMethods(in, rule);
                const double best = costs.cost.back();
                for (double c : costs.cost) EXPECT_LE(best, c + 1e-9);
                EXPECT_LE(costs.bound, best + 1e-9);
                const Transitions t(in.sets, in.costs, rule);
                EXPECT_LE(incomingBound(t), assignmentBound(t) + 1e-9);
                EXPECT_LE(assignmentBound(t), t.pathCost(bestOrder(t, {submitOrder(n)}).order) + 1e-9);
                if (n <= kHeldKarpLimit) {
                    EXPECT_TRUE(costs.exact);
                    EXPECT_LE(t.pathCost(heldKarpOrder(t)), t.pathCost(searchOrder(t).order) + 1e-9);
                }
            }
        }
    }
}

TEST(OrderTest, DistinctSetsKeepTheOptimum) {
    // Copies drawn together cost nothing, so the distinct RSSs' optimum is everyone's.
    std::mt19937_64 rng(9);
    for (int trial = 0; trial < 20; ++trial) {
        const Instance in = paperInstance(rng, 8, 2);
        const DistinctSets distinct = distinctSets(in.sets);
        ASSERT_EQ(distinct.classOf.size(), in.sets.size());
        for (CostRule rule : {CostRule::SetNotHeld, CostRule::SymmetricDifference}) {
            const Transitions all(in.sets, in.costs, rule), d(distinct.sets, in.costs, rule);
            const std::vector<int> expanded = expandOrder(distinct, heldKarpOrder(d));
            ASSERT_TRUE(isPermutation(expanded, 8));
            EXPECT_DOUBLE_EQ(all.pathCost(expanded), bruteForce(all));
            EXPECT_EQ(classOrder(distinct, expanded), heldKarpOrder(d));
        }
    }
}

TEST(OrderTest, EverySetCostsTheSameInEveryOrder) {
    std::mt19937_64 rng(13);
    const Instance in = paperInstance(rng, 6, 4);
    const Transitions t(in.sets, in.costs, CostRule::EverySet);
    std::vector<int> order = submitOrder(6);
    const double first = t.pathCost(order);
    while (std::next_permutation(order.begin(), order.end())) ASSERT_DOUBLE_EQ(t.pathCost(order), first);
}

TEST(OrderTest, MeanCiIsTheNormalInterval) {
    const MeanCi m = meanCi({1, 2, 3, 4});
    EXPECT_DOUBLE_EQ(m.mean, 2.5);
    EXPECT_NEAR(m.ci95, 1.96 * std::sqrt(5.0 / 3.0) / 2.0, 1e-12);
    EXPECT_EQ(meanCi({7}).ci95, 0.0);
}

TEST(OrderTest, PaperInstancesFollowThePapersParameters) {
    std::mt19937_64 rng(1);
    for (int trial = 0; trial < 20; ++trial) {
        const Instance in = paperInstance(rng, 40, 10);
        ASSERT_EQ(in.costs.size(), 10u);
        ASSERT_EQ(in.sets.size(), 40u);
        const auto costly = std::count_if(in.costs.begin(), in.costs.end(), [](double c) { return c >= 21 && c <= 30; });
        const auto cheap = std::count_if(in.costs.begin(), in.costs.end(), [](double c) { return c >= 1 && c <= 10; });
        EXPECT_EQ(costly, 3);
        EXPECT_EQ(cheap, 7);
    }
    std::mt19937_64 a(42), b(42);
    EXPECT_EQ(paperInstance(a, 20, 5).sets, paperInstance(b, 20, 5).sets);
}

}  // namespace
}  // namespace frugal::order
