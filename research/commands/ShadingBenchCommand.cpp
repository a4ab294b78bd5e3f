// `frugal-lab shading-bench`: what each shading term costs on one frame (lab/ShadingBench.h).
#include <ostream>

#include "commands/LabCommands.h"
#include "lab/ShadingBench.h"

namespace frugal {

const char* shadingBenchHelp() {
    return R"(usage: frugal-lab shading-bench [SCENE] [options]

Times one frame of SCENE (default builtin:materials) as the settings draw it ("full") and, in the
same run, interleaved, the same frame with one shading term taken away: --shading lambert, the
environment's specular term, the environment, the uniform stand-in for --environment-map, every
texture, the normal maps, blending (BLEND materials drawn opaque); and with multisampling added
(--samples 4, or 1 when the settings ask for more). A term the scene does not use is skipped, with
why. Per variant: the median frame time (clear + draws + finish; min and max), its ratio to full's,
and the pixels where its image differs from full's. Each variant draws on its own stage (a context
of the one backend --backend opens, its own uploads). Prints a line per variant.
)";
}

int runShadingBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    const FrameBenchCommand bench{
        "shading-bench",
        shadingBenchHelp(),
        "variant",
        "{\"scene\",\"size\",\"backend\",\"renderer\",\"runs\",\"rows\":[{\"term\",\"change\",\"median_ms\","
        "\"min_ms\",\"max_ms\",\"pixels_differing\",\"over_full\"}],\"skipped\":[{\"term\",\"why\"}]}",
        "one row per variant",
        "each variant's median frame time over full's, drawn by gnuplot from the CSV (--csv, or FILE.csv beside the "
        "plot); the script is written as FILE.gp",
        [](const Scene& scene, const FrameSetup& setup, const RenderOptions& options, int repeat, int warmup,
           const std::function<void(const std::string&)>& progress) {
            return measureShadingTerms(scene, setup,
                                       ShadingBenchSettings{options.scene, options.settings, repeat, warmup}, progress);
        },
        shadingBenchGnuplot};
    return runFrameBench(bench, args, out, err);
}

}  // namespace frugal
