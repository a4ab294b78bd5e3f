// frugal's commands (frugalProgram, app/Cli.h). Each returns an ExitCode.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace frugal {

int runRender(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runReport(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runInfo(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runCompare(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runDiff(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runCullReport(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runBatch(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

const char* renderHelp();
const char* reportHelp();
const char* infoHelp();
const char* compareHelp();
const char* diffHelp();
const char* cullReportHelp();
const char* batchHelp();

}  // namespace frugal
