#include "lab/WriteBench.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>
#include <system_error>

#include <sys/resource.h>

#include <nlohmann/json.hpp>
#include <zlib.h>

#include <frugal/Files.h>
#include <frugal/Renderer.h>

#include "renderer/Research.h"
#include "lab/MinimalFrame.h"

namespace frugal {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The process's CPU time so far (user and system, every thread), in milliseconds.
double cpuMsNow() {
    rusage usage{};
    ::getrusage(RUSAGE_SELF, &usage);
    const auto ms = [](const timeval& t) { return double(t.tv_sec) * 1e3 + double(t.tv_usec) * 1e-3; };
    return ms(usage.ru_utime) + ms(usage.ru_stime);
}

// The encoder frugal had before libdeflate: rows unfiltered, zlib's compress2 at level 6.
Result<Bytes> zlibLevel6(std::span<const std::uint8_t> rows) {
    if (rows.size() > std::numeric_limits<uLong>::max() / 2)
        return Error{"baseline encoder: " + std::to_string(rows.size()) + " bytes is more than zlib takes at once"};
    uLongf size = compressBound(uLong(rows.size()));
    Bytes packed(size);
    if (const int z = compress2(packed.data(), &size, rows.data(), uLong(rows.size()), 6); z != Z_OK)
        return Error{"baseline encoder: zlib compress2 failed: " + std::string(zError(z))};
    packed.resize(size);
    return packed;
}

PngOptions baselineOptions() {
    PngOptions options;
    options.filter = PngFilter::None;
    options.compress = zlibLevel6;
    return options;
}

const char* filterName(PngFilter filter) {
    switch (filter) {
        case PngFilter::None:
            return "none";
        case PngFilter::Sub:
            return "sub";
        case PngFilter::Up:
            return "up";
        case PngFilter::Paeth:
            return "paeth";
    }
    return "?";
}

constexpr PngFilter kFilters[] = {PngFilter::None, PngFilter::Sub, PngFilter::Up, PngFilter::Paeth};
const char* const kPlanes[] = {"color", "depth", "ids"};

// Level 1 is frugal's run-length deflate, 0 and 2 to 12 libdeflate's (frugal/Files.h).
const char* encoderName(int level) { return level == kRunLengthPngLevel ? "run-length" : "libdeflate"; }

Result<Bytes> encodePlane(const Frame& frame, int plane, const PngOptions& options) {
    switch (plane) {
        case 0:
            return encodeColorPng(frame.color, options);
        case 1:
            return encodeDepthPng(frame.depth, options);
        default:
            return encodeIdPng(frame.ids, options);
    }
}

bool samePixels(const DecodedImage& a, const DecodedImage& b) {
    return a.width == b.width && a.height == b.height && a.channels == b.channels && a.bitDepth == b.bitDepth &&
           a.pixels8 == b.pixels8 && a.pixels16 == b.pixels16;
}

// The baseline's files for `paths`, as one set.
Result<bool> writeBaseline(const FramePaths& paths, const Frame& frame) {
    OutputSet set;
    if (!paths.color.empty()) set.add(paths.color, encodeColorPng(frame.color, baselineOptions()));
    if (!paths.depth.empty()) set.add(paths.depth, encodeDepthPng(frame.depth, baselineOptions()));
    if (!paths.ids.empty()) set.add(paths.ids, encodeIdPng(frame.ids, baselineOptions()));
    return set.commit();
}

Result<bool> encoderTable(const std::vector<std::pair<std::string, Scene>>& scenes, const WriteBenchSettings& s,
                          WriteBench& bench, const std::function<void(const std::string&)>& progress) {
    for (const auto& [name, scene] : scenes) {
        Settings settings = s.render;
        settings.ids = true;
        Result<Renderer> renderer = Renderer::create(scene, settings);
        if (!renderer) return renderer.error();
        Result<Frame> frame = renderer->render(Camera::automatic(), 0.0);
        if (!frame) return frame.error();
        progress("write-bench: " + name + ": encoding its colour, depth and ids at " + std::to_string(settings.width) +
                 "x" + std::to_string(settings.height));
        for (int plane = 0; plane < 3; ++plane) {
            // Each row's encodings are timed one after another; the medians absorb the noise.
            // The median and the fastest: noise only ever adds time, so the choice goes by the fastest.
            const auto timed = [&](const PngOptions& options, Bytes& bytes) -> Result<std::pair<double, double>> {
                std::vector<double> ms;
                for (int k = 0; k < s.repeat; ++k) {
                    const auto start = Clock::now();
                    Result<Bytes> encoded = encodePlane(*frame, plane, options);
                    ms.push_back(msSince(start));
                    if (!encoded) return encoded.error();
                    bytes = std::move(*encoded);
                }
                return std::pair{median(ms), *std::min_element(ms.begin(), ms.end())};
            };
            Bytes baselineBytes;
            Result<std::pair<double, double>> baselineMs = timed(baselineOptions(), baselineBytes);
            if (!baselineMs) return baselineMs.error();
            Result<DecodedImage> baselinePixels = decodePng(baselineBytes, name + " baseline");
            if (!baselinePixels) return baselinePixels.error();
            bench.encodes.push_back({name, kPlanes[plane], "baseline", 6, "none", baselineMs->first, baselineMs->second,
                                     baselineBytes.size(), 1.0, 1.0, true});
            for (const int level : s.levels)
                for (const PngFilter filter : kFilters) {
                    PngOptions options = PngOptions::atLevel(level);
                    options.filter = filter;
                    Bytes bytes;
                    Result<std::pair<double, double>> ms = timed(options, bytes);
                    if (!ms) return ms.error();
                    Result<DecodedImage> pixels = decodePng(bytes, name);
                    if (!pixels) return pixels.error();
                    bench.encodes.push_back({name, kPlanes[plane], encoderName(level), level, filterName(filter),
                                             ms->first, ms->second, bytes.size(),
                                             double(bytes.size()) / double(baselineBytes.size()),
                                             baselineMs->first / ms->first, samePixels(*pixels, *baselinePixels)});
                }
        }
    }
    // Per plane, the fastest level and filter within the size limit on every scene.
    for (const char* plane : kPlanes) {
        EncodeChoice best;
        best.plane = plane;
        double baselineMs = 0.0;
        for (const EncodeRow& row : bench.encodes)
            if (row.plane == plane && row.encoder == "baseline") baselineMs += row.minMs;
        for (const int level : s.levels)
            for (const PngFilter filter : kFilters) {
                double total = 0.0, worst = 0.0;
                for (const EncodeRow& row : bench.encodes)
                    if (row.plane == plane && row.encoder != "baseline" && row.level == level &&
                        row.filter == filterName(filter)) {
                        total += row.minMs;
                        worst = std::max(worst, row.sizeRatio);
                    }
                if (worst <= s.sizeLimit && (!best.found || total < best.totalMs))
                    best = {plane, filterName(filter), level, worst, total, baselineMs, true};
            }
        if (!best.found) best.baselineTotalMs = baselineMs;
        bench.choices.push_back(best);
    }
    return true;
}

Result<bool> sequence(const std::string& name, const Scene& scene, const WriteBenchSettings& s, WriteBench& bench,
                      const std::function<void(const std::string&)>& progress) {
    std::string folder = s.dir;
    if (folder.empty()) {
        std::string pattern = (std::filesystem::temp_directory_path() / "frugal-write-bench-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr)
            return Error{pattern + ": cannot make a folder: " + std::strerror(errno), ErrorKind::Io};
        folder = pattern;
    } else if (std::error_code made; !std::filesystem::create_directories(folder, made) && made) {
        return Error{folder + ": cannot make the folder: " + made.message(), ErrorKind::Io};
    }
    // Removed however this returns.
    struct Remove {
        std::filesystem::path dir;
        ~Remove() {
            std::error_code ignored;
            std::filesystem::remove_all(dir, ignored);
        }
    } const remove{folder};
    const std::filesystem::path& dir = remove.dir;
    struct Planes {
        const char* name;
        bool all;
    };
    for (const Planes planes : {Planes{"color", false}, Planes{"color+depth+ids", true}}) {
        Settings settings = s.render;
        settings.ids = planes.all;
        Result<Renderer> made = Renderer::create(scene, settings);
        if (!made) return made.error();
        Renderer& renderer = *made;
        const auto pathsOf = [&](const std::string& variant, int frame) {
            char number[16];
            std::snprintf(number, sizeof number, "_%04d", frame);
            const std::string stem = (dir / (variant + number)).string();
            return planes.all ? FramePaths{stem + ".png", stem + "-depth.png", stem + "-ids.png", ""}
                              : FramePaths{stem + ".png", "", "", ""};
        };
        const std::vector<std::string> variants = {"render", "async",    "async level 1",
                                                   "sync",   "baseline", "one-frame async"};
        std::map<std::string, std::vector<double>> perFrame, cpuPerFrame;
        std::vector<double> renderMs, readbackMs;
        Frame frame;
        // As `frugal render` does, the depth is read back only when a file holds it.
        const Renderer::ReadBack readBack{.depth = planes.all};
        for (int warm = 0; warm < 3; ++warm)  // llvmpipe compiles its shaders on the first frames
            if (Result<bool> rendered = renderer.render(Camera::automatic(), 0.0, frame, readBack); !rendered)
                return rendered;
        for (int round = 0; round < s.rounds; ++round)
            for (const std::string& variant : variants) {
                progress("write-bench: " + name + " " + planes.name + ", round " + std::to_string(round + 1) + " of " +
                         std::to_string(s.rounds) + ": " + variant);
                const auto start = Clock::now();
                const double cpuStart = cpuMsNow();
                std::optional<FrameWriter> writer;
                if (variant == "async") writer.emplace();
                if (variant == "async level 1") writer.emplace(std::move(*FrameWriter::create({.pngLevel = 1})));
                for (int i = 0; i < s.frames; ++i) {
                    if (Result<bool> rendered = renderer.render(Camera::automatic(), 0.0, frame, readBack); !rendered)
                        return rendered;
                    Result<bool> written = true;
                    if (variant == "render") {
                        renderMs.push_back(frame.stats.renderMs);
                        readbackMs.push_back(frame.stats.readbackMs);
                    } else if (writer) {
                        written = writer->write(pathsOf(variant, i), frame);
                    } else if (variant == "sync") {
                        written = writeFrame(pathsOf(variant, i), frame);
                    } else if (variant == "baseline") {
                        written = writeBaseline(pathsOf(variant, i), frame);
                    } else {  // one frame: its own writer, made and finished
                        FrameWriter one;
                        written = one.write(pathsOf(variant, i), frame);
                        if (written) written = one.finish();
                    }
                    if (!written) return written;
                }
                if (writer)
                    if (Result<bool> finished = writer->finish(); !finished) return finished;
                perFrame[variant].push_back(msSince(start) / s.frames);
                cpuPerFrame[variant].push_back((cpuMsNow() - cpuStart) / s.frames);
            }
        const double floor = median(perFrame["render"]), baseline = median(perFrame["baseline"]);
        for (const std::string& variant : variants) {
            SequenceRow row{planes.name, variant, perFrame[variant], median(perFrame[variant]), 0.0, 0.0, 0.0,
                            0.0,         0.0};
            row.overRender = row.medianMs / floor;
            row.overBaseline = row.medianMs / baseline;
            row.cpuMs = median(cpuPerFrame[variant]);
            if (variant == "render") {
                row.renderMs = median(renderMs);
                row.readbackMs = median(readbackMs);
            }
            bench.sequence.push_back(std::move(row));
        }
    }
    return true;
}

// Part three: the minimal frame of `scene` (MinimalFrame: the fewest GL calls that draw it) read
// back four ways, the variants taking turns for s.rounds rounds of s.readbackFrames frames.
Result<bool> readBackRun(const std::string& name, const Scene& scene, const WriteBenchSettings& s, WriteBench& bench,
                         const std::function<void(const std::string&)>& progress) {
    const Settings& r = s.render;
    std::optional<ContextKind> kind;
    {
        Result<Renderer> renderer = Renderer::create(scene, r);  // which context `frugal render` would use
        if (!renderer) return renderer.error();
        kind = contextKindNamed(renderer->backendName());
        if (!kind) {
            bench.readbackSkipped = "the " + renderer->backendName() + " backend reads no GL framebuffer";
            return true;
        }
    }
    if (std::string unsupported = minimalFrameUnsupported(scene); !unsupported.empty()) {
        bench.readbackSkipped = name + ": " + unsupported;
        return true;
    }
    Result<std::unique_ptr<MinimalFrame>> made = createMinimalFrame(*kind, scene, r.width, r.height, r.depthFormat);
    if (!made) return made.error();
    MinimalFrame& minimal = **made;
    Result<FrameSetup> setup = setUpFrame(scene, Camera::automatic(), 0.0, r.width, r.height, false, r.depthFormat);
    if (!setup) return Error{name + ": " + setup.error().message};
    applyShading(r, setup->params);
    const auto draw = [&] { minimal.render(setup->params, setup->world, r.background); };
    const std::vector<std::string> variants = {"draw", "readpixels", "pbo", "pbo, a frame late"};
    for (const bool depth : {false, true}) {
        const char* planes = depth ? "color+depth" : "color";
        // Each way's images against glReadPixels' (the same frame every time: a static camera).
        draw();
        minimal.finish();
        const Buffers reference = minimal.readBack(depth);
        std::map<std::string, std::vector<double>> perFrame;
        std::map<std::string, bool> equal;
        std::map<std::string, Buffers> images;
        for (int round = 0; round < s.rounds; ++round)
            for (const std::string& variant : variants) {
                progress("write-bench: read-back of " + name + " " + planes + ", round " + std::to_string(round + 1) +
                         " of " + std::to_string(s.rounds) + ": " + variant);
                Buffers& last = images[variant];  // kept across rounds: its memory is used again
                const auto start = Clock::now();
                for (int i = 0; i < s.readbackFrames; ++i) {
                    draw();
                    if (variant == "draw") {
                        minimal.finish();
                    } else if (variant == "readpixels") {
                        minimal.finish();
                        minimal.readBackInto(last, depth);
                    } else if (variant == "pbo") {
                        minimal.startReadBack(0, depth);
                        minimal.endReadBack(0, last, depth);
                    } else {  // frame i's read queued, frame i - 1's copied out while frame i is read
                        minimal.startReadBack(i % 2, depth);
                        if (i > 0) minimal.endReadBack((i - 1) % 2, last, depth);
                    }
                }
                if (variant == "pbo, a frame late") minimal.endReadBack((s.readbackFrames - 1) % 2, last, depth);
                perFrame[variant].push_back(msSince(start) / s.readbackFrames);
                if (variant != "draw")
                    equal[variant] = last.rgba == reference.rgba && last.depth == reference.depth &&
                                     (round == 0 || equal[variant]);
            }
        const double floor = median(perFrame["draw"]), readPixels = median(perFrame["readpixels"]);
        for (const std::string& variant : variants) {
            ReadBackRow row{planes, variant, perFrame[variant], median(perFrame[variant]), 0.0, 0.0, std::nullopt};
            row.overDraw = row.medianMs / floor;
            row.overReadPixels = row.medianMs / readPixels;
            if (variant != "draw") row.pixelsEqual = equal[variant];
            bench.readback.push_back(std::move(row));
        }
    }
    bench.readbackScene = name;
    return true;
}

}  // namespace

Result<WriteBench> measureWriteBench(const std::vector<std::pair<std::string, Scene>>& scenes,
                                     const WriteBenchSettings& settings,
                                     const std::function<void(const std::string&)>& progress) {
    WriteBench bench;
    bench.settings = settings;
    for (const auto& [name, scene] : scenes) bench.scenes.push_back(name);
    if (Result<bool> table = encoderTable(scenes, settings, bench, progress); !table) return table.error();
    if (settings.frames > 0 && !scenes.empty()) {
        bench.sequenceScene = scenes.front().first;
        if (Result<bool> run = sequence(scenes.front().first, scenes.front().second, settings, bench, progress); !run)
            return run.error();
    }
    if (settings.readbackFrames > 0 && !scenes.empty())
        if (Result<bool> run = readBackRun(scenes.front().first, scenes.front().second, settings, bench, progress);
            !run)
            return run.error();
    return bench;
}

std::string writeBenchJson(const WriteBench& bench) {
    nlohmann::ordered_json j;
    const WriteBenchSettings& s = bench.settings;
    j["command"] = "write-bench";
    j["scenes"] = bench.scenes;
    j["size"] = std::to_string(s.render.width) + "x" + std::to_string(s.render.height);
    j["repeat"] = s.repeat;
    j["size_limit"] = s.sizeLimit;
    j["baseline"] = "no filter, zlib compress2 level 6, one thread (frugal's encoder before libdeflate)";
    j["default_level"] = kDefaultPngLevel;
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const EncodeRow& r : bench.encodes)
        rows.push_back({{"scene", r.scene},
                        {"plane", r.plane},
                        {"encoder", r.encoder},
                        {"level", r.level},
                        {"filter", r.filter},
                        {"median_ms", r.medianMs},
                        {"min_ms", r.minMs},
                        {"bytes", r.bytes},
                        {"size_over_baseline", r.sizeRatio},
                        {"speedup_over_baseline", r.speedup},
                        {"pixels_equal", r.pixelsEqual}});
    j["encodes"] = rows;
    nlohmann::ordered_json choices = nlohmann::ordered_json::array();
    for (const EncodeChoice& c : bench.choices) {
        nlohmann::ordered_json choice = {{"plane", c.plane}, {"found", c.found}};
        if (c.found)
            choice.update({{"level", c.level},
                           {"filter", c.filter},
                           {"worst_size_over_baseline", c.worstSizeRatio},
                           {"total_ms", c.totalMs},
                           {"baseline_total_ms", c.baselineTotalMs},
                           {"speedup_over_baseline", c.baselineTotalMs / c.totalMs}});
        choices.push_back(choice);
    }
    j["choices"] = choices;
    if (!bench.sequence.empty()) {
        nlohmann::ordered_json seq;
        seq["scene"] = bench.sequenceScene;
        seq["frames"] = s.frames;
        seq["rounds"] = s.rounds;
        nlohmann::ordered_json seqRows = nlohmann::ordered_json::array();
        for (const SequenceRow& r : bench.sequence) {
            nlohmann::ordered_json row = {{"planes", r.planes},
                                          {"variant", r.variant},
                                          {"median_ms_per_frame", r.medianMs},
                                          {"ms_per_frame", r.msPerFrame},
                                          {"cpu_ms_per_frame", r.cpuMs},
                                          {"over_render", r.overRender},
                                          {"over_baseline", r.overBaseline}};
            if (r.variant == "render") row.update({{"render_ms", r.renderMs}, {"readback_ms", r.readbackMs}});
            seqRows.push_back(row);
        }
        seq["results"] = seqRows;
        j["sequence"] = seq;
    }
    if (!bench.readback.empty() || !bench.readbackSkipped.empty()) {
        nlohmann::ordered_json part;
        if (!bench.readbackSkipped.empty()) part["skipped"] = bench.readbackSkipped;
        if (!bench.readback.empty()) {
            part["scene"] = bench.readbackScene;
            part["frames"] = s.readbackFrames;
            part["rounds"] = s.rounds;
            nlohmann::ordered_json readRows = nlohmann::ordered_json::array();
            for (const ReadBackRow& r : bench.readback) {
                nlohmann::ordered_json row = {{"planes", r.planes},
                                              {"variant", r.variant},
                                              {"median_ms_per_frame", r.medianMs},
                                              {"ms_per_frame", r.msPerFrame},
                                              {"over_draw", r.overDraw},
                                              {"over_readpixels", r.overReadPixels}};
                if (r.pixelsEqual) row["pixels_equal"] = *r.pixelsEqual;
                readRows.push_back(row);
            }
            part["results"] = readRows;
        }
        j["readback"] = part;
    }
    return j.dump(2) + "\n";
}

std::string writeBenchCsv(const WriteBench& bench) {
    std::ostringstream out;
    out << "scene,plane,encoder,level,filter,median_ms,bytes,size_over_baseline,speedup_over_baseline,pixels_equal,min_"
           "ms\n";
    for (const EncodeRow& r : bench.encodes)
        out << r.scene << "," << r.plane << "," << r.encoder << "," << r.level << "," << r.filter << ","
            << fmt(r.medianMs) << "," << r.bytes << "," << fmt(r.sizeRatio) << "," << fmt(r.speedup) << ","
            << (r.pixelsEqual ? 1 : 0) << "," << fmt(r.minMs) << "\n";
    return out.str();
}

std::string writeBenchGnuplot(const WriteBench& bench, const std::string& csvPath, const std::string& svgPath) {
    // One panel per plane: size against time, a series per filter, every scene and level a point.
    std::ostringstream gp;
    gp << "# frugal-lab write-bench: PNG size against encoding time per plane (drawn from the CSV)\n"
       << "set terminal svg size 1200,420 dynamic\nset output '" << svgPath << "'\n"
       << "set datafile separator ','\nset key top right\nset grid\n"
       << "set multiplot layout 1,3\n";
    for (const char* plane : kPlanes) {
        gp << "set title '" << plane
           << "'\nset xlabel 'encode ms (fastest of the repeats)'\nset ylabel 'bytes / baseline'\n"
           << "set yrange [0:*]\n"
           << "plot ";
        bool first = true;
        for (const char* filter : {"none", "sub", "up", "paeth"}) {
            gp << (first ? "" : ", ") << "'" << csvPath << "' every ::1 using (strcol(2) eq '" << plane
               << "' && strcol(3) ne 'baseline' && strcol(5) eq '" << filter << "' ? $11 : NaN):8 with points title '"
               << filter << "'";
            first = false;
        }
        gp << ", '" << csvPath << "' every ::1 using (strcol(2) eq '" << plane
           << "' && strcol(3) eq 'baseline' ? $11 : NaN):8 with points pt 7 ps 1.5 title 'baseline (zlib 6)', "
           << bench.settings.sizeLimit << " with lines dt 2 title 'size limit'\n";
    }
    gp << "unset multiplot\n";
    return gp.str();
}

std::string writeBenchText(const WriteBench& bench) {
    std::ostringstream out;
    out << "PNG encoding at " << bench.settings.render.width << "x" << bench.settings.render.height << " ("
        << bench.scenes.size() << " scenes), the fastest level and filter within " << fmt(bench.settings.sizeLimit)
        << "x the baseline's size (zlib 6, no filter):\n";
    for (const EncodeChoice& c : bench.choices) {
        if (!c.found) {
            out << "  " << c.plane << ": none within the limit\n";
            continue;
        }
        out << "  " << c.plane << ": level " << c.level << ", filter " << c.filter << ": " << fmt(c.totalMs)
            << " ms against " << fmt(c.baselineTotalMs) << " ms (fastest of the repeats, summed over the scenes; "
            << fmt(c.baselineTotalMs / c.totalMs) << "x faster), files at most " << fmt(c.worstSizeRatio) << "x\n";
    }
    if (!bench.sequence.empty()) {
        out << "Sequence of " << bench.settings.frames << " frames (" << bench.sequenceScene
            << "), wall ms per frame, median of " << bench.settings.rounds << " rounds:\n";
        for (const SequenceRow& r : bench.sequence)
            out << "  " << r.planes << " " << r.variant << ": " << fmt(r.medianMs) << " ms (" << fmt(r.overRender)
                << "x render, " << fmt(r.overBaseline) << "x baseline; CPU " << fmt(r.cpuMs) << " ms)\n";
    }
    if (!bench.readbackSkipped.empty()) out << "Read-back: skipped: " << bench.readbackSkipped << "\n";
    if (!bench.readback.empty()) {
        out << "Read-back of the minimal frame (" << bench.readbackScene << "), wall ms per frame, median of "
            << bench.settings.rounds << " rounds of " << bench.settings.readbackFrames << " frames:\n";
        for (const ReadBackRow& r : bench.readback)
            out << "  " << r.planes << " " << r.variant << ": " << fmt(r.medianMs) << " ms (" << fmt(r.overDraw)
                << "x draw, " << fmt(r.overReadPixels) << "x readpixels"
                << (r.pixelsEqual && !*r.pixelsEqual ? "; IMAGES DIFFER" : "") << ")\n";
    }
    return out.str();
}

}  // namespace frugal
