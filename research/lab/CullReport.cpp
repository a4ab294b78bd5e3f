#include "lab/CullReport.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <nlohmann/json.hpp>

#include "renderer/Research.h"
#include "lab/ReportText.h"

namespace frugal {

namespace {

using namespace reporttext;

Json vec3(const glm::vec3& v) { return Json::array({number(v.x), number(v.y), number(v.z)}); }

// One method's rows over all views, in view order.
struct MethodRows {
    std::string method;
    std::vector<std::pair<const ViewResult*, const MethodResult*>> rows;
};

// Methods in the order they first appear.
std::vector<MethodRows> byMethod(const CullReport& report) {
    std::vector<MethodRows> methods;
    for (const ViewResult& view : report.views)
        for (const MethodResult& m : view.methods) {
            auto it = std::find_if(methods.begin(), methods.end(),
                                   [&m](const MethodRows& rows) { return rows.method == m.method; });
            if (it == methods.end()) it = methods.insert(methods.end(), MethodRows{m.method, {}});
            it->rows.emplace_back(&view, &m);
        }
    return methods;
}

Json summaryJson(const MethodRows& rows) {
    std::vector<double> pvs, cull, draw, oracle, full, cullface, cullShare;
    std::size_t totalMisses = 0, totalPixels = 0, viewsWithMisses = 0;
    // The worst view has the largest ratio to the oracle (NaN ranks below any number; ties: the first).
    const ViewResult* worstView = nullptr;
    const MethodResult* worst = nullptr;
    for (const auto& [view, m] : rows.rows) {
        pvs.push_back(double(m->pvs));
        cull.push_back(m->cullMs);
        draw.push_back(m->drawMs);
        oracle.push_back(m->ratioToOracle);
        full.push_back(m->ratioToFull);
        cullface.push_back(m->ratioToFullCullface);
        if (m->drawMs > 0.0) cullShare.push_back(m->cullMs / m->drawMs);
        totalMisses += m->misses;
        totalPixels += m->pixelsDiffering;
        viewsWithMisses += m->misses > 0;
        if (!worst || (!std::isnan(m->ratioToOracle) &&
                       (std::isnan(worst->ratioToOracle) || m->ratioToOracle > worst->ratioToOracle))) {
            worst = m;
            worstView = view;
        }
    }
    Json worstJson = nullptr;
    if (worst)
        worstJson = Json{{"index", worstView->index},
                         {"class", worstView->viewClass},
                         {"ratio_to_oracle", number(worst->ratioToOracle)}};
    return Json{{"views", rows.rows.size()},
                {"median_pvs", number(median(pvs))},
                {"median_cull_ms", number(median(cull))},
                {"median_draw_ms", number(median(draw))},
                {"median_ratio_to_oracle", number(median(oracle))},
                {"median_ratio_to_full", number(median(full))},
                {"median_ratio_to_full_cullface", number(median(cullface))},
                {"median_cull_over_draw", number(cullShare.empty() ? 0.0 : median(cullShare))},
                {"worst_view", worstJson},
                {"total_misses", totalMisses},
                {"total_pixels_differing", totalPixels},
                {"views_with_misses", viewsWithMisses}};
}

// Per view class (paper 002 reports partial and whole views apart), classes and methods by name:
// medians of pvs and of the speed-up over the full draw (plain and with GL face culling), and totals.
Json byClassJson(const CullReport& report) {
    std::map<std::string, std::map<std::string, std::vector<const MethodResult*>>> grouped;
    for (const ViewResult& view : report.views)
        for (const MethodResult& m : view.methods) grouped[view.viewClass][m.method].push_back(&m);
    Json byClass = Json::object();
    for (const auto& [viewClass, methods] : grouped)
        for (const auto& [method, results] : methods) {
            std::vector<double> pvs, speedUp, cullfaceSpeedUp;
            std::size_t misses = 0, pixels = 0;
            for (const MethodResult* m : results) {
                pvs.push_back(double(m->pvs));
                speedUp.push_back(1.0 / m->ratioToFull);
                cullfaceSpeedUp.push_back(1.0 / m->ratioToFullCullface);
                misses += m->misses;
                pixels += m->pixelsDiffering;
            }
            byClass[viewClass][method] = Json{{"views", results.size()},
                                              {"tos", results.front()->tos},
                                              {"median_pvs", number(median(pvs))},
                                              {"median_speed_up", number(median(speedUp))},
                                              {"median_speed_up_over_cullface", number(median(cullfaceSpeedUp))},
                                              {"total_misses", misses},
                                              {"total_pixels_differing", pixels}};
        }
    return byClass;
}

}  // namespace

std::string cullReportJson(const CullReport& report) {
    Json views = Json::array();
    for (const ViewResult& view : report.views) {
        Json methods = Json::array();
        for (const MethodResult& m : view.methods)
            methods.push_back(Json{{"method", m.method},
                                   {"tos", m.tos},
                                   {"pvs", m.pvs},
                                   {"rvs", m.rvs},
                                   {"misses", m.misses},
                                   {"waste", m.waste},
                                   {"pixels_differing", m.pixelsDiffering},
                                   {"cull_ms", number(m.cullMs)},
                                   {"draw_ms", number(m.drawMs)},
                                   {"ratio_to_oracle", number(m.ratioToOracle)},
                                   {"ratio_to_full", number(m.ratioToFull)},
                                   {"ratio_to_full_cullface", number(m.ratioToFullCullface)}});
        Json v{{"index", view.index},
               {"class", view.viewClass},
               {"eye", vec3(view.eye)},
               {"target", vec3(view.target)},
               {"methods", std::move(methods)}};
        if (const std::optional<OcclusionView>& o = view.occlusion)
            v["occlusion"] = Json{{"runs", o->runs},
                                  {"frames", o->frames},
                                  {"pass_ms", number(o->passMs)},
                                  {"triangles_hidden", o->trianglesHidden},
                                  {"clusters_hidden", o->clustersHidden},
                                  {"clusters_tested", o->clustersTested},
                                  {"draws_saved", o->drawsSaved},
                                  {"saved_ms_estimate", number(o->savedMs)},
                                  {"image", o->image.empty() ? Json() : Json(o->image)}};
        views.push_back(std::move(v));
    }
    Json summary = Json::object();
    for (const MethodRows& rows : byMethod(report)) summary[rows.method] = summaryJson(rows);
    const Json j = {{"scene", report.scene},          {"size", Json::array({report.width, report.height})},
                    {"backend", report.backend},      {"timing", report.timing},
                    {"views", std::move(views)},      {"summary", std::move(summary)},
                    {"by_class", byClassJson(report)}};
    return jsonText(j);
}

std::string cullReportCsv(const CullReport& report) {
    std::string csv =
        "view,class,method,tos,pvs,rvs,misses,waste,pixels_differing,cull_ms,draw_ms,ratio_to_oracle,"
        "ratio_to_full,ratio_to_full_cullface\n";
    for (const ViewResult& view : report.views)
        for (const MethodResult& m : view.methods) {
            csv += std::to_string(view.index) + ',' + csvField(view.viewClass) + ',' + csvField(m.method) + ',' +
                   std::to_string(m.tos) + ',' + std::to_string(m.pvs) + ',' + std::to_string(m.rvs) + ',' +
                   std::to_string(m.misses) + ',' + std::to_string(m.waste) + ',' + std::to_string(m.pixelsDiffering) +
                   ',' + csvNumber(m.cullMs) + ',' + csvNumber(m.drawMs) + ',' + csvNumber(m.ratioToOracle) + ',' +
                   csvNumber(m.ratioToFull) + ',' + csvNumber(m.ratioToFullCullface) + '\n';
        }
    return csv;
}

std::string cullReportGnuplot(const std::string& csvPath, const std::string& svgPath) {
    const std::string csv = gnuplotQuoted(csvPath);
    // Each method is a series filtered on column 3; a method absent from the CSV plots nothing. The
    // invisible point at (0, 0) keeps the ranges valid when the CSV has no rows at all.
    const std::string anchor = ", '+' using (0):(0) with points lc rgb '#FF000000' notitle\n";
    std::string s;
    s += "# frugal cull-report: the CSV's two plots (gnuplot 5, svg terminal)\n";
    s += "set terminal svg size 1000,700 dynamic enhanced font 'sans,10'\n";
    s += "set output " + gnuplotQuoted(svgPath) + "\n";
    s += "set datafile separator ','\n";
    s += "methods = \"none sphere backface cones paper conservative oracle\"\n";
    s += "n = words(methods)\n";
    s += "is(k) = strcol(3) eq word(methods, k)\n";
    s += "set key outside right top noenhanced\n";
    s += "set multiplot layout 2,1\n";
    // 1: time against misses.
    s += "set title 'cull + draw time against misses (one point per view)' noenhanced\n";
    s += "set xlabel 'misses (visible triangles not drawn)' noenhanced\n";
    s += "set ylabel 'cull + draw (ms)' noenhanced\n";
    s += "set offsets graph 0.03, graph 0.03, graph 0.05, 0\n";
    s += "plot for [k=1:n] " + csv +
         " skip 1 using (is(k) ? $7 : NaN):(is(k) ? $10 + $11 : NaN) with points lt k pt 7 title word(methods, k)" +
         anchor;
    // 2: per view, one bar per method (a fixed slot each), ratio to the oracle.
    s += "set title '(cull + draw) / oracle draw, per view' noenhanced\n";
    s += "set xlabel 'view' noenhanced\n";
    s += "set ylabel 'ratio to oracle' noenhanced\n";
    s += "set autoscale xfix\n";
    s += "set offsets 0.5, 0.5, graph 0.05, 0\n";
    s += "set xtics 1\n";
    s += "set style fill solid 0.8 border -1\n";
    s += "w = 0.8 / n\n";
    s += "set boxwidth w absolute\n";
    s += "plot for [k=1:n] " + csv +
         " skip 1 using (is(k) ? $1 + (k - (n + 1) / 2.0) * w : NaN):(is(k) ? $12 : NaN) with boxes lt k"
         " title word(methods, k), 1 with lines dt 2 lc 'black' title 'ratio 1'" +
         anchor;
    s += "unset multiplot\n";
    return s;
}

}  // namespace frugal
