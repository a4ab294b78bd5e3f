#include "lab/SoakReport.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lab/ReportText.h"
#include "renderer/Research.h"

namespace frugal {

using reporttext::Json;
using reporttext::number;

double growthPercent(std::uint64_t from, std::uint64_t to) {
    if (from == 0) return std::nan("");
    return 100.0 * (double(to) - double(from)) / double(from);
}

namespace {

// FNV-1a over a frame's size and planes.
std::uint64_t planesHash(int width, int height, const std::vector<std::uint8_t>& rgba,
                         const std::vector<std::uint32_t>& depth, const std::vector<std::uint32_t>& ids) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    const auto mix = [&h](const void* data, std::size_t bytes) {
        const auto* p = static_cast<const std::uint8_t*>(data);
        for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
    };
    const std::int32_t size[2] = {width, height};
    mix(size, sizeof size);
    mix(rgba.data(), rgba.size());
    mix(depth.data(), depth.size() * sizeof(std::uint32_t));
    mix(ids.data(), ids.size() * sizeof(std::uint32_t));
    return h;
}

}  // namespace

std::uint64_t imageHash(const Buffers& image) {
    return planesHash(image.width, image.height, image.rgba, image.depth, image.ids);
}
std::uint64_t imageHash(const Frame& frame) {
    return planesHash(frame.color.width, frame.color.height, frame.color.rgba, frame.depth.values, frame.ids.ids);
}

namespace {
bool allBackground(const std::vector<std::uint8_t>& rgba, const std::array<std::uint8_t, 4>& background) {
    for (std::size_t i = 0; i + 4 <= rgba.size(); i += 4)
        if (!std::equal(background.begin(), background.end(), rgba.begin() + std::ptrdiff_t(i))) return false;
    return true;
}
}  // namespace

bool isBlank(const Buffers& image, const std::array<std::uint8_t, 4>& background) {
    return allBackground(image.rgba, background);
}
bool isBlank(const ColorImage& color, const std::array<std::uint8_t, 4>& background) {
    return allBackground(color.rgba, background);
}

void EqualTimeImages::add(std::int64_t frame, std::uint64_t hash, bool isBlankFrame) {
    if (isBlankFrame) {
        ++blank;
        if (firstBlank < 0) firstBlank = frame;
    }
    std::optional<std::uint64_t>& reference = reference_[std::size_t(frame % std::int64_t(reference_.size()))];
    if (!reference) {
        reference = hash;
        return;
    }
    ++compared;
    if (hash != *reference) {
        ++mismatched;
        if (firstMismatch < 0) firstMismatch = frame;
    }
}

GrowthSummary summarizeGrowth(const std::vector<MemorySample>& samples, std::int64_t baselineIndex) {
    GrowthSummary s;
    const auto base = std::find_if(samples.begin(), samples.end(),
                                   [baselineIndex](const MemorySample& m) { return m.index >= baselineIndex; });
    if (base == samples.end()) {
        s.growthPct = s.peakGrowthPct = std::nan("");
        return s;
    }
    s.baseline = base->memory;
    s.end = samples.back().memory;
    s.lowRssKb = base->memory.rssKb;
    for (auto it = base; it != samples.end(); ++it) {
        s.lowRssKb = std::min(s.lowRssKb, it->memory.rssKb);
        s.peakRssKb = std::max(s.peakRssKb, it->memory.rssKb);
    }
    s.growthPct = growthPercent(s.baseline.rssKb, s.end.rssKb);
    s.peakGrowthPct = growthPercent(s.baseline.rssKb, s.peakRssKb);
    return s;
}

GrowthSummary summarizeGrowth(const SoakFrames& run) { return summarizeGrowth(run.samples, run.warmup); }
GrowthSummary summarizeGrowth(const SoakCycles& run) { return summarizeGrowth(run.samples, run.warmup); }

namespace {

// NaN (no baseline) fails: a growth that could not be measured is not shown to be small.
bool withinLimit(double growthPct, double maxGrowthPct) { return growthPct <= maxGrowthPct; }

Json frameOrNull(std::int64_t frame) { return frame < 0 ? Json(nullptr) : Json(frame); }

double msPer(double seconds, std::int64_t count) { return count > 0 ? 1000.0 * seconds / double(count) : 0.0; }

}  // namespace

bool passed(const SoakFrames& run, double maxGrowthPct) {
    return withinLimit(summarizeGrowth(run).growthPct, maxGrowthPct) && run.images.mismatched == 0 &&
           run.images.blank == 0;
}

bool passed(const SoakCycles& run, double maxGrowthPct) {
    return run.failures == 0 && withinLimit(summarizeGrowth(run).growthPct, maxGrowthPct);
}

bool passed(const SoakReport& report) {
    return std::all_of(report.frames.begin(), report.frames.end(),
                       [&](const SoakFrames& run) { return passed(run, report.maxGrowthPct); }) &&
           std::all_of(report.cycles.begin(), report.cycles.end(),
                       [&](const SoakCycles& run) { return passed(run, report.maxGrowthPct); });
}

std::string soakReportJson(const SoakReport& report) {
    Json frames = Json::array();
    for (const SoakFrames& run : report.frames) {
        const GrowthSummary g = summarizeGrowth(run);
        const EqualTimeImages& images = run.images;
        frames.push_back(Json{{"backend", run.backend},
                              {"renderer", run.renderer},
                              {"frames", run.frames},
                              {"warmup", run.warmup},
                              {"seconds", number(run.seconds)},
                              {"ms_per_frame", number(msPer(run.seconds, run.frames))},
                              {"rss_start_kb", run.samples.empty() ? 0 : run.samples.front().memory.rssKb},
                              {"rss_warm_kb", g.baseline.rssKb},
                              {"rss_end_kb", g.end.rssKb},
                              {"rss_low_kb", g.lowRssKb},
                              {"rss_peak_kb", g.peakRssKb},
                              {"hwm_kb", g.end.hwmKb},
                              {"growth_pct", number(g.growthPct)},
                              {"peak_growth_pct", number(g.peakGrowthPct)},
                              {"compared_frames", images.compared},
                              {"mismatched_frames", images.mismatched},
                              {"first_mismatch", frameOrNull(images.firstMismatch)},
                              {"blank_frames", images.blank},
                              {"first_blank", frameOrNull(images.firstBlank)},
                              {"passed", passed(run, report.maxGrowthPct)}});
    }
    Json cycles = Json::array();
    for (const SoakCycles& run : report.cycles) {
        const GrowthSummary g = summarizeGrowth(run);
        cycles.push_back(Json{{"backend", run.backend},
                              {"kind", run.kind},
                              {"cycles", run.cycles},
                              {"warmup", run.warmup},
                              {"seconds", number(run.seconds)},
                              {"failures", run.failures},
                              {"first_failure", run.firstFailure.empty() ? Json(nullptr) : Json(run.firstFailure)},
                              {"rss_before_kb", run.before.rssKb},
                              {"rss_warm_kb", g.baseline.rssKb},
                              {"rss_end_kb", g.end.rssKb},
                              {"rss_low_kb", g.lowRssKb},
                              {"rss_peak_kb", g.peakRssKb},
                              {"growth_pct", number(g.growthPct)},
                              {"peak_growth_pct", number(g.peakGrowthPct)},
                              {"passed", passed(run, report.maxGrowthPct)}});
    }
    Json skipped = Json::array();
    for (const auto& [backend, reason] : report.skipped)
        skipped.push_back(Json{{"backend", backend}, {"reason", reason}});
    const Json j{{"command", "soak"},
                 {"scene", report.scene},
                 {"size", {report.width, report.height}},
                 {"period", report.period},
                 {"fps", number(report.fps)},
                 {"ids", report.ids},
                 {"max_growth_pct", number(report.maxGrowthPct)},
                 {"passed", passed(report)},
                 {"frames", frames},
                 {"cycles", cycles},
                 {"skipped", skipped}};
    return reporttext::jsonText(j);
}

std::string soakReportCsv(const SoakReport& report) {
    using reporttext::csvField;
    using reporttext::csvNumber;
    std::string csv = "run,backend,index,rss_kb,hwm_kb,ms_each\n";
    const auto rows = [&csv](const std::string& run, const std::string& backend,
                             const std::vector<MemorySample>& samples) {
        for (const MemorySample& m : samples)
            csv += run + "," + csvField(backend) + "," + std::to_string(m.index) + "," +
                   std::to_string(m.memory.rssKb) + "," + std::to_string(m.memory.hwmKb) + "," + csvNumber(m.msEach) +
                   "\n";
    };
    for (const SoakFrames& run : report.frames) rows("frames", run.backend, run.samples);
    for (const SoakCycles& run : report.cycles) rows(run.kind, run.backend, run.samples);
    return csv;
}

std::string soakReportGnuplot(const std::string& csvPath, const std::string& plotPath, const SoakReport& report) {
    using reporttext::gnuplotQuoted;
    const bool png = plotPath.size() >= 4 && plotPath.compare(plotPath.size() - 4, 4, ".png") == 0;
    const int panels = (report.frames.empty() ? 0 : 1) + (report.cycles.empty() ? 0 : 1);
    const std::string size = panels == 2 ? "1000,800" : "1000,420";
    std::string s =
        "# frugal-lab soak: resident memory (VmRSS) over frames and over create/destroy cycles, from the CSV.\n"
        "# Run gnuplot on this file to draw it again.\n";
    s += png ? "set terminal pngcairo size " + size + " font 'sans,10'\n"
             : "set terminal svg size " + size + " dynamic background rgb 'white' font 'sans,10'\n";
    s += "set output " + gnuplotQuoted(plotPath) +
         "\n"
         "set datafile separator ','\n"
         "set ylabel 'resident memory (MiB)'\n"
         "set yrange [0:*]\n"
         "set grid\n"
         "set key bottom right noenhanced\n";
    if (panels == 2) s += "set multiplot layout 2,1\n";
    char growth[64];
    // One line per run, picked out of the CSV by its first two columns (the other rows' x is NaN, so
    // they leave the axis range alone too).
    s += "row(run, backend) = strcol(1) eq run && strcol(2) eq backend\n";
    const auto line = [&](const std::string& run, const std::string& backend, const std::string& title) {
        return gnuplotQuoted(csvPath) + " skip 1 using (row(" + gnuplotQuoted(run) + ", " + gnuplotQuoted(backend) +
               ") ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title " + gnuplotQuoted(title);
    };
    const std::string where = report.scene + ", " + std::to_string(report.width) + "x" + std::to_string(report.height);
    if (!report.frames.empty()) {
        s += "set title " + gnuplotQuoted("frames: " + where + ", growth after warm-up in the key") +
             " noenhanced\n"
             "set xlabel 'frames rendered'\n";
        std::string plot;
        for (const SoakFrames& run : report.frames) {
            std::snprintf(growth, sizeof growth, " (%+.2f %%)", summarizeGrowth(run).growthPct);
            plot += (plot.empty() ? "plot " : ", \\\n     ") + line("frames", run.backend, run.backend + growth);
        }
        s += "set arrow 1 from " + std::to_string(report.frames.front().warmup) + ", graph 0 to " +
             std::to_string(report.frames.front().warmup) + ", graph 1 nohead dashtype 2\n";
        s += plot + "\nunset arrow 1\n";
    }
    if (!report.cycles.empty()) {
        s += "set title " + gnuplotQuoted("create/destroy cycles: " + where + ", growth after warm-up in the key") +
             " noenhanced\nset xlabel 'cycles'\n";
        std::string plot;
        for (const SoakCycles& run : report.cycles) {
            std::snprintf(growth, sizeof growth, " (%+.2f %%)", summarizeGrowth(run).growthPct);
            plot += (plot.empty() ? "plot " : ", \\\n     ") +
                    line(run.kind, run.backend, run.backend + " " + run.kind + growth);
        }
        s += plot + "\n";
    }
    if (panels == 2) s += "unset multiplot\n";
    return s;
}

std::string soakReportText(const SoakReport& report) {
    const auto mib = [](std::uint64_t kb) { return double(kb) / 1024.0; };
    char line[320];
    std::snprintf(line, sizeof line, "soak %s, %dx%d, period %d frames at %g fps%s, memory growth limit %g %%\n",
                  report.scene.c_str(), report.width, report.height, report.period, report.fps,
                  report.ids ? ", ids" : "", report.maxGrowthPct);
    std::string text = line;
    int width = 16;  // the backend column
    for (const SoakFrames& run : report.frames) width = std::max(width, int(run.backend.size()));
    for (const SoakCycles& run : report.cycles) width = std::max(width, int(run.backend.size()));
    if (!report.frames.empty()) {
        std::snprintf(line, sizeof line, "  %-*s %9s %8s %9s %11s %10s %10s %8s %11s %9s %10s %6s  %s\n", width,
                      "frames", "frames", "warm-up", "ms/frame", "RSS warm MiB", "end MiB", "peak MiB", "growth",
                      "peak growth", "compared", "mismatched", "blank", "verdict");
        text += line;
        for (const SoakFrames& run : report.frames) {
            const GrowthSummary g = summarizeGrowth(run);
            std::snprintf(line, sizeof line,
                          "  %-*s %9lld %8lld %9.3f %11.1f %10.1f %10.1f %+7.2f%% %+10.2f%% %9lld %10lld %6lld  %s\n",
                          width, run.backend.c_str(), (long long)run.frames, (long long)run.warmup,
                          msPer(run.seconds, run.frames), mib(g.baseline.rssKb), mib(g.end.rssKb), mib(g.peakRssKb),
                          g.growthPct, g.peakGrowthPct, (long long)run.images.compared,
                          (long long)run.images.mismatched, (long long)run.images.blank,
                          passed(run, report.maxGrowthPct) ? "pass" : "FAIL");
            text += line;
        }
    }
    if (!report.cycles.empty()) {
        std::snprintf(line, sizeof line, "  %-*s %-8s %7s %8s %9s %14s %10s %10s %8s %9s  %s\n", width, "cycles",
                      "kind", "cycles", "warm-up", "ms/cycle", "RSS before MiB", "warm MiB", "end MiB", "growth",
                      "failures", "verdict");
        text += line;
        for (const SoakCycles& run : report.cycles) {
            const GrowthSummary g = summarizeGrowth(run);
            std::snprintf(line, sizeof line, "  %-*s %-8s %7lld %8lld %9.3f %14.1f %10.1f %10.1f %+7.2f%% %9lld  %s\n",
                          width, run.backend.c_str(), run.kind.c_str(), (long long)run.cycles, (long long)run.warmup,
                          msPer(run.seconds, run.cycles), mib(run.before.rssKb), mib(g.baseline.rssKb),
                          mib(g.end.rssKb), g.growthPct, (long long)run.failures,
                          passed(run, report.maxGrowthPct) ? "pass" : "FAIL");
            text += line;
            if (!run.firstFailure.empty()) text += "    first failure: " + run.firstFailure + "\n";
        }
    }
    for (const auto& [backend, reason] : report.skipped) text += "  skipped " + backend + ": " + reason + "\n";
    text += passed(report) ? "soak: passed\n" : "soak: FAILED\n";
    return text;
}

}  // namespace frugal
