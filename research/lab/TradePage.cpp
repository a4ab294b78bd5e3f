#include "lab/TradePage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>

#include "renderer/Research.h"
#include "lab/PaperFigures.h"
#include "lab/ReportText.h"

namespace frugal {

using reporttext::csvField;
using reporttext::csvNumber;

std::string base64(const Bytes& bytes) {
    static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
        std::uint32_t v = std::uint32_t(bytes[i]) << 16;
        if (n > 1) v |= std::uint32_t(bytes[i + 1]) << 8;
        if (n > 2) v |= bytes[i + 2];
        out += kDigits[(v >> 18) & 63];
        out += kDigits[(v >> 12) & 63];
        out += n > 1 ? kDigits[(v >> 6) & 63] : '=';
        out += n > 2 ? kDigits[v & 63] : '=';
    }
    return out;
}

std::string methodSlug(const std::string& name) {
    std::string out;
    for (const char c : name) {
        if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9'))
            out += c;
        else if (c >= 'A' && c <= 'Z')
            out += char(c - 'A' + 'a');
        else if (!out.empty() && out.back() != '-')
            out += '-';
    }
    while (!out.empty() && out.back() == '-') out.pop_back();
    return out.empty() ? "method" : out;
}

Buffers maskThumbnail(const Buffers& mask, int maxWidth) {
    const int factor = std::max(1, (mask.width + maxWidth - 1) / std::max(maxWidth, 1));
    Buffers out;
    out.width = (mask.width + factor - 1) / factor;
    out.height = (mask.height + factor - 1) / factor;
    out.rgba.assign(out.pixelCount() * 4, 0);
    for (int ty = 0; ty < out.height; ++ty)
        for (int tx = 0; tx < out.width; ++tx) {
            bool differs = false;
            unsigned grey = 0, count = 0;
            for (int y = ty * factor; y < std::min(mask.height, (ty + 1) * factor); ++y)
                for (int x = tx * factor; x < std::min(mask.width, (tx + 1) * factor); ++x) {
                    const std::uint8_t* p = &mask.rgba[(std::size_t(y) * std::size_t(mask.width) + std::size_t(x)) * 4];
                    differs = differs || (p[0] == 255 && p[1] == 0 && p[2] == 0);  // grey has r = g = b
                    grey += p[0];
                    ++count;
                }
            std::uint8_t* q = &out.rgba[(std::size_t(ty) * std::size_t(out.width) + std::size_t(tx)) * 4];
            const auto g = std::uint8_t(grey / std::max(count, 1u));
            q[0] = differs ? 255 : g;
            q[1] = differs ? 0 : g;
            q[2] = differs ? 0 : g;
            q[3] = 255;
        }
    return out;
}

namespace {

std::string escape(const std::string& text) {
    std::string out;
    for (const char c : text) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        case '\'': out += "&#39;"; break;
        default: out += c;
        }
    }
    return out;
}

std::string fixed(double value, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
    return buf;
}

// 1234567 -> "1,234,567".
std::string grouped(std::uint64_t value) {
    std::string digits = std::to_string(value), out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

std::string bytesText(std::uint64_t bytes) {
    if (bytes == 0) return "0";
    if (bytes < 1024 * 1024) return fixed(double(bytes) / 1024.0, 1) + " KiB";
    return fixed(double(bytes) / (1024.0 * 1024.0), 1) + " MiB";
}

std::string psnrText(double psnr) { return std::isinf(psnr) ? "&infin;" : fixed(psnr, 1); }

int levelPercent() { return int(std::lround(100.0 * kIntervalLevel)); }

// "0.891 [0.874, 0.905]": a row's paired ratio to the plain render and its interval.
std::string pairedText(const PairedRatio& p) {
    if (p.pairs == 0) return "";
    if (!p.known()) return fixed(p.estimate, 3) + " <small>(too few pairs for an interval)</small>";
    return fixed(p.estimate, 3) + " <small>[" + fixed(p.low, 3) + ", " + fixed(p.high, 3) + "]</small>";
}

const char* familyColor(const std::string& family) {
    static const std::map<std::string, const char*> colors{
        {"plain", "#333333"}, {"cull", "#1f77b4"},  {"order", "#ff7f0e"},       {"hsr", "#2ca02c"},
        {"interp", "#9467bd"}, {"reuse", "#d62728"}, {"combination", "#8c564b"}, {"floor", "#7f7f7f"},
        {"shading", "#e377c2"}};
    const auto found = colors.find(family);
    return found == colors.end() ? "#000000" : found->second;
}

// A step of 1, 2 or 5 times a power of ten giving about `count` ticks over [0, top].
double niceStep(double top, int count) {
    const double raw = std::max(top, 1e-9) / count;
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    for (const double m : {1.0, 2.0, 5.0})
        if (m * power >= raw) return m * power;
    return 10.0 * power;
}

// The Pareto chart: median ms (x) against the differing pixels over all shots (y, log(1 + px) so that
// exact methods sit on the axis), a point per method, the front joined, the plain render and the
// floor as vertical lines.
std::string paretoSvg(const TradeReport& report) {
    constexpr double kW = 760, kH = 440, kLeft = 70, kRight = 590, kTop = 20, kBottom = 380;
    double maxMs = 0;
    std::uint64_t maxPx = 0;
    for (const TradeRow& r : report.rows) {
        maxMs = std::max(maxMs, r.medianMs);
        maxPx = std::max(maxPx, r.differingPx);
    }
    const double xStep = niceStep(maxMs * 1.05, 6);
    const double xTop = std::max(xStep, std::ceil(maxMs * 1.05 / xStep) * xStep);
    const int decades = std::max(1, int(std::ceil(std::log10(1.0 + double(maxPx)))));
    const auto x = [&](double ms) { return kLeft + (kRight - kLeft) * ms / xTop; };
    const auto y = [&](std::uint64_t px) { return kBottom - (kBottom - kTop) * std::log10(1.0 + double(px)) / decades; };

    std::ostringstream s;
    s << "<svg id=\"pareto\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << kW << " " << kH
      << "\" width=\"" << kW << "\" height=\"" << kH << "\" role=\"img\" aria-label=\"median time against differing pixels\">\n";
    s << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << kRight - kLeft << "\" height=\"" << kBottom - kTop
      << "\" fill=\"#fafafa\" stroke=\"#999\"/>\n";
    for (double v = 0; v <= xTop + xStep / 2; v += xStep)
        s << "<line x1=\"" << fixed(x(v), 1) << "\" y1=\"" << kBottom << "\" x2=\"" << fixed(x(v), 1) << "\" y2=\"" << kTop
          << "\" stroke=\"#e4e4e4\"/><text x=\"" << fixed(x(v), 1) << "\" y=\"" << kBottom + 16
          << "\" text-anchor=\"middle\">" << fmt(v) << "</text>\n";
    for (int d = 0; d <= decades; ++d) {
        const std::uint64_t px = d == 0 ? 0 : std::uint64_t(std::llround(std::pow(10.0, d)));
        s << "<line x1=\"" << kLeft << "\" y1=\"" << fixed(y(px), 1) << "\" x2=\"" << kRight << "\" y2=\""
          << fixed(y(px), 1) << "\" stroke=\"#e4e4e4\"/><text x=\"" << kLeft - 6 << "\" y=\"" << fixed(y(px) + 4, 1)
          << "\" text-anchor=\"end\">" << (d == 0 ? "0" : d <= 3 ? grouped(px) : "1e" + std::to_string(d)) << "</text>\n";
    }
    s << "<text x=\"" << (kLeft + kRight) / 2 << "\" y=\"" << kBottom + 36
      << "\" text-anchor=\"middle\">median time a frame (ms)</text>\n";
    s << "<text transform=\"translate(16 " << (kTop + kBottom) / 2
      << ") rotate(-90)\" text-anchor=\"middle\">differing pixels, all frames (log scale)</text>\n";

    // Labelled at the bottom, above the axis, one under the other (the points near them are few: the
    // exact methods sit on the axis only right of the floor).
    const auto vertical = [&](double ms, const std::string& label, const char* dash, double labelY) {
        s << "<line x1=\"" << fixed(x(ms), 1) << "\" y1=\"" << kBottom << "\" x2=\"" << fixed(x(ms), 1) << "\" y2=\"" << kTop
          << "\" stroke=\"#555\" stroke-dasharray=\"" << dash << "\"/><text x=\"" << fixed(x(ms) - 3, 1) << "\" y=\""
          << labelY << "\" font-size=\"11\" text-anchor=\"end\">" << escape(label) << "</text>\n";
    };
    vertical(report.rows.front().medianMs, "plain", "2 3", kBottom - 34);
    if (const std::optional<double> f = report.floorMs()) vertical(*f, "floor (oracle)", "6 3", kBottom - 20);

    std::vector<std::size_t> front = report.pareto;
    std::sort(front.begin(), front.end(),
              [&](std::size_t a, std::size_t b) { return report.rows[a].medianMs < report.rows[b].medianMs; });
    s << "<polyline class=\"front\" fill=\"none\" stroke=\"#222\" stroke-width=\"1.5\" points=\"";
    for (const std::size_t i : front)
        s << fixed(x(report.rows[i].medianMs), 1) << "," << fixed(y(report.rows[i].differingPx), 1) << " ";
    s << "\"/>\n";
    for (std::size_t i = 0; i < report.rows.size(); ++i) {
        const TradeRow& r = report.rows[i];
        s << "<circle cx=\"" << fixed(x(r.medianMs), 1) << "\" cy=\"" << fixed(y(r.differingPx), 1) << "\" r=\""
          << (report.onFront(i) ? 6 : 4) << "\" fill=\"" << familyColor(r.candidate.family)
          << "\" fill-opacity=\"0.85\"><title>" << escape(r.candidate.name) << ": " << fixed(r.medianMs, 2) << " ms, "
          << grouped(r.differingPx) << " px differ</title></circle>\n";
        if (report.onFront(i))
            s << "<text x=\"" << fixed(x(r.medianMs) + 8, 1) << "\" y=\"" << fixed(y(r.differingPx) - 8, 1)
              << "\" font-size=\"11\">" << escape(r.candidate.name) << "</text>\n";
    }
    // The legend: a colour per family present.
    double ly = kTop + 6;
    std::vector<std::string> seen;
    for (const TradeRow& r : report.rows) {
        if (std::find(seen.begin(), seen.end(), r.candidate.family) != seen.end()) continue;
        seen.push_back(r.candidate.family);
        s << "<circle cx=\"" << kRight + 20 << "\" cy=\"" << ly << "\" r=\"5\" fill=\"" << familyColor(r.candidate.family)
          << "\"/><text x=\"" << kRight + 32 << "\" y=\"" << ly + 4 << "\">" << escape(r.candidate.family) << "</text>\n";
        ly += 20;
    }
    s << "<text x=\"" << kRight + 14 << "\" y=\"" << ly + 10 << "\" font-size=\"11\">line: the front</text>\n";
    s << "</svg>\n";
    return s.str();
}

std::string recommendationHtml(const TradeReport& report, const TradeSettings& settings) {
    const TradeRow& plain = report.rows.front();
    const auto line = [&](const std::string& what, const std::optional<std::size_t>& pick) {
        std::string s = "<p><b>" + escape(what) + ":</b> ";
        if (!pick)
            return s + "plain render (" + fixed(plain.medianMs, 2) + " ms a frame): no method is surely at least " +
                   fixed(100.0 * (1.0 - kPays), 0) + " % faster on this scene (none has the " +
                   std::to_string(levelPercent()) + " % interval of its paired ratio below " + fixed(kPays, 2) +
                   ", a no-op aside).</p>\n";
        const TradeRow& row = report.rows[*pick];
        return s + "<code>" + escape(row.candidate.name) + "</code>, " + fixed(row.medianMs, 2) + " ms a frame, " +
               fixed(row.medianMs / plain.medianMs, 2) + "&times; the plain render's " + fixed(plain.medianMs, 2) +
               " ms; paired with it shot by shot, " + fixed(row.paired.estimate, 3) + "&times; (" +
               std::to_string(levelPercent()) + " % interval " + fixed(row.paired.low, 3) + "&ndash;" +
               fixed(row.paired.high, 3) + "); " + grouped(row.differingPx) + " pixels differ.</p>\n";
    };
    return "<section id=\"recommendation\">\n" + line("Fastest exact", report.bestExact) +
           line("Fastest within " + grouped(settings.budgetPx) + " differing pixels a frame", report.bestWithinBudget) +
           "<p>Use it: <code>frugal render SCENE --settings settings.json</code>, "
           "<code>frugal::readSettingsFile(\"settings.json\")</code> or "
           "<code>frugal.Renderer(scene, settings=\"settings.json\")</code>.</p>\n</section>\n";
}

std::string methodsTable(const TradeReport& report, const std::map<std::size_t, std::string>& thumbnails) {
    std::ostringstream s;
    s << "<table id=\"methods\">\n<thead><tr><th>method</th><th>family</th><th>median ms</th><th>&times; plain</th>"
         "<th>paired &times; plain [" << levelPercent() << " %]</th><th>&times; floor</th><th>differing px</th><th>worst frame px</th><th>misses</th><th>worst PSNR dB</th>"
         "<th>worst depth</th><th>submitted</th><th>binds a frame</th><th>extra memory</th><th>prepare ms</th>"
         "<th>front</th><th>error mask (worst frame)</th></tr></thead>\n<tbody>\n";
    for (std::size_t i = 0; i < report.rows.size(); ++i) {
        const TradeRow& r = report.rows[i];
        const bool picked = report.bestExact == i || report.bestWithinBudget == i;
        s << "<tr" << (picked ? " class=\"picked\"" : r.candidate.floor ? " class=\"floor\"" : "") << "><td>"
          << escape(r.candidate.name) << "</td><td>" << escape(r.candidate.family) << "</td><td>" << fixed(r.medianMs, 3)
          << "</td><td>" << fixed(report.xPlain(r), 3) << "</td><td" << (report.pays(i) ? " class=\"pays\"" : "")
          << ">" << (i > 0 ? pairedText(r.paired) : "");
        if (r.noOp())
            s << "<br><small>no-op: draws the plain render's draws</small>";
        else if (r.sameDrawsAs)
            s << "<br><small>adds nothing to " << escape(report.rows[*r.sameDrawsAs].candidate.name)
              << ": draws its draws</small>";
        s << "</td><td>" << (report.xFloor(r) ? fixed(*report.xFloor(r), 2) : "") << "</td><td>" << grouped(r.differingPx)
          << "</td><td>" << grouped(r.worstFramePx) << "</td><td>" << grouped(r.misses) << "</td><td>"
          << psnrText(r.worstPsnr) << "</td><td>"
          << r.worstDepth << "</td><td>" << fixed(100.0 * r.submittedShare, 1) << " %</td><td>"
          << fixed(r.stateChanges, 0) << "</td><td>" << bytesText(r.extraBytes) << "</td><td>"
          << (r.prepareMs > 0 ? fixed(r.prepareMs, 1) : "") << "</td><td>" << (report.onFront(i) ? "&#9679;" : "")
          << "</td><td>";
        if (const auto t = thumbnails.find(i); t != thumbnails.end())
            s << "<a href=\"masks/" << methodSlug(r.candidate.name) << ".png\"><img class=\"mask\" src=\"data:image/png;base64,"
              << t->second << "\" alt=\"error mask of " << escape(r.candidate.name) << "\"></a><br><small>"
              << escape(r.worstShot) << ": " << grouped(r.worstFramePx) << " px</small>";
        else if (i > 0)
            s << (r.exact() ? "exact" : r.differingPx == 0 ? "colour exact; depth differs" : "");
        else
            s << "the reference";
        s << "</td></tr>\n";
    }
    s << "</tbody>\n</table>\n";
    return s.str();
}

// The published figures of the methods this report measured.
std::vector<std::pair<const PaperFigure*, const TradeRow*>> paperPairs(const TradeReport& report) {
    std::vector<std::pair<const PaperFigure*, const TradeRow*>> out;
    for (const PaperFigure& f : paperFigures())
        for (const TradeRow& r : report.rows)
            if (r.candidate.name == f.method) out.emplace_back(&f, &r);
    return out;
}

std::string papersTable(const TradeReport& report) {
    std::ostringstream s;
    s << "<table id=\"papers\">\n<thead><tr><th>method</th><th>paper</th><th>table</th><th>its setting</th>"
         "<th>its baseline</th><th>its result</th><th>paper: &times; baseline</th><th>this run: &times; plain</th>"
         "<th>this run: differing px</th><th>the ratio is of</th></tr></thead>\n<tbody>\n";
    for (const auto& [f, r] : paperPairs(report))
        s << "<tr><td>" << escape(f->method) << "</td><td>" << f->paper << "</td><td>" << escape(f->source) << "</td><td>"
          << escape(f->setting) << "</td><td>" << escape(f->baseline) << "</td><td>" << escape(f->result) << "</td><td>"
          << fixed(f->timeRatio, 3) << "</td><td>" << fixed(report.xPlain(*r), 3) << "</td><td>"
          << grouped(r->differingPx) << "</td><td>" << escape(f->unit) << "</td></tr>\n";
    s << "</tbody>\n</table>\n";
    return s.str();
}

constexpr const char* kStyle = R"(body{font:14px/1.45 system-ui,sans-serif;margin:24px auto;max-width:1240px;color:#222;padding:0 12px}
h1{font-size:22px;margin-bottom:4px}h2{font-size:17px;margin-top:28px}
.meta{color:#555;margin-top:0}
#recommendation{background:#eef6ee;border:1px solid #9c9;padding:8px 14px;border-radius:4px}
#recommendation p{margin:6px 0}
svg text{font-size:12px;fill:#222}
table{border-collapse:collapse;margin-top:8px}
th,td{border:1px solid #ccc;padding:3px 7px;text-align:right;vertical-align:middle}
th{background:#f3f3f3}
td:first-child,td:nth-child(2),#papers td{text-align:left}
tr.picked td{background:#eef6ee;font-weight:600}
td.pays{font-weight:600}
tr.floor td{color:#777}
img.mask{width:160px;image-rendering:pixelated;border:1px solid #999;display:block}
code{background:#f3f3f3;padding:0 3px}
)";

}  // namespace

std::string paperFiguresCsv(const TradeReport& report) {
    std::string out = "method,paper,source,setting,baseline,result,paper_ratio,unit,x_plain,differing_px\n";
    for (const auto& [f, r] : paperPairs(report))
        out += csvField(f->method) + "," + csvField(f->paper) + "," + csvField(f->source) + "," + csvField(f->setting) +
               "," + csvField(f->baseline) + "," + csvField(f->result) + "," + csvNumber(f->timeRatio) + "," +
               csvField(f->unit) + "," + csvNumber(report.xPlain(*r)) + "," +
               std::to_string(r->differingPx) + "\n";
    return out;
}

Result<TradePageFiles> tradePage(const TradeReport& report, const TradeSettings& settings) {
    TradePageFiles files;
    std::map<std::size_t, std::string> thumbnails;
    for (std::size_t i = 1; i < report.rows.size(); ++i) {
        const TradeRow& r = report.rows[i];
        if (r.worstMask.rgba.empty()) continue;
        Result<Bytes> full = encodeColorPng(r.worstMask);
        if (!full) return Error{"mask of " + r.candidate.name + ": " + full.error().message};
        Result<Bytes> small = encodeColorPng(maskThumbnail(r.worstMask, kMaskThumbnailWidth));
        if (!small) return Error{"mask of " + r.candidate.name + ": " + small.error().message};
        files.masks.emplace_back("masks/" + methodSlug(r.candidate.name) + ".png", std::move(*full));
        thumbnails[i] = base64(*small);
    }

    const TradeRow& plain = report.rows.front();
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>frugal report: "
      << escape(settings.scene) << "</title>\n<style>\n" << kStyle << "</style>\n</head>\n<body>\n";
    h << "<h1>What to turn on for " << escape(settings.scene) << "</h1>\n<p class=\"meta\">"
      << plain.candidate.settings.width << "&times;" << plain.candidate.settings.height << " on "
      << escape(report.backend) << "; " << settings.shots.size() << (settings.sequence ? " frames of a sequence" : " views")
      << ", each rendered " << (settings.sequence ? 1 : settings.repeat) << " time(s) by every method, interleaved; "
      << report.rows.size() << " methods. A method pays when, paired with the plain render shot by shot and round by "
         "round, the " << levelPercent() << " % interval of its time's ratio to the plain render's lies below "
      << fixed(kPays, 2) << " (a bootstrap of the " << int(std::lround(100 * kTrim))
      << " % trimmed geometric mean over the shots, " << kBootstrapResamples
      << " resamples, seed " << kBootstrapSeed << "), and when its draws are not the plain render's: a no-op is never "
         "picked.</p>\n";
    h << recommendationHtml(report, settings);
    h << "<h2>Time against error</h2>\n" << paretoSvg(report);
    h << "<p>Each point is a method: its median time a frame and the pixels that differ from the plain render over all "
         "frames. The line joins the methods no other beats in both. The floor is the oracle: it submits exactly the "
         "visible triangles, a bound no culling method can pass.</p>\n";
    h << "<h2>Every method</h2>\n" << methodsTable(report, thumbnails);
    h << "<p><i>paired &times; plain</i>: per shot, the median over its rounds of the method's time &divide; the plain "
         "render's in the same round, then the geometric mean over the shots without the lowest and highest "
      << int(std::lround(100 * kTrim)) << " %, and in brackets its "
      << levelPercent() << " % interval; bold where it pays. <i>no-op</i>: in every timed frame the method asked the "
         "backend for exactly the plain render's clears, copies and draws (an order of a single draw, a cull that keeps "
         "every triangle), so whatever its time says it cannot pay. "
         "<i>differing px</i>: over all frames, against the plain render; <i>misses</i>: triangles the plain "
         "render shows that the method's image lacks, summed over the frames (for culling: visible triangles it did "
         "not submit); <i>worst depth</i>: the largest depth "
         "difference where both cover, in LSB (d24) or ULP (d32f); <i>submitted</i>: triangles submitted &divide; the "
         "scene's; <i>binds</i>: program, mesh, texture binds and toggles; <i>extra memory</i>: kept beyond the plain "
         "render (static pair, culling maps and hull, hidden-surface polygons). A mask is red where the worst frame "
         "differs; click it for the full size.</p>\n";
    h << "<h2>The papers beside this run</h2>\n" << papersTable(report);
    h << "<p>The paper columns are the published figures (other machines, other scenes); every other figure on this "
         "page was measured in this run.</p>\n";
    h << "<p>Files: <a href=\"report.json\">report.json</a>, <a href=\"report.csv\">report.csv</a> (the methods), "
         "<a href=\"papers.csv\">papers.csv</a> (the papers), <a href=\"settings.json\">settings.json</a>, "
         "<a href=\"pareto.gp\">pareto.gp</a> (the chart by gnuplot from report.csv).</p>\n</body>\n</html>\n";
    files.html = h.str();
    files.papersCsv = paperFiguresCsv(report);
    files.gnuplot =
        "# frugal report: the Pareto chart from report.csv (gnuplot 5). Run in this folder: gnuplot pareto.gp\n"
        "set terminal svg size 900,560 dynamic enhanced font 'sans,11'\n"
        "set output 'pareto.svg'\n"
        "set datafile separator ','\n"
        "set key off\n"
        "set grid\n"
        "set xlabel 'median time a frame (ms)' noenhanced\n"
        "set ylabel 'log10(1 + differing pixels, all frames)' noenhanced\n"
        "set xrange [0:*]\n"
        "set yrange [-0.2:*]\n"
        "plot 'report.csv' skip 1 using 4:(log10(1 + $7)):($16 == 1 ? 2 : 1) with points pt 7 ps variable lc 'black', \\\n"
        "     '' skip 1 using 4:(log10(1 + $7)):1 with labels offset char 1,0.6 left font ',9' noenhanced\n";
    return files;
}

}  // namespace frugal
