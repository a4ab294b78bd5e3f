// The skeleton every command shares: one argument loop. A command supplies its own flags (a table:
// app/Flags.h), its positional arguments and its work; messages, help and exit codes come out the
// same everywhere.
#pragma once

#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <frugal/Renderer.h>

#include "app/Options.h"

namespace frugal {

struct CommandLine {
    CommandLine(std::string name_, std::string help_, RenderOptions* shared_ = nullptr)
        : name(std::move(name_)), help(std::move(help_)), shared(shared_) {}

    std::string name;        // as in "see 'frugal help NAME'"
    std::string help;        // usage and description, printed by -h/--help before the flags' help
    RenderOptions* shared;   // the shared render options (renderFlags) are parsed into it, when given
    std::vector<FlagGroup> flags;  // the command's own flags
    // The command's own flags: false when `flag` is not one of them. Usage errors go to the cursor.
    std::function<bool(const std::string& flag, ArgCursor& cursor)> option;
    // A positional argument; fail the cursor when there is no room for it.
    std::function<void(const std::string& argument, ArgCursor& cursor)> positional;
    // Checks once every argument is read (missing positionals, flags that conflict).
    std::function<void(ArgCursor& cursor)> finish;
};

// The help of `command`: its text, its flags', and the shared flags' when it takes them.
std::string commandHelp(const CommandLine& command);

// The one argument loop. Returns nothing when the command should go on, or the exit status to
// return: kExitOk after -h/--help printed the help to `out`, kExitUsage after "error: <why>" on `err`.
std::optional<int> parseCommandLine(const CommandLine& command, const std::vector<std::string>& args,
                                    std::ostream& out, std::ostream& err);

// The positional of the commands that render: one SCENE, "unexpected argument 'x' (one SCENE only)".
std::function<void(const std::string&, ArgCursor&)> sceneArgument(RenderOptions& options, bool* given = nullptr);

// What a renderer prepared, as `render` says it before the first frame: "cull: 1 mesh, ..." (with
// culling), "backend: egl-surfaceless (llvmpipe ...)", "order best: state costs on ..." (with a
// cost-driven order).
void printRendererStart(const Renderer& renderer, std::ostream& err);

// Where a command's progress lines go (the lab's `progress` callbacks): `err`, one a line, unless quiet.
std::function<void(const std::string&)> progressTo(std::ostream& err, bool quiet);

}  // namespace frugal
