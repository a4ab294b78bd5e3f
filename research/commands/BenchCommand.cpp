// `frugal-lab bench render`: the same frame on every available backend, and with the file's triangle
// order beside the vertex-cache order, in one process; JSON with medians and ratios. The
// measurement is lab/RenderBench.h's (frugal's frame beside the minimal GL program, unbatched,
// premerged and in the other depth format); this parses the flags, loads the scene in both orders,
// runs it and prints the report.
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "app/Cli.h"
#include "app/Command.h"
#include "commands/LabCommands.h"
#include "lab/RenderBench.h"

namespace frugal {

const char* benchHelp() {
    return R"(usage: frugal-lab bench render [SCENE] [options]

Renders the same frame repeatedly on each available backend (egl-device, egl-surfaceless, osmesa
and the software reference; or only --backend), once with the vertex-cache triangle order and once
with the file's order, and prints JSON: median/min/max ms per frame, triangles per second, and
ratios.
--threads N sets the thread count of every backend (llvmpipe and software) for a fair comparison.

On each GL backend the frame is also drawn by a minimal GL program on its own context of the same
kind (one program with position and normal, glClear, glDrawElements per instance), its timed frames
alternating with frugal's: rows with "variant": "minimal", the ratios "over_minimal" (frugal ÷
minimal, vertex-cache order) and "over_minimal_file_order", and "minimal_pixels_equal" (both colour
images read back once, after timing). Scenes with textures or vertex colours, and --ids, have no
minimal variant; "skipped" says why.

The cache order also times the same frame in the other depth format (--depth-format, default d24;
see 'frugal help render'), into a target of its own, interleaved with frugal's frames: a row with
"variant": "d32f" (or "d24"), its "pixels_differing" from frugal's image, and the ratio
"d32f_over_d24". A backend without glClipControl skips it ("skipped" says so).
)";
}

int runBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    if (args.empty() || (args[0] != "render" && args[0] != "-h" && args[0] != "--help"))
        return usageError(err, "bench: expected 'bench render [SCENE] [options]'");
    RenderOptions options;
    bool ids = false;
    int runs = 30, warmup = 5;
    std::vector<std::string> rest(args.begin() + (args[0] == "render" ? 1 : 0), args.end());
    CommandLine command{"bench", benchHelp(), &options};
    command.flags = {{"", {
        flag::whole("--repeat", "N", "timed frames per variant (default 30)", runs, 1, 100000),
        flag::whole("--warmup", "N", "untimed frames first (default 5)", warmup, 0, 100000),
        flag::on("--ids", "also write triangle ids (the id pass)", ids),
        settingFlag("hsr", options.settings, options.given,
                    "the hidden-surface mode (see 'frugal help render'); the plan is timed with the frame; the minimal "
                    "program stays z-buffered"),
        settingFlag("order", options.settings, options.given,
                    "the draw order (see 'frugal help render'); consecutive draws of one mesh are one instanced draw. In the cache order two more rows: "
                             "\"unbatched\" (one draw per instance) and \"premerged\" (the floor: the instances "
                             "pre-transformed into one mesh per material); \"pixels_differing\" says where each image "
                             "differs from frugal's, and for frugal's own row, where --order changed it from "
                             "submission order (exact depth ties); ratios \"unbatched_over_batched\" and "
                             "\"over_premerged\""),
    }}};
    command.positional = sceneArgument(options);
    if (std::optional<int> status = parseCommandLine(command, rest, out, err)) return *status;

    // Two loads of the same file: the only difference is the triangle order.
    LoadOptions fileOrder = options.load;
    fileOrder.optimizeOrder = false;
    LoadOptions cacheOrder = options.load;
    cacheOrder.optimizeOrder = true;
    Result<Scene> optimized = loadScene(options.scene, cacheOrder);
    if (!optimized) return fail(err, optimized.error());
    Result<Scene> original = loadScene(options.scene, fileOrder);
    if (!original) return fail(err, original.error());
    if (const std::string warning = fitSizeToCamera(options, *optimized); !warning.empty() && !options.quiet)
        err << "warning: " << warning << "\n";

    const int frame = options.frames ? options.frames->first : 0;
    RenderBenchSettings settings;
    settings.scene = options.scene;
    settings.render = options.settings;
    settings.runs = runs;
    settings.warmup = warmup;
    settings.camera = cameraOf(options, frame);
    settings.time = frameTimeOf(options, *optimized, frame);
    settings.render.ids = ids;
    Result<RenderBench> bench = measureRenderBench(*optimized, *original, settings, progressTo(err, options.quiet));
    if (!bench) return fail(err, bench.error());
    out << renderBenchJson(*bench);
    return kExitOk;
}

}  // namespace frugal
