#include "lab/StateSim.h"

#include <algorithm>
#include <cstdio>
#include <ostream>
#include <random>
#include <sstream>
#include <tuple>
#include <utility>

#include <nlohmann/json.hpp>

#include "lab/ReportText.h"

namespace frugal::order {

namespace {

constexpr int kHcsSize = 3;
constexpr int kCostlyStates = 3;
constexpr int kWindow = 4;
constexpr double kSubsetProbability = 0.5;
constexpr std::array<int, 2> kCheckStates{5, 25};  // the ends of Table 7
constexpr std::array<CostRule, 3> kRules{CostRule::SetNotHeld, CostRule::EverySet, CostRule::SymmetricDifference};

constexpr std::array<PaperCell, 5> kTable6{{{40, 5, 334, 921}, {80, 5, 553, 1801}, {120, 5, 643, 2694},
                                            {160, 5, 979, 3701}, {200, 5, 1213, 4588}}};
constexpr std::array<PaperCell, 5> kTable7{{{50, 5, 334, 1179}, {50, 10, 672, 1384}, {50, 15, 1097, 1776},
                                            {50, 20, 1352, 2114}, {50, 25, 1685, 2447}}};

using Progress = std::function<void(const std::string&)>;

// The generator of one instance: a function of the table, the cell and the instance's number only.
std::mt19937_64 instanceRng(int table, const PaperCell& cell, int index) {
    std::seed_seq seed{table, cell.rssCount, cell.states, index};
    return std::mt19937_64(seed);
}

// Every rule's cells of one table, on the same instances.
void runTable(int table, const std::array<PaperCell, 5>& cells, int seeds, SimReport& report, const Progress& progress) {
    for (const PaperCell& paper : cells) {
        if (progress)
            progress("table " + std::to_string(table) + ": " + std::to_string(paper.rssCount) + " RSSs, " +
                     std::to_string(paper.states) + " states");
        std::array<std::array<std::vector<double>, kMethods.size()>, kRules.size()> costs;
        std::array<std::vector<double>, kRules.size()> bounds;
        std::array<int, kRules.size()> exact{};
        for (int i = 0; i < seeds; ++i) {
            std::mt19937_64 rng = instanceRng(table, paper, i);
            const Instance instance = paperInstance(rng, paper.rssCount, paper.states, kCostlyStates, kSubsetProbability);
            for (std::size_t r = 0; r < kRules.size(); ++r) {
                const InstanceCosts c = runMethods(instance, kRules[r], kHcsSize, kWindow);
                for (std::size_t m = 0; m < kMethods.size(); ++m) costs[r][m].push_back(c.cost[m]);
                bounds[r].push_back(c.bound);
                exact[r] += c.exact;
            }
        }
        for (std::size_t r = 0; r < kRules.size(); ++r) {
            SimCell cell{paper, {}, meanCi(bounds[r]), exact[r]};
            for (std::size_t m = 0; m < kMethods.size(); ++m) cell.methods[m] = meanCi(costs[r][m]);
            (table == 6 ? report.rules[r].table6 : report.rules[r].table7).push_back(cell);
        }
    }
}

// The search that stands in for the optimum above kHeldKarpLimit RSSs, against Held–Karp at
// kSimCheckRss RSSs, set-not-held, on the distinct RSSs as best works (DistinctSets).
OptimumCheck runCheck(int states, int seeds) {
    OptimumCheck check;
    check.states = states;
    check.instances = seeds;
    std::vector<double> optimum, search, greedySearch, bound;
    const PaperCell cell{kSimCheckRss, states, 0, 0};
    for (int i = 0; i < seeds; ++i) {
        std::mt19937_64 rng = instanceRng(16, cell, i);
        const Instance instance = paperInstance(rng, kSimCheckRss, states, kCostlyStates, kSubsetProbability);
        const InstanceCosts exact = runMethods(instance, CostRule::SetNotHeld, kHcsSize, kWindow, true);
        const InstanceCosts searched = runMethods(instance, CostRule::SetNotHeld, kHcsSize, kWindow, false);
        const DistinctSets distinct = distinctSets(instance.sets);
        const double best = exact.cost.back(), found = searched.cost.back();
        const double fromGreedy = searchOrder(Transitions(distinct.sets, instance.costs, CostRule::SetNotHeld)).cost;
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
    check.optimum = meanCi(optimum);
    check.search = meanCi(search);
    check.greedySearch = meanCi(greedySearch);
    check.bound = meanCi(bound);
    return check;
}

}  // namespace

Result<SimReport> runSimulation(const SimSettings& settings, const Progress& progress) {
    if (settings.seeds < 1)
        return Error{"seeds " + std::to_string(settings.seeds) + ": at least 1 instance per cell", ErrorKind::BadInput, true};
    SimReport report;
    report.seeds = settings.seeds;
    for (CostRule rule : kRules) report.rules.push_back({rule, {}, {}});
    runTable(6, kTable6, settings.seeds, report, progress);
    runTable(7, kTable7, settings.seeds, report, progress);
    for (int states : kCheckStates) {
        if (progress) progress("optimum check: " + std::to_string(kSimCheckRss) + " RSSs, " + std::to_string(states) + " states");
        report.checks.push_back(runCheck(states, settings.seeds));
    }
    return report;
}

namespace {

nlohmann::json meanJson(const MeanCi& m) { return {{"mean", m.mean}, {"ci95", m.ci95}}; }

nlohmann::json cellsJson(const std::vector<SimCell>& cells) {
    nlohmann::json out = nlohmann::json::array();
    for (const SimCell& c : cells) {
        nlohmann::json methods;
        for (std::size_t m = 0; m < kMethods.size(); ++m) methods[methodName(kMethods[m])] = meanJson(c.methods[m]);
        out.push_back({{"rss_count", c.paper.rssCount}, {"states", c.paper.states}, {"paper_sorted", c.paper.sorted},
                       {"paper_unsorted", c.paper.unsorted}, {"methods", methods}});
    }
    return out;
}

nlohmann::json boundsJson(const std::vector<SimCell>& cells) {
    nlohmann::json out = nlohmann::json::array();
    for (const SimCell& c : cells)
        out.push_back({{"rss_count", c.paper.rssCount}, {"states", c.paper.states}, {"mean", c.bound.mean},
                       {"ci95", c.bound.ci95}, {"best_exact", c.exact}});
    return out;
}

nlohmann::json checkJson(const OptimumCheck& c) {
    return {{"rss_count", kSimCheckRss}, {"states", c.states}, {"instances", c.instances},
            {"cost_rule", costRuleName(CostRule::SetNotHeld)}, {"optimum", meanJson(c.optimum)},
            {"search", meanJson(c.search)}, {"greedy_search", meanJson(c.greedySearch)},
            {"lower_bound", meanJson(c.bound)}, {"mean_gap", c.meanGap}, {"worst_gap", c.worstGap},
            {"greedy_mean_gap", c.greedyMeanGap}, {"greedy_worst_gap", c.greedyWorstGap}, {"optimum_found", c.hits}};
}

}  // namespace

std::string simJson(const SimReport& r) {
    nlohmann::json j;
    const SimRuleTables& main = r.rules.front();
    j["table6"] = cellsJson(main.table6);
    j["table7"] = cellsJson(main.table7);
    j["seeds"] = r.seeds;
    j["cost_rule"] = costRuleName(main.rule);
    j["subset_probability"] = kSubsetProbability;
    j["hcs_size"] = kHcsSize;
    j["hcs_threshold"] = "the sum of the two largest costs of each instance (|HCS| = 3)";
    j["lookahead_window"] = kWindow;
    j["lower_bound"] = {{"table6", boundsJson(main.table6)}, {"table7", boundsJson(main.table7)}};
    nlohmann::json alternatives;
    for (std::size_t i = 1; i < r.rules.size(); ++i)
        alternatives[costRuleName(r.rules[i].rule)] = {{"table6", cellsJson(r.rules[i].table6)},
                                                       {"table7", cellsJson(r.rules[i].table7)},
                                                       {"lower_bound", {{"table6", boundsJson(r.rules[i].table6)},
                                                                        {"table7", boundsJson(r.rules[i].table7)}}}};
    j["alternatives"] = alternatives;
    nlohmann::json checks = nlohmann::json::array();
    for (const OptimumCheck& c : r.checks) checks.push_back(checkJson(c));
    j["optimum_check"] = checks;
    return j.dump(2) + "\n";
}

std::string simCsv(const SimReport& r) {
    std::string text = "rule,table,rss_count,states,method,mean,ci95,paper_sorted,paper_unsorted\n";
    const auto row = [&text](const SimRuleTables& rt, const char* table, const SimCell& c, const char* method, const MeanCi& m) {
        char line[200];
        std::snprintf(line, sizeof line, "%s,%s,%d,%d,%s,%.3f,%.3f,%.0f,%.0f\n", costRuleName(rt.rule), table, c.paper.rssCount,
                      c.paper.states, method, m.mean, m.ci95, c.paper.sorted, c.paper.unsorted);
        text += line;
    };
    for (const SimRuleTables& rt : r.rules)
        for (const auto& [table, cells] : {std::pair{"table6", &rt.table6}, std::pair{"table7", &rt.table7}})
            for (const SimCell& c : *cells) {
                for (std::size_t m = 0; m < kMethods.size(); ++m) row(rt, table, c, methodName(kMethods[m]), c.methods[m]);
                row(rt, table, c, "bound", c.bound);
            }
    return text;
}

std::string simGnuplot(const std::string& csvPath, const std::string& svgPath) {
    using reporttext::gnuplotQuoted;
    std::string s;
    s += "# frugal-lab state-sim: total state-change cost per order (set-not-held), with paper 004's columns.\n";
    s += "set terminal svg size 1100,440 dynamic enhanced\nset output " + gnuplotQuoted(svgPath) + "\n";
    s += "set datafile separator ','\nset grid\nset key top left\nset ylabel 'total change cost'\nset yrange [0:*]\n";
    s += "set multiplot layout 1,2\n";
    const auto select = [&csvPath](const char* table, int x, const std::string& method, const std::string& y) {
        return gnuplotQuoted(csvPath) + " every ::1 using " + std::to_string(x) + ":((strcol(1) eq 'set-not-held' && strcol(2) eq '" +
               table + "' && strcol(5) eq '" + method + "') ? " + y + " : NaN)";
    };
    for (const auto& [table, x, title, label] :
         {std::tuple{"table6", 3, "Table 6: 5 states", "RSSs"}, std::tuple{"table7", 4, "Table 7: 50 RSSs", "states"}}) {
        s += std::string("set title '") + title + "'\nset xlabel '" + label + "'\nplot ";
        for (Method m : kMethods) {
            const std::string name = methodName(m);
            s += select(table, x, name, "$6") + " with linespoints title '" + name + "', \\\n     ";
        }
        s += select(table, x, "submit", "$9") + " with points pt 6 ps 1.5 title 'paper: not-sorted', \\\n     ";
        s += select(table, x, "submit", "$8") + " with points pt 4 ps 1.5 title 'paper: sorted'\n";
    }
    s += "unset multiplot\n";
    return s;
}

namespace {

const char* kTableHead = "  %-7s %7s %8s  %-13s %-13s %-13s %-13s %-13s %-13s %-13s\n";

std::string meanText(const MeanCi& m) {
    char text[48];
    std::snprintf(text, sizeof text, "%.1f±%.1f", m.mean, m.ci95);
    return text;
}

void printTable(std::ostream& out, const char* title, const char* axis, const std::vector<SimCell>& cells, bool byStates) {
    out << title << "\n";
    char line[320];
    std::snprintf(line, sizeof line, kTableHead, axis, "sorted", "unsorted", "submit", "paper", "key", "greedy", "lookahead",
                  "best", "bound");
    out << line;
    for (const SimCell& c : cells) {
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
void printRatios(std::ostream& out, const char* axis, const std::vector<SimCell>& cells, bool byStates) {
    out << "  ratios:\n";
    char line[200];
    std::snprintf(line, sizeof line, "  %-7s %16s %20s %15s %19s %12s %12s\n", axis, "submit/unsorted", "paper sorted/ours",
                  "ours paper/best", "paper sorted/best", "best/bound", "best exact");
    out << line;
    for (const SimCell& c : cells) {
        const double best = c.methods[5].mean, ours = c.methods[1].mean;
        std::snprintf(line, sizeof line, "  %-7d %16.3f %20.3f %15.2f %19.2f %12.2f %12d\n", byStates ? c.paper.states : c.paper.rssCount,
                      c.methods[0].mean / c.paper.unsorted, c.paper.sorted / ours, ours / best, c.paper.sorted / best,
                      c.bound.mean > 0.0 ? best / c.bound.mean : 0.0, c.exact);
        out << line;
    }
}

// The alternatives: the paper's two columns beside submit, paper and best under another rule.
void printAlternative(std::ostream& out, const SimRuleTables& rt) {
    out << "\ncost rule " << costRuleName(rt.rule) << " (the same instances):\n";
    char line[200];
    std::snprintf(line, sizeof line, "  %-6s %7s %7s %8s  %-13s %-13s %-13s %16s\n", "table", "cell", "sorted", "unsorted", "submit",
                  "paper", "best", "submit/unsorted");
    out << line;
    for (const auto& [table, cells] : {std::pair{"6", &rt.table6}, std::pair{"7", &rt.table7}})
        for (const SimCell& c : *cells) {
            const std::string cell = table[0] == '6' ? std::to_string(c.paper.rssCount) + " RSS" : std::to_string(c.paper.states) + " st";
            std::snprintf(line, sizeof line, "  %-6s %7s %7.0f %8.0f  %-13s %-13s %-13s %16.3f\n", table, cell.c_str(), c.paper.sorted,
                          c.paper.unsorted, meanText(c.methods[0]).c_str(), meanText(c.methods[1]).c_str(),
                          meanText(c.methods[5]).c_str(), c.methods[0].mean / c.paper.unsorted);
            out << line;
        }
}

void printChecks(std::ostream& out, const std::vector<OptimumCheck>& checks) {
    out << "\nbest's search (2-opt, or-opt from greedy and from the cheapest other order) and the search from\n"
        << "greedy alone, against Held-Karp's optimum at " << kSimCheckRss << " RSSs, " << costRuleName(CostRule::SetNotHeld)
        << "; gaps (found - optimum) / optimum:\n";
    char line[240];
    std::snprintf(line, sizeof line, "  %-7s %9s  %-13s %-13s %-13s %-13s %9s %9s %11s %11s %7s\n", "states", "instances", "optimum",
                  "search", "from greedy", "bound", "mean gap", "worst gap", "greedy mean", "greedy worst", "optimal");
    out << line;
    for (const OptimumCheck& c : checks) {
        std::snprintf(line, sizeof line, "  %-7d %9d  %-13s %-13s %-13s %-13s %8.2f%% %8.2f%% %10.2f%% %10.2f%% %7d\n", c.states,
                      c.instances, meanText(c.optimum).c_str(), meanText(c.search).c_str(), meanText(c.greedySearch).c_str(),
                      meanText(c.bound).c_str(), 100.0 * c.meanGap, 100.0 * c.worstGap, 100.0 * c.greedyMeanGap,
                      100.0 * c.greedyWorstGap, c.hits);
        out << line;
    }
}

}  // namespace

std::string simText(const SimReport& r) {
    std::ostringstream out;
    const SimRuleTables& main = r.rules.front();
    out << "paper 004's simulation: " << r.seeds << " instances per cell, mean ± 95 % CI; cost rule "
        << costRuleName(main.rule) << " (C(s) when an RSS sets s and the one before did not hold it);\n"
        << "each RSS sets each state with probability " << kSubsetProbability << "; sorted/unsorted: the paper's figures\n\n";
    printTable(out, "Table 6: 5 states (3 costly), by RSS count", "RSSs", main.table6, false);
    printRatios(out, "RSSs", main.table6, false);
    out << "\n";
    printTable(out, "Table 7: 50 RSSs (3 costly states), by state count", "states", main.table7, true);
    printRatios(out, "states", main.table7, true);
    for (std::size_t i = 1; i < r.rules.size(); ++i) printAlternative(out, r.rules[i]);
    printChecks(out, r.checks);
    return out.str();
}

}  // namespace frugal::order
