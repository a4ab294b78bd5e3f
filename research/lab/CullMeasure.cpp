#include "lab/CullMeasure.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "lab/ImageCompare.h"
#include "lab/Views.h"
#include "renderer/Research.h"

namespace frugal {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// The times of one row over the rounds, and its latest plan.
struct Timing {
    std::vector<double> cull, draw;
    DrawList list;
};

// One view, measured: the rows of every method, and its progress line.
class ViewMeasure {
public:
    ViewMeasure(const Scene& scene, const SceneCuller& culler, Stage& stage, const CullMeasureSettings& settings,
                const std::optional<hsr::Planner>& planner, std::vector<std::pair<std::string, Bytes>>& images)
        : scene_(scene), culler_(culler), stage_(stage), s_(settings), planner_(planner), images_(images) {}

    Result<ViewResult> run(std::size_t v, const ReportView& reportView, std::string& progressLine);

private:
    // Draws `list` (the renderer's full list when null) in the hsr mode; the plan is timed with it.
    void draw(SceneRenderer& r, const DrawList* list);
    // One frame of `list` by `r`, timed into `t` when `record`.
    void frame(SceneRenderer& r, const DrawList* list, Timing& t, bool record);

    const Scene& scene_;
    const SceneCuller& culler_;
    Stage& stage_;
    const CullMeasureSettings& s_;
    const std::optional<hsr::Planner>& planner_;
    std::vector<std::pair<std::string, Bytes>>& images_;  // the occlusion buffers (--masks), as PNG
    std::optional<FrameSetup> setup_;
    std::optional<Oracle> oracle_;
    std::optional<hsr::Planner> oraclePlanner_;
    CullAhead ahead_;  // occlusion-ahead: the next round's plan
};

void ViewMeasure::draw(SceneRenderer& r, const DrawList* list) {
    const Settings& s = s_.render;
    const FrameParams& params = setup_->params;
    const std::vector<glm::mat4>& world = setup_->world;
    const TargetHandle target = stage_.target();
    if (!planner_) {
        if (list)
            r.renderFrame(target, s.width, s.height, params, world, s.background, *list);
        else
            r.renderFrame(target, s.width, s.height, params, world, s.background);
        return;
    }
    const hsr::Planner& p = &r == &stage_.renderer() ? *planner_ : *oraclePlanner_;
    r.renderFrame(target, s.width, s.height, params, world, s.background,
                  p.plan(s.hsr, params, world, list ? *list : r.fullList(), s.width, s.height));
}

void ViewMeasure::frame(SceneRenderer& r, const DrawList* list, Timing& t, bool record) {
    stage_.backend().finish();
    const auto t0 = Clock::now();
    draw(r, list);
    stage_.backend().finish();
    if (record) t.draw.push_back(msSince(t0));
}

Result<ViewResult> ViewMeasure::run(std::size_t v, const ReportView& reportView, std::string& progressLine) {
    const Settings& s = s_.render;
    const std::vector<Cull>& methods = s_.methods;
    Backend& backend = stage_.backend();
    SceneRenderer& renderer = stage_.renderer();
    const TargetHandle target = stage_.target();
    Result<FrameSetup> setup =
        setUpFrame(scene_, reportView.camera, s_.time, s.width, s.height, false, s.depthFormat);
    if (!setup) return Error{"view " + std::to_string(v) + " (" + reportView.viewClass + "): " + setup.error().message};
    applyShading(s, setup->params);
    setup_.emplace(std::move(*setup));
    const FrameParams& params = setup_->params;
    const std::vector<glm::mat4>& world = setup_->world;

    // The reference colour, then the oracle (its id pass gives the RVS).
    renderer.renderFrame(target, s.width, s.height, params, world, s.background);
    const Buffers reference = backend.readBack(target);
    Result<Oracle> oracle = makeOracle(renderer, target, s.width, s.height, params, world, s.background);
    if (!oracle) return Error{"view " + std::to_string(v) + ": " + oracle.error().message};
    oracle_.emplace(std::move(*oracle));
    if (planner_) oraclePlanner_.emplace(*oracle_->scene);

    // Timed rounds: the methods asked for, then the baselines (none is the full draw and oracle the
    // oracle's: their rows take the baselines' times).
    std::vector<Timing> timings(methods.size());
    std::optional<OcclusionView> occlusionView;
    std::vector<double> passMs;
    const OcclusionTarget occlusionTarget = frugal::occlusionTarget(backend, s);
    Timing fullTiming, cullfaceTiming, oracleTiming;
    for (int round = -1; round < s_.repeat; ++round) {  // round -1: warm-up, untimed
        const bool record = round >= 0;
        for (std::size_t m = 0; m < methods.size(); ++m) {
            Timing& t = timings[m];
            const CullTraits& traits = traitsOf(methods[m]);
            if (!traits.prepares || traits.idPass) continue;
            if (traits.ahead) {
                // As a sequence runs it: this frame's plan was made while the frame before it drew
                // (the warm-up frame makes its own), and the next frame's (this view's next round)
                // is made while this one draws. The row's cull time is what the frame then waits for
                // that plan after its draw.
                std::optional<DrawList> made = ahead_.take(methods[m], world, setup_->view, occlusionTarget);
                t.list = made ? std::move(*made) : culler_.cull(methods[m], scene_, world, setup_->view, occlusionTarget);
                ahead_.start(culler_, methods[m], scene_, world, setup_->view, aheadTarget(occlusionTarget));
                frame(renderer, &t.list, t, record);
                const auto t0 = Clock::now();
                ahead_.wait();  // nothing else may use the culler while it runs
                if (record) t.cull.push_back(msSince(t0));
                continue;
            }
            const auto t0 = Clock::now();
            t.list = culler_.cull(methods[m], scene_, world, setup_->view, occlusionTarget);
            const double cullMs = msSince(t0);
            if (record) t.cull.push_back(cullMs);
            if (traits.occlusion && record) {
                if (!occlusionView) occlusionView.emplace();
                const OcclusionStats& o = culler_.occlusion().stats();
                ++occlusionView->frames;
                if (o.ran) ++occlusionView->runs, passMs.push_back(o.ms);
            }
            frame(renderer, &t.list, t, record);
        }
        frame(renderer, nullptr, fullTiming, record);
        renderer.setCullAllBackFaces(true);
        frame(renderer, nullptr, cullfaceTiming, record);
        renderer.setCullAllBackFaces(false);
        frame(*oracle_->renderer, nullptr, oracleTiming, record);
    }
    ahead_.settle();  // the plan of a round after the last
    const double fullMs = median(fullTiming.draw), cullfaceMs = median(cullfaceTiming.draw),
                 oracleMs = median(oracleTiming.draw);
    if (occlusionView) {
        // One more pass, untimed, that runs whatever the policy says: what it removes, and its buffer.
        OcclusionTarget always = occlusionTarget;
        always.adaptive = false;
        (void)culler_.cull(Cull::Occlusion, scene_, world, setup_->view, always);
        const OcclusionStats& o = culler_.occlusion().stats();
        occlusionView->passMs = passMs.empty() ? 0.0 : median(passMs);
        occlusionView->trianglesHidden = o.trianglesHidden;
        occlusionView->clustersHidden = o.clustersHidden;
        occlusionView->clustersTested = o.clustersTested;
        occlusionView->drawsSaved = o.drawsSaved;
        occlusionView->savedMs = o.savedMs;
        if (!s_.masksDir.empty()) {
            int w = 0, h = 0;
            const std::vector<std::uint8_t> rgba = culler_.occlusion().image(w, h);
            Result<Bytes> png = encodePng(w, h, 4, 8, rgba.data());
            if (!png) return Error{"view " + std::to_string(v) + ": occlusion buffer: " + png.error().message};
            occlusionView->image = s_.masksDir + "/occlusion-view-" + std::to_string(v) + ".png";
            images_.emplace_back(occlusionView->image, std::move(*png));
        }
    }

    ViewResult view;
    view.index = int(v);
    view.viewClass = reportView.viewClass;
    view.eye = setup_->view.eye;
    view.target = reportView.camera.target.value_or(setup_->view.eye + setup_->view.forward);
    std::ostringstream progress;
    progress << "rvs " << oracle_->rvs.count << " of " << scene_.primitiveCount() << ", full " << fmt(fullMs)
             << " ms, oracle " << fmt(oracleMs) << " ms";
    for (std::size_t m = 0; m < methods.size(); ++m) {
        Timing& t = timings[m];
        const CullTraits& traits = traitsOf(methods[m]);
        if (!traits.prepares) {
            t = fullTiming;
            t.list = renderer.fullList();
        } else if (traits.idPass) {
            t = oracleTiming;
        }
        MethodResult result;
        result.method = toString(methods[m]);
        const TriangleSet pvs = traits.idPass ? oracle_->rvs : drawnSet(scene_, t.list);
        const SetCounts counts = compareSets(scene_, pvs, oracle_->rvs);
        result.tos = counts.tos;
        result.pvs = counts.pvs;
        result.rvs = counts.rvs;
        result.misses = counts.misses;
        result.waste = counts.waste;
        // The image this plan draws, against the full render's.
        if (traits.idPass)
            draw(*oracle_->renderer, nullptr);
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
        if (traits.prepares && !traits.idPass)
            progress << "; " << result.method << " x" << fmt(std::round(result.ratioToOracle * 100) / 100)
                     << (result.misses ? " misses " + std::to_string(result.misses) : "");
        view.methods.push_back(std::move(result));
    }
    if (occlusionView) {
        progress << "; occlusion pass " << occlusionView->runs << "/" << occlusionView->frames << " frames, "
                 << fmt(occlusionView->passMs) << " ms, hides " << occlusionView->trianglesHidden << " triangles";
        view.occlusion = std::move(occlusionView);
    }
    progressLine = progress.str();
    return view;
}

// The report's document: cullReportJson's, with the pre-processing figures beside the paper's.
std::string documentOf(const CullReport& report, const Scene& scene, const SceneCuller& culler,
                       const CullMeasureSettings& s, const std::string& rendererName) {
    nlohmann::json json = nlohmann::json::parse(cullReportJson(report));
    nlohmann::json meshes = nlohmann::json::array();
    for (std::size_t i = 0; i < culler.maps().size(); ++i) {
        const MeshMap& map = culler.maps()[i];
        const PrepStats& p = map.stats;
        meshes.push_back({{"mesh", i}, {"name", scene.meshes[i].name}, {"triangles", scene.meshes[i].triangleCount()},
                          {"sphere_ms", p.sphereMs}, {"map_ms", p.mapMs}, {"cluster_ms", p.clusterMs},
                          {"hull_ms", p.hullMs}, {"total_ms", p.totalMs()}, {"map_bytes", p.mapBytes},
                          {"access_bytes", p.accessBytes}, {"clusters", map.clusters.size()},
                          {"hull_kind", hullKindName(map.hull.kind)}, {"hull_vertices", map.hull.vertices.size()},
                          {"hull_faces", map.hull.faces}, {"sphere_radius", map.sphere.radius}});
    }
    json["preprocess"] = {{"bins", {s.render.cullBinsTheta, s.render.cullBinsPhi}},
                          {"meshes", meshes},
                          {"paper_bunny", {{"hull_ms", 5000}, {"hull_vertices", 3023}, {"hull_faces", 6042},
                                           {"map_bytes", 4.3e6}, {"access_bytes", 0.51e6}}}};
    json["repeat"] = s.repeat;
    json["hsr"] = toString(s.render.hsr);
    json["renderer"] = rendererName;
    return json.dump(2) + "\n";
}

}  // namespace

std::string cullPreparedLine(const Scene& scene, const Renderer::CullPreparation& prep) {
    std::size_t triangles = 0;
    for (const Mesh& mesh : scene.meshes) triangles += mesh.triangleCount();
    std::string line = "cull: " + std::to_string(scene.meshes.size()) +
                       (scene.meshes.size() == 1 ? " mesh, " : " meshes, ") + std::to_string(triangles) +
                       " triangles prepared in " + fmt(prep.totalMs) + " ms (sphere " + fmt(prep.sphereMs) + ", map " +
                       fmt(prep.mapMs) + ", clusters " + fmt(prep.clusterMs);
    if (prep.hull) line += ", hull " + fmt(prep.hullMs);
    return line + ")";
}

SceneCuller prepareCulling(Scene& scene, const MapParams& bins,
                           const std::function<void(const std::string&)>& progress) {
    SceneCuller culler = SceneCuller::prepare(scene, bins);
    const PrepStats t = culler.totals();
    progress(cullPreparedLine(scene, {t.sphereMs, t.mapMs, t.clusterMs, t.hullMs, t.totalMs(), bins.hull}));
    return culler;
}

Result<CullMeasurement> measureCulling(Scene& scene, const std::vector<ReportView>& views,
                                       const CullMeasureSettings& settings,
                                       const std::function<void(const std::string&)>& progress) {
    const Settings& s = settings.render;
    MapParams bins{s.cullBinsTheta, s.cullBinsPhi};
    bins.hull = std::any_of(settings.methods.begin(), settings.methods.end(), [](Cull c) { return traitsOf(c).hull; });
    const SceneCuller culler = prepareCulling(scene, bins, progress);

    Result<Stage> stage = Stage::open(s);
    if (!stage) return stage.error();
    progress("backend: " + describe(stage->backend()));
    if (Result<bool> uploaded = stage->upload(scene); !uploaded) return uploaded.error();
    std::optional<hsr::Planner> planner;
    if (s.hsr != Hsr::ZBuffer) planner.emplace(scene);

    CullMeasurement measured;
    CullReport& report = measured.report;
    report.scene = settings.scene;
    report.width = s.width;
    report.height = s.height;
    report.backend = stage->backend().name();
    report.timing = settings.timing;
    for (std::size_t v = 0; v < views.size(); ++v) {
        ViewMeasure measure(scene, culler, *stage, settings, planner, measured.images);
        std::string line;
        Result<ViewResult> view = measure.run(v, views[v], line);
        if (!view) return view.error();
        progress("view " + std::to_string(v + 1) + "/" + std::to_string(views.size()) + " (" + view->viewClass +
                 "): " + line);
        report.views.push_back(std::move(*view));
    }
    measured.json = documentOf(report, scene, culler, settings, stage->backend().renderer());
    return measured;
}

std::string cullReportSummary(const CullMeasurement& measured, const std::vector<Cull>& methods) {
    const nlohmann::json json = nlohmann::json::parse(measured.json);
    std::string out =
        "method        median pvs  misses  views missed  pixels  cull ms  draw ms  /oracle  /full  /cullface  worst view\n";
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
        out += line;
    }
    // The occlusion pass over the views: how often it ran, what it cost and what it hides.
    int runs = 0, frames = 0;
    std::vector<double> pass, hidden;
    for (const ViewResult& view : measured.report.views)
        if (view.occlusion) {
            runs += view.occlusion->runs;
            frames += view.occlusion->frames;
            if (view.occlusion->runs > 0) pass.push_back(view.occlusion->passMs);
            hidden.push_back(double(view.occlusion->trianglesHidden));
        }
    if (frames > 0)
        out += "\nocclusion: the pass ran in " + std::to_string(runs) + " of " + std::to_string(frames) +
               " timed frames (median " + fmt(pass.empty() ? 0.0 : median(pass)) +
               " ms where it ran; it skips itself where it does not pay); run on every view, it hides a median of " +
               fmt(median(hidden)) + " triangles of conservative's plan\n";
    out += "\nclass     method        views  median pvs of tos   speed-up (full, cullface)  misses\n";
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
            out += line;
        }
    return out;
}

}  // namespace frugal
