// frugal-lab's own commands: the benchmarks and paper reproductions (labProgram). Each returns an
// ExitCode (app/Cli.h).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "app/Cli.h"

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

const char* benchHelp();
const char* reuseBenchHelp();
const char* orderBenchHelp();
const char* hsrBenchHelp();
const char* spanBenchHelp();
const char* stateSimHelp();
const char* soakHelp();
const char* writeBenchHelp();
const char* shadingBenchHelp();

// frugal-lab: these commands, then frugal's (a batch run by frugal-lab takes reuse-bench jobs too).
const Program& labProgram();

}  // namespace frugal
