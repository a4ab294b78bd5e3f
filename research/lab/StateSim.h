// `frugal-lab state-sim`'s tables: paper 004's simulation (Kim, "Rendering States Changing Costs
// Reducing Technique for Real-time 3D Graphics", 2009, section 4.2), Tables 6 and 7 reproduced with
// every draw order of order/Order.h on the same random instances (lab/Simulation.h), each cell a
// mean with its 95 % confidence interval beside the paper's single figures. The paper does not say
// when a state's cost is paid: the tables use set-not-held (the rule whose unsorted figures match
// the paper's), and the other two rules are run on the same instances. A check at 16 RSSs, where
// Held–Karp gives the optimum, measures how far the local search that stands in for the optimum
// above 16 RSSs stays from it.
//
// The paper's parameters throughout: 3 costly states, each RSS setting each state with probability
// 1/2, the paper's sort with |HCS| = 3, a look-ahead window of 4 RSSs.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include <frugal/Result.h>

#include "lab/Simulation.h"

namespace frugal::order {

struct SimSettings {
    int seeds = 100;  // instances per cell (and per check), >= 1: about 10 s on one core at 100
};

// A cell of the paper's Table 6 (5 states, by RSS count) or Table 7 (50 RSSs, by state count), as
// the paper prints it: the total state-change cost of its sorted order and of the not-sorted one,
// in the simulation's units (cheap states cost 1–10, the 3 costly ones 21–30).
struct PaperCell {
    int rssCount, states;
    double sorted, unsorted;
};

// One cell under one rule: each method's mean over the instances, and the lower bound's.
struct SimCell {
    PaperCell paper;
    std::array<MeanCi, kMethods.size()> methods;  // indexed like kMethods
    MeanCi bound;
    int exact = 0;  // instances whose best is the optimum
};

struct SimRuleTables {
    CostRule rule;
    std::vector<SimCell> table6, table7;  // the paper's cells in its order
};

// Best's local search against Held–Karp's optimum, at kSimCheckRss RSSs, set-not-held.
struct OptimumCheck {
    int states = 0, instances = 0;
    MeanCi optimum, search, greedySearch, bound;
    // (found − optimum) / optimum: of best's search (from greedy and the cheapest other order), and of
    // local search from greedy alone.
    double meanGap = 0.0, worstGap = 0.0, greedyMeanGap = 0.0, greedyWorstGap = 0.0;
    int hits = 0;  // instances where best's search found the optimum
};

constexpr int kSimCheckRss = 16;  // the check's RSS count: Held–Karp's optimum is at hand

struct SimReport {
    int seeds = 0;
    std::vector<SimRuleTables> rules;  // set-not-held (the paper's tables), every-set, symmetric-difference
    std::vector<OptimumCheck> checks;  // at 5 and 25 states (the ends of Table 7)
};

// Runs both tables under every rule and the optimum checks. Instances come from std::mt19937_64
// seeded by the table, the cell and the instance's number only: the same seeds give the same report,
// bit for bit. Fails only on seeds < 1: "seeds 0: at least 1 instance per cell" (BadInput,
// Error::aboutSetting). `progress`, when given, gets one line before each cell's instances
// ("table 6: 40 RSSs, 5 states") and each check's ("optimum check: 16 RSSs, 5 states").
Result<SimReport> runSimulation(const SimSettings& settings, const std::function<void(const std::string&)>& progress = {});

// The report's JSON document: the set-not-held tables ("table6", "table7", "lower_bound"), the
// parameters, the other rules' ("alternatives") and "optimum_check" (keys sorted), indented by 2,
// with a final line break.
std::string simJson(const SimReport& report);
// One row per cost rule, table, cell and method, and the bound:
// "rule,table,rss_count,states,method,mean,ci95,paper_sorted,paper_unsorted".
std::string simCsv(const SimReport& report);
// The gnuplot script that draws cost against RSS count (Table 6) and against states (Table 7), per
// method with the paper's columns, from the CSV at `csvPath` into the SVG at `svgPath`.
std::string simGnuplot(const std::string& csvPath, const std::string& svgPath);
// The text `frugal-lab state-sim` prints: both tables with their ratios, the other rules, the checks.
std::string simText(const SimReport& report);

}  // namespace frugal::order
