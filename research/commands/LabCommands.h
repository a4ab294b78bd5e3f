// frugal-lab's own commands: the benchmarks and paper reproductions (labProgram). Each returns an
// ExitCode (app/Cli.h).
#pragma once

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "app/Cli.h"
#include "app/Options.h"
#include "lab/Frames.h"  // FrameSetup
#include "lab/ReportText.h"

namespace frugal {

int runBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runReuseBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runOrderBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runHsrBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runSpanBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runStateSim(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runSoak(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runWriteBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runShadingBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runPoseBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runCompress(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

const char* benchHelp();
const char* reuseBenchHelp();
const char* orderBenchHelp();
const char* hsrBenchHelp();
const char* spanBenchHelp();
const char* stateSimHelp();
const char* soakHelp();
const char* writeBenchHelp();
const char* shadingBenchHelp();
const char* poseBenchHelp();
const char* compressHelp();

// A one-frame benchmark's command (order-bench, shading-bench, pose-bench): its name and help, what
// one unit of it is called ("order", "variant"), the report outputs' descriptions (reportFlags), the
// measurement (the scene, its frame set up from the settings, --repeat, --warmup, the progress lines)
// and its gnuplot script; the scene without a SCENE argument (`defaultScene`, made by `generated`
// when it has one: a scene of the command's own, no file) and --repeat's default.
struct FrameBenchCommand {
    std::string name;
    const char* help;
    std::string unit;
    std::string jsonShape, csvRows, plot;
    std::function<Result<BenchTexts>(const Scene&, const FrameSetup&, const RenderOptions&, int repeat, int warmup,
                                     const std::function<void(const std::string&)>& progress)>
        measure;
    std::function<std::string(const std::string& csvPath, const std::string& svgPath, const std::string& scene)>
        gnuplot;
    std::string defaultScene = "builtin:materials";
    std::function<Scene()> generated = nullptr;
    int defaultRepeat = 20;
};
// Parses `args` (SCENE, --repeat, --warmup, the render options and report outputs), sets up the
// frame, measures it and writes the report: the command's exit status.
int runFrameBench(const FrameBenchCommand& bench, const std::vector<std::string>& args, std::ostream& out,
                  std::ostream& err);

// frugal-lab: these commands, then frugal's (a batch run by frugal-lab takes reuse-bench jobs too).
const Program& labProgram();

}  // namespace frugal
