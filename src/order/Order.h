// Draw orders that make costly render-state changes rare (paper 004, Kim 2009), and the baselines
// they are judged against. Pure: no GL, no scene; a later plan maps its draws' states onto these types.
//
// Conventions:
// - A render-state set (RSS) holds one value per state kind; 0 means the RSS does not set that kind.
//   "Holds the same state" means the same non-zero value. The paper's simulation uses values 0/1.
// - Costs C(s) are per state kind, non-negative. A transition's cost depends on a CostRule (below);
//   the paper does not say when a cost is paid, so the rule is a parameter and the reports show all three.
// - An order is a permutation of the RSS indices. Its cost is the path's: from the empty state (every
//   kind unset) to the first RSS, then RSS to RSS; nothing is paid after the last one.
// - Every order breaks ties by the lower index, so each is a deterministic function of its input.
#pragma once

#include <cstdint>
#include <vector>

namespace frugal::order {

using Rss = std::vector<std::uint32_t>;  // one value per state kind, 0 = not set

enum class CostRule {
    SetNotHeld,           // C(s) when the next RSS sets s and the previous did not hold that value (the default)
    EverySet,             // C(s) for every state the next RSS sets, held before or not
    SymmetricDifference,  // C(s) whenever kind s's value differs: set, changed or unset
};
const char* costRuleName(CostRule rule);  // "set-not-held", "every-set", "symmetric-difference"

// The cost of going from `previous` to `next` (both sized costs.size(); an empty `previous` is the
// empty state).
double transitionCost(const Rss& previous, const Rss& next, const std::vector<double>& costs, CostRule rule);

// The asymmetric costs of n RSSs and of the empty start: at(i, j) is RSS i → RSS j, start(j) the
// empty state → RSS j.
class Transitions {
public:
    Transitions(const std::vector<Rss>& sets, const std::vector<double>& costs, CostRule rule);
    int size() const { return n_; }
    double at(int from, int to) const { return cost_[std::size_t(from) * std::size_t(n_ + 1) + std::size_t(to)]; }
    double start(int to) const { return at(n_, to); }
    // The path's cost: start → order[0] → … → order.back().
    double pathCost(const std::vector<int>& order) const;

private:
    int n_;
    std::vector<double> cost_;  // (n + 1)², row n = the empty start
};

// ---- the paper's sort -----------------------------------------------------------------------------

// Definition 4.1: the states sorted by cost, descending (ties: lower index first), taken until the
// running sum first exceeds `threshold` (all of them if it never does). Returns their indices, costliest first.
std::vector<int> highCostSet(const std::vector<double>& costs, double threshold);
// The threshold t that gives |HCS| = size: the sum of the size − 1 largest costs (the running sum passes
// it at the size-th state when that state costs more than 0).
double thresholdForSize(const std::vector<double>& costs, int size);
// Table 5's binary id: one bit per HCS member that the RSS sets, hcs[0] in the most significant bit.
std::uint32_t paperId(const Rss& rss, const std::vector<int>& hcs);
// RSSs sorted by id, descending; stable (equal ids keep submission order).
std::vector<int> paperOrder(const std::vector<Rss>& sets, const std::vector<int>& hcs);

// ---- baselines ------------------------------------------------------------------------------------

std::vector<int> submitOrder(int n);
// bgfx's fixed sort key: kinds in index order, ascending values, lexicographic; it knows no costs. Stable.
std::vector<int> keyOrder(const std::vector<Rss>& sets);
// Nearest neighbour from the empty state: always the cheapest transition to an RSS not yet drawn.
std::vector<int> greedyOrder(const Transitions& t);
// An online look-ahead buffer of `window` RSSs filled in submission order: draw the one whose
// transition from the current state is cheapest, refill, repeat. window 1 is submission order.
std::vector<int> lookaheadOrder(const Transitions& t, int window = 4);

// ---- the optimum and its bounds -------------------------------------------------------------------

constexpr int kHeldKarpLimit = 16;  // 2^16 · 16 path ends: 9 MB and some tens of ms

// The exact optimum by Held–Karp (dynamic programming over subsets), a path from the empty state
// ending anywhere. Requires t.size() <= kHeldKarpLimit.
std::vector<int> heldKarpOrder(const Transitions& t);
// Local search from `order`: 2-opt (reverse a run, paid at the asymmetric costs both ways) and or-opt
// (move a run of 1–3 RSSs elsewhere, as it is or reversed), first improvement, until a whole pass
// improves nothing.
std::vector<int> improveOrder(const Transitions& t, std::vector<int> order);

struct BestOrder {
    std::vector<int> order;
    double cost = 0.0;
    bool exact = false;  // Held–Karp's optimum (n <= kHeldKarpLimit); else local search's result
};
// improveOrder from greedy and from each of `starts`, the cheapest result. Passing the other methods'
// orders as `starts` makes it <= each of them.
BestOrder searchOrder(const Transitions& t, const std::vector<std::vector<int>>& starts = {});
// Held–Karp for n <= kHeldKarpLimit, searchOrder above it.
BestOrder bestOrder(const Transitions& t, const std::vector<std::vector<int>>& starts = {});

// Identical RSSs. Under SetNotHeld and SymmetricDifference the costs obey the triangle inequality and
// an RSS's copy costs nothing after it, so taking a copy out of an order never raises its cost and putting
// it back right after its twin costs nothing: some optimal order draws copies together, and the optimum
// and the bounds of the distinct RSSs are those of all of them. (Under EverySet every order costs the same.)
struct DistinctSets {
    std::vector<Rss> sets;      // in order of first appearance
    std::vector<int> classOf;   // per RSS, its index in `sets`
};
DistinctSets distinctSets(const std::vector<Rss>& sets);
// An order of all RSSs as an order of their classes (each where its first RSS comes).
std::vector<int> classOrder(const DistinctSets& distinct, const std::vector<int>& order);
// An order of the classes as an order of all RSSs, each class's RSSs together in submission order.
std::vector<int> expandOrder(const DistinctSets& distinct, const std::vector<int>& classes);

// Lower bounds on every order's cost. incomingBound: each RSS's cheapest transition in (from another
// RSS or the start), summed. assignmentBound: the assignment relaxation (each RSS gets one predecessor,
// each RSS and the start precede at most one; cycles allowed), solved exactly by the Hungarian method
// in O(n³); it is never below incomingBound.
double incomingBound(const Transitions& t);
double assignmentBound(const Transitions& t);

}  // namespace frugal::order
