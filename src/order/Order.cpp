#include "order/Order.h"

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <limits>
#include <map>
#include <numeric>

namespace frugal::order {

namespace {

constexpr int kStart = -1;  // the empty state before the first RSS
constexpr int kEnd = -1;    // after the last RSS: nothing is paid
// An improvement counts only above this, so that rounding in the prefix sums cannot cycle local search.
constexpr double kEpsilon = 1e-9;

// The transition cost with the start and the end as kStart/kEnd.
double edge(const Transitions& t, int from, int to) {
    if (to == kEnd) return 0.0;
    return from == kStart ? t.start(to) : t.at(from, to);
}

}  // namespace

const char* costRuleName(CostRule rule) {
    switch (rule) {
    case CostRule::SetNotHeld: return "set-not-held";
    case CostRule::EverySet: return "every-set";
    case CostRule::SymmetricDifference: return "symmetric-difference";
    }
    return "?";
}

double transitionCost(const Rss& previous, const Rss& next, const std::vector<double>& costs, CostRule rule) {
    double sum = 0.0;
    for (std::size_t s = 0; s < costs.size(); ++s) {
        const std::uint32_t before = previous.empty() ? 0u : previous[s];
        const std::uint32_t after = next[s];
        bool pays = false;
        switch (rule) {
        case CostRule::SetNotHeld: pays = after != 0 && before != after; break;
        case CostRule::EverySet: pays = after != 0; break;
        case CostRule::SymmetricDifference: pays = before != after; break;
        }
        if (pays) sum += costs[s];
    }
    return sum;
}

Transitions::Transitions(const std::vector<Rss>& sets, const std::vector<double>& costs, CostRule rule)
    : n_(int(sets.size())), cost_(std::size_t(n_ + 1) * std::size_t(n_ + 1), 0.0) {
    const Rss empty;
    for (int from = 0; from <= n_; ++from)
        for (int to = 0; to < n_; ++to)
            cost_[std::size_t(from) * std::size_t(n_ + 1) + std::size_t(to)] =
                transitionCost(from == n_ ? empty : sets[std::size_t(from)], sets[std::size_t(to)], costs, rule);
}

double Transitions::pathCost(const std::vector<int>& order) const {
    double sum = 0.0;
    int previous = kStart;
    for (int next : order) {
        sum += edge(*this, previous, next);
        previous = next;
    }
    return sum;
}

// ---- the paper's sort -----------------------------------------------------------------------------

namespace {

// State indices by cost, descending; ties keep the lower index first.
std::vector<int> byCostDescending(const std::vector<double>& costs) {
    std::vector<int> states(costs.size());
    std::iota(states.begin(), states.end(), 0);
    std::stable_sort(states.begin(), states.end(), [&](int a, int b) { return costs[std::size_t(a)] > costs[std::size_t(b)]; });
    return states;
}

}  // namespace

std::vector<int> highCostSet(const std::vector<double>& costs, double threshold) {
    std::vector<int> hcs;
    double sum = 0.0;
    for (int s : byCostDescending(costs)) {
        hcs.push_back(s);
        sum += costs[std::size_t(s)];
        if (sum > threshold) break;
    }
    return hcs;
}

double thresholdForSize(const std::vector<double>& costs, int size) {
    const std::vector<int> states = byCostDescending(costs);
    double sum = 0.0;
    for (int i = 0; i + 1 < size && i < int(states.size()); ++i) sum += costs[std::size_t(states[std::size_t(i)])];
    return sum;
}

std::uint32_t paperId(const Rss& rss, const std::vector<int>& hcs) {
    std::uint32_t id = 0;
    for (int s : hcs) id = (id << 1) | (rss[std::size_t(s)] != 0 ? 1u : 0u);
    return id;
}

std::vector<int> paperOrder(const std::vector<Rss>& sets, const std::vector<int>& hcs) {
    std::vector<std::uint32_t> ids;
    for (const Rss& rss : sets) ids.push_back(paperId(rss, hcs));
    std::vector<int> order = submitOrder(int(sets.size()));
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return ids[std::size_t(a)] > ids[std::size_t(b)]; });
    return order;
}

// ---- baselines ------------------------------------------------------------------------------------

std::vector<int> submitOrder(int n) {
    std::vector<int> order(std::size_t(std::max(n, 0)));
    std::iota(order.begin(), order.end(), 0);
    return order;
}

std::vector<int> keyOrder(const std::vector<Rss>& sets) {
    std::vector<int> order = submitOrder(int(sets.size()));
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return sets[std::size_t(a)] < sets[std::size_t(b)]; });
    return order;
}

std::vector<int> greedyOrder(const Transitions& t) {
    const int n = t.size();
    std::vector<bool> drawn(std::size_t(n), false);
    std::vector<int> order;
    int current = kStart;
    for (int step = 0; step < n; ++step) {
        int pick = -1;
        for (int j = 0; j < n; ++j)
            if (!drawn[std::size_t(j)] && (pick < 0 || edge(t, current, j) < edge(t, current, pick))) pick = j;
        drawn[std::size_t(pick)] = true;
        order.push_back(pick);
        current = pick;
    }
    return order;
}

std::vector<int> lookaheadOrder(const Transitions& t, int window) {
    assert(window >= 1);
    const int n = t.size();
    std::vector<int> buffer;  // in submission order, so a tie goes to the earliest submitted
    std::vector<int> order;
    int next = 0, current = kStart;
    while (int(order.size()) < n) {
        while (int(buffer.size()) < window && next < n) buffer.push_back(next++);
        std::size_t pick = 0;
        for (std::size_t k = 1; k < buffer.size(); ++k)
            if (edge(t, current, buffer[k]) < edge(t, current, buffer[pick])) pick = k;
        current = buffer[pick];
        order.push_back(current);
        buffer.erase(buffer.begin() + std::ptrdiff_t(pick));
    }
    return order;
}

// ---- the optimum and its bounds -------------------------------------------------------------------

std::vector<int> heldKarpOrder(const Transitions& t) {
    const int n = t.size();
    assert(n <= kHeldKarpLimit);
    if (n == 0) return {};
    const std::size_t masks = std::size_t(1) << n, width = std::size_t(n);
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> step(width * width);  // RSS → RSS, contiguous
    for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k) step[std::size_t(j) * width + std::size_t(k)] = t.at(j, k);
    // best[mask · n + j]: the cheapest path from the start through exactly `mask`, ending at j.
    std::vector<double> best(masks * width, inf);
    std::vector<std::int8_t> before(masks * width, -1);
    for (int j = 0; j < n; ++j) best[(std::size_t(1) << j) * width + std::size_t(j)] = t.start(j);
    // Pulled rather than pushed: each entry reads one earlier row of n values, which stays in cache.
    for (std::size_t mask = 1; mask < masks; ++mask)
        for (int k = 0; k < n; ++k) {
            const std::size_t rest = mask & ~(std::size_t(1) << k);
            if (!(mask >> k & 1u) || rest == 0) continue;
            const double* from = &best[rest * width];
            double cheapest = inf;
            int previous = -1;
            for (int j = 0; j < n; ++j) {
                if (!(rest >> j & 1u)) continue;
                const double cost = from[j] + step[std::size_t(j) * width + std::size_t(k)];
                if (cost < cheapest) {
                    cheapest = cost;
                    previous = j;
                }
            }
            best[mask * width + std::size_t(k)] = cheapest;
            before[mask * width + std::size_t(k)] = std::int8_t(previous);
        }
    std::size_t mask = masks - 1;
    int last = 0;
    for (int j = 1; j < n; ++j)
        if (best[mask * width + std::size_t(j)] < best[mask * width + std::size_t(last)]) last = j;
    std::vector<int> order;
    while (last >= 0) {
        order.push_back(last);
        const int previous = before[mask * width + std::size_t(last)];
        mask &= ~(std::size_t(1) << last);
        last = previous;
    }
    std::reverse(order.begin(), order.end());
    return order;
}

std::vector<int> improveOrder(const Transitions& t, std::vector<int> order) {
    const int n = int(order.size());
    const auto at = [&](int position) { return position < 0 ? kStart : position >= n ? kEnd : order[std::size_t(position)]; };
    // forward[k], backward[k]: the costs along order[0..k] read forwards, and each step read backwards.
    std::vector<double> forward(std::size_t(n) + 1, 0.0), backward(std::size_t(n) + 1, 0.0);
    const auto prefixes = [&] {
        for (int k = 0; k + 1 < n; ++k) {
            forward[std::size_t(k) + 1] = forward[std::size_t(k)] + t.at(order[std::size_t(k)], order[std::size_t(k) + 1]);
            backward[std::size_t(k) + 1] = backward[std::size_t(k)] + t.at(order[std::size_t(k) + 1], order[std::size_t(k)]);
        }
    };
    prefixes();
    bool improved = true;
    while (improved) {
        improved = false;
        // 2-opt: reverse order[i..j]; the run inside is paid in the other direction.
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j) {
                const int before = at(i - 1), after = at(j + 1), first = order[std::size_t(i)], last = order[std::size_t(j)];
                const double old = edge(t, before, first) + (forward[std::size_t(j)] - forward[std::size_t(i)]) + edge(t, last, after);
                const double now = edge(t, before, last) + (backward[std::size_t(j)] - backward[std::size_t(i)]) + edge(t, first, after);
                if (now < old - kEpsilon) {
                    std::reverse(order.begin() + i, order.begin() + j + 1);
                    prefixes();
                    improved = true;
                }
            }
        // or-opt: move order[i..i+len-1] into the gap before position g, as it is or reversed.
        for (int len = 1; len <= 3; ++len)
            for (int i = 0; i + len <= n; ++i)
                for (int g = 0; g <= n; ++g) {
                    if (g >= i && g <= i + len) continue;  // the run's own place
                    const int before = at(i - 1), after = at(i + len), first = order[std::size_t(i)],
                              last = order[std::size_t(i + len - 1)];
                    const int left = at(g - 1), right = at(g);
                    const double inside = forward[std::size_t(i + len - 1)] - forward[std::size_t(i)];
                    const double insideReversed = backward[std::size_t(i + len - 1)] - backward[std::size_t(i)];
                    const double removed = edge(t, before, first) + inside + edge(t, last, after) - edge(t, before, after);
                    const double kept = edge(t, left, first) + inside + edge(t, last, right) - edge(t, left, right);
                    const double flipped = edge(t, left, last) + insideReversed + edge(t, first, right) - edge(t, left, right);
                    const bool reverse = flipped < kept;
                    if (std::min(kept, flipped) < removed - kEpsilon) {
                        std::vector<int> run(order.begin() + i, order.begin() + i + len);
                        if (reverse) std::reverse(run.begin(), run.end());
                        order.erase(order.begin() + i, order.begin() + i + len);
                        const int gap = g > i ? g - len : g;
                        order.insert(order.begin() + gap, run.begin(), run.end());
                        prefixes();
                        improved = true;
                    }
                }
    }
    return order;
}

BestOrder searchOrder(const Transitions& t, const std::vector<std::vector<int>>& starts) {
    BestOrder best;
    std::vector<std::vector<int>> from{greedyOrder(t)};
    from.insert(from.end(), starts.begin(), starts.end());
    for (const std::vector<int>& start : from) {
        std::vector<int> order = improveOrder(t, start);
        const double cost = t.pathCost(order);
        if (best.order.empty() || cost < best.cost) {
            best.order = std::move(order);
            best.cost = cost;
        }
    }
    return best;
}

BestOrder bestOrder(const Transitions& t, const std::vector<std::vector<int>>& starts) {
    if (t.size() > kHeldKarpLimit) return searchOrder(t, starts);
    BestOrder best;
    best.order = heldKarpOrder(t);
    best.cost = t.pathCost(best.order);
    best.exact = true;
    return best;
}

DistinctSets distinctSets(const std::vector<Rss>& sets) {
    DistinctSets out;
    std::map<Rss, int> seen;
    for (const Rss& rss : sets) {
        const auto [it, added] = seen.emplace(rss, int(out.sets.size()));
        if (added) out.sets.push_back(rss);
        out.classOf.push_back(it->second);
    }
    return out;
}

std::vector<int> classOrder(const DistinctSets& distinct, const std::vector<int>& order) {
    std::vector<bool> placed(distinct.sets.size(), false);
    std::vector<int> classes;
    for (int i : order) {
        const int c = distinct.classOf[std::size_t(i)];
        if (!placed[std::size_t(c)]) classes.push_back(c);
        placed[std::size_t(c)] = true;
    }
    return classes;
}

std::vector<int> expandOrder(const DistinctSets& distinct, const std::vector<int>& classes) {
    std::vector<std::vector<int>> members(distinct.sets.size());
    for (std::size_t i = 0; i < distinct.classOf.size(); ++i) members[std::size_t(distinct.classOf[i])].push_back(int(i));
    std::vector<int> order;
    for (int c : classes) order.insert(order.end(), members[std::size_t(c)].begin(), members[std::size_t(c)].end());
    return order;
}

double incomingBound(const Transitions& t) {
    double sum = 0.0;
    for (int j = 0; j < t.size(); ++j) {
        double cheapest = t.start(j);
        for (int i = 0; i < t.size(); ++i)
            if (i != j) cheapest = std::min(cheapest, t.at(i, j));
        sum += cheapest;
    }
    return sum;
}

double assignmentBound(const Transitions& t) {
    // Rows: RSS 0..n-1, then the start; columns: RSS 0..n-1, then the end. A path is an assignment
    // (every row and column used once), so the cheapest assignment is at most the cheapest path.
    const int n = t.size();
    if (n == 0) return 0.0;
    const int m = n + 1;
    double largest = 0.0;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j < n; ++j) largest = std::max(largest, t.at(i, j));
    // Forbidden pairs (RSS → itself, start → end) cost more than any whole assignment of allowed pairs,
    // and stay finite so that the potentials keep their precision.
    const double forbidden = (largest + 1.0) * double(m + 1);
    const auto cost = [&](int row, int col) {  // 0-based
        if (col == n) return row == n ? forbidden : 0.0;
        if (row == col) return forbidden;
        return t.at(row, col);
    };
    // The Hungarian method with potentials (1-based, column 0 a sentinel), O(m³).
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> u(std::size_t(m) + 1, 0.0), v(std::size_t(m) + 1, 0.0);
    std::vector<int> rowOf(std::size_t(m) + 1, 0), way(std::size_t(m) + 1, 0);
    for (int row = 1; row <= m; ++row) {
        rowOf[0] = row;
        int col0 = 0;
        std::vector<double> slack(std::size_t(m) + 1, inf);
        std::vector<bool> used(std::size_t(m) + 1, false);
        do {
            used[std::size_t(col0)] = true;
            const int row0 = rowOf[std::size_t(col0)];
            double delta = inf;
            int col1 = 0;
            for (int col = 1; col <= m; ++col) {
                if (used[std::size_t(col)]) continue;
                const double reduced = cost(row0 - 1, col - 1) - u[std::size_t(row0)] - v[std::size_t(col)];
                if (reduced < slack[std::size_t(col)]) {
                    slack[std::size_t(col)] = reduced;
                    way[std::size_t(col)] = col0;
                }
                if (slack[std::size_t(col)] < delta) {
                    delta = slack[std::size_t(col)];
                    col1 = col;
                }
            }
            for (int col = 0; col <= m; ++col) {
                if (used[std::size_t(col)]) {
                    u[std::size_t(rowOf[std::size_t(col)])] += delta;
                    v[std::size_t(col)] -= delta;
                } else {
                    slack[std::size_t(col)] -= delta;
                }
            }
            col0 = col1;
        } while (rowOf[std::size_t(col0)] != 0);
        do {
            const int col1 = way[std::size_t(col0)];
            rowOf[std::size_t(col0)] = rowOf[std::size_t(col1)];
            col0 = col1;
        } while (col0 != 0);
    }
    double sum = 0.0;
    for (int col = 1; col <= m; ++col) sum += cost(rowOf[std::size_t(col)] - 1, col - 1);
    return sum;
}

}  // namespace frugal::order
