// `frugal-lab state-sim`: the simulation of paper 004 (Kim, "Rendering States Changing Costs Reducing
// Technique for Real-time 3D Graphics", 2009, section 4.2), Tables 6 and 7 reproduced
// with every draw order of src/order/ on the same random instances, each cell a mean with its 95 %
// confidence interval beside the paper's single figures. The paper does not say when a state's cost is
// paid: the tables use set-not-held (the rule whose unsorted figures match the paper's), and the other
// two rules are reported beside it. A check at 16 RSSs, where Held–Karp gives the optimum, measures
// how far the local search that stands in for the optimum above 16 RSSs stays from it.
// The simulation and its texts are the lab's (lab/StateSim.h); this file parses, prints and writes.
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "app/Cli.h"
#include "app/Command.h"
#include "commands/LabCommands.h"
#include "app/Options.h"
#include "app/ReportOutputs.h"
#include "lab/StateSim.h"

namespace frugal {

const char* stateSimHelp() {
    return R"(usage: frugal-lab state-sim [options]

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

int runStateSim(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    order::SimSettings settings;
    ReportPaths outputs;
    CommandLine command{"state-sim", stateSimHelp()};
    command.flags = {{"", {
        flag::whole("--seeds", "N", "instances per cell (default 100: about 10 s on one core)", settings.seeds, 1, 100000),
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

    const Result<order::SimReport> report = order::runSimulation(settings);
    if (!report) return fail(err, report.error());
    const ReportTexts texts{[&report] { return order::simJson(*report); }, [&report] { return order::simCsv(*report); },
                            [](const std::string& csvPath, const std::string& svgPath) { return order::simGnuplot(csvPath, svgPath); }};
    if (const int status = writeReportFiles(outputs, texts, err); status != kExitOk) return status;
    out << order::simText(*report);
    return kExitOk;
}

}  // namespace frugal
