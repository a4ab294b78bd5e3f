// `frugal state-sim`: the simulation of paper 004 (Kim, "Rendering States Changing Costs Reducing
// Technique for Real-time 3D Graphics", 2009, section 4.2), Tables 6 and 7 reproduced
// with every draw order of src/order/ on the same random instances, each cell a mean with its 95 %
// confidence interval beside the paper's single figures. The paper does not say when a state's cost is
// paid: the tables use set-not-held (the rule whose unsorted figures match the paper's), and the other
// two rules are reported beside it. A check at 16 RSSs, where Held–Karp gives the optimum, measures
// how far the local search that stands in for the optimum above 16 RSSs stays from it.
#include <algorithm>
#include <array>
#include <cstdio>
#include <optional>
#include <ostream>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "app/Options.h"
#include "app/ReportOutputs.h"
#include "lab/Simulation.h"
#include "order/Order.h"

namespace frugal {

const char* stateSimHelp() {
    return R"(usage: frugal state-sim [options]

Paper 004's simulation (Kim 2009, section 4.2): random render-state sets (RSSs), 3 costly states
(cost a uniform integer 21-30) among cheap ones (1-10), each RSS setting each state with probability
1/2. Table 6: 5 states, 40/80/120/160/200 RSSs; Table 7: 50 RSSs, 5/10/15/20/25 states. Each cell is
the mean total state-change cost over --seeds instances with its 95 % confidence interval
(1.96 sd / sqrt(n)), beside the paper's sorted and unsorted figures, for the orders:
  submit     the order generated (the paper's "not-sorted")
  paper      the paper's sort: |HCS| = 3, binary id with the costliest state in the top bit,
             descending
  key        a fixed key as bgfx sorts: states in index order, lexicographic, blind to costs
  greedy     nearest neighbour on the transition costs, from the empty state
  lookahead  a look-ahead buffer of 4 RSSs in submission order, cheapest transition first
  best       the optimum (Held-Karp) for <= 16 distinct RSSs; above, local search (2-opt, or-opt)
             from greedy and from the cheapest other order
and a lower bound (the assignment relaxation). A cost C(s) is paid when an RSS sets state s and the
RSS before did not hold it (set-not-held); the tables under every-set (C(s) for every state set) and
symmetric-difference (C(s) for every state set or unset) follow. Last, at 16 RSSs, best's local
search (and the search from greedy alone) against Held-Karp's optimum. Instances come from
std::mt19937_64 seeded by the table, the cell and the instance's number: the same --seeds gives the
same figures.
)";
}

namespace {

using order::CostRule;
using order::kMethods;
using order::MeanCi;

constexpr int kHcsSize = 3;
constexpr int kCostlyStates = 3;
constexpr int kWindow = 4;
constexpr double kSubsetProbability = 0.5;
constexpr int kDefaultSeeds = 100;
constexpr int kCheckRss = 16;                      // Held–Karp's optimum is at hand
constexpr std::array<int, 2> kCheckStates{5, 25};  // the ends of Table 7
constexpr std::array<CostRule, 3> kRules{CostRule::SetNotHeld, CostRule::EverySet, CostRule::SymmetricDifference};

// A cell of the paper's Table 6 (5 states, by RSS count) or Table 7 (50 RSSs, by state count), as
// the paper prints it: the total state-change cost of its sorted order and of the not-sorted one,
// in the simulation's units (cheap states cost 1–10, the 3 costly ones 21–30).
struct PaperCell {
    int rssCount, states;
    double sorted, unsorted;
};
constexpr std::array<PaperCell, 5> kTable6{{{40, 5, 334, 921}, {80, 5, 553, 1801}, {120, 5, 643, 2694},
                                            {160, 5, 979, 3701}, {200, 5, 1213, 4588}}};
constexpr std::array<PaperCell, 5> kTable7{{{50, 5, 334, 1179}, {50, 10, 672, 1384}, {50, 15, 1097, 1776},
                                            {50, 20, 1352, 2114}, {50, 25, 1685, 2447}}};

struct Cell {
    PaperCell paper;
    std::array<MeanCi, kMethods.size()> methods;
    MeanCi bound;
    int exact = 0;  // instances whose best is the optimum
};

struct RuleTables {
    CostRule rule;
    std::vector<Cell> table6, table7;
};

struct OptimumCheck {
    int states = 0, instances = 0;
    MeanCi optimum, search, greedySearch, bound;
    // (found − optimum) / optimum: of best's search (from greedy and the cheapest other order), and of
    // local search from greedy alone.
    double meanGap = 0.0, worstGap = 0.0, greedyMeanGap = 0.0, greedyWorstGap = 0.0;
    int hits = 0;  // instances where best's search found the optimum
};

struct Report {
    int seeds = kDefaultSeeds;
    std::vector<RuleTables> rules;  // kRules' order
    std::vector<OptimumCheck> checks;
};

// The generator of one instance: a function of the table, the cell and the instance's number only.
std::mt19937_64 instanceRng(int table, const PaperCell& cell, int index) {
    std::seed_seq seed{table, cell.rssCount, cell.states, index};
    return std::mt19937_64(seed);
}

// Every rule's cells of one table, on the same instances.
void runTable(int table, const std::array<PaperCell, 5>& cells, int seeds, Report& report) {
    for (const PaperCell& paper : cells) {
        std::array<std::array<std::vector<double>, kMethods.size()>, kRules.size()> costs;
        std::array<std::vector<double>, kRules.size()> bounds;
        std::array<int, kRules.size()> exact{};
        for (int i = 0; i < seeds; ++i) {
            std::mt19937_64 rng = instanceRng(table, paper, i);
            const order::Instance instance = order::paperInstance(rng, paper.rssCount, paper.states, kCostlyStates, kSubsetProbability);
            for (std::size_t r = 0; r < kRules.size(); ++r) {
                const order::InstanceCosts c = order::runMethods(instance, kRules[r], kHcsSize, kWindow);
                for (std::size_t m = 0; m < kMethods.size(); ++m) costs[r][m].push_back(c.cost[m]);
                bounds[r].push_back(c.bound);
                exact[r] += c.exact;
            }
        }
        for (std::size_t r = 0; r < kRules.size(); ++r) {
            Cell cell{paper, {}, order::meanCi(bounds[r]), exact[r]};
            for (std::size_t m = 0; m < kMethods.size(); ++m) cell.methods[m] = order::meanCi(costs[r][m]);
            (table == 6 ? report.rules[r].table6 : report.rules[r].table7).push_back(cell);
        }
    }
}

// The search that stands in for the optimum above kHeldKarpLimit RSSs, against Held–Karp at kCheckRss
// RSSs, set-not-held, on the distinct RSSs as best works (order::DistinctSets).
OptimumCheck runCheck(int states, int seeds) {
    OptimumCheck check;
    check.states = states;
    check.instances = seeds;
    std::vector<double> optimum, search, greedySearch, bound;
    const PaperCell cell{kCheckRss, states, 0, 0};
    for (int i = 0; i < seeds; ++i) {
        std::mt19937_64 rng = instanceRng(16, cell, i);
        const order::Instance instance = order::paperInstance(rng, kCheckRss, states, kCostlyStates, kSubsetProbability);
        const order::InstanceCosts exact = order::runMethods(instance, CostRule::SetNotHeld, kHcsSize, kWindow, true);
        const order::InstanceCosts searched = order::runMethods(instance, CostRule::SetNotHeld, kHcsSize, kWindow, false);
        const order::DistinctSets distinct = order::distinctSets(instance.sets);
        const double best = exact.cost.back(), found = searched.cost.back();
        const double fromGreedy = order::searchOrder(order::Transitions(distinct.sets, instance.costs, CostRule::SetNotHeld)).cost;
        optimum.push_back(best);
        search.push_back(found);
        greedySearch.push_back(fromGreedy);
        bound.push_back(exact.bound);
        const double gap = best > 0.0 ? (found - best) / best : 0.0, greedyGap = best > 0.0 ? (fromGreedy - best) / best : 0.0;
        check.meanGap += gap / double(seeds);
        check.worstGap = std::max(check.worstGap, gap);
        check.greedyMeanGap += greedyGap / double(seeds);
        check.greedyWorstGap = std::max(check.greedyWorstGap, greedyGap);
        check.hits += found <= best + 1e-9;
    }
    check.optimum = order::meanCi(optimum);
    check.search = order::meanCi(search);
    check.greedySearch = order::meanCi(greedySearch);
    check.bound = order::meanCi(bound);
    return check;
}

nlohmann::json meanJson(const MeanCi& m) { return {{"mean", m.mean}, {"ci95", m.ci95}}; }

nlohmann::json cellsJson(const std::vector<Cell>& cells) {
    nlohmann::json out = nlohmann::json::array();
    for (const Cell& c : cells) {
        nlohmann::json methods;
        for (std::size_t m = 0; m < kMethods.size(); ++m) methods[order::methodName(kMethods[m])] = meanJson(c.methods[m]);
        out.push_back({{"rss_count", c.paper.rssCount}, {"states", c.paper.states}, {"paper_sorted", c.paper.sorted},
                       {"paper_unsorted", c.paper.unsorted}, {"methods", methods}});
    }
    return out;
}

nlohmann::json boundsJson(const std::vector<Cell>& cells) {
    nlohmann::json out = nlohmann::json::array();
    for (const Cell& c : cells)
        out.push_back({{"rss_count", c.paper.rssCount}, {"states", c.paper.states}, {"mean", c.bound.mean},
                       {"ci95", c.bound.ci95}, {"best_exact", c.exact}});
    return out;
}

std::string reportJson(const Report& r) {
    nlohmann::json j;
    const RuleTables& main = r.rules.front();
    j["table6"] = cellsJson(main.table6);
    j["table7"] = cellsJson(main.table7);
    j["seeds"] = r.seeds;
    j["cost_rule"] = order::costRuleName(main.rule);
    j["subset_probability"] = kSubsetProbability;
    j["hcs_size"] = kHcsSize;
    j["hcs_threshold"] = "the sum of the two largest costs of each instance (|HCS| = 3)";
    j["lookahead_window"] = kWindow;
    j["lower_bound"] = {{"table6", boundsJson(main.table6)}, {"table7", boundsJson(main.table7)}};
    nlohmann::json alternatives;
    for (std::size_t i = 1; i < r.rules.size(); ++i)
        alternatives[order::costRuleName(r.rules[i].rule)] = {{"table6", cellsJson(r.rules[i].table6)},
                                                              {"table7", cellsJson(r.rules[i].table7)},
                                                              {"lower_bound", {{"table6", boundsJson(r.rules[i].table6)},
                                                                               {"table7", boundsJson(r.rules[i].table7)}}}};
    j["alternatives"] = alternatives;
    nlohmann::json checks = nlohmann::json::array();
    for (const OptimumCheck& c : r.checks)
        checks.push_back({{"rss_count", kCheckRss}, {"states", c.states}, {"instances", c.instances},
                          {"cost_rule", order::costRuleName(CostRule::SetNotHeld)}, {"optimum", meanJson(c.optimum)},
                          {"search", meanJson(c.search)}, {"greedy_search", meanJson(c.greedySearch)},
                          {"lower_bound", meanJson(c.bound)}, {"mean_gap", c.meanGap}, {"worst_gap", c.worstGap},
                          {"greedy_mean_gap", c.greedyMeanGap}, {"greedy_worst_gap", c.greedyWorstGap}, {"optimum_found", c.hits}});
    j["optimum_check"] = checks;
    return j.dump(2) + "\n";
}

std::string reportCsv(const Report& r) {
    std::string text = "rule,table,rss_count,states,method,mean,ci95,paper_sorted,paper_unsorted\n";
    const auto row = [&text](const RuleTables& rt, const char* table, const Cell& c, const char* method, const MeanCi& m) {
        char line[200];
        std::snprintf(line, sizeof line, "%s,%s,%d,%d,%s,%.3f,%.3f,%.0f,%.0f\n", order::costRuleName(rt.rule), table, c.paper.rssCount,
                      c.paper.states, method, m.mean, m.ci95, c.paper.sorted, c.paper.unsorted);
        text += line;
    };
    for (const RuleTables& rt : r.rules)
        for (const auto& [table, cells] : {std::pair{"table6", &rt.table6}, std::pair{"table7", &rt.table7}})
            for (const Cell& c : *cells) {
                for (std::size_t m = 0; m < kMethods.size(); ++m) row(rt, table, c, order::methodName(kMethods[m]), c.methods[m]);
                row(rt, table, c, "bound", c.bound);
            }
    return text;
}

std::string reportGnuplot(const std::string& csvPath, const std::string& svgPath) {
    std::string s;
    s += "# frugal state-sim: total state-change cost per order (set-not-held), with paper 004's columns.\n";
    s += "set terminal svg size 1100,440 dynamic enhanced\nset output '" + svgPath + "'\n";
    s += "set datafile separator ','\nset grid\nset key top left\nset ylabel 'total change cost'\nset yrange [0:*]\n";
    s += "set multiplot layout 1,2\n";
    const auto select = [&csvPath](const char* table, int x, const std::string& method, const std::string& y) {
        return "'" + csvPath + "' every ::1 using " + std::to_string(x) + ":((strcol(1) eq 'set-not-held' && strcol(2) eq '" +
               table + "' && strcol(5) eq '" + method + "') ? " + y + " : NaN)";
    };
    for (const auto& [table, x, title, label] :
         {std::tuple{"table6", 3, "Table 6: 5 states", "RSSs"}, std::tuple{"table7", 4, "Table 7: 50 RSSs", "states"}}) {
        s += std::string("set title '") + title + "'\nset xlabel '" + label + "'\nplot ";
        for (order::Method m : kMethods) {
            const std::string name = order::methodName(m);
            s += select(table, x, name, "$6") + " with linespoints title '" + name + "', \\\n     ";
        }
        s += select(table, x, "submit", "$9") + " with points pt 6 ps 1.5 title 'paper: not-sorted', \\\n     ";
        s += select(table, x, "submit", "$8") + " with points pt 4 ps 1.5 title 'paper: sorted'\n";
    }
    s += "unset multiplot\n";
    return s;
}

const char* kTableHead = "  %-7s %7s %8s  %-13s %-13s %-13s %-13s %-13s %-13s %-13s\n";

std::string meanText(const MeanCi& m) {
    char text[48];
    std::snprintf(text, sizeof text, "%.1f±%.1f", m.mean, m.ci95);
    return text;
}

void printTable(std::ostream& out, const char* title, const char* axis, const std::vector<Cell>& cells, bool byStates) {
    out << title << "\n";
    char line[320];
    std::snprintf(line, sizeof line, kTableHead, axis, "sorted", "unsorted", "submit", "paper", "key", "greedy", "lookahead",
                  "best", "bound");
    out << line;
    for (const Cell& c : cells) {
        std::snprintf(line, sizeof line, kTableHead, std::to_string(byStates ? c.paper.states : c.paper.rssCount).c_str(),
                      std::to_string(int(c.paper.sorted)).c_str(), std::to_string(int(c.paper.unsorted)).c_str(),
                      meanText(c.methods[0]).c_str(), meanText(c.methods[1]).c_str(), meanText(c.methods[2]).c_str(),
                      meanText(c.methods[3]).c_str(), meanText(c.methods[4]).c_str(), meanText(c.methods[5]).c_str(),
                      meanText(c.bound).c_str());
        out << line;
    }
}

// The ratios the goals are stated in: our unsorted against the paper's, the paper's sorted figure
// against its sort here, and how far below the paper's sort the best order lies.
void printRatios(std::ostream& out, const char* axis, const std::vector<Cell>& cells, bool byStates) {
    out << "  ratios:\n";
    char line[200];
    std::snprintf(line, sizeof line, "  %-7s %16s %20s %15s %19s %12s %12s\n", axis, "submit/unsorted", "paper sorted/ours",
                  "ours paper/best", "paper sorted/best", "best/bound", "best exact");
    out << line;
    for (const Cell& c : cells) {
        const double best = c.methods[5].mean, ours = c.methods[1].mean;
        std::snprintf(line, sizeof line, "  %-7d %16.3f %20.3f %15.2f %19.2f %12.2f %12d\n", byStates ? c.paper.states : c.paper.rssCount,
                      c.methods[0].mean / c.paper.unsorted, c.paper.sorted / ours, ours / best, c.paper.sorted / best,
                      c.bound.mean > 0.0 ? best / c.bound.mean : 0.0, c.exact);
        out << line;
    }
}

// The alternatives: the paper's two columns beside submit, paper and best under another rule.
void printAlternative(std::ostream& out, const RuleTables& rt) {
    out << "\ncost rule " << order::costRuleName(rt.rule) << " (the same instances):\n";
    char line[200];
    std::snprintf(line, sizeof line, "  %-6s %7s %7s %8s  %-13s %-13s %-13s %16s\n", "table", "cell", "sorted", "unsorted", "submit",
                  "paper", "best", "submit/unsorted");
    out << line;
    for (const auto& [table, cells] : {std::pair{"6", &rt.table6}, std::pair{"7", &rt.table7}})
        for (const Cell& c : *cells) {
            const std::string cell = table[0] == '6' ? std::to_string(c.paper.rssCount) + " RSS" : std::to_string(c.paper.states) + " st";
            std::snprintf(line, sizeof line, "  %-6s %7s %7.0f %8.0f  %-13s %-13s %-13s %16.3f\n", table, cell.c_str(), c.paper.sorted,
                          c.paper.unsorted, meanText(c.methods[0]).c_str(), meanText(c.methods[1]).c_str(),
                          meanText(c.methods[5]).c_str(), c.methods[0].mean / c.paper.unsorted);
            out << line;
        }
}

void printReport(std::ostream& out, const Report& r) {
    const RuleTables& main = r.rules.front();
    out << "paper 004's simulation: " << r.seeds << " instances per cell, mean ± 95 % CI; cost rule "
        << order::costRuleName(main.rule) << " (C(s) when an RSS sets s and the one before did not hold it);\n"
        << "each RSS sets each state with probability " << kSubsetProbability << "; sorted/unsorted: the paper's figures\n\n";
    printTable(out, "Table 6: 5 states (3 costly), by RSS count", "RSSs", main.table6, false);
    printRatios(out, "RSSs", main.table6, false);
    out << "\n";
    printTable(out, "Table 7: 50 RSSs (3 costly states), by state count", "states", main.table7, true);
    printRatios(out, "states", main.table7, true);
    for (std::size_t i = 1; i < r.rules.size(); ++i) printAlternative(out, r.rules[i]);
    out << "\nbest's search (2-opt, or-opt from greedy and from the cheapest other order) and the search from\n"
        << "greedy alone, against Held-Karp's optimum at " << kCheckRss << " RSSs, " << order::costRuleName(CostRule::SetNotHeld)
        << "; gaps (found - optimum) / optimum:\n";
    char line[240];
    std::snprintf(line, sizeof line, "  %-7s %9s  %-13s %-13s %-13s %-13s %9s %9s %11s %11s %7s\n", "states", "instances", "optimum",
                  "search", "from greedy", "bound", "mean gap", "worst gap", "greedy mean", "greedy worst", "optimal");
    out << line;
    for (const OptimumCheck& c : r.checks) {
        std::snprintf(line, sizeof line, "  %-7d %9d  %-13s %-13s %-13s %-13s %8.2f%% %8.2f%% %10.2f%% %10.2f%% %7d\n", c.states,
                      c.instances, meanText(c.optimum).c_str(), meanText(c.search).c_str(), meanText(c.greedySearch).c_str(),
                      meanText(c.bound).c_str(), 100.0 * c.meanGap, 100.0 * c.worstGap, 100.0 * c.greedyMeanGap,
                      100.0 * c.greedyWorstGap, c.hits);
        out << line;
    }
}

}  // namespace

int runStateSim(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    Report report;
    ReportPaths outputs;
    CommandLine command{"state-sim", stateSimHelp()};
    command.flags = {{"", {
        flag::whole("--seeds", "N", "instances per cell (default 100: about 10 s on one core)", report.seeds, 1, 100000),
    }}};
    for (Flag& f : reportFlags(outputs,
                               "{\"table6\":[{rss_count,states,paper_sorted,paper_unsorted,methods:{submit:{mean,ci95},"
                               "paper,key,greedy,lookahead,best}}],\"table7\":[...],\"lower_bound\":{...},"
                               "\"alternatives\":{\"every-set\":{...},\"symmetric-difference\":{...}},"
                               "\"optimum_check\":[...],...}",
                               "one row per cost rule, table, cell and method (and the bound)",
                               "cost against RSS count (Table 6) and against states (Table 7) per method, with the "
                               "paper's columns, drawn by gnuplot from the CSV (--csv, or FILE.csv beside the plot); the "
                               "script is written as FILE.gp"))
        command.flags[0].flags.push_back(std::move(f));
    command.finish = [&](ArgCursor& cursor) {
        if (const std::string problem = plotProblem(outputs); !problem.empty()) cursor.fail(problem);
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;

    for (CostRule rule : kRules) report.rules.push_back({rule, {}, {}});
    runTable(6, kTable6, report.seeds, report);
    runTable(7, kTable7, report.seeds, report);
    for (int states : kCheckStates) report.checks.push_back(runCheck(states, report.seeds));

    const ReportTexts texts{[&report] { return reportJson(report); }, [&report] { return reportCsv(report); },
                            [](const std::string& csvPath, const std::string& svgPath) { return reportGnuplot(csvPath, svgPath); }};
    if (const int status = writeReportFiles(outputs, texts, err); status != kExitOk) return status;
    printReport(out, report);
    return kExitOk;
}

}  // namespace frugal
