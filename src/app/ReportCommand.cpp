// `frugal report`: every method that trades accuracy for speed, on one scene, in one run, with the
// settings to use (the measurement is lab/Trades.h's).
#include <filesystem>
#include <ostream>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "io/ImageIO.h"
#include "lab/Trades.h"

namespace frugal {

const char* reportHelp() {
    return R"(usage: frugal report [SCENE] [--views N | --frames A:B] [options] -o DIR

Runs every method that trades accuracy for speed on SCENE (default builtin:default), in one
process with interleaved timing: the culling methods (the oracle as their floor), the draw orders
key and greedy, the hidden-surface modes, on the software backend the interpolators, in a sequence
(--frames) temporal reuse, and combinations. Each is judged against the plain render of the same
view or frame: pixels that differ, the worst frame, PSNR, the worst depth difference. Prints the
fastest exact settings and the fastest within --budget-px pixels a frame ("plain render" when
nothing is at least 3 % faster than it), and writes DIR/report.json, DIR/report.csv and
DIR/settings.json (the fastest exact settings, for 'frugal render --settings', the library's
readSettingsFile and Python's frugal.Renderer(scene, settings=...)).
)";
}

namespace {

// The shots: a sequence's frames through the render's camera, or `count` views around the scene.
Result<TradeSettings> shotsOf(const RenderOptions& options, const Scene& scene, int count) {
    TradeSettings t;
    t.scene = options.scene;
    if (options.frames) {
        t.sequence = true;
        for (int f = options.frames->first; f <= options.frames->last; ++f)
            t.shots.push_back({"frame " + std::to_string(f), cameraOf(options, f), frameTimeOf(options, scene, f)});
        return t;
    }
    const double time = options.time.value_or(0.0);
    Result<std::vector<ReportView>> views = viewsAround(options, scene, count, time);
    if (!views) return views.failure();
    for (std::size_t i = 0; i < views->size(); ++i)
        t.shots.push_back({"view " + std::to_string(i) + " (" + (*views)[i].viewClass + ")", (*views)[i].camera, time});
    return t;
}

}  // namespace

int runReport(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    std::string dir = "frugal-report";
    int views = 32, repeat = 3;
    long long budget = 0;
    CommandLine command{"report", reportHelp(), &options};
    command.flags = {{"report", {
        flag::text("-o, --output", "DIR", "the folder for report.json, report.csv and settings.json (default "
                   "frugal-report; made when missing)", dir),
        flag::whole("--views", "N", "views around the scene's bounding sphere, as cull-report's (default 32); "
                    "with --frames A:B the frames of the sequence instead", views, 1, 10000),
        flag::whole("--repeat", "K", "timed renders of each view by each method, interleaved (default 3; a "
                    "sequence renders each frame once)", repeat, 1, 1000),
        {"--budget-px", "N", "differing pixels a frame the second recommendation may have (default 0)",
         [&budget](const std::string& text) { return flag::readWhole(text, 0, 1LL << 40, budget); }},
    }}};
    command.positional = sceneArgument(options);
    command.finish = [&dir](ArgCursor& cursor) {
        std::error_code ignored;
        if (std::filesystem::exists(dir, ignored) && !std::filesystem::is_directory(dir, ignored))
            cursor.fail("-o " + dir + ": a file, not a folder");
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;

    Result<Scene> loaded = loadForRender(options, err);
    if (!loaded) return fail(err, loaded.failure());
    Result<TradeSettings> shots = shotsOf(options, *loaded, views);
    if (!shots) return fail(err, shots.failure());
    TradeSettings& settings = *shots;
    settings.repeat = repeat;
    settings.budgetPx = std::uint64_t(budget);
    const Settings base = rendererSettings(options);
    const std::vector<TradeCandidate> candidates =
        tradeCandidates(base, settings.sequence, base.backend == BackendKind::Software);
    Result<TradeReport> report = measureTrades(*loaded, candidates, settings, progressTo(err, options.quiet));
    if (!report) return fail(err, report.failure());
    out << tradeRecommendationText(*report, settings);

    std::error_code made;
    std::filesystem::create_directories(dir, made);
    if (made) return fail(err, Error{dir + ": cannot make the folder (" + made.message() + ")", ErrorKind::Io});
    const Settings& pick = report->bestExact ? report->rows[*report->bestExact].candidate.settings : base;
    const auto bytes = [](const std::string& text) { return Bytes(text.begin(), text.end()); };
    OutputSet files;
    files.add(dir + "/report.json", bytes(tradeReportJson(*report, settings)));
    files.add(dir + "/report.csv", bytes(tradeReportCsv(*report)));
    files.add(dir + "/settings.json", bytes(settingsJson(pick)));
    if (Result<bool> written = files.commit(); !written) return fail(err, written.failure());
    if (!options.quiet) err << "wrote " << dir << "/report.json, report.csv, settings.json\n";
    return kExitOk;
}

}  // namespace frugal
