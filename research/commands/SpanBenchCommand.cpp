// `frugal-lab span-bench`: the bit-level model of paper 001's shading engine (src/span/):
// Fig. 11 reproduced, the schemes it rules out, the error tables of midpoint subdivision, of the
// same tree truncating at each level, of a DDA and of double evaluation against the exact line, and
// the model's spans per second beside the paper's 59,000; with --scene, the software backend's
// --interp modes on whole scenes (how span and dda depart from exact, and the slow path's speed).
// The measurement and its texts are the lab's (lab/SpanBench.h); this file parses, prints and writes.
#include <optional>
#include <ostream>

#include "app/Cli.h"
#include "app/Command.h"
#include "commands/LabCommands.h"
#include "app/Options.h"
#include "app/ReportOutputs.h"
#include "lab/SpanBench.h"

namespace frugal {

const char* spanBenchHelp() {
    return R"(usage: frugal-lab span-bench [options]

The shading engine of paper 001 (Bang, Bae, Kyung 1990) modelled bit by bit: 64-pixel engines, the
L/R multipliers f(XL), f(XR), the midpoint-subdivision tree, the Edge Painting Tree, the LSB-first
z comparator. Prints Fig. 11 as the model computes it (and which rounding schemes contradict the
figure), then the error of each interpolator against the exact line, rounded to nearest:
  span        the paper's engine: ends rounded, exact subdivision, pixels rounded (<= 1 LSB)
  span_trunc  the same tree truncating at every level (PIPE's add-and-shift-right)
  dda         add-and-shift: the slope accumulated per pixel in a --dda-bits register
  exact       double evaluation, rounded
and the spans per second of the model on this machine beside the paper's one span per 17 us.
With --scene, also renders each scene's frame 0 on the software backend (one thread) with
--interp exact, span and dda, and reports how span and dda depart from the exact render and how
fast the slow path runs.
)";
}

int runSpanBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    span::BenchSettings bench;
    span::ErrorTableSettings& settings = bench.table;
    ReportPaths outputs;
    CommandLine command{"span-bench", spanBenchHelp()};
    command.flags = {{"", {
        flag::wholeList("--lengths", "L,L,...", "span lengths in pixels (default 8,64,512,8192)", settings.lengths, 2,
                        span::kMaxTableLength),
        flag::wholeList("--widths", "W,W,...", "channel widths in bits (default 16,24: colour and z)", settings.widths,
                        1, span::kMaxWidth),
        flag::whole("--spans", "N", "random spans per width, length and method (default 2000); a quarter of them the "
                    "steepest ramp (0 to the top, or back)", settings.spans, 1, 1000000),
        flag::whole("--seed", "S", "seed of the random spans (default 1)", settings.seed, 0, 2147483647),
        flag::whole("--dda-bits", "N", "the DDA's register: N bits, N − width of them fraction bits; wider than every "
                    "width (default 32)", settings.accumulatorBits, 2, 62),
        flag::whole("--speed-ms", "N", "time each spans-per-second figure for N ms; 0 skips the measurement (default "
                    "100)", bench.speedMs, 0, 60000),
        {"--scene", "SCENE", "a scene as the other commands take it (builtin:cubes, a .obj, .gltf or .glb file); may be "
         "given several times. OBJ files are drawn single-sided (as with --cull-backfaces). For each, frame 0 at "
         "--render-size on the software backend with one thread, in exact, span and dda; per mode: pixels whose colour "
         "differs from exact, pixels another triangle won (ids differ), worst and mean depth error in 24-bit LSB over "
         "covered pixels, pixels whose depth changed, overflowing spans, spans per frame, the frame time (best of 5, "
         "rasterization included) beside exact's, and spans per second (spans per frame / best frame time). Timings "
         "are printed, never asserted",
         [&bench](const std::string& text) -> std::string {
             if (text.empty()) return "is not a scene (builtin:NAME or a file)";
             bench.scenes.push_back(text);
             return {};
         }},
        flag::size("--render-size", "WxH", "image size of every --scene (default 800x600)", bench.renderWidth,
                   bench.renderHeight, span::kMaxBenchRenderSize),
    }}};
    for (Flag& f : reportFlags(outputs,
                               "{\"fig11\":{...},\"errors\":[{width,length,method,worst_lsb,mean_lsb,spans,...}],"
                               "\"spans_per_second\":{...},\"render\":[{scene,size,mode,colour_px,id_px,worst_lsb,"
                               "mean_lsb,depth_changed_px,overflow,spans,frame_ms,exact_frame_ms,spans_per_second}]}",
                               "the error table, one row per width, length and method",
                               "worst and mean error against span length, drawn by gnuplot from the CSV (--csv, or "
                               "FILE.csv beside the plot); the script is written as FILE.gp"))
        command.flags[0].flags.push_back(std::move(f));
    command.finish = [&](ArgCursor& cursor) {
        if (const std::optional<Error> problem = span::benchSettingsProblem(bench))
            cursor.fail("--" + problem->message);
        else if (const std::string plot = plotProblem(outputs); !plot.empty())
            cursor.fail(plot);
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;

    const Result<span::BenchReport> report = span::runBenchmark(bench);
    if (!report) return fail(err, report.error());
    const ReportTexts texts{[&report] { return span::benchJson(*report); }, [&report] { return span::benchCsv(*report); },
                            [&report](const std::string& csvPath, const std::string& svgPath) {
                                return span::benchGnuplot(*report, csvPath, svgPath);
                            }};
    if (const int status = writeReportFiles(outputs, texts, err); status != kExitOk) return status;
    out << span::benchText(*report);
    return kExitOk;
}

}  // namespace frugal
