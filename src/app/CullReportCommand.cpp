// `frugal cull-report`: how exact each culling method's visible set is, and what it saves, view by
// view (the measurement is lab/CullMeasure.h's).
#include <algorithm>
#include <filesystem>
#include <ostream>
#include <sstream>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "app/ReportOutputs.h"
#include "lab/Views.h"
#include "lab/CullMeasure.h"

namespace frugal {

const char* cullReportHelp() {
    return R"(usage: frugal cull-report [SCENE] [options]

Measures every culling method on a set of views of SCENE (default builtin:default): per view and
method the total triangles (tos), the submitted ones (pvs), the really visible ones (rvs: owning a
pixel of the full render), misses (visible yet dropped), waste (submitted yet hidden), pixels that
differ from the full render, the CPU time to cull and the time to draw, and ratios to the oracle's
draw, to the full draw and to the full draw with GL back-face culling on. Each view is timed cold:
no method learns from an earlier view. Prints a summary per method; --json/--csv/--plot write the
whole report.
)";
}

namespace {

struct Outputs : ReportPaths {
    std::string cameraPath;
};

// --methods A,B,...: the methods, each once, in the order given.
Flag methodsFlag(std::vector<Cull>& methods) {
    return {"--methods", "A,B,...", "among none, sphere, backface, cones, paper, conservative, occlusion, occlusion-ahead, oracle "
            "(default all; occlusion-ahead makes each frame's plan while the frame before draws)",
            [&methods](const std::string& list) -> std::string {
                methods.clear();
                std::stringstream items(list);
                std::string item;
                while (std::getline(items, item, ',')) {
                    const std::optional<Cull> method = fromString(item, kCulls);
                    if (!method) return "names '" + item + "', not a method (" + namesOf(kCulls) + ")";
                    if (std::find(methods.begin(), methods.end(), *method) == methods.end()) methods.push_back(*method);
                }
                if (methods.empty()) return "is not a list of methods (" + namesOf(kCulls) + ")";
                return {};
            }};
}

// The views: a camera path (timed in order), the one camera the options give, or `count` views
// around the scene's bounding sphere. The render's --near/--far and depth settings apply to each.
Result<std::vector<ReportView>> viewsOf(const RenderOptions& options, const std::string& cameraPath, int count,
                                        const Scene& scene, CullMeasureSettings& settings) {
    if (cameraPath.empty() && !oneCamera(options)) return viewsAround(options, scene, count, settings.time);
    std::vector<ReportView> views;
    if (!cameraPath.empty()) {
        Result<std::vector<Camera>> path = readCameraPath(cameraPath);
        if (!path) return path.error();
        for (const Camera& camera : *path) views.push_back(ReportView{"path", camera});
        settings.timing = "path";
    } else {
        views.push_back(ReportView{"camera", options.camera});
    }
    for (ReportView& view : views) applyDepthOptions(options.camera, view.camera);
    return views;
}


}  // namespace

int runCullReport(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    Outputs outputs;
    int viewCount = 32, repeat = 5;
    std::string masksDir;
    bool viewsGiven = false;
    std::vector<Cull> methods(std::begin(kCulls), std::end(kCulls));
    CommandLine command{"cull-report", cullReportHelp(), &options};
    command.flags = {
        {"views (default: --views 32)", {
            flag::whole("--views", "N", "N views around the scene's bounding sphere: the two poles of the map (view "
                        "axis along +z and -z), then whole-in-view, partial (less than half of the sphere inside the "
                        "frustum), grazing, and camera-inside views",
                        viewCount, 1, 10000, &viewsGiven),
            flag::text("--camera-path", "FILE", "a JSON list of {\"eye\":[x,y,z],\"target\":[x,y,z],\"up\":[x,y,z],"
                       "\"fov\":deg} (up and fov optional), timed in order; or the render's camera options "
                       "(--camera, --eye, ...) for one view", outputs.cameraPath),
        }},
        {"methods and timing", {
            methodsFlag(methods),
            flag::whole("--repeat", "K", "timed frames per view and method, interleaved; medians (default 5)", repeat, 1,
                        10000),
            settingFlag("hsr", options.settings, options.given,
                        "every row draws in this hidden-surface mode ('frugal help render'), its plan timed with the "
                        "draw; the reference stays the z-buffered full render"),
            settingFlag("cull-bins", options.settings, options.given),
        }},
        {"occlusion (with the occlusion method)", {
            flag::text("--masks", "DIR", "write each view's occlusion buffer to DIR/occlusion-view-<v>.png (the "
                       "nearest occluder's depth bound, grey, lighter nearer; blue where no occluder covers the "
                       "pixel), as one more untimed pass made to run; the JSON names each file",
                       masksDir),
        }},
        {"outputs (each written whole or not at all)",
         reportFlags(outputs,
                     "the report: views, methods, summary (medians, worst view, total misses, the share of the draw "
                     "time culling takes), and medians per view class",
                     "one row per view and method",
                     "plots drawn by gnuplot from the CSV (--csv, or FILE.csv beside the plot); the gnuplot script is "
                     "written beside it as FILE.gp, to restyle and rerun")},
    };
    command.positional = sceneArgument(options);
    command.finish = [&](ArgCursor& cursor) {
        if (!outputs.cameraPath.empty() && (viewsGiven || oneCamera(options)))
            cursor.fail("--camera-path: give either a camera path, --views N, or one camera");
        else if (viewsGiven && oneCamera(options))
            cursor.fail("--views: give either --views N or one camera (--camera/--eye/--target)");
        else if (options.frames)
            cursor.fail("--frames: cull-report measures views at one time; use --time");
        else if (const std::string problem = plotProblem(outputs); !problem.empty())
            cursor.fail(problem);
        else if (!masksDir.empty() && std::find(methods.begin(), methods.end(), Cull::Occlusion) == methods.end())
            cursor.fail("--masks: the occlusion buffers come from the occlusion method; add it to --methods");
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;

    Result<Scene> loaded = loadForRender(options, err);
    if (!loaded) return fail(err, loaded.error());
    CullMeasureSettings settings{options.scene, options.settings, methods, repeat, options.time.value_or(0.0), "cold",
                                 masksDir};
    Result<std::vector<ReportView>> views = viewsOf(options, outputs.cameraPath, viewCount, *loaded, settings);
    if (!views) return fail(err, views.error());

    Result<CullMeasurement> measured = measureCulling(*loaded, *views, settings, progressTo(err, options.quiet));
    if (!measured) return fail(err, measured.error());
    const ReportTexts texts{[&measured] { return measured->json; },
                            [&measured] { return cullReportCsv(measured->report); }, cullReportGnuplot};
    if (!measured->images.empty()) {
        std::error_code made;
        std::filesystem::create_directories(masksDir, made);
        if (made) return fail(err, Error{"--masks " + masksDir + ": cannot make the folder (" + made.message() + ")",
                                         ErrorKind::Io});
    }
    // The buffers' images with the report's files, all or none.
    if (const int status = writeReportFiles(outputs, texts, err, std::move(measured->images)); status != kExitOk)
        return status;
    out << cullReportSummary(*measured, methods);
    return kExitOk;
}

}  // namespace frugal
