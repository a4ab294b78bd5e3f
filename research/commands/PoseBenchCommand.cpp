// `frugal-lab pose-bench`: what skins and morph targets cost a frame (lab/PoseBench.h).
#include <ostream>

#include "commands/LabCommands.h"
#include "lab/PoseBench.h"

namespace frugal {

const char* poseBenchHelp() {
    return R"(usage: frugal-lab pose-bench [SCENE] [options]

Times the frames of SCENE's animation as they are ("deforming": every deforming mesh posed on the
CPU at each frame's time, its vertices written in place) and, interleaved in the same run, the same
frames of the scene with its skins and morph targets taken away ("rest pose"), each on a stage of
its own, at the same times and with the same camera. Without SCENE: a generated tube of 100,000
triangles on a chain of 64 joints that all turn (the skinning goal: at most 1.2x the rest pose's
frame on the GL path). Per variant: the median frame time (clear + pose + draws + finish; min and
max) and its ratio to the rest pose's. Prints a line per variant.
)";
}

int runPoseBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    FrameBenchCommand bench{
        "pose-bench",
        poseBenchHelp(),
        "variant",
        "{\"scene\",\"size\",\"backend\",\"renderer\",\"runs\",\"deforming_instances\",\"vertices_posed\","
        "\"rows\":[{\"variant\",\"median_ms\",\"min_ms\",\"max_ms\",\"over_rest\"}]}",
        "one row per variant",
        "each variant's median frame time and its range, drawn by gnuplot from the CSV (--csv, or FILE.csv beside the "
        "plot); the script is written as FILE.gp",
        [](const Scene& scene, const FrameSetup& setup, const RenderOptions& options, int repeat, int warmup,
           const std::function<void(const std::string&)>& progress) {
            return measurePoses(scene, setup, PoseBenchSettings{options.scene, options.settings, repeat, warmup},
                                progress);
        },
        poseBenchGnuplot};
    bench.defaultScene = "tube";
    bench.generated = [] { return poseBenchTube(); };
    bench.defaultRepeat = 60;
    return runFrameBench(bench, args, out, err);
}

}  // namespace frugal
