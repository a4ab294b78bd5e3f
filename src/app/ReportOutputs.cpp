#include "app/ReportOutputs.h"

#include <filesystem>
#include <optional>
#include <ostream>

#include "app/Cli.h"
#include "lab/Gnuplot.h"

namespace frugal {

std::vector<Flag> reportFlags(ReportPaths& paths, std::string jsonHelp, std::string csvHelp, std::string plotHelp) {
    return {flag::text("--json", "FILE", std::move(jsonHelp), paths.json),
            flag::text("--csv", "FILE", std::move(csvHelp), paths.csv),
            flag::text("--plot", "FILE.svg", std::move(plotHelp), paths.plot)};
}

std::string plotProblem(const ReportPaths& paths, bool pngToo) {
    if (paths.plot.empty()) return {};
    const std::filesystem::path extension = std::filesystem::path(paths.plot).extension();
    if (pngToo && extension != ".svg" && extension != ".png")
        return "--plot " + paths.plot + ": gnuplot writes SVG or PNG here; name it .svg or .png";
    if (!pngToo && extension != ".svg") return "--plot " + paths.plot + ": gnuplot writes SVG here; name it .svg";
    if (hasSingleQuote(paths.plot)) return "--plot " + paths.plot + ": a path with a single quote cannot be passed to gnuplot";
    if (hasSingleQuote(paths.csv)) return "--csv " + paths.csv + ": a path with a single quote cannot be passed to gnuplot";
    return {};
}

int writeReportFiles(const ReportPaths& paths, const ReportTexts& texts, std::ostream& err,
                     std::vector<std::pair<std::string, std::vector<std::uint8_t>>> extra) {
    if (Result<bool> written = writeReport(paths, texts, std::move(extra)); !written)
        return fail(err, written.error());
    return kExitOk;
}

}  // namespace frugal
