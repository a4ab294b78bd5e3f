// The CLI's commands. Each returns an ExitCode (app/Cli.h).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace frugal {

int runRender(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runReport(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runInfo(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runCompare(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runDiff(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runCullReport(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runReuseBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runOrderBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runHsrBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runSpanBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runStateSim(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runSoak(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runBatch(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runWriteBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

const char* renderHelp();
const char* reportHelp();
const char* infoHelp();
const char* benchHelp();
const char* compareHelp();
const char* diffHelp();
const char* cullReportHelp();
const char* reuseBenchHelp();
const char* orderBenchHelp();
const char* hsrBenchHelp();
const char* spanBenchHelp();
const char* stateSimHelp();
const char* soakHelp();
const char* batchHelp();
const char* writeBenchHelp();

}  // namespace frugal
