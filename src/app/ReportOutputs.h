// The files of the report commands (cull-report, reuse-bench): --json, --csv and --plot, parsed
// and checked alike, written together, then the plot drawn by gnuplot.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "app/Options.h"

namespace frugal {

// --json FILE, --csv FILE, --plot FILE.svg (its gnuplot script beside it as FILE.gp); "" when not asked for.
struct ReportPaths {
    std::string json, csv, plot;
};

// --json, --csv and --plot into `paths`, each with its help.
std::vector<Flag> reportFlags(ReportPaths& paths, std::string jsonHelp, std::string csvHelp, std::string plotHelp);

// The usage error of --plot, or "": gnuplot writes SVG here, and gets its path and the CSV's (which
// its script reads) inside single quotes.
// `pngToo`: a .png is taken as well (a report whose script picks gnuplot's pngcairo terminal for it).
std::string plotProblem(const ReportPaths& paths, bool pngToo = false);

// A report's texts, each made only when its file is asked for.
struct ReportTexts {
    std::function<std::string()> json, csv;
    // The gnuplot script that reads the CSV at `csvPath` and draws into `svgPath`.
    std::function<std::string(const std::string& csvPath, const std::string& svgPath)> gnuplot;
};

// Writes the files asked for, all or none (OutputSet): the JSON, the CSV (at --csv, or with --plot
// alone beside the plot as FILE.csv) and the script; then runs gnuplot on the script. On failure
// prints the one error line ("error: <path>: <why>", "error: --plot FILE: <gnuplot's problem>",
// "error: --csv FILE: a path with a single quote cannot be passed to gnuplot") and returns
// kExitError; kExitOk when everything is written.
int writeReportFiles(const ReportPaths& paths, const ReportTexts& texts, std::ostream& err);

}  // namespace frugal
