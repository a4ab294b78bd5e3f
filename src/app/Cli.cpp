#include "app/Cli.h"

#include <ostream>

#include "app/Commands.h"
#include "app/Options.h"

namespace frugal {

namespace {

const char* kUsage = R"(frugal — offscreen OpenGL renderer (Mesa EGL/OSMesa) that does only the work a scene requires

usage:
  frugal render [SCENE] [-o FILE.png] [options]   render a frame or a sequence to PNG
  frugal info SCENE                               what a scene holds, and what frugal does not model
  frugal bench render [SCENE] [options]           frame time per backend, as JSON
  frugal help [COMMAND]                           this text, or a command's options

SCENE is a .gltf/.glb (glTF 2.0) or .obj file, or builtin:NAME[?key=value&...]:
)";

const char* kExitCodes = R"(
exit status: 0 success, 1 bad input or failed output, 2 bad command line,
             3 the requested backend is not available (no EGL display, no OSMesa, ...)
)";

void printUsage(std::ostream& out) {
    out << kUsage;
    for (const auto& [name, description] : builtinScenes()) out << "  " << name << "  " << description << "\n";
    out << "with no SCENE, render and bench use builtin:default.\n";
    out << "\nrun 'frugal help render' (or info, bench) for a command's options.\n" << kExitCodes;
}

}  // namespace

int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    if (args.empty()) {
        printUsage(err);
        return kExitUsage;
    }
    const std::string& command = args[0];
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    if (command == "-h" || command == "--help" || command == "help") {
        if (!rest.empty() && rest[0] == "render") out << renderHelp() << kExitCodes;
        else if (!rest.empty() && rest[0] == "info") out << infoHelp() << kExitCodes;
        else if (!rest.empty() && rest[0] == "bench") out << benchHelp() << kExitCodes;
        else printUsage(out);
        return kExitOk;
    }
    if (command == "--version") {
        out << "frugal 0.1.0\n";
        return kExitOk;
    }
    if (command == "render") return runRender(rest, out, err);
    if (command == "info") return runInfo(rest, out, err);
    if (command == "bench") return runBench(rest, out, err);
    err << "error: unknown command '" << command << "' (commands: render, info, bench, help)\n";
    return kExitUsage;
}

}  // namespace frugal
