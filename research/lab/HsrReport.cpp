#include "lab/HsrReport.h"

#include <algorithm>
#include <cstdio>
#include <numeric>

#include "renderer/Research.h"
#include "lab/PaperFigures.h"
#include "lab/ReportText.h"

namespace frugal {

using reporttext::Json;
using reporttext::number;

double paperFps(const std::string& mode) {
    if (mode == "zbuffer") return paper003::kZBufferFps;
    if (mode == "depthsort") return paper003::kDepthSortFps;
    if (mode == "adaptive") return paper003::kAdaptiveFps;  // adaptive-convex, sorted-zbuffer: ours, not in the paper
    return 0.0;
}

std::vector<HsrModeSummary> summarizeHsr(const HsrReport& report) {
    std::vector<HsrModeSummary> out;
    const auto mean = [](const std::vector<double>& v) {
        return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
    };
    for (const HsrModeResult& r : report.modes) {
        HsrModeSummary s;
        s.mode = r.mode;
        const double meanMs = mean(r.ms);
        s.fps = meanMs > 0.0 ? 1000.0 / meanMs : 0.0;
        s.medianMs = median(r.ms);
        if (!r.ms.empty()) {
            s.minMs = *std::min_element(r.ms.begin(), r.ms.end());
            s.maxMs = *std::max_element(r.ms.begin(), r.ms.end());
        }
        s.planMs = r.planMs.empty() ? 0.0 : median(r.planMs);
        s.paperFps = paperFps(r.mode);
        for (std::size_t px : r.differingPx) {
            s.differingPx += px;
            s.worstFramePx = std::max(s.worstFramePx, px);
            s.framesDiffering += px > 0 ? 1 : 0;
        }
        s.flaggedShare = mean(r.zbufferedShare);
        s.draws = median(std::vector<double>(r.draws.begin(), r.draws.end()));
        out.push_back(s);
    }
    if (!out.empty())
        for (HsrModeSummary& s : out) {
            s.speedup = out.front().fps > 0.0 ? s.fps / out.front().fps : 0.0;
            const double paperBase = paperFps(out.front().mode);
            s.paperSpeedup = paperBase > 0.0 && s.paperFps > 0.0 ? s.paperFps / paperBase : 0.0;
        }
    return out;
}

std::string hsrReportJson(const HsrReport& report) {
    const std::vector<HsrModeSummary> summary = summarizeHsr(report);
    Json modes = Json::array();
    for (std::size_t i = 0; i < summary.size(); ++i) {
        const HsrModeSummary& s = summary[i];
        const HsrModeResult& r = report.modes[i];
        Json perFrameMs = Json::array(), perFramePlan = Json::array(), perFrameShare = Json::array();
        for (double v : r.ms) perFrameMs.push_back(number(v));
        for (double v : r.planMs) perFramePlan.push_back(number(v));
        for (double v : r.zbufferedShare) perFrameShare.push_back(number(v));
        modes.push_back(Json{{"mode", s.mode},
                             {"fps", number(s.fps)},
                             {"median_ms", number(s.medianMs)},
                             {"min_ms", number(s.minMs)},
                             {"max_ms", number(s.maxMs)},
                             {"plan_ms", number(s.planMs)},
                             {"speedup", number(s.speedup)},
                             {"paper_fps", s.paperFps > 0.0 ? number(s.paperFps) : Json(nullptr)},
                             {"paper_speedup", s.paperSpeedup > 0.0 ? number(s.paperSpeedup) : Json(nullptr)},
                             {"differing_px", s.differingPx},
                             {"worst_frame_px", s.worstFramePx},
                             {"frames_differing", s.framesDiffering},
                             {"flagged_share", number(s.flaggedShare)},
                             {"draws", number(s.draws)},
                             {"per_frame", Json{{"ms", perFrameMs},
                                                {"plan_ms", perFramePlan},
                                                {"differing_px", r.differingPx},
                                                {"flagged_share", perFrameShare},
                                                {"polygons", r.polygons},
                                                {"draws", r.draws}}}});
    }
    const Json json{{"command", "hsr-bench"},
                    {"scene", report.scene},
                    {"size", {report.width, report.height}},
                    {"backend", report.backend},
                    {"renderer", report.renderer},
                    {"frames", {report.firstFrame, report.lastFrame}},
                    {"repeat", report.repeat},
                    {"polygons", report.polygons},
                    {"triangles", report.triangles},
                    {"paper", "Table 1 of paper 003: IPAQ 3660, 28 cubes (168 polygons), 240x320"},
                    {"modes", modes}};
    return reporttext::jsonText(json);
}

std::string hsrReportCsv(const HsrReport& report) {
    using reporttext::csvField;
    using reporttext::csvNumber;
    std::string csv =
        "scene,backend,width,height,mode,fps,median_ms,min_ms,max_ms,plan_ms,speedup,paper_fps,"
        "paper_speedup,differing_px,worst_frame_px,frames_differing,flagged_share,draws\n";
    for (const HsrModeSummary& s : summarizeHsr(report)) {
        csv += csvField(report.scene) + "," + csvField(report.backend) + "," + std::to_string(report.width) + "," +
               std::to_string(report.height) + "," + s.mode + "," + csvNumber(s.fps) + "," + csvNumber(s.medianMs) +
               "," + csvNumber(s.minMs) + "," + csvNumber(s.maxMs) + "," + csvNumber(s.planMs) + "," +
               csvNumber(s.speedup) + "," + (s.paperFps > 0 ? csvNumber(s.paperFps) : "") + "," +
               (s.paperSpeedup > 0 ? csvNumber(s.paperSpeedup) : "") + "," + std::to_string(s.differingPx) + "," +
               std::to_string(s.worstFramePx) + "," + std::to_string(s.framesDiffering) + "," +
               csvNumber(s.flaggedShare) + "," + csvNumber(s.draws) + "\n";
    }
    return csv;
}

std::string hsrReportGnuplot(const std::string& csvPath, const std::string& svgPath, const HsrReport& report) {
    using reporttext::gnuplotQuoted;
    return "# frugal-lab hsr-bench: speed-up over the z-buffer per mode, measured and the paper's (Table 1).\n"
           "# Drawn from the CSV; run gnuplot on this file to draw it again.\n"
           "set terminal svg size 720,420 dynamic background rgb 'white'\n"
           "set output " +
           gnuplotQuoted(svgPath) +
           "\n"
           "set datafile separator ','\n"
           "set title " +
           gnuplotQuoted("hidden-surface modes: " + report.scene + ", " + std::to_string(report.width) + "x" +
                         std::to_string(report.height) + ", " + report.backend) +
           " noenhanced\n"
           "set ylabel 'frames per second / z-buffer'\n"
           "set style data histograms\n"
           "set style histogram clustered gap 1\n"
           "set style fill solid 0.8 border -1\n"
           "set boxwidth 0.9\n"
           "set yrange [0:*]\n"
           "set grid ytics\n"
           "set key top left\n"
           "plot " +
           gnuplotQuoted(csvPath) + " using 11:xtic(5) title 'measured', '' using 13 title 'paper (IPAQ 3660)'\n";
}

std::string hsrReportText(const HsrReport& report) {
    std::string text = "hsr-bench " + report.scene + ", " + std::to_string(report.width) + "x" +
                       std::to_string(report.height) + ", " + report.backend + " (" + report.renderer + "), frames " +
                       std::to_string(report.firstFrame) + ":" + std::to_string(report.lastFrame) + " x" +
                       std::to_string(report.repeat) + ", " + std::to_string(report.polygons) + " polygons\n";
    char line[256];
    std::snprintf(line, sizeof line, "  %-15s %9s %10s %8s %9s %10s %13s %12s %11s %7s\n", "mode", "fps", "median ms",
                  "plan ms", "speed-up", "paper (x)", "differing px", "worst frame", "z-buffered", "draws");
    text += line;
    for (const HsrModeSummary& s : summarizeHsr(report)) {
        char paper[32] = "-";
        if (s.paperSpeedup > 0) std::snprintf(paper, sizeof paper, "%.2f", s.paperSpeedup);
        std::snprintf(line, sizeof line, "  %-15s %9.1f %10.3f %8.3f %9.2f %10s %13zu %12zu %10.1f%% %7.0f\n",
                      s.mode.c_str(), s.fps, s.medianMs, s.planMs, s.speedup, paper, s.differingPx, s.worstFramePx,
                      100.0 * s.flaggedShare, s.draws);
        text += line;
    }
    return text;
}

}  // namespace frugal
