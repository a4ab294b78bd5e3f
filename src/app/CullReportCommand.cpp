// `frugal cull-report`: how exact each culling method's visible set is, and what it saves, view by
// view. Every view is judged against the full render of that view on the same backend: its id image
// gives the really visible set (RVS), its colour image the pixels a method changed. Times are medians
// of interleaved repeats (every method once per round, so machine noise hits all alike), with three
// baselines timed in the same rounds: the full draw, the full draw with GL back-face culling on
// (the fair baseline), and the oracle (the RVS from index buffers of its own, built before timing).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/CameraPath.h"
#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "app/CullSupport.h"
#include "app/HsrSupport.h"
#include "app/ReportOutputs.h"
#include "base/Stats.h"
#include "cull/Views.h"
#include "lab/CullReport.h"
#include "renderer/Oracle.h"
#include "report/ImageCompare.h"

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

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

struct Outputs : ReportPaths {
    std::string cameraPath;
};


}  // namespace

int runCullReport(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    CullOptions cull;
    Outputs outputs;
    int viewCount = 32, repeat = 5;
    bool viewsGiven = false;
    hsr::Mode hsrMode = hsr::Mode::ZBuffer;
    std::vector<Cull> methods(std::begin(kCulls), std::end(kCulls));
    CommandLine command{"cull-report", cullReportHelp(), &options};
    command.flags = {
        {"views (default: --views 32)", {
            {"--views", "N", "N views around the scene's bounding sphere: the two poles of the map (view axis along +z "
             "and -z), then whole-in-view, partial (less than half of the sphere inside the frustum), grazing, and "
             "camera-inside views",
             [&](const std::string& text) {
                 viewsGiven = true;
                 long long n = 0;
                 std::string why = flag::readWhole(text, 1, 10000, n);
                 if (why.empty()) viewCount = int(n);
                 return why;
             }},
            flag::text("--camera-path", "FILE", "a JSON list of {\"eye\":[x,y,z],\"target\":[x,y,z],\"up\":[x,y,z],"
                       "\"fov\":deg} (up and fov optional), timed in order; or the render's camera options "
                       "(--camera, --eye, ...) for one view", outputs.cameraPath),
        }},
        {"methods and timing", {
            {"--methods", "A,B,...", "among none, sphere, backface, cones, paper, conservative, oracle (default all)",
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
             }},
            flag::whole("--repeat", "K", "timed frames per view and method, interleaved; medians (default 5)", repeat, 1,
                        10000),
            hsrFlag(hsrMode, "every row draws in this hidden-surface mode (zbuffer, depthsort or adaptive; 'frugal help "
                             "render'), its plan timed with the draw; the reference stays the z-buffered full render"),
            cullFlags(cull, false)[0],
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
        const bool oneCamera = options.camera.sceneCamera || options.camera.eye || options.camera.target;
        if (!outputs.cameraPath.empty() && (viewsGiven || oneCamera))
            cursor.fail("--camera-path: give either a camera path, --views N, or one camera");
        else if (viewsGiven && oneCamera)
            cursor.fail("--views: give either --views N or one camera (--camera/--eye/--target)");
        else if (options.frames)
            cursor.fail("--frames: cull-report measures views at one time; use --time");
        else if (const std::string problem = plotProblem(outputs); !problem.empty())
            cursor.fail(problem);
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;

    Result<Scene> loaded = loadForRender(options, err);
    if (!loaded) {
        err << "error: " << loaded.error() << "\n";
        return kExitError;
    }
    Scene& scene = *loaded;
    const double time = options.time.value_or(0.0);

    // The views.
    std::vector<ReportView> views;
    std::string timing = "cold";
    if (!outputs.cameraPath.empty()) {
        Result<std::vector<Camera>> path = readCameraPath(outputs.cameraPath);
        if (!path) {
            err << "error: " << path.error() << "\n";
            return kExitError;
        }
        for (const Camera& camera : *path) views.push_back(ReportView{"path", camera});
        timing = "path";
    } else if (options.camera.sceneCamera || options.camera.eye || options.camera.target) {
        views.push_back(ReportView{"camera", options.camera});
    } else {
        const Bounds bounds = scene.bounds(time);
        if (bounds.empty()) {
            err << "error: " << options.scene << ": the scene has no geometry to view\n";
            return kExitError;
        }
        views = reportViews(bounds.center(), bounds.radius(), viewCount, options.camera.yfovDegrees.value_or(40.0f),
                            float(options.width) / float(options.height));
    }
    // The render's --near/--far and depth settings apply to every view.
    for (ReportView& view : views) applyDepthOptions(options.camera, view.camera);

    cull.bins.hull = std::find(methods.begin(), methods.end(), Cull::Paper) != methods.end();
    const SceneCuller culler = prepareCulling(scene, cull.bins, err, options.quiet);

    std::variant<Session, int> started = startSession(options, scene, err);
    if (const int* status = std::get_if<int>(&started)) return *status;
    Session& session = std::get<Session>(started);
    Backend& backend = *session.backend;
    SceneRenderer& renderer = *session.renderer;
    const TargetHandle target = session.target;
    const int width = options.width, height = options.height;
    const DrawList full = fullDrawList(scene);
    // --hsr: every row, methods and baselines, draws its list in that mode; the reference stays the
    // z-buffered full render, so pixels_differing counts what culling and the mode together change.
    std::optional<hsr::Planner> planner;
    if (hsrMode != hsr::Mode::ZBuffer) planner.emplace(scene);

    CullReport report;
    report.scene = options.scene;
    report.width = width;
    report.height = height;
    report.backend = backend.name();
    report.timing = timing;

    for (std::size_t v = 0; v < views.size(); ++v) {
        Result<FrameSetup> setup = setUpFrame(scene, views[v].camera, time, width, height, false, options.depthFormat);
        if (!setup) {
            err << "error: view " << v << " (" << views[v].viewClass << "): " << setup.error() << "\n";
            return kExitError;
        }
        const FrameParams& params = setup->params;
        const std::vector<glm::mat4>& world = setup->world;

        // The reference colour, then the oracle (its id pass gives the RVS).
        renderer.renderFrame(target, width, height, params, world, options.background);
        const Buffers reference = backend.readBack(target);
        Result<Oracle> oracle = makeOracle(renderer, target, width, height, params, world, options.background);
        if (!oracle) {
            err << "error: view " << v << ": " << oracle.error() << "\n";
            return kExitError;
        }

        // Timed rounds: the methods asked for, then the baselines (none is the full draw and oracle the
        // oracle's: their rows take the baselines' times).
        struct Timing {
            std::vector<double> cull, draw;
            DrawList list;
        };
        std::vector<Timing> timings(methods.size());
        Timing fullTiming, cullfaceTiming, oracleTiming;
        std::optional<hsr::Planner> oraclePlanner;
        if (planner) oraclePlanner.emplace(*oracle->scene);
        // Draws `list` (the renderer's full list when null) in the --hsr mode; the plan is timed.
        auto draw = [&](SceneRenderer& r, const DrawList* list) {
            if (!planner) {
                if (list) r.renderFrame(target, width, height, params, world, options.background, *list);
                else r.renderFrame(target, width, height, params, world, options.background);
                return;
            }
            const hsr::Planner& p = &r == &renderer ? *planner : *oraclePlanner;
            r.renderFrame(target, width, height, params, world, options.background,
                          p.plan(hsrMode, params, world, list ? *list : r.fullList(), width, height));
        };
        auto frame = [&](SceneRenderer& r, const DrawList* list, Timing& t, bool record) {
            backend.finish();
            const auto t0 = Clock::now();
            draw(r, list);
            backend.finish();
            if (record) t.draw.push_back(msSince(t0));
        };
        for (int round = -1; round < repeat; ++round) {  // round -1: warm-up, untimed
            const bool record = round >= 0;
            for (std::size_t m = 0; m < methods.size(); ++m) {
                Timing& t = timings[m];
                if (methods[m] == Cull::None || methods[m] == Cull::Oracle) continue;
                const auto t0 = Clock::now();
                t.list = culler.cull(methods[m], scene, world, setup->view);
                const double cullMs = msSince(t0);
                if (record) t.cull.push_back(cullMs);
                frame(renderer, &t.list, t, record);
            }
            frame(renderer, nullptr, fullTiming, record);
            renderer.setCullAllBackFaces(true);
            frame(renderer, nullptr, cullfaceTiming, record);
            renderer.setCullAllBackFaces(false);
            frame(*oracle->renderer, nullptr, oracleTiming, record);
        }
        const double fullMs = median(fullTiming.draw), cullfaceMs = median(cullfaceTiming.draw),
                     oracleMs = median(oracleTiming.draw);

        ViewResult view;
        view.index = int(v);
        view.viewClass = views[v].viewClass;
        view.eye = setup->view.eye;
        view.target = views[v].camera.target.value_or(setup->view.eye + setup->view.forward);
        std::ostringstream progress;
        progress << "view " << (v + 1) << "/" << views.size() << " (" << view.viewClass << "): rvs " << oracle->rvs.count
                 << " of " << scene.triangleCount() << ", full " << fmt(fullMs) << " ms, oracle " << fmt(oracleMs) << " ms";
        for (std::size_t m = 0; m < methods.size(); ++m) {
            Timing& t = timings[m];
            if (methods[m] == Cull::None) {
                t = fullTiming;
                t.list = full;
            } else if (methods[m] == Cull::Oracle) {
                t = oracleTiming;
            }
            MethodResult result;
            result.method = toString(methods[m]);
            const TriangleSet pvs = methods[m] == Cull::Oracle ? oracle->rvs : drawnSet(scene, t.list);
            const SetCounts counts = compareSets(scene, pvs, oracle->rvs);
            result.tos = counts.tos;
            result.pvs = counts.pvs;
            result.rvs = counts.rvs;
            result.misses = counts.misses;
            result.waste = counts.waste;
            // The image this plan draws, against the full render's.
            if (methods[m] == Cull::Oracle)
                draw(*oracle->renderer, nullptr);
            else
                draw(renderer, &t.list);
            Result<ImageComparison> compared = compareBuffers(backend.readBack(target), reference);
            result.pixelsDiffering = compared ? compared->failingPixels : reference.pixelCount();
            result.cullMs = t.cull.empty() ? 0.0 : median(t.cull);  // none, oracle: no plan to make
            result.drawMs = median(t.draw);
            const double total = result.cullMs + result.drawMs;
            result.ratioToOracle = total / oracleMs;
            result.ratioToFull = total / fullMs;
            result.ratioToFullCullface = total / cullfaceMs;
            if (methods[m] != Cull::None && methods[m] != Cull::Oracle)
                progress << "; " << result.method << " x" << fmt(std::round(result.ratioToOracle * 100) / 100)
                         << (result.misses ? " misses " + std::to_string(result.misses) : "");
            view.methods.push_back(std::move(result));
        }
        if (!options.quiet) err << progress.str() << "\n";
        report.views.push_back(std::move(view));
    }

    // The report, with the pre-processing figures beside the paper's.
    nlohmann::json json = nlohmann::json::parse(cullReportJson(report));
    nlohmann::json meshes = nlohmann::json::array();
    for (std::size_t i = 0; i < culler.maps().size(); ++i) {
        const MeshMap& map = culler.maps()[i];
        const PrepStats& s = map.stats;
        meshes.push_back({{"mesh", i}, {"name", scene.meshes[i].name}, {"triangles", scene.meshes[i].triangleCount()},
                          {"sphere_ms", s.sphereMs}, {"map_ms", s.mapMs}, {"cluster_ms", s.clusterMs},
                          {"hull_ms", s.hullMs}, {"total_ms", s.totalMs()}, {"map_bytes", s.mapBytes},
                          {"access_bytes", s.accessBytes}, {"clusters", map.clusters.size()},
                          {"hull_kind", hullKindName(map.hull.kind)}, {"hull_vertices", map.hull.vertices.size()},
                          {"hull_faces", map.hull.faces}, {"sphere_radius", map.sphere.radius}});
    }
    json["preprocess"] = {{"bins", {cull.bins.thetaBins, cull.bins.phiBins}},
                          {"meshes", meshes},
                          {"paper_bunny", {{"hull_ms", 5000}, {"hull_vertices", 3023}, {"hull_faces", 6042},
                                           {"map_bytes", 4.3e6}, {"access_bytes", 0.51e6}}}};
    json["repeat"] = repeat;
    json["hsr"] = toString(hsrMode);
    json["renderer"] = backend.renderer();

    const ReportTexts texts{[&json] { return json.dump(2) + "\n"; }, [&report] { return cullReportCsv(report); },
                            cullReportGnuplot};
    if (const int status = writeReportFiles(outputs, texts, err); status != kExitOk) return status;

    // The summary, a line per method, then per view class.
    out << "method        median pvs  misses  views missed  pixels  cull ms  draw ms  /oracle  /full  /cullface  worst view\n";
    for (Cull method : methods) {
        const nlohmann::json& s = json["summary"][toString(method)];
        char line[256];
        std::snprintf(
            line, sizeof line, "%-13s %10.0f %7zu %13zu %7zu %8.3f %8.3f %8.3f %6.3f %10.3f  %d (%s, x%.3f)\n",
            toString(method), s["median_pvs"].get<double>(), s["total_misses"].get<std::size_t>(),
            s["views_with_misses"].get<std::size_t>(), s["total_pixels_differing"].get<std::size_t>(),
            s["median_cull_ms"].get<double>(), s["median_draw_ms"].get<double>(),
            s["median_ratio_to_oracle"].get<double>(), s["median_ratio_to_full"].get<double>(),
            s["median_ratio_to_full_cullface"].get<double>(), s["worst_view"]["index"].get<int>(),
            s["worst_view"]["class"].get<std::string>().c_str(), s["worst_view"]["ratio_to_oracle"].get<double>());
        out << line;
    }
    out << "\nclass     method        views  median pvs of tos   speed-up (full, cullface)  misses\n";
    for (const auto& [viewClass, byMethod] : json["by_class"].items())
        for (Cull method : methods) {
            if (!byMethod.contains(toString(method))) continue;
            const nlohmann::json& c = byMethod[toString(method)];
            char line[256];
            std::snprintf(line, sizeof line, "%-9s %-13s %5zu  %10.0f of %-6zu  %8.3f %8.3f          %7zu\n",
                          viewClass.c_str(), toString(method), c["views"].get<std::size_t>(),
                          c["median_pvs"].get<double>(), c["tos"].get<std::size_t>(),
                          c["median_speed_up"].get<double>(), c["median_speed_up_over_cullface"].get<double>(),
                          c["total_misses"].get<std::size_t>());
            out << line;
        }
    return kExitOk;
}

}  // namespace frugal
