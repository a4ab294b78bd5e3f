// The report of `frugal-lab soak` (issue 11): long runs in one process, judged by what a user of an
// offscreen renderer fears from them — resident memory that keeps growing, images that drift or go
// blank after many frames, and backends or targets that stop working after many creations.
//
// Frames: one backend renders N frames of an animation looped every `period` frames, so frames
// f and f + k·period have the same scene time and must give the same colour, depth and ids, bit for
// bit; the first image of each time is the reference of every later one. Resident memory (VmRSS) is
// sampled along the way; its growth is measured from the end of the warm-up to the end.
// Cycles: a backend (or a target, or the scene's uploads) created, used for one frame and destroyed,
// many times; every frame is compared with one drawn before the cycles, and memory is measured from
// the end of the first cycles on.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <frugal/Image.h>
#include <frugal/Renderer.h>
#include "renderer/Research.h"

namespace frugal {

// The process's memory at one time: resident set (VmRSS) and its high-water mark (VmHWM), in KiB.
struct MemoryUse {
    std::uint64_t rssKb = 0, hwmKb = 0;
};

// Growth from `from` to `to` in percent of `from` (NaN when `from` is 0).
double growthPercent(std::uint64_t from, std::uint64_t to);

// FNV-1a (64 bits) of the colour, depth and id buffers: equal images, equal hashes; a different
// image gives another hash but for a chance of 2⁻⁶⁴.
std::uint64_t imageHash(const Buffers& image);
std::uint64_t imageHash(const Frame& frame);  // colour, depth and ids as the renderer gave them

// True when every colour pixel is `background` (8-bit RGBA as the target holds it): nothing drawn.
bool isBlank(const Buffers& image, const std::array<std::uint8_t, 4>& background);
bool isBlank(const ColorImage& color, const std::array<std::uint8_t, 4>& background);

// Frame by frame, the check "images at equal times are identical": frame f has time f mod period;
// the first frame of each time is its reference, and every later one is compared with it.
// A blank frame (isBlank) is counted whether or not it is the reference.
class EqualTimeImages {
public:
    explicit EqualTimeImages(int period) : reference_(std::size_t(period > 0 ? period : 1)) {}
    void add(std::int64_t frame, std::uint64_t hash, bool blank);

    std::int64_t compared = 0;        // frames checked against an earlier one of the same time
    std::int64_t mismatched = 0;      // of those, frames whose image differs
    std::int64_t firstMismatch = -1;  // the first such frame, or -1
    std::int64_t blank = 0;           // frames with nothing drawn
    std::int64_t firstBlank = -1;

private:
    std::vector<std::optional<std::uint64_t>> reference_;
};

// One memory sample of a run: after `index` frames (or cycles).
struct MemorySample {
    std::int64_t index = 0;
    MemoryUse memory;
    double msEach = 0.0;  // mean time a frame (or cycle) took since the sample before
};

// One backend's frames.
struct SoakFrames {
    std::string backend, renderer;
    std::int64_t frames = 0, warmup = 0;
    std::vector<MemorySample> samples;  // the first after 0 frames, one after the warm-up, the last at the end
    EqualTimeImages images{1};
    double seconds = 0.0;  // wall time of the frames
};

// One backend's create/destroy cycles of one kind.
struct SoakCycles {
    std::string backend;
    std::string kind;                     // "backend", "target" or "scene"
    std::int64_t cycles = 0, warmup = 1;  // cycles before the memory baseline
    std::int64_t failures = 0;            // a cycle that could not create, or drew another image
    std::string firstFailure;             // "cycle N: why"
    MemoryUse before;                     // before the first cycle
    std::vector<MemorySample> samples;    // after cycle 1, the warm-up, every few cycles, and the last
    double seconds = 0.0;
};

struct SoakReport {
    std::string scene;
    int width = 0, height = 0;
    int period = 1;
    double fps = 0.0;
    bool ids = false;
    double maxGrowthPct = 5.0;  // the limit of memory growth after warm-up
    std::vector<SoakFrames> frames;
    std::vector<SoakCycles> cycles;
    std::vector<std::array<std::string, 2>> skipped;  // backend, why it did not open
};

// The memory figures of a run: the baseline is the sample at the end of its warm-up (frames or
// cycles); growth is the last sample's over it, peak growth the largest sample's after it.
struct GrowthSummary {
    MemoryUse baseline, end;
    std::uint64_t lowRssKb = 0, peakRssKb = 0;  // the least and the most from the baseline on
    double growthPct = 0.0, peakGrowthPct = 0.0;
};
GrowthSummary summarizeGrowth(const std::vector<MemorySample>& samples, std::int64_t baselineIndex);
GrowthSummary summarizeGrowth(const SoakFrames& run);
GrowthSummary summarizeGrowth(const SoakCycles& run);

// A run passes when its growth is at most the limit and, for frames, no image differs from its
// time's reference and none is blank; for cycles, no cycle failed.
bool passed(const SoakFrames& run, double maxGrowthPct);
bool passed(const SoakCycles& run, double maxGrowthPct);
bool passed(const SoakReport& report);

// {"command","scene","size","period","fps","ids","max_growth_pct","passed",
//  "frames":[{"backend","renderer","frames","warmup","seconds","ms_per_frame","rss_start_kb","rss_warm_kb",
//             "rss_end_kb","rss_low_kb","rss_peak_kb","hwm_kb","growth_pct","peak_growth_pct","compared_frames",
//             "mismatched_frames","first_mismatch","blank_frames","first_blank","passed"}],
//  "cycles":[{"backend","kind","cycles","warmup","seconds","failures","first_failure","rss_before_kb",
//             "rss_warm_kb","rss_end_kb","rss_low_kb","rss_peak_kb","growth_pct","peak_growth_pct","passed"}],
//  "skipped":[{"backend","reason"}]}
std::string soakReportJson(const SoakReport& report);
// Every memory sample: run (frames, or the cycles' kind), backend, index, rss_kb, hwm_kb, ms_each.
std::string soakReportCsv(const SoakReport& report);
// Resident memory over frames (one line per backend) and over cycles (one per backend and kind),
// in MiB, drawn from the CSV into `plotPath` (a .png gets gnuplot's pngcairo terminal, else svg).
std::string soakReportGnuplot(const std::string& csvPath, const std::string& plotPath, const SoakReport& report);
// The tables printed on the terminal, and the verdict.
std::string soakReportText(const SoakReport& report);

}  // namespace frugal
