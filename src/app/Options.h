// Command-line options shared by the commands that render (render, bench, diff), and the
// set-up they share: load the scene, pick the backend, resolve the camera.
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/Backends.h"
#include "render/Backend.h"
#include "render/Camera.h"
#include "scene/Load.h"

namespace frugal {

// Walks the argument list; every malformed value becomes one usage error.
class ArgCursor {
public:
    explicit ArgCursor(const std::vector<std::string>& args) : args_(args) {}
    bool done() const { return index_ >= args_.size(); }
    // The next argument; "--flag=value" is split so that value() returns the part after '='.
    std::string next();
    // The value of the flag just read: the inline "=value" or the following argument.
    std::optional<std::string> value(const std::string& flag);
    std::string error;  // first usage error, "<flag>: <why>"
    void fail(const std::string& message) { if (error.empty()) error = message; }

private:
    const std::vector<std::string>& args_;
    std::size_t index_ = 0;
    std::optional<std::string> inlineValue_;
};

struct FrameRange {
    int first = 0, last = 0;  // inclusive
    bool sequence = false;    // --frames given: numbered outputs
};

struct RenderOptions {
    std::string scene = "builtin:default";
    int width = 800, height = 600;
    BackendSelection backend;
    std::string backendName = "auto";  // as given, for messages
    int threads = 0;                   // rasterizer threads (software pool, LP_NUM_THREADS); 0 = default
    CameraSpec camera;
    std::optional<double> time;   // seconds; default frame 0
    std::optional<FrameRange> frames;
    std::optional<double> fps;    // default: the scene's
    glm::vec4 background{0.12f, 0.13f, 0.15f, 1.0f};
    LoadOptions load;
    bool quiet = false;
};

// Parses one shared option at the cursor (the flag already read into `flag`). Returns false if the
// flag is not a shared one; usage errors go to cursor.error.
bool parseSharedOption(const std::string& flag, ArgCursor& cursor, RenderOptions& options);
// Help text of the shared options.
const char* sharedOptionsHelp();

// The value of `flag` as a whole number in [lo, hi]; a usage error otherwise.
std::optional<int> wholeNumber(const std::string& flag, ArgCursor& cursor, int lo, int hi);

// A clear colour as the 8-bit target holds it (GL's unorm conversion: clamp, ×255, round).
std::array<std::uint8_t, 4> colorBytes(const glm::vec4& color);

// Scene time of frame `frame`.
double frameTime(const RenderOptions& options, const Scene& scene, int frame);

// Loads the scene, prints its warnings (unsupported features, dropped triangles) to `err`, and checks
// the first frame's camera, so that a bad camera fails before any backend is opened.
Result<Scene> loadForRender(const RenderOptions& options, std::ostream& err);

// Everything one frame needs: its time, node transforms, camera and frame parameters.
struct FrameSetup {
    double time = 0.0;
    std::vector<glm::mat4> world;
    View view;
    FrameParams params;
};
// Error: "<scene>: <camera problem>" (print it after "error: ").
Result<FrameSetup> setUpFrame(const RenderOptions& options, const Scene& scene, int frame, bool writeIds);

// Creates the render target, or prints the one-line error (the size and the backend's limit) and
// returns kNoHandle.
TargetHandle createTargetOrReport(Backend& backend, const RenderOptions& options, std::ostream& err);

// Numbers as the CLI prints them ("%g").
std::string fmt(double value);

}  // namespace frugal
