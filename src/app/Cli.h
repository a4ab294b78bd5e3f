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

// A command of a program: its name, its usage line after the program's name, one line of what it
// does, and its function (each returns an ExitCode).
struct CommandEntry {
    const char* name;
    const char* usage;    // "[SCENE] [-o FILE.png] [options]"
    const char* summary;  // "render a frame or a sequence to PNG"
    int (*run)(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
};

// A program of commands: `frugal` (what users run daily) or `frugal-lab` (research/app: the
// benchmarks and paper reproductions, and frugal's own commands besides).
struct Program {
    const char* name;   // "frugal"
    const char* title;  // the usage's first line
    std::vector<CommandEntry> commands;
    const char* footer = "";  // a paragraph after the commands' list
};

// frugal's commands: render, report, info, compare, diff, cull-report, batch.
const Program& frugalProgram();
// The program running (for "see 'frugal help render'"): frugal until runCli says otherwise.
const char* programName();
// Whether the program running has command `name` (a batch job runs in this process).
bool hasCommand(const std::string& name);

// Runs `<program> args...` (args without the program name). Normal output goes to `out`, progress,
// warnings and errors (one line each, "error: <what>: <why>") to `err`.
int runCli(const Program& program, const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
// frugal's commands: runCli(frugalProgram(), ...), as a batch job runs them.
int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
// A program's main(): the signal handlers, the allocator's trim threshold, runCli, and an
// allocation that fails past the checks made up front as one line.
int runMain(const Program& program, int argc, char** argv);

}  // namespace frugal
