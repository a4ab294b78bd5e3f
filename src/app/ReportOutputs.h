// The report commands' flags for their files, --json, --csv and --plot, parsed and checked alike;
// the files are written by lab/ReportFiles.h.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "app/Options.h"
#include "lab/ReportFiles.h"

namespace frugal {

// --json, --csv and --plot into `paths`, each with its help.
std::vector<Flag> reportFlags(ReportPaths& paths, std::string jsonHelp, std::string csvHelp, std::string plotHelp);

// The usage error of --plot, or "": gnuplot writes SVG here, and gets its path and the CSV's (which
// its script reads) inside single quotes.
// `pngToo`: a .png is taken as well (a report whose script picks gnuplot's pngcairo terminal for it).
std::string plotProblem(const ReportPaths& paths, bool pngToo = false);

// writeReport (lab/ReportFiles.h), its error printed by fail(): kExitOk when everything is written.
int writeReportFiles(const ReportPaths& paths, const ReportTexts& texts, std::ostream& err,
                     std::vector<std::pair<std::string, std::vector<std::uint8_t>>> extra = {});

}  // namespace frugal
