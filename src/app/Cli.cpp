#include "app/Cli.h"

#include <algorithm>
#include <iostream>
#include <new>
#include <ostream>

#include <malloc.h>

#include <frugal/Interrupt.h>
#include <frugal/Renderer.h>
#include <frugal/Settings.h>
#include <frugal/Version.h>

#include "app/Commands.h"
#include "app/Options.h"

namespace frugal {

namespace {

const Program* running = nullptr;
}  // namespace

const char* exitCodesHelp() {
    return R"(
exit status: 0 success (compare, diff: within tolerance), 1 bad input, failed output, or
             (compare, diff) images outside tolerance, 2 bad command line,
             3 the requested backend is not available (no EGL display, no OSMesa, ...);
             stopped by SIGINT, SIGTERM or SIGHUP: ends by that signal (130, 143, 129 in a shell)
             after one line, the files already written kept whole and no temporary file left
)";
}

namespace {

void printUsage(const Program& program, std::ostream& out) {
    out << program.title << "\n\nusage:\n";
    const std::string name = program.name;
    // The summaries in one column, after the longest usage (at least column 50).
    std::size_t column = 50;
    for (const CommandEntry& c : program.commands)
        column = std::max(column, 2 + name.size() + 1 + std::string(c.name).size() + 1 + std::string(c.usage).size() + 1);
    const auto line = [&out, &name, column](const std::string& usage, const std::string& summary) {
        std::string text = "  " + name + " " + usage;
        text.resize(column, ' ');
        out << text << summary << "\n";
    };
    for (const CommandEntry& c : program.commands) line(std::string(c.name) + " " + c.usage, c.summary);
    line("help [COMMAND]", "this text, or a command's options");
    line("help settings", "every renderer setting: flag, settings file, Python");
    out << "\nSCENE is a .gltf/.glb (glTF 2.0) or .obj file, or builtin:NAME[?key=value&...]:\n";
    for (const auto& [scene, description] : builtinScenes()) out << "  " << scene << "  " << description << "\n";
    out << "with no SCENE, a command that renders uses builtin:default.\n" << program.footer;
    out << "\nrun '" << name << " help COMMAND' (for example '" << name << " help render') for a command's options.\n"
        << exitCodesHelp();
}

// `frugal help settings`: the schema (frugal/Settings.h) as Markdown tables, which docs/cli.md
// holds as its "Settings" section (scripts/cli-doc).
std::string settingsHelp() {
    const auto code = [](const std::string& text) { return "`" + text + "`"; };
    std::string out =
        "Every setting of a renderer, once: the option of `frugal render` (and of the commands that render), the key "
        "of a settings file (`render --settings FILE`, `report`'s settings.json), the keyword argument of Python's "
        "frugal.Renderer, and the member of the library's frugal::Settings.\n\n"
        "| option | Python | value | default | what it does |\n|---|---|---|---|---|\n";
    const Settings defaults;
    for (const SettingInfo& info : settingInfos()) {
        std::string value = expected(info);
        if (info.kind == SettingKind::Pair) value += "; JSON also [A, B], Python (A, B)";
        if (info.kind == SettingKind::Colour) value += "; JSON [r, g, b(, a)], Python (r, g, b(, a))";
        std::string help = info.help;
        for (const ChoiceInfo& c : info.choices) help += "; " + std::string(c.name) + ": " + std::string(c.summary);
        out += "| " + (info.flag ? code("--" + info.name) : info.name + " (no flag)") + " | " + code(info.pythonName()) +
               " | " + value + " | " + code(settingText(info, info.get(defaults))) + " | " + help + " |\n";
    }
    out += "\nSettings that may not go together, refused with one line in each (the same words after the "
           "settings it names):\n\n| settings | when |\n|---|---|\n";
    for (const SettingsConflict& c : settingsConflicts())
        out += "| " + code(c.first) + " with " + code(c.second) + " | " + c.when + " |\n";
    return out;
}

std::string commandNames(const Program& program) {
    std::string names;
    for (const CommandEntry& entry : program.commands) names += std::string(entry.name) + ", ";
    return names + "help";
}

const CommandEntry* findCommand(const Program& program, const std::string& name) {
    for (const CommandEntry& entry : program.commands)
        if (name == entry.name) return &entry;
    return nullptr;
}

}  // namespace

const Program& frugalProgram() {
    static const Program program{
        "frugal",
        "frugal — offscreen OpenGL renderer (Mesa EGL/OSMesa) that does only the work a scene requires",
        {
            {"render", "[SCENE] [-o FILE.png] [options]", "render a frame or a sequence to PNG", runRender},
            {"report", "[SCENE] [options] -o DIR", "every speed-accuracy trade on SCENE, and the settings to use",
             runReport},
            {"info", "SCENE", "what a scene holds, and what frugal does not model", runInfo},
            {"compare", "A.png B.png [options]", "compare an image with a reference (B)", runCompare},
            {"diff", "[SCENE] [options]", "a GL render against the software reference", runDiff},
            {"cull-report", "[SCENE] [options]", "how exact and how fast each culling method is", runCullReport},
            {"batch", "MANIFEST [--shard I/N] [options]",
             "the jobs of a manifest, or shard I of N of them; status, merge", runBatch},
        },
        "\nThe benchmarks and paper reproductions (bench, reuse-bench, order-bench, hsr-bench, shading-bench,\n"
        "span-bench, write-bench, state-sim, soak) are frugal-lab's: run 'frugal-lab help'.\n"};
    return program;
}

const char* programName() { return running ? running->name : "frugal"; }

bool hasCommand(const std::string& name) {
    return findCommand(running ? *running : frugalProgram(), name) != nullptr;
}

int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    return runCli(running ? *running : frugalProgram(), args, out, err);
}

int runCli(const Program& program, const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    running = &program;
    if (args.empty()) {
        printUsage(program, err);
        return kExitUsage;
    }
    const std::string& name = args[0];
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    if (name == "-h" || name == "--help" || name == "help") {
        if (rest.empty()) {
            printUsage(program, out);
            return kExitOk;
        }
        if (rest[0] == "settings") {
            out << settingsHelp();
            return kExitOk;
        }
        // `frugal help COMMAND` is `frugal COMMAND --help`: one help text per command.
        if (const CommandEntry* entry = findCommand(program, rest[0])) return entry->run({"--help"}, out, err);
        return usageError(err, "help " + rest[0] + ": no such command (commands: " + commandNames(program) + ")");
    }
    if (name == "--version") {
        out << program.name << " " << version() << "\n";
        return kExitOk;
    }
    if (const CommandEntry* entry = findCommand(program, name)) return entry->run(rest, out, err);
    return usageError(err, "unknown command '" + name + "' (commands: " + commandNames(program) + ")");
}

int runMain(const Program& program, int argc, char** argv) {
    installInterruptHandler();  // before any file is written or any thread started
    // llvmpipe frees and reallocates large scratch memory every frame; glibc's default trim threshold
    // hands it back to the kernel each time. Keeping it cuts llvmpipe's frame time sharply, and a
    // larger M_MMAP_THRESHOLD gained nothing more (docs/gl/README.md).
    mallopt(M_TRIM_THRESHOLD, 512 * 1024 * 1024);
    std::vector<std::string> args(argv + 1, argv + argc);
    int status = kExitError;
    try {
        status = runCli(program, args, std::cout, std::cerr);
    } catch (const std::bad_alloc&) {  // past the checks made up front (renderer/Backends.h)
        std::cerr << "error: " << outOfMemoryMessage() << "\n";
    }
    raiseNotedSignal();  // a command stopped by a signal ends by it (io/Interrupt.h)
    return status;
}

int exitStatus(ErrorKind kind) { return kind == ErrorKind::BackendUnavailable ? kExitNoBackend : kExitError; }

int usageError(std::ostream& err, const std::string& message) {
    err << "error: " << message << "\n";
    return kExitUsage;
}

int fail(std::ostream& err, const Error& error) {
    err << "error: " << (error.aboutSetting ? "--" : "") << error.message << "\n";
    return exitStatus(error.kind);
}

}  // namespace frugal
