// The skeleton every command shares: one argument loop, and one way to open a backend with a
// target and the scene uploaded. A command supplies its own flags, its positional arguments and its
// work; messages, help and exit codes come out the same everywhere.
// The flags themselves are a table (app/Flags.h).
#pragma once

#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <frugal/Renderer.h>

#include "app/Options.h"
#include "render/SceneRenderer.h"
#include "renderer/StateOrder.h"

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

// A backend with one target of the options' size and the scene uploaded: what render, bench and
// diff draw into.
struct Session {
    std::unique_ptr<Backend> backend;
    std::vector<std::string> log;  // the contexts tried (GL), or "software: ok"
    TargetHandle target = kNoHandle;
    std::optional<SceneRenderer> renderer;
};

// A target of `backend` destroyed when this goes (the static pair of --reuse, bench's other depth
// format); kNoHandle holds nothing.
class ScopedTarget {
public:
    explicit ScopedTarget(Backend& backend, TargetHandle handle = kNoHandle) : backend_(backend), handle_(handle) {}
    ~ScopedTarget() {
        if (handle_ != kNoHandle) backend_.destroyTarget(handle_);
    }
    ScopedTarget(const ScopedTarget&) = delete;
    ScopedTarget& operator=(const ScopedTarget&) = delete;
    TargetHandle get() const { return handle_; }
    void reset(TargetHandle handle) {
        if (handle_ != kNoHandle) backend_.destroyTarget(handle_);
        handle_ = handle;
    }

private:
    Backend& backend_;
    TargetHandle handle_;
};

// What a renderer prepared, as `render` says it before the first frame: "cull: 1 mesh, ..." (with
// culling), "backend: egl-surfaceless (llvmpipe ...)", "order best: state costs on ..." (with a
// cost-driven order).
void printRendererStart(const Renderer& renderer, std::ostream& err);

// OrderCosts::start, with stateCostsLine on `err` unless quiet (for paper, greedy and best).
Result<OrderCosts> startOrderCosts(Order order, Backend& backend, int refineEvery, std::ostream& err, bool quiet);

// The one-backend start of render and cull-report: opens --backend, says which unless quiet, creates
// the target and uploads `scene`. On failure prints the one error line and gives the exit status
// (kExitNoBackend or kExitError) instead of a session.
std::variant<Session, int> startSession(const RenderOptions& options, const Scene& scene, std::ostream& err);

// Opens `selection` with the options' thread count and --interp. A failure means the backend is not
// available here (exit status kExitNoBackend); the message is its reason (print it after
// "error: <label>: ").
Result<Session> openSession(BackendKind kind, const RenderOptions& options);

// Creates the target (unless the session has one) and uploads `scene` into an open session,
// replacing the scene uploaded before. On failure prints the one error line
// and returns the exit status (kExitError); returns kExitOk on success.
int prepareSession(Session& session, const RenderOptions& options, const Scene& scene, std::ostream& err);

}  // namespace frugal
