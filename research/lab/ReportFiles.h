// A report's files, as the report commands write them: --json, --csv and --plot (a gnuplot script
// beside the plot, then gnuplot run on it), all or none.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <frugal/Result.h>

namespace frugal {

// --json FILE, --csv FILE, --plot FILE.svg (its gnuplot script beside it as FILE.gp); "" when not asked for.
struct ReportPaths {
    std::string json, csv, plot;
};

// A report's texts, each made only when its file is asked for.
struct ReportTexts {
    std::function<std::string()> json, csv;
    // The gnuplot script that reads the CSV at `csvPath` and draws into `svgPath`.
    std::function<std::string(const std::string& csvPath, const std::string& svgPath)> gnuplot;
};

// Writes the files asked for, all or none (OutputSet): the JSON, the CSV (at paths.csv, or with a
// plot alone beside it as FILE.csv) and the script (FILE.gp); then runs gnuplot on the script.
// Errors: "<path>: <why>" (Io), "plot FILE: <gnuplot's problem>", "csv FILE: a path with a single
// quote cannot be passed to gnuplot" (both about a setting). `extra` files (path, bytes) are
// written with them, all or none.
Result<bool> writeReport(const ReportPaths& paths, const ReportTexts& texts,
                         std::vector<std::pair<std::string, std::vector<std::uint8_t>>> extra = {});

}  // namespace frugal
