#include <algorithm>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <ostream>
#include <regex>

#include <nlohmann/json.hpp>

#include <frugal/Files.h>
#include <frugal/Interrupt.h>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "lab/RenderRecord.h"

namespace frugal {

const char* renderHelp() {
    return R"(usage: frugal render [SCENE] [-o FILE.png] [options]

Renders SCENE (default builtin:default) offscreen and writes the colour image.
)";
}

namespace {

struct Outputs {
    std::string color = "frame.png";
    std::string depth, ids, linear, json;
    std::string settings;  // --save-settings
    int pngLevel = kDefaultPngLevel;
};

// The file name of frame `frame`: the pattern's single %d/%0Nd, or "_%04d" before the extension.
std::string framePath(const std::string& pattern, int frame, bool sequence) {
    if (!sequence) return pattern;
    char number[32];
    static const std::regex kSpec("%(0?[0-9]*)d");
    std::smatch match;
    if (std::regex_search(pattern, match, kSpec)) {
        const int width = match[1].length() ? std::stoi(match[1].str()) : 0;
        std::snprintf(number, sizeof number, "%0*d", width, frame);
        return match.prefix().str() + number + match.suffix().str();
    }
    std::snprintf(number, sizeof number, "_%04d", frame);
    const std::filesystem::path p(pattern);
    return (p.parent_path() / (p.stem().string() + number + p.extension().string())).string();
}

std::string checkPattern(const std::string& flag, const std::string& path) {
    const auto percents = std::count(path.begin(), path.end(), '%');
    static const std::regex kOnly("[^%]*%0?[0-9]*d[^%]*");
    if (percents > 1 || (percents == 1 && !std::regex_match(path, kOnly)))
        return flag + " " + path + ": at most one %d (or %0Nd) and no other % in a file name";
    return {};
}


// Everything `render` reads from its command line: the settings (in `options`), and the files.
struct RenderRequest {
    RenderOptions options;
    Outputs outputs;
};

// --settings FILE (frugal/Settings.h): its values are where the flags start from, so a flag given
// beside it wins wherever it stands; its keys count as given. "ids" and "linear" are left out: they
// are drawn when --ids and --linear name a file.
Result<bool> applySettingsFile(const std::vector<std::string>& args, RenderOptions& o) {
    const auto given = std::find(args.begin(), args.end(), "--settings");
    if (given == args.end() || std::next(given) == args.end()) return true;  // the flag reports a missing value
    Result<SettingsFile> file = readSettingsFile(*std::next(given), o.settings);
    if (!file) return file.error();
    o.settings = file->settings;
    o.given = file->keys;
    return true;
}

// The checks of render's own flags, once all are read.
void checkRender(const RenderRequest& r, ArgCursor& cursor) {
    const Outputs& o = r.outputs;
    if (!hasExtension(o.color, ".png"))
        cursor.fail("-o " + o.color + ": the colour image is written as PNG; name it .png");
    else if (!o.depth.empty() && !hasExtension(o.depth, ".png") && !hasExtension(o.depth, ".pfm"))
        cursor.fail("--depth " + o.depth + ": name it .png (16-bit) or .pfm (float32)");
    else if (!o.ids.empty() && !hasExtension(o.ids, ".png"))
        cursor.fail("--ids " + o.ids + ": the id image is written as PNG; name it .png");
    else if (!o.linear.empty() && !linearPathProblem(o.linear).empty())
        cursor.fail("--linear " + o.linear + ": " + linearPathProblem(o.linear));
    else if (r.options.frames)
        for (const auto& [flag, path] :
             {std::pair{"-o", o.color}, {"--depth", o.depth}, {"--ids", o.ids}, {"--linear", o.linear}})
            if (!path.empty()) {
                const std::string problem = checkPattern(flag, path);
                if (!problem.empty()) cursor.fail(problem);
            }
}

// --png-level N|auto into `level`.
Flag pngLevelFlag(int& level) {
    return {"--png-level", "N|auto", "PNG compression: 0 (stored: fastest, largest files), 1 (frugal's run-length "
            "deflate: several times faster, files somewhat larger), 2 to 12 (libdeflate: smaller, slower), or auto "
            "(default): per kind of image the fastest level whose files stayed within 1.1x those of the old encoder "
            "on every scene measured (colour 3, depth 1, ids 6; docs/writing.md). Files are encoded on threads of "
            "their own while the next frame renders",
            [&level](const std::string& text) -> std::string {
                if (text == "auto") {
                    level = kAutoPngLevel;
                    return {};
                }
                const auto digit = [](char c) { return c >= '0' && c <= '9'; };
                if (text.empty() || text.size() > 2 || !std::all_of(text.begin(), text.end(), digit) ||
                    std::stoi(text) > kMaxPngLevel)
                    return "must be 0 to " + std::to_string(kMaxPngLevel) + " or auto";
                level = std::stoi(text);
                return {};
            }};
}

// The command line into `request`: the exit status to return, or nothing to go on.
std::optional<int> parseRender(const std::vector<std::string>& args, RenderRequest& r, std::ostream& out,
                               std::ostream& err) {
    if (Result<bool> applied = applySettingsFile(args, r.options); !applied) return fail(err, applied.error());
    CommandLine command{"render", renderHelp(), &r.options};
    Outputs& files = r.outputs;
    RenderOptions& o = r.options;
    std::string settingsFile;  // read above, before the other flags
    std::vector<Flag> reuse = topicFlags(o, "reuse");
    reuse.push_back(cameraPathFlag(o));
    command.flags = {
        {"settings file",
         {
             flag::text("--settings", "FILE",
                        "start from a settings file: a JSON object of the options below by "
                        "name, e.g. {\"cull\": \"conservative\", \"reuse\": true} (docs/cli.md, 'Settings "
                        "files'); flags given beside it win",
                        settingsFile),
         }},
        {"outputs (each written to a temporary file and renamed, never left half-written)",
         {
             flag::text("-o, --output", "FILE",
                        "colour PNG (default frame.png). With --frames, FILE may hold a printf "
                        "number such as out_%04d.png; otherwise _%04d is put before the extension",
                        files.color),
             flag::text("--depth", "FILE",
                        "depth: .png = 16-bit grey, 0 near, 65535 far (d24: the top 16 of its 24 "
                        "bits), with the format and planes in its text chunks; .pfm = float32 window z, exact (d32f: "
                        "reversed, 1 near, 0 far)",
                        files.depth),
             flag::text("--ids", "FILE",
                        "triangle ids: PNG whose RGBA bytes are the 32-bit id, little-endian (R = low "
                        "byte); 0 = background",
                        files.ids),
             flag::text("--linear", "FILE",
                        "the colour in linear light, drawn into a float target (after tone "
                        "mapping, before the display encoding; blended surfaces and multisampled edges mix in linear "
                        "light, and the -o image is then its display encoding): .pfm = float32 rgb, unclamped, exact; "
                        ".png = 16-bit RGBA, clamped to [0, 1], gAMA 1.0",
                        files.linear),
             pngLevelFlag(files.pngLevel),
             flag::text(
                 "--json", "FILE",
                 "metadata: scene counts, camera (the planes drawn with and the given ones, the "
                 "aspect ratios, the depth format), backend, GL renderer, per-frame timings (render_ms, readback_ms; "
                 "write_ms: encoding and writing the frame's files on the writer's threads, encode_ms of it; with "
                 "--cull: "
                 "per-frame tos, pvs and cull_ms too), and per frame the state changes the backend issued, by "
                 "kind (\"state_changes\": draws, programs, meshes, textures, toggles, uniforms; software: draws "
                 "only)",
                 files.json),
             flag::text("--save-settings", "FILE",
                        "write the settings this render uses as a settings file (the form "
                        "--settings reads), before the first frame",
                        files.settings),
         }},
        {"culling (only the triangles that may be visible are submitted; src/cull/Culling.h)",
         topicFlags(o, "culling")},
        {"draw order (costly state changes made rare; src/order/)", topicFlags(o, "order")},
        {"temporal reuse (with a still camera only what changed is redrawn; src/reuse/Reuse.h)", reuse},
        {"hidden-surface removal (paper 003; src/hsr/Plan.h)", topicFlags(o, "hsr")},
    };
    command.positional = sceneArgument(o);
    command.finish = [&r](ArgCursor& cursor) { checkRender(r, cursor); };
    std::optional<int> status = parseCommandLine(command, args, out, err);
    o.settings.ids = !files.ids.empty();
    o.settings.linear = !files.linear.empty();
    return status;
}

// The frame's files (FrameWriter writes them as one set).
FramePaths framePaths(const Outputs& o, int index, bool sequence) {
    const auto path = [&](const std::string& given) { return given.empty() ? given : framePath(given, index, sequence); };
    return {path(o.color), path(o.depth), path(o.ids), path(o.linear)};
}

// "frame 3 (4/10): 8.2 ms (conservative: 31000 of 69666 triangles) -> out_0003.png".
std::string progressLine(const Settings& s, std::size_t triangles, const FrameStats& stats, int index, int done,
                         int count, const std::string& file) {
    std::string line = "frame " + std::to_string(index) + " (" + std::to_string(done) + "/" + std::to_string(count) +
                       "): " + fmt(stats.renderMs) + " ms";
    if (stats.cull)
        line += std::string(" (") + toString(s.cull) + ": " + std::to_string(stats.cull->pvs) + " of " +
                std::to_string(triangles) + " triangles)";
    if (stats.hsr)
        line += std::string(" (") + toString(s.hsr) + ": " + std::to_string(stats.hsr->zbuffered(s.hsr)) + " of " +
                std::to_string(stats.hsr->polygons) + " polygons depth-tested)";
    if (stats.reuse) {
        line += std::string(" (") + toString(stats.reuse->mode) + ": " + std::to_string(stats.reuse->redrawnTris) +
                " of " + std::to_string(stats.reuse->drawnTris) + " triangles drawn";
        if (stats.reuse->mode == ReuseMode::Full) line += "; " + stats.reuse->reason;
        line += ")";
    }
    return line + " -> " + file;
}

// Frames whose files the writer has queued: each frame's JSON record and progress line wait until
// its files exist (FrameWriter writes them in order), then go to the render JSON and stderr.
class WrittenFrames {
public:
    WrittenFrames(RenderJsonFile& json, bool quiet, std::ostream& err) : json_(json), quiet_(quiet), err_(err) {}

    void push(nlohmann::json record, const FrameStats& stats, std::string progress) {
        waiting_.push_back({std::move(record), stats, std::move(progress)});
    }
    // Records the frames the writer has finished since the last call.
    Result<bool> collect(FrameWriter& writer) {
        for (const FrameWriter::Written& w : writer.takeWritten()) {
            Waiting next = std::move(waiting_.front());
            waiting_.pop_front();
            next.record.update({{"write_ms", w.encodeMs + w.writeMs}, {"encode_ms", w.encodeMs}});
            if (Result<bool> kept = json_.add(std::move(next.record), next.stats); !kept) return kept;
            if (!quiet_) err_ << next.progress << "\n";
            ++written_;
        }
        return true;
    }
    // Waits for every frame given, then records them; the writer's first error, if any.
    Result<bool> finish(FrameWriter& writer) {
        const Result<bool> finished = writer.finish();
        if (Result<bool> collected = collect(writer); !collected) return collected;
        return finished;
    }
    int written() const { return written_; }

private:
    struct Waiting {
        nlohmann::json record;
        FrameStats stats;
        std::string progress;
    };
    RenderJsonFile& json_;
    bool quiet_;
    std::ostream& err_;
    std::deque<Waiting> waiting_;
    int written_ = 0;
};

// Renders the frames asked for and queues their files. Files are encoded and written on the
// writer's threads while the next frame renders. SIGINT, SIGTERM and SIGHUP stop the sequence
// between frames: the frames rendered are written, the JSON is not (frugal/Interrupt.h). `camera`
// gets the first frame's view.
Result<bool> renderFrames(Renderer& renderer, const RenderRequest& r, RenderJsonFile& json, nlohmann::json& camera,
                          std::ostream& err) {
    const RenderOptions& options = r.options;
    const Settings& s = renderer.settings();
    const FrameRange range = options.frames.value_or(FrameRange{});
    const int frameCount = range.last - range.first + 1;
    Result<FrameWriter> madeWriter = FrameWriter::create({.threads = 0, .queue = 0, .pngLevel = r.outputs.pngLevel});
    if (!madeWriter) return madeWriter.error();
    FrameWriter& writer = *madeWriter;
    WrittenFrames written(json, options.quiet, err);
    InterruptPoints interrupts;
    std::uint64_t overflow = 0;  // --interp: spans that overflowed, over every frame
    Frame frame;  // the memory of a frame already written comes back here (FrameWriter::write)
    for (int index = range.first; index <= range.last; ++index) {
        if (const int caught = interrupts.arrived()) {
            if (Result<bool> finished = written.finish(writer); !finished) return finished;
            return Error{interruptedAfter(caught, written.written(), frameCount), ErrorKind::Interrupted};
        }
        // With --cull occlusion-ahead, the next frame's plan is made while this one draws.
        if (index < range.last)
            renderer.setNextFrame(cameraOf(options, index + 1), frameTimeOf(options, renderer.scene(), index + 1));
        // The depth is read back only for a file that holds it.
        Result<bool> rendered = renderer.render(cameraOf(options, index), frameTimeOf(options, renderer.scene(), index),
                                                frame, {.depth = !r.outputs.depth.empty()});
        if (!rendered) return rendered;
        const std::string file = framePath(r.outputs.color, index, range.sequence);
        if (index == range.first) camera = viewJson(frame.view, s);
        nlohmann::json record = frameStatsJson(frame.stats, s);
        record.update({{"frame", index}, {"file", file}});
        if (frame.stats.interp) overflow += frame.stats.interp->overflow;
        written.push(std::move(record), frame.stats,
                     options.quiet ? std::string()
                                   : progressLine(s, renderer.scene().triangleCount(), frame.stats, index,
                                                  index - range.first + 1, frameCount, file));
        if (Result<bool> queued = writer.write(framePaths(r.outputs, index, range.sequence), frame); !queued)
            return queued;
        if (Result<bool> collected = written.collect(writer); !collected) return collected;
    }
    if (Result<bool> finished = written.finish(writer); !finished) return finished;
    if (overflow > 0)
        err << "warning: --interp " << toString(s.interp) << ": " << overflow
            << " spans overflowed the 24-bit depth and were clamped (see the JSON's per-frame \"interp\")\n";
    return true;
}

}  // namespace

int runRender(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderRequest r;
    if (std::optional<int> status = parseRender(args, r, out, err)) return *status;
    Result<Scene> loaded = loadForRender(r.options, err);
    if (!loaded) return fail(err, loaded.error());
    if (!r.outputs.settings.empty())
        if (Result<bool> saved = writeFile(r.outputs.settings, settingsJson(r.options.settings)); !saved)
            return fail(err, saved.error());
    Result<Renderer> made = Renderer::create(std::move(*loaded), r.options.settings);
    if (!made) return fail(err, made.error());
    Renderer& renderer = *made;
    if (!r.options.quiet) printRendererStart(renderer, err);
    RenderJsonFile json(r.outputs.json);
    nlohmann::json camera;
    if (Result<bool> rendered = renderFrames(renderer, r, json, camera, err); !rendered)
        return fail(err, rendered.error());
    if (Result<bool> written = json.finish(renderJsonMeta(renderer, r.options.scene, camera)); !written)
        return fail(err, written.error());
    if (!r.options.quiet && !(r.options.frames && r.options.frames->sequence)) out << "wrote " << r.outputs.color << "\n";
    return kExitOk;
}

}  // namespace frugal
