#include "lab/ReuseReport.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "renderer/Research.h"
#include "lab/ReportText.h"

namespace frugal {

namespace {

using namespace reporttext;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Solves the k × k system g · x = b in place (Gaussian elimination, partial pivoting). False when
// a pivot is below `tiny` (the columns are dependent).
bool solve(std::vector<double>& g, std::vector<double>& b, std::size_t k, double tiny) {
    for (std::size_t c = 0; c < k; ++c) {
        std::size_t pivot = c;
        for (std::size_t r = c + 1; r < k; ++r)
            if (std::abs(g[r * k + c]) > std::abs(g[pivot * k + c])) pivot = r;
        if (!(std::abs(g[pivot * k + c]) > tiny)) return false;
        if (pivot != c) {
            for (std::size_t j = 0; j < k; ++j) std::swap(g[c * k + j], g[pivot * k + j]);
            std::swap(b[c], b[pivot]);
        }
        for (std::size_t r = c + 1; r < k; ++r) {
            const double f = g[r * k + c] / g[c * k + c];
            for (std::size_t j = c; j < k; ++j) g[r * k + j] -= f * g[c * k + j];
            b[r] -= f * b[c];
        }
    }
    for (std::size_t c = k; c-- > 0;) {
        double sum = b[c];
        for (std::size_t j = c + 1; j < k; ++j) sum -= g[c * k + j] * b[j];
        b[c] = sum / g[c * k + c];
    }
    return true;
}

bool finiteFrame(const ReuseBenchFrame& f) {
    return std::isfinite(f.fullMs) && std::isfinite(f.reuseMs) && std::isfinite(f.planMs);
}

// Medians of one set of frames.
Json mediansJson(const std::vector<const ReuseBenchFrame*>& frames) {
    std::vector<double> full, reuse, oracle, oracleWhole, plan;
    for (const ReuseBenchFrame* f : frames) {
        full.push_back(f->fullMs);
        reuse.push_back(f->reuseMs);
        oracle.push_back(f->oracleMs);
        oracleWhole.push_back(f->oracleWholeMs);
        plan.push_back(f->planMs);
    }
    const double fullMs = median(full), reuseMs = median(reuse), oracleMs = median(oracle);
    const double oracleWholeMs = median(oracleWhole);
    return Json{{"frames", frames.size()},
                {"median_full_ms", number(fullMs)},
                {"median_reuse_ms", number(reuseMs)},
                {"median_oracle_ms", number(oracleMs)},
                {"median_oracle_whole_ms", number(oracleWholeMs)},
                {"median_plan_ms", number(median(plan))},
                {"speedup", number(fullMs / reuseMs)},
                {"ratio_to_oracle", number(reuseMs / oracleMs)},
                {"ratio_to_oracle_whole", number(reuseMs / oracleWholeMs)}};
}

}  // namespace

double ReuseBenchFrame::staticShare() const {
    const double all = double(pDD) + double(pDS) + double(pSD) + double(pSS);
    return all > 0.0 ? (double(pSS) + double(pDS)) / all : kNaN;
}

std::vector<double> nonNegativeLeastSquares(const std::vector<std::vector<double>>& rows,
                                            const std::vector<double>& y) {
    const std::size_t n = rows.empty() ? 0 : std::min<std::size_t>(rows.front().size(), 8);
    const std::size_t m = std::min(rows.size(), y.size());
    std::vector<double> best(n, 0.0);
    if (m == 0 || n == 0) return best;
    // Columns scaled to unit norm, so one pivot threshold fits every unit (pixels, triangles, 1).
    std::vector<double> scale(n, 0.0);
    for (std::size_t j = 0; j < n; ++j) {
        double sum = 0.0;
        for (std::size_t i = 0; i < m; ++i) sum += rows[i][j] * rows[i][j];
        scale[j] = std::isfinite(sum) && sum > 0.0 ? std::sqrt(sum) : 0.0;
    }
    auto a = [&](std::size_t i, std::size_t j) { return rows[i][j] / scale[j]; };
    double bestResidual = 0.0;
    for (std::size_t i = 0; i < m; ++i) bestResidual += y[i] * y[i];
    std::vector<double> bestScaled(n, 0.0);
    std::vector<std::size_t> columns;
    std::vector<double> g, b;
    // Supports by size, so that a tie keeps the smaller one (found first).
    for (int size = 1; size <= int(n); ++size)
        for (unsigned mask = 1; mask < (1u << n); ++mask) {
            if (std::popcount(mask) != size) continue;
            columns.clear();
            bool usable = true;
            for (std::size_t j = 0; j < n; ++j)
                if (mask & (1u << j)) {
                    usable = usable && scale[j] > 0.0;
                    columns.push_back(j);
                }
            if (!usable) continue;
            const std::size_t k = columns.size();
            g.assign(k * k, 0.0);
            b.assign(k, 0.0);
            for (std::size_t i = 0; i < m; ++i)
                for (std::size_t r = 0; r < k; ++r) {
                    const double ar = a(i, columns[r]);
                    b[r] += ar * y[i];
                    for (std::size_t c = 0; c < k; ++c) g[r * k + c] += ar * a(i, columns[c]);
                }
            if (!solve(g, b, k, 1e-10)) continue;
            if (std::any_of(b.begin(), b.end(), [](double x) { return !(x >= 0.0); })) continue;
            double residual = 0.0;
            for (std::size_t i = 0; i < m; ++i) {
                double fitted = 0.0;
                for (std::size_t r = 0; r < k; ++r) fitted += a(i, columns[r]) * b[r];
                residual += (y[i] - fitted) * (y[i] - fitted);
            }
            if (residual < bestResidual - 1e-12 * std::max(1.0, bestResidual)) {
                bestResidual = residual;
                std::fill(bestScaled.begin(), bestScaled.end(), 0.0);
                for (std::size_t r = 0; r < k; ++r) bestScaled[columns[r]] = b[r];
            }
        }
    for (std::size_t j = 0; j < n; ++j) best[j] = scale[j] > 0.0 ? bestScaled[j] / scale[j] : 0.0;
    return best;
}

CostModel fitCostModel(const ReuseBench& bench) {
    CostModel model;
    model.twMs = std::isfinite(bench.clearMs) ? bench.clearMs : 0.0;
    // t_r: every frame's full render, over what the clear leaves.
    {
        std::vector<std::vector<double>> rows;
        std::vector<double> y;
        for (const ReuseBenchFrame& f : bench.frames)
            if (std::isfinite(f.fullMs)) {
                rows.push_back({double(f.drawnTris)});
                y.push_back(f.fullMs - model.twMs);
            }
        const std::vector<double> x = nonNegativeLeastSquares(rows, y);
        model.trNs = x.empty() ? 0.0 : x[0] * 1e6;
    }
    // The reuse fit: frames in reuse mode, the plan's own time taken out.
    std::vector<std::vector<double>> rows;
    std::vector<double> y;
    for (const ReuseBenchFrame& f : bench.frames) {
        if (f.mode != "reuse") {
            ++model.excludedFrames;
            continue;
        }
        if (!finiteFrame(f)) continue;
        rows.push_back({1.0, double(f.copiedPx), double(f.clearedPx), double(f.redrawnTris)});
        y.push_back(f.reuseMs - f.planMs);
    }
    model.fittedFrames = rows.size();
    const std::vector<double> x = rows.empty() ? std::vector<double>(4, 0.0) : nonNegativeLeastSquares(rows, y);
    model.t0Ms = x[0];
    model.tcNs = x[1] * 1e6;
    model.tiNs = x[2] * 1e6;
    model.trReuseNs = x[3] * 1e6;

    model.reuseR2 = kNaN;
    if (y.size() >= 2) {
        double mean = 0.0;
        for (double v : y) mean += v;
        mean /= double(y.size());
        double total = 0.0, residual = 0.0;
        for (std::size_t i = 0; i < y.size(); ++i) {
            const double fitted = x[0] * rows[i][0] + x[1] * rows[i][1] + x[2] * rows[i][2] + x[3] * rows[i][3];
            total += (y[i] - mean) * (y[i] - mean);
            residual += (y[i] - fitted) * (y[i] - fitted);
        }
        if (total > 0.0) model.reuseR2 = 1.0 - residual / total;
    }
    std::vector<double> reuseErrors, fullErrors;
    for (const ReuseBenchFrame& f : bench.frames) {
        if (std::isfinite(f.fullMs) && f.fullMs > 0.0)
            fullErrors.push_back(std::abs(fullModelMs(model, f) - f.fullMs) / f.fullMs);
        if (f.mode == "reuse" && finiteFrame(f) && f.reuseMs > 0.0)
            reuseErrors.push_back(std::abs(modelMs(model, f) - f.reuseMs) / f.reuseMs);
    }
    model.medianReuseError = median(reuseErrors);
    model.medianFullError = median(fullErrors);
    return model;
}

double fullModelMs(const CostModel& model, const ReuseBenchFrame& frame) {
    return model.twMs + model.trNs * 1e-6 * double(frame.drawnTris);
}

double modelMs(const CostModel& model, const ReuseBenchFrame& frame) {
    if (frame.mode == "reuse")
        return frame.planMs + model.t0Ms +
               1e-6 * (model.tcNs * double(frame.copiedPx) + model.tiNs * double(frame.clearedPx) +
                       model.trReuseNs * double(frame.redrawnTris));
    // Full: a clear and every triangle; rebuild: the same, and the whole target copied to the static pair.
    return frame.planMs + model.twMs + 1e-6 * model.trNs * double(frame.redrawnTris) +
           (frame.mode == "rebuild" ? 1e-6 * model.tcNs * double(frame.copiedPx) : 0.0);
}

namespace {

// The report as one document (reuseReportJson's text, reuseReportSummary's numbers).
Json reportDocument(const ReuseBench& bench) {
    const CostModel model = fitCostModel(bench);
    Json frames = Json::array();
    std::vector<const ReuseBenchFrame*> all, reuse;
    std::size_t full = 0, rebuild = 0;
    std::uint64_t ties = 0, errors = 0, framesWithErrors = 0;
    Json firstError = nullptr;
    double maxOverlap = 0.0, shareSum = 0.0;
    std::size_t shares = 0;
    for (const ReuseBenchFrame& f : bench.frames) {
        frames.push_back(Json{{"frame", f.frame},
                              {"mode", f.mode},
                              {"reason", f.reason},
                              {"full_ms", number(f.fullMs)},
                              {"reuse_ms", number(f.reuseMs)},
                              {"plan_ms", number(f.planMs)},
                              {"oracle_ms", number(f.oracleMs)},
                              {"oracle_whole_ms", number(f.oracleWholeMs)},
                              {"model_ms", number(modelMs(model, f))},
                              {"full_model_ms", number(fullModelMs(model, f))},
                              {"speedup", number(f.speedup())},
                              {"static_share", number(f.staticShare())},
                              {"p_dd", f.pDD},
                              {"p_ds", f.pDS},
                              {"p_sd", f.pSD},
                              {"p_ss", f.pSS},
                              {"copied_px", f.copiedPx},
                              {"cleared_px", f.clearedPx},
                              {"redrawn_tris", f.redrawnTris},
                              {"static_redrawn_tris", f.staticRedrawnTris},
                              {"drawn_tris", f.drawnTris},
                              {"rects", f.rects},
                              {"draws", f.draws},
                              {"full_draws", f.fullDraws},
                              {"overlap_ms", number(f.overlapMs)},
                              {"tie_px", f.tiePx},
                              {"error_px", f.errorPx}});
        all.push_back(&f);
        if (f.mode == "reuse")
            reuse.push_back(&f);
        else if (f.mode == "rebuild")
            ++rebuild;
        else
            ++full;
        ties += f.tiePx;
        errors += f.errorPx;
        if (f.errorPx > 0) {
            if (framesWithErrors == 0) firstError = f.frame;
            ++framesWithErrors;
        }
        if (std::isfinite(f.overlapMs)) maxOverlap = std::max(maxOverlap, f.overlapMs);
    }
    // The static share of the frames reuse applies to (a first frame counts everything static).
    for (const ReuseBenchFrame* f : reuse.empty() ? all : reuse)
        if (std::isfinite(f->staticShare())) {
            shareSum += f->staticShare();
            ++shares;
        }
    const Json reuseMedians = mediansJson(reuse);
    Json summary = {{"frames", bench.frames.size()},
                    {"modes", {{"full", full}, {"rebuild", rebuild}, {"reuse", reuse.size()}}},
                    {"speedup", reuseMedians["speedup"]},
                    {"ratio_to_oracle", reuseMedians["ratio_to_oracle"]},
                    {"ratio_to_oracle_whole", reuseMedians["ratio_to_oracle_whole"]}};
    if (reuse.empty())
        summary["note"] =
            bench.frames.size() <= 1
                ? "no frame in reuse mode: one frame has no predecessor to reuse (give --frames A:B with B > A)"
                : "no frame in reuse mode: every frame was a full render or a rebuild (see each frame's reason)";
    summary["reuse_frames"] = reuseMedians;
    summary["all_frames"] = mediansJson(all);
    summary["static_share"] = number(shares ? shareSum / double(shares) : kNaN);
    summary["static_pair_bytes"] = bench.staticPairBytes;
    summary["max_overlap_ms"] = number(maxOverlap);
    summary["total_tie_px"] = ties;
    summary["total_error_px"] = errors;
    summary["frames_with_errors"] = framesWithErrors;
    summary["first_error_frame"] = firstError;
    summary["model"] = Json{{"t_w_ms", number(model.twMs)},
                            {"t_r_ns_per_tri", number(model.trNs)},
                            {"t_0_ms", number(model.t0Ms)},
                            {"t_c_ns_per_px", number(model.tcNs)},
                            {"t_i_ns_per_px", number(model.tiNs)},
                            {"t_r_reuse_ns_per_tri", number(model.trReuseNs)},
                            {"fitted_frames", model.fittedFrames},
                            {"excluded_frames", model.excludedFrames},
                            {"r2", number(model.reuseR2)},
                            {"median_reuse_error", number(model.medianReuseError)},
                            {"median_full_error", number(model.medianFullError)}};
    Json j = {{"scene", bench.scene},
              {"size", Json::array({bench.width, bench.height})},
              {"backend", bench.backend},
              {"renderer", bench.renderer},
              {"repeat", bench.repeat},
              {"cull", bench.cull},
              {"reuse", {{"grain", bench.grain}, {"cell", bench.cell}, {"fallback", bench.fallback}}},
              {"ids", bench.ids},
              {"frames", std::move(frames)},
              {"summary", std::move(summary)}};
    return j;
}

double numberOr(const Json& value, double fallback) { return value.is_number() ? value.get<double>() : fallback; }

std::string percent(double share) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f %%", 100.0 * share);
    return buf;
}

}  // namespace

std::string reuseReportJson(const ReuseBench& bench) { return jsonText(reportDocument(bench)); }

std::string reuseReportSummary(const ReuseBench& bench) {
    const Json document = reportDocument(bench);
    const Json& summary = document["summary"];
    const Json& modes = summary["modes"];
    const int first = bench.frames.empty() ? 0 : bench.frames.front().frame;
    const int last = bench.frames.empty() ? 0 : bench.frames.back().frame;
    std::ostringstream out;
    out << "reuse-bench " << bench.scene << ", " << bench.width << "x" << bench.height << ", " << bench.backend
        << ", frames " << first << ".." << last << ", " << bench.repeat << (bench.repeat == 1 ? " round" : " rounds")
        << (bench.cull != "none" ? ", cull " + bench.cull : std::string()) << "\n";
    out << "frames " << bench.frames.size() << ": reuse " << modes["reuse"].get<std::size_t>() << ", rebuild "
        << modes["rebuild"].get<std::size_t>() << ", full " << modes["full"].get<std::size_t>() << "; static share "
        << percent(numberOr(summary["static_share"], 0.0)) << " of the triangles (mean over reuse frames)\n";
    // oracle ms: the cells oracle (copies what reuse copies); whole ms: the whole oracle (copies the whole image).
    out << "                frames   full ms  reuse ms  oracle ms  whole ms  plan ms  speed-up  reuse/oracle  "
           "reuse/whole\n";
    for (const char* set : {"reuse_frames", "all_frames"}) {
        const Json& s = summary[set];
        char line[256];
        std::snprintf(line, sizeof line, "%-14s %7zu %9.3f %9.3f %10.3f %9.3f %8.3f %9.3f %13.3f %12.3f\n",
                      set == std::string("reuse_frames") ? "reuse frames" : "all frames",
                      s["frames"].get<std::size_t>(), numberOr(s["median_full_ms"], kNaN),
                      numberOr(s["median_reuse_ms"], kNaN), numberOr(s["median_oracle_ms"], kNaN),
                      numberOr(s["median_oracle_whole_ms"], kNaN), numberOr(s["median_plan_ms"], kNaN),
                      numberOr(s["speedup"], kNaN), numberOr(s["ratio_to_oracle"], kNaN),
                      numberOr(s["ratio_to_oracle_whole"], kNaN));
        out << line;
    }
    const Json& m = summary["model"];
    out << "cost model: full = t_w " << fmt(numberOr(m["t_w_ms"], kNaN)) << " ms + t_r "
        << fmt(numberOr(m["t_r_ns_per_tri"], kNaN)) << " ns/triangle (median error "
        << percent(numberOr(m["median_full_error"], kNaN)) << ")\n";
    out << "            reuse = plan + t_0 " << fmt(numberOr(m["t_0_ms"], kNaN)) << " ms + t_c "
        << fmt(numberOr(m["t_c_ns_per_px"], kNaN)) << " ns/px copied + t_i " << fmt(numberOr(m["t_i_ns_per_px"], kNaN))
        << " ns/px cleared + t_r' " << fmt(numberOr(m["t_r_reuse_ns_per_tri"], kNaN)) << " ns/triangle (fitted on "
        << m["fitted_frames"].get<std::size_t>() << " reuse frames, " << m["excluded_frames"].get<std::size_t>()
        << " full/rebuild left out; R² " << fmt(numberOr(m["r2"], kNaN)) << ", median error "
        << percent(numberOr(m["median_reuse_error"], kNaN)) << ")\n";
    out << "static pair " << summary["static_pair_bytes"].get<std::uint64_t>() << " bytes, max overlap "
        << fmt(numberOr(summary["max_overlap_ms"], 0.0)) << " ms, ties " << summary["total_tie_px"].get<std::uint64_t>()
        << " px, errors " << summary["total_error_px"].get<std::uint64_t>() << " px\n";
    if (summary.contains("note")) out << "note: " << summary["note"].get<std::string>() << "\n";
    return out.str();
}

std::string reuseReportCsv(const ReuseBench& bench) {
    const CostModel model = fitCostModel(bench);
    std::string csv =
        "frame,mode,full_ms,reuse_ms,plan_ms,oracle_ms,oracle_whole_ms,model_ms,full_model_ms,speedup,static_share,"
        "p_dd,p_ds,p_sd,p_ss,copied_px,cleared_px,redrawn_tris,static_redrawn_tris,drawn_tris,rects,draws,full_draws,"
        "overlap_ms,tie_px,error_px,reason\n";
    for (const ReuseBenchFrame& f : bench.frames) {
        csv += std::to_string(f.frame) + ',' + csvField(f.mode) + ',' + csvNumber(f.fullMs) + ',' +
               csvNumber(f.reuseMs) + ',' + csvNumber(f.planMs) + ',' + csvNumber(f.oracleMs) + ',' +
               csvNumber(f.oracleWholeMs) + ',' + csvNumber(modelMs(model, f)) + ',' +
               csvNumber(fullModelMs(model, f)) + ',' + csvNumber(f.speedup()) + ',' + csvNumber(f.staticShare()) +
               ',' + std::to_string(f.pDD) + ',' + std::to_string(f.pDS) + ',' + std::to_string(f.pSD) + ',' +
               std::to_string(f.pSS) + ',' + std::to_string(f.copiedPx) + ',' + std::to_string(f.clearedPx) + ',' +
               std::to_string(f.redrawnTris) + ',' + std::to_string(f.staticRedrawnTris) + ',' +
               std::to_string(f.drawnTris) + ',' + std::to_string(f.rects) + ',' + std::to_string(f.draws) + ',' +
               std::to_string(f.fullDraws) + ',' + csvNumber(f.overlapMs) + ',' + std::to_string(f.tiePx) + ',' +
               std::to_string(f.errorPx) + ',' + csvField(f.reason) + '\n';
    }
    return csv;
}

std::string reuseReportGnuplot(const std::string& csvPath, const std::string& svgPath, int firstFrame) {
    const std::string csv = gnuplotQuoted(csvPath);
    // An invisible point keeps the ranges valid when the CSV has no rows at all (and, at the first
    // frame, does not stretch the frame axis).
    const auto anchor = [](double x) {
        return ", '+' using (" + csvNumber(x) + "):(1) with points lc rgb '#FF000000' notitle\n";
    };
    std::string s;
    s += "# frugal-lab reuse-bench: the CSV's two plots (gnuplot 5, svg terminal)\n";
    s += "set terminal svg size 1000,800 dynamic enhanced font 'sans,10'\n";
    s += "set output " + gnuplotQuoted(svgPath) + "\n";
    s += "set datafile separator ','\n";
    s += "modes = \"reuse rebuild full\"\n";
    s += "is(k) = strcol(2) eq word(modes, k)\n";
    // Paper 000 (software, P-II 266): 804 polygons 55.44 % static 316 -> 170 ms; 1,404 polygons 98.66 % 158 -> 19 ms.
    s += "$paper << EOD\n55.44,1.8588,804 polygons\n98.66,8.3158,1404 polygons\nEOD\n";
    s += "set key outside right top noenhanced\n";
    s += "set multiplot layout 2,1\n";
    // 1: speed-up against the static share.
    s += "set title 'speed-up (full ÷ reuse) against the static share, one point per frame' noenhanced\n";
    s += "set xlabel 'static triangles (%)' noenhanced\n";
    s += "set ylabel 'speed-up' noenhanced\n";
    s += "set xrange [0:100]\n";
    s += "set yrange [0:*]\n";
    s += "plot for [k=1:3] " + csv +
         " skip 1 using (is(k) ? 100 * $11 : NaN):(is(k) ? $10 : NaN) with points lt k pt 7 title word(modes, k), "
         "$paper using 1:2 with points pt 5 ps 1.5 lc 'black' title 'paper 000', "
         "$paper using 1:2:3 with labels offset char -1,1 right notitle, "
         "1 with lines dt 2 lc 'black' title 'speed-up 1'" +
         anchor(50.0);
    // 2: the times per frame.
    s += "set title 'time per frame (medians of the rounds)' noenhanced\n";
    s += "set xlabel 'frame' noenhanced\n";
    s += "set ylabel 'ms' noenhanced\n";
    s += "set autoscale x\n";
    s += "set yrange [0:*]\n";
    s += "plot " + csv + " skip 1 using 1:3 with linespoints pt 7 ps 0.5 title 'full', " + csv +
         " skip 1 using 1:4 with linespoints pt 7 ps 0.5 title 'reuse', " + csv +
         " skip 1 using 1:6 with linespoints pt 7 ps 0.5 title 'oracle (cells)', " + csv +
         " skip 1 using 1:7 with linespoints pt 7 ps 0.5 title 'oracle (whole)', " + csv +
         " skip 1 using 1:8 with lines dt 2 title 'model'" + anchor(firstFrame);
    s += "unset multiplot\n";
    return s;
}

}  // namespace frugal
