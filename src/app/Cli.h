// The `frugal` command line, as a library so tests can run it in-process.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace frugal {

// Exit codes, also listed by `frugal --help`.
enum ExitCode : int {
    kExitOk = 0,
    kExitError = 1,        // bad input file, failed output, comparison outside tolerance
    kExitUsage = 2,        // bad command line
    kExitNoBackend = 3,    // the requested backend is not available on this machine
};

// Runs `frugal args...` (args without the program name). Normal output goes to `out`, progress,
// warnings and errors (one line each, "error: <what>: <why>") to `err`.
int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace frugal
