#include "app/Command.h"

#include <algorithm>
#include <ostream>

#include "app/Cli.h"
#include "base/Format.h"
#include "lab/CullMeasure.h"
#include "lab/SceneInfo.h"

namespace frugal {

namespace {

// The flag of `groups` spelled `spelling`, or nullptr.
const Flag* findFlag(const std::vector<FlagGroup>& groups, const std::string& spelling) {
    for (const FlagGroup& group : groups)
        for (const Flag& f : group.flags)
            if (f.matches(spelling)) return &f;
    return nullptr;
}

// The shared flags `command` takes: renderFlags without those the command defines itself (soak's
// --frames is a count, not render's range).
FlagGroup sharedFlags(const CommandLine& command) {
    FlagGroup shared = renderFlags(*command.shared);
    shared.title = "image, backend, camera and time (every command that renders)";
    std::erase_if(shared.flags, [&](const Flag& f) { return findFlag(command.flags, f.canonical()) != nullptr; });
    return shared;
}

}  // namespace

std::string commandHelp(const CommandLine& command) {
    std::string text = command.help + flagsHelp(command.flags);
    if (command.shared) text += flagsHelp({sharedFlags(command)});
    return text + exitCodesHelp();
}

std::optional<int> parseCommandLine(const CommandLine& command, const std::vector<std::string>& args,
                                    std::ostream& out, std::ostream& err) {
    ArgCursor cursor(args);
    // The command's own flags come first, then its legacy option parser, then the shared flags.
    std::vector<FlagGroup> shared;
    if (command.shared) shared.push_back(sharedFlags(command));
    while (!cursor.done() && cursor.error.empty()) {
        const std::string flag = cursor.next();
        if (flag == "-h" || flag == "--help") {
            out << commandHelp(command);
            return kExitOk;
        }
        const Flag* f = findFlag(command.flags, flag);
        if (!f && command.option && command.option(flag, cursor)) continue;
        if (!f) f = findFlag(shared, flag);
        if (f) {
            std::optional<std::string> value;
            if (f->value.empty()) {
                value = "";
            } else if (f->arity == 1) {
                value = cursor.value(flag);
            } else if (const std::optional<std::string> first = cursor.value(flag)) {
                const std::optional<std::string> second = cursor.done() ? std::string() : cursor.value(flag);
                if (second) value = *first + '\0' + *second;
            }
            if (!value) continue;
            if (const std::string why = f->set(*value); !why.empty())
                cursor.fail(f->canonical() + ": " + (f->arity == 1 ? "'" + *value + "' " : "") + why);
            continue;
        }
        if (flag.size() > 1 && flag[0] == '-')
            cursor.fail(flag + ": unknown option (see '" + std::string(programName()) + " help " + command.name + "')");
        else if (command.positional)
            command.positional(flag, cursor);
        else
            cursor.fail("unexpected argument '" + flag + "'");
    }
    if (cursor.error.empty() && command.shared) checkSharedOptions(*command.shared, cursor);
    if (cursor.error.empty() && command.finish) command.finish(cursor);
    if (!cursor.error.empty()) {
        return usageError(err, cursor.error);
    }
    return std::nullopt;
}

void printRendererStart(const Renderer& renderer, std::ostream& err) {
    if (const std::optional<Renderer::CullPreparation> prep = renderer.cullPreparation())
        err << cullPreparedLine(renderer.scene(), *prep) << "\n";
    err << "backend: " << renderer.backendName() << " (" << renderer.backendRenderer() << ")\n";
    if (const std::optional<Renderer::EnvironmentPreparation> env = renderer.environmentPreparation())
        err << "environment-map " << renderer.settings().environmentMap << ": " << env->width << "x" << env->height
            << ", read and prefiltered in " << fmt(env->ms) << " ms (once a process)\n";
    if (const std::optional<StateCosts> costs = renderer.stateCosts())
        err << stateCostsLine(renderer.settings().order, renderer.backendName(), *costs) << "\n";
}

std::function<void(const std::string&, ArgCursor&)> sceneArgument(RenderOptions& options, bool* given) {
    return [&options, given, seen = false](const std::string& argument, ArgCursor& cursor) mutable {
        if (seen) {
            cursor.fail("unexpected argument '" + argument + "' (one SCENE only)");
            return;
        }
        options.scene = argument;
        seen = true;
        if (given) *given = true;
    };
}

std::function<void(const std::string&)> progressTo(std::ostream& err, bool quiet) {
    return [&err, quiet](const std::string& line) {
        if (!quiet) err << line << "\n";
    };
}

}  // namespace frugal
