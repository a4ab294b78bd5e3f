// Command-line options shared by the commands that render (render, bench, diff): the argument
// cursor, the shared flags, and the command-line side of frame set-up (which frame, which time).
// The frame itself is set up by the library (pipeline/Frame.h).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <frugal/Camera.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>

#include "app/Flags.h"
#include "base/Format.h"
#include "lab/Frames.h"
#include "lab/Views.h"

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
    // The renderer's settings (frugal/Settings.h): the schema's flags set them, a settings file
    // (render --settings) before them. The command holds these, not a copy of its own.
    Settings settings;
    std::vector<std::string> given;  // the settings the command line (or its settings file) named
    Camera camera;
    // --camera-path (render, reuse-bench; frugal/Camera.h readCameraPath): entry i is frame first + i, the last
    // one holds; --near/--far still apply. Empty: `camera` for every frame.
    std::vector<Camera> cameraPath;
    std::string cameraPathFile;   // --camera-path FILE, read into cameraPath by checkSharedOptions
    std::optional<double> time;   // seconds; default frame 0
    std::optional<FrameRange> frames;
    std::optional<double> fps;    // default: the scene's
    LoadOptions load;
    bool quiet = false;

    // Whether the command line named setting `name` (--size: else the scene camera's aspect ratio
    // sizes the image, kLongSide).
    bool gave(std::string_view name) const { return std::find(given.begin(), given.end(), name) != given.end(); }
};

// The flags every command that renders takes (size, backend, camera, time, frames, ...), setting
// `options`; `options` must outlive the group.
FlagGroup renderFlags(RenderOptions& options);
// --camera-path FILE into `render.cameraPathFile` (read with the shared options' checks): render and
// reuse-bench.
Flag cameraPathFlag(RenderOptions& render);
// The flags of the settings whose topic is `topic` (settingInfos(): "culling", "order", "reuse", ...).
std::vector<Flag> topicFlags(RenderOptions& options, std::string_view topic);
// Checks between them, once all are read ("--far 1: must exceed --near 5"; settings that may not go
// together, settingsProblem), and reads --camera-path's file.
void checkSharedOptions(RenderOptions& options, ArgCursor& cursor);
// A settings problem as the command line says it: the settings named as flags ("--reuse with --cull
// oracle: ..."), those the command line did not give left out when it gave any.
std::string commandLineProblem(const SettingsProblem& problem, const RenderOptions& options);
// The flags of `group` named in `names` (a command that takes a few of them).
FlagGroup someFlags(const FlagGroup& group, const std::vector<std::string>& names);

// "AxB" as two whole numbers (--size 800x600, --cull-bins 16x32); false for anything else.
bool parseIntPair(const std::string& text, int& first, int& second);

// Whether the options name one camera: --camera N, --eye or --target.
bool oneCamera(const RenderOptions& options);

// What --near, --far and --depth-range (in `options`) give every view of a camera path or a report:
// a view's own planes are replaced by them, given or not.
void applyDepthOptions(const Camera& options, Camera& view);

// `count` views around the scene's bounding sphere at `time` (lab/Views.h reportViews), with the
// options' field of view and aspect ratio, and --near, --far and --depth-range applied to each.
// Error: "<scene>: the scene has no geometry to view".
Result<std::vector<ReportView>> viewsAround(const RenderOptions& options, const Scene& scene, int count, double time);

// Scene time of frame `frame`: --time when no --frames, else frame / fps (--fps or the scene's).
double frameTimeOf(const RenderOptions& options, const Scene& scene, int frame);

// The default image's longer side when the first frame's camera has an aspect ratio of its own.
inline constexpr int kLongSide = 800;

// Without --size, sizes the image to the aspect ratio of the scene camera the first frame uses (the
// longer side kLongSide: 800x600 at 4:3, 800x800 at 1:1). Returns the warning to print when the
// image's aspect ratio differs from that camera's (--size given, or a camera without one), or "".
std::string fitSizeToCamera(RenderOptions& options, const Scene& scene);

// Loads the scene, prints its warnings (unsupported features, dropped triangles, a camera's aspect
// ratio the image does not have) to `err`, sizes the image (fitSizeToCamera), and checks the first
// frame's camera, so that a bad camera fails before any backend is opened.
Result<Scene> loadForRender(RenderOptions& options, std::ostream& err);

// The camera of frame `frame`: the --camera-path entry (the last holds) with --near, --far and
// --depth-range, or the camera the options give.
Camera cameraOf(const RenderOptions& options, int frame);

// The frames as the options ask for them, set up as a renderer sets them up (lab/Frames.h), for the
// harnesses. Error of a frame: "<scene>: <camera problem>".
FrameSetupOf frameSetups(const RenderOptions& options, const Scene& scene, bool writeIds);

}  // namespace frugal
