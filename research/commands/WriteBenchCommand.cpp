// `frugal-lab write-bench`: what writing a frame's files costs (the PNG encoder's levels and filters
// against the encoder frugal had before) and whether a sequence runs at the speed of rendering
// (files written while the next frame renders). The measurement and its texts are the lab's
// (lab/WriteBench.h); this file parses, loads the scenes, prints and writes.
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "app/Cli.h"
#include "app/Command.h"
#include "commands/LabCommands.h"
#include "app/Options.h"
#include "app/ReportOutputs.h"
#include "lab/WriteBench.h"

namespace frugal {

const char* writeBenchHelp() {
    return R"(usage: frugal-lab write-bench [--scene SCENE ...] [options]

Part one: each scene's frame (camera 0, --size, default 1920x1080) is rendered once with colour,
depth and ids, and each of the three images encoded as PNG --repeat times per libdeflate level
(--levels) and PNG filter (none, sub, up, paeth), beside the baseline: the encoder frugal had
before (no filter, zlib level 6, one thread). Per row: median ms, bytes, bytes and speed against
the baseline, and whether the decoded pixels equal the baseline's (they must: PNG is lossless).
Then, per image kind, the fastest level and filter whose files are at most --size-limit times the
baseline's on every scene: how frugal's defaults were chosen.

Part two (--frames N, 0 skips it): N frames of the first scene per variant, the variants taking
turns for --rounds rounds, wall ms per frame: render (render and read back only: the floor), async
(files encoded and written while the next frame renders, as `frugal render` does), sync (the same
encoder after each frame), baseline (the old encoder after each frame: what `frugal render` did
before) and one-frame async (a writer made, one frame written, finished: a one-frame run); once
with the colour file and once with colour, depth and ids. Files go to a temporary folder, removed
after.

Part three (--readback-frames N, 0 skips it; GL backends and scenes the bench's minimal frame
draws: no textures, no vertex colours): the first scene's frame drawn by the fewest GL calls and
read back four ways, in turns for --rounds rounds, wall ms per frame: draw (nothing read: the
floor), readpixels (glFinish, then glReadPixels: what frugal does), pbo (glReadPixels into a pixel
buffer object, then copied out) and pbo, a frame late (frame N read into one of two buffers while
frame N-1 is copied out of the other); once with the colour and once with colour and depth, each
way's images checked equal to glReadPixels'. Timings are printed, never asserted.
)";
}

int runWriteBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    options.settings.width = 1920;
    options.settings.height = 1080;
    options.given.push_back("size");  // the size stays 1920x1080 unless --size says otherwise
    std::vector<std::string> scenes;
    WriteBenchSettings settings;
    ReportPaths outputs;
    CommandLine command{"write-bench", writeBenchHelp()};
    FlagGroup shared = someFlags(renderFlags(options), {"--size", "--backend", "--threads", "--quiet"});
    command.flags = {shared, {"", {
        {"--scene", "SCENE", "a scene as the other commands take it (builtin:cubes, a .obj, .gltf or .glb file); may be "
         "given several times (default builtin:default); parts two and three render the first",
         [&scenes](const std::string& text) -> std::string {
             if (text.empty()) return "is not a scene (builtin:NAME or a file)";
             scenes.push_back(text);
             return {};
         }},
        flag::wholeList("--levels", "L,L,...", "libdeflate levels in the table, 0 to 12 (default 1,2,3,4,6,9)",
                        settings.levels, 0, 12),
        flag::whole("--repeat", "N", "encodings per row: the median and the fastest are reported, the choice goes by the "
                    "fastest (noise only ever adds time; default 5)", settings.repeat, 1, 1000),
        flag::number("--size-limit", "X", "the choice's largest file over the baseline's (default 1.1)",
                     settings.sizeLimit, 0.01, 100.0),
        flag::whole("--frames", "N", "part two: frames per variant and round (default 30; 0 skips part two)",
                    settings.frames, 0, 100000),
        flag::whole("--rounds", "N", "parts two and three: rounds of the variants in turn (default 3)", settings.rounds,
                    1, 1000),
        flag::whole("--readback-frames", "N", "part three: frames per variant and round (default 30; 0 skips part "
                    "three)", settings.readbackFrames, 0, 100000),
    }}};
    for (Flag& f : reportFlags(outputs,
                               "{\"encodes\":[{scene,plane,encoder,level,filter,median_ms,min_ms,bytes,size_over_baseline,"
                               "speedup_over_baseline,pixels_equal}],\"choices\":[...],\"sequence\":{\"results\":[{planes,"
                               "variant,median_ms_per_frame,ms_per_frame,over_render,over_baseline}]},\"readback\":{\"results\":[{planes,"
                               "variant,median_ms_per_frame,ms_per_frame,over_draw,over_readpixels,pixels_equal}]}}",
                               "the encoder table, one row per scene, image, level and filter",
                               "size against time per image kind, drawn by gnuplot from the CSV (--csv, or FILE.csv "
                               "beside the plot); the script is written as FILE.gp"))
        command.flags[1].flags.push_back(std::move(f));
    command.finish = [&](ArgCursor& cursor) {
        if (const std::string plot = plotProblem(outputs); !plot.empty()) cursor.fail(plot);
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;
    if (scenes.empty()) scenes.push_back("builtin:default");

    std::vector<std::pair<std::string, Scene>> loaded;
    for (const std::string& name : scenes) {
        options.scene = name;
        Result<Scene> scene = loadForRender(options, err);
        if (!scene) return fail(err, scene.error());
        loaded.emplace_back(name, std::move(*scene));
    }
    settings.render = options.settings;
    Result<WriteBench> bench = measureWriteBench(loaded, settings, progressTo(err, options.quiet));
    if (!bench) return fail(err, bench.error());
    const ReportTexts texts{[&bench] { return writeBenchJson(*bench); }, [&bench] { return writeBenchCsv(*bench); },
                            [&bench](const std::string& csvPath, const std::string& svgPath) {
                                return writeBenchGnuplot(*bench, csvPath, svgPath);
                            }};
    if (const int status = writeReportFiles(outputs, texts, err); status != kExitOk) return status;
    // JSON on stdout unless it went to a file; the summary on stderr unless --quiet.
    if (outputs.json.empty()) out << writeBenchJson(*bench);
    if (!options.quiet) err << writeBenchText(*bench);
    return kExitOk;
}

}  // namespace frugal
