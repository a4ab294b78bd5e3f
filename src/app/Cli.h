// The `frugal` command line, as a library so tests can run it in-process.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include <frugal/Result.h>

namespace frugal {

// Exit codes, also listed by `frugal --help`.
enum ExitCode : int {
    kExitOk = 0,
    kExitError = 1,        // bad input file, failed output, comparison outside tolerance
    kExitUsage = 2,        // bad command line
    kExitNoBackend = 3,    // the requested backend is not available on this machine
};

// The help's closing paragraph: what each exit status means.
const char* exitCodesHelp();

// The exit status of an error of `kind` (the one place that decides it): backend unavailable 3,
// every other 1 (an interrupted command then ends by its signal: io/Interrupt.h).
int exitStatus(ErrorKind kind);

// Prints `error` as its one line, "error: <message>" ("error: --<message>" when the message starts
// with a setting's name: Error::aboutSetting), and gives exitStatus(error.kind).
int fail(std::ostream& err, const Error& error);

// Prints a bad command line's one line, "error: <message>", and gives kExitUsage.
int usageError(std::ostream& err, const std::string& message);

// Runs `frugal args...` (args without the program name). Normal output goes to `out`, progress,
// warnings and errors (one line each, "error: <what>: <why>") to `err`.
int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace frugal
