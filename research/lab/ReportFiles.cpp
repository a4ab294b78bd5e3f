#include "lab/ReportFiles.h"

#include <filesystem>

#include "renderer/Research.h"
#include "lab/Gnuplot.h"

namespace frugal {

Result<bool> writeReport(const ReportPaths& paths, const ReportTexts& texts,
                         std::vector<std::pair<std::string, std::vector<std::uint8_t>>> extra) {
    OutputSet files;
    for (auto& [path, bytes] : extra) files.add(path, std::move(bytes));
    if (!paths.json.empty()) {
        const std::string text = texts.json();
        files.add(paths.json, Bytes(text.begin(), text.end()));
    }
    std::string csvPath = paths.csv;
    std::string scriptPath;
    if (!paths.plot.empty()) {
        if (csvPath.empty()) csvPath = std::filesystem::path(paths.plot).replace_extension(".csv").string();
        scriptPath = std::filesystem::path(paths.plot).replace_extension(".gp").string();
        // The script names the CSV inside single quotes (plotProblem refuses such a path first, as a
        // usage error; this holds for a command that did not ask it).
        if (hasSingleQuote(csvPath))
            return Error{"csv " + csvPath + ": a path with a single quote cannot be passed to gnuplot",
                         ErrorKind::BadInput, true};
        const std::string script = texts.gnuplot(csvPath, paths.plot);
        files.add(scriptPath, Bytes(script.begin(), script.end()));
    }
    if (!csvPath.empty()) {
        const std::string text = texts.csv();
        files.add(csvPath, Bytes(text.begin(), text.end()));
    }
    if (Result<bool> written = files.commit(); !written) return written;
    if (!paths.plot.empty()) {
        // gnuplot writes the plot itself: it inherits the block, so a signal waits for a whole file.
        const SignalsHeld held;
        const std::string problem = runGnuplot(scriptPath);
        if (!problem.empty()) return Error{"plot " + paths.plot + ": " + problem, ErrorKind::Io, true};
    }
    return true;
}

}  // namespace frugal
