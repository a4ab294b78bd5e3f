#include "app/Cli.h"

#include <ostream>

#include <frugal/Settings.h>
#include <frugal/Version.h>

#include "app/Commands.h"
#include "app/Options.h"

namespace frugal {

namespace {

const char* kUsage = R"(frugal — offscreen OpenGL renderer (Mesa EGL/OSMesa) that does only the work a scene requires

usage:
  frugal render [SCENE] [-o FILE.png] [options]   render a frame or a sequence to PNG
  frugal report [SCENE] [options] -o DIR          every speed-accuracy trade on SCENE, and the settings to use
  frugal info SCENE                               what a scene holds, and what frugal does not model
  frugal bench render [SCENE] [options]           frame time per backend, as JSON
  frugal compare A.png B.png [options]            compare an image with a reference (B)
  frugal diff [SCENE] [options]                   a GL render against the software reference
  frugal cull-report [SCENE] [options]            how exact and how fast each culling method is
  frugal reuse-bench [SCENE] --frames A:B [opts]  what temporal reuse saves, frame by frame
  frugal order-bench [SCENE] [options]            a frame in every draw order: time, state changes, ties
  frugal hsr-bench [SCENE] [options]              depth sort and the adaptive z-buffer against the z-buffer
  frugal span-bench [options]                     paper 001's shading engine model: Fig. 11, error tables
  frugal write-bench [--scene SCENE ...] [opts]   PNG levels and filters: time against size; sequence wall time
  frugal state-sim [options]                      paper 004's draw orders on random state sets: Tables 6, 7
  frugal soak [SCENE] [options]                   100,000 frames and 1,000 create/destroy cycles: memory, images
  frugal batch MANIFEST [--shard I/N] [options]   the jobs of a manifest, or shard I of N of them; status, merge
  frugal help [COMMAND]                           this text, or a command's options
  frugal help settings                            every renderer setting: flag, settings file, Python

SCENE is a .gltf/.glb (glTF 2.0) or .obj file, or builtin:NAME[?key=value&...]:
)";

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

void printUsage(std::ostream& out) {
    out << kUsage;
    for (const auto& [name, description] : builtinScenes()) out << "  " << name << "  " << description << "\n";
    out << "with no SCENE, render, report, bench, diff, cull-report and reuse-bench use builtin:default.\n";
    out << "\nrun 'frugal help COMMAND' (for example 'frugal help render') for a command's options.\n" << exitCodesHelp();
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

struct CommandEntry {
    const char* name;
    int (*run)(const std::vector<std::string>&, std::ostream&, std::ostream&);
};

const CommandEntry kCommands[] = {
    {"render", runRender},           {"report", runReport},     {"info", runInfo},         {"bench", runBench},
    {"compare", runCompare},         {"diff", runDiff},         {"cull-report", runCullReport},
    {"reuse-bench", runReuseBench},  {"hsr-bench", runHsrBench}, {"order-bench", runOrderBench},
    {"span-bench", runSpanBench},    {"state-sim", runStateSim}, {"soak", runSoak},
    {"batch", runBatch},             {"write-bench", runWriteBench},
};

std::string commandNames() {
    std::string names;
    for (const CommandEntry& entry : kCommands) names += std::string(entry.name) + ", ";
    return names + "help";
}

const CommandEntry* findCommand(const std::string& name) {
    for (const CommandEntry& entry : kCommands)
        if (name == entry.name) return &entry;
    return nullptr;
}

}  // namespace

int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    if (args.empty()) {
        printUsage(err);
        return kExitUsage;
    }
    const std::string& name = args[0];
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    if (name == "-h" || name == "--help" || name == "help") {
        if (rest.empty()) {
            printUsage(out);
            return kExitOk;
        }
        if (rest[0] == "settings") {
            out << settingsHelp();
            return kExitOk;
        }
        // `frugal help COMMAND` is `frugal COMMAND --help`: one help text per command.
        if (const CommandEntry* entry = findCommand(rest[0])) return entry->run({"--help"}, out, err);
        return usageError(err, "help " + rest[0] + ": no such command (commands: " + commandNames() + ")");
    }
    if (name == "--version") {
        out << "frugal " << version() << "\n";
        return kExitOk;
    }
    if (const CommandEntry* entry = findCommand(name)) return entry->run(rest, out, err);
    return usageError(err, "unknown command '" + name + "' (commands: " + commandNames() + ")");
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
