#include "app/ReportOutputs.h"

#include <filesystem>
#include <optional>
#include <ostream>

#include "app/Cli.h"
#include "app/Gnuplot.h"
#include "io/ImageIO.h"
#include "io/Interrupt.h"

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

int writeReportFiles(const ReportPaths& paths, const ReportTexts& texts, std::ostream& err) {
    OutputSet files;
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
            return fail(err, Error{"csv " + csvPath + ": a path with a single quote cannot be passed to gnuplot",
                                   ErrorKind::BadInput, true});
        const std::string script = texts.gnuplot(csvPath, paths.plot);
        files.add(scriptPath, Bytes(script.begin(), script.end()));
    }
    if (!csvPath.empty()) {
        const std::string text = texts.csv();
        files.add(csvPath, Bytes(text.begin(), text.end()));
    }
    if (Result<bool> written = files.commit(); !written) return fail(err, written.failure());
    if (!paths.plot.empty()) {
        // gnuplot writes the plot itself: it inherits the block, so a signal waits for a whole file.
        const SignalsHeld held;
        const std::string problem = runGnuplot(scriptPath);
        if (!problem.empty()) return fail(err, Error{"plot " + paths.plot + ": " + problem, ErrorKind::Io, true});
    }
    return kExitOk;
}

}  // namespace frugal
