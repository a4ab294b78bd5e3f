// `frugal report`: every method that trades accuracy for speed, on one scene, in one run, with the
// settings to use (the measurement is lab/Trades.h's).
#include <algorithm>
#include <filesystem>
#include <ostream>

#include <frugal/Files.h>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "lab/TradePage.h"
#include "lab/Trades.h"

namespace frugal {

const char* reportHelp() {
    return R"(usage: frugal report [SCENE] [--views N | --camera-path F | --frames A:B] [options] -o DIR

Runs every method that trades accuracy for speed on SCENE (default builtin:default), in one process
with interleaved timing: the culling methods (the oracle as their floor), the draw orders key and
greedy, the hidden-surface modes, on the software backend the interpolators, the shading trades
(--shading lambert; --no-environment-specular; --samples 1 where more are asked for; --no-mipmaps
where the scene has mipmaps), in a sequence (--frames) temporal reuse, and combinations. Each is
judged against the plain render of the same view or frame: pixels that differ, the worst frame, the
visible triangles it lacks (misses), PSNR, the worst depth difference. Prints the fastest exact
settings (the plain render's colour and depth, bit for bit) and the fastest within --budget-px
differing pixels a frame, each with the 95 % interval of its time's ratio to the plain render's,
paired shot by shot and round by round (a bootstrap of a trimmed mean over the shots, fixed seed): a
method is picked only when that interval lies below 0.97, and never when its draws are the plain
render's (a no-op, such as an order of a single draw); "plain render" when nothing pays.
Writes into DIR:
  index.html      one page that works offline: the recommendation, the chart of time against
                  error (SVG), every method's figures with an error mask beside each one whose
                  colour differs, and the seed papers' published figures beside this run's
  report.json     every figure of the page; report.csv the methods, papers.csv the papers
  settings.json   the fastest exact settings, for 'frugal render --settings', the library's
                  readSettingsFile and Python's frugal.Renderer(scene, settings=...)
  masks/*.png     the full-size error mask of the worst frame of each method whose colour
                  differs
  pareto.gp       the chart again by gnuplot from report.csv ('gnuplot pareto.gp' in DIR)
)";
}

namespace {

// The shots: a sequence's frames through the render's camera (or --camera-path, entry i at frame
// A+i), or views at one time: the path's entries, the one camera the options give, or `count` views
// around the scene.
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
    if (!options.cameraPath.empty()) {
        for (std::size_t i = 0; i < options.cameraPath.size(); ++i)
            t.shots.push_back({"path " + std::to_string(i), cameraOf(options, int(i)), time});
        return t;
    }
    if (oneCamera(options)) {
        t.shots.push_back({"camera", options.camera, time});
        return t;
    }
    Result<std::vector<ReportView>> views = viewsAround(options, scene, count, time);
    if (!views) return views.error();
    for (std::size_t i = 0; i < views->size(); ++i)
        t.shots.push_back({"view " + std::to_string(i) + " (" + (*views)[i].viewClass + ")", (*views)[i].camera, time});
    return t;
}

}  // namespace

int runReport(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    std::string dir = "frugal-report";
    int views = 32, repeat = 3;
    bool viewsGiven = false;
    long long budget = 0;
    CommandLine command{"report", reportHelp(), &options};
    command.flags = {{"report", {
        flag::text("-o, --output", "DIR", "the folder for index.html and the files beside it (default frugal-report; "
                   "made when missing)", dir),
        flag::whole("--views", "N", "views around the scene's bounding sphere, as cull-report's (default 32); with "
                    "--frames A:B the frames of the sequence instead, with one camera (--camera, --eye, ...) that view "
                    "alone", views, 1, 10000, &viewsGiven),
        flag::text("--camera-path", "FILE", "a JSON list of {\"eye\":[x,y,z],\"target\":[x,y,z],\"up\":[x,y,z],"
                   "\"fov\":deg} (up and fov optional): each entry a view; with --frames A:B entry i is frame A+i, "
                   "the last entry holds (equal entries: a still camera, where reuse pays)", options.cameraPathFile),
        flag::whole("--repeat", "K", "timed renders of each view by each method, interleaved (default 3; a "
                    "sequence renders each frame once)", repeat, 1, 1000),
        {"--budget-px", "N", "differing pixels a frame the second recommendation may have (default 0)",
         [&budget](const std::string& text) { return flag::readWhole(text, 0, 1LL << 40, budget); }},
    }}};
    command.positional = sceneArgument(options);
    command.finish = [&](ArgCursor& cursor) {
        std::error_code ignored;
        if (std::filesystem::exists(dir, ignored) && !std::filesystem::is_directory(dir, ignored))
            cursor.fail("-o " + dir + ": a file, not a folder");
        else if (viewsGiven && (options.frames || !options.cameraPathFile.empty() || oneCamera(options)))
            cursor.fail("--views: give either --views N, --frames A:B, --camera-path or one camera");
        else if (!options.cameraPathFile.empty() && oneCamera(options))
            cursor.fail("--camera-path: give either a camera path or one camera (--camera, --eye, ...)");
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;

    Result<Scene> loaded = loadForRender(options, err);
    if (!loaded) return fail(err, loaded.error());
    Result<TradeSettings> shots = shotsOf(options, *loaded, views);
    if (!shots) return fail(err, shots.error());
    TradeSettings& settings = *shots;
    settings.repeat = repeat;
    settings.budgetPx = std::uint64_t(budget);
    const Settings base = options.settings;
    const bool mipmapped = std::any_of(loaded->textures.begin(), loaded->textures.end(),
                                       [](const Texture& t) { return t.mipmaps != MipFilter::None; });
    // The hidden-surface modes plan from fixed triangles: not for meshes that deform, nor for points and lines.
    const bool noHsr = loaded->deforms() || std::any_of(loaded->meshes.begin(), loaded->meshes.end(),
                                                        [](const Mesh& mesh) { return !mesh.triangles(); });
    const std::vector<TradeCandidate> candidates =
        tradeCandidates(base, settings.sequence, base.backend == BackendKind::Software, mipmapped, noHsr);
    Result<TradeReport> report = measureTrades(*loaded, candidates, settings, progressTo(err, options.quiet));
    if (!report) return fail(err, report.error());
    out << tradeRecommendationText(*report, settings);

    Result<TradePageFiles> page = tradePage(*report, settings);
    if (!page) return fail(err, page.error());
    std::error_code made;
    std::filesystem::create_directories(page->masks.empty() ? dir : dir + "/masks", made);
    if (made) return fail(err, Error{dir + ": cannot make the folder (" + made.message() + ")", ErrorKind::Io});
    const Settings& pick = report->bestExact ? report->rows[*report->bestExact].candidate.settings : base;
    FileSet files;
    files.add(dir + "/report.json", tradeReportJson(*report, settings));
    files.add(dir + "/report.csv", tradeReportCsv(*report));
    files.add(dir + "/settings.json", settingsJson(pick));
    files.add(dir + "/index.html", page->html);
    files.add(dir + "/papers.csv", page->papersCsv);
    files.add(dir + "/pareto.gp", page->gnuplot);
    for (auto& [name, png] : page->masks) files.add(dir + "/" + name, std::move(png));
    if (Result<bool> written = files.commit(); !written) return fail(err, written.error());
    if (!options.quiet)
        err << "wrote " << dir << "/index.html (" << page->html.size() / 1024 << " KiB), report.json, report.csv, "
            << "papers.csv, settings.json, pareto.gp, " << page->masks.size() << " masks\n";
    return kExitOk;
}

}  // namespace frugal
