#include "app/Options.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <ostream>
#include <string_view>


namespace frugal {

std::string ArgCursor::next() {
    inlineValue_.reset();
    std::string arg = args_[index_++];
    const std::size_t eq = arg.find('=');
    if (arg.rfind("--", 0) == 0 && eq != std::string::npos) {
        inlineValue_ = arg.substr(eq + 1);
        arg.resize(eq);
    }
    return arg;
}

std::optional<std::string> ArgCursor::value(const std::string& flag) {
    if (inlineValue_) {
        std::string v = *inlineValue_;
        inlineValue_.reset();
        return v;
    }
    if (done()) {
        fail(flag + ": missing value");
        return std::nullopt;
    }
    return args_[index_++];
}

bool parseIntPair(const std::string& text, int& first, int& second) {
    const std::size_t x = text.find('x');
    const auto parse = [](std::string_view part, int& out) {
        auto [stop, ec] = std::from_chars(part.data(), part.data() + part.size(), out);
        return !part.empty() && ec == std::errc() && stop == part.data() + part.size();
    };
    return x != std::string::npos && parse(std::string_view(text).substr(0, x), first) &&
           parse(std::string_view(text).substr(x + 1), second);
}

FlagGroup renderFlags(RenderOptions& o) {
    Camera& c = o.camera;
    const auto setting = [&o](std::string_view name) { return settingFlag(name, o.settings, o.given); };
    return {"", {
        setting("size"),
        setting("backend"),
        setting("threads"),
        setting("interp"),
        {"--camera", "N", "use the scene's camera N (default: camera 0 if the scene has one, else a view that fits "
         "the scene's bounds)", [&c](const std::string& text) -> std::string {
             long long index = 0;
             if (!flag::readWhole(text, 0, 1 << 30, index).empty()) return "is not a camera index (0, 1, ...)";
             c.sceneCamera = int(index);
             return {};
         }},
        flag::point("--eye", "X,Y,Z", "look from here (with --target, default the bounds' centre, and --up)", c.eye),
        flag::point("--target", "X,Y,Z", "look at this point", c.target),
        flag::point("--up", "X,Y,Z", "the image's up (default 0,1,0)", c.up),
        flag::number("--fov", "DEGREES", "vertical field of view (default: the camera's, or 40)", c.yfovDegrees, 1e-3,
                     179.999),
        flag::number("--near", "Z", "near clip plane (default: the camera's, or around the scene)", c.znear, 1e-30, 1e30),
        flag::number("--far", "Z", "far clip plane (default: the camera's, or around the scene); 0 = infinite", c.zfar,
                     0, 1e30),
        flag::choice("--depth-range", "MODE", "a depth range",
                     "fit (default): near and far moved inward to where the scene is (its bounds over the whole "
                     "animation, along the view), never past the planes above, so nothing they keep is clipped and "
                     "depth precision goes to the scene; file: the planes above as they are",
                     c.depthRange, kDepthRanges),
        setting("depth-format"),
        flag::number("--time", "SECONDS", "animation time of the frame (default 0)", o.time, -1e9, 1e9),
        flag::frames("--frames", "frames A to B inclusive, at --fps (default the scene's, 30)", o.frames),
        flag::number("--fps", "N", "frames per second of --frames (default the scene's)", o.fps, 1e-3, 1e6),
        setting("background"),
        setting("tonemap"),
        setting("samples"),
        setting("shading"),
        setting("no-mipmaps"),
        setting("light"),
        setting("environment"),
        setting("environment-map"),
        setting("no-environment-specular"),
        flag::on("--cull-backfaces", "draw OBJ files single-sided (OBJ is double-sided by default; glTF follows each "
                 "material's doubleSided)", o.load.objDoubleSided, false),
        flag::on("--file-order", "keep the file's triangle order (default: reordered for the vertex cache)",
                 o.load.optimizeOrder, false),
        flag::on("-q, --quiet", "no progress lines", o.quiet),
    }};
}

Flag cameraPathFlag(RenderOptions& render) {
    return flag::text("--camera-path", "FILE", "a JSON list of {\"eye\":[x,y,z],\"target\":[x,y,z],"
                      "\"up\":[x,y,z],\"fov\":deg}: entry i is frame A+i of --frames A:B, the last entry "
                      "holds (equal entries = still)", render.cameraPathFile);
}

std::vector<Flag> topicFlags(RenderOptions& o, std::string_view topic) {
    std::vector<Flag> flags;
    for (const SettingInfo& info : settingInfos())
        if (info.flag && info.topic == topic) flags.push_back(settingFlag(info.name, o.settings, o.given));
    return flags;
}

FlagGroup someFlags(const FlagGroup& group, const std::vector<std::string>& names) {
    FlagGroup out{group.title, {}};
    for (const Flag& f : group.flags)
        if (std::find(names.begin(), names.end(), f.canonical()) != names.end()) out.flags.push_back(f);
    return out;
}

void checkSharedOptions(RenderOptions& o, ArgCursor& cursor) {
    if (const std::optional<SettingsProblem> problem = settingsProblem(o.settings))
        cursor.fail(commandLineProblem(*problem, o));
    const std::optional<float>& near = o.camera.znear;
    const std::optional<float>& far = o.camera.zfar;
    if (near && far && *far != 0.0f && !(*far > *near))
        cursor.fail("--far " + fmt(*far) + ": must exceed --near " + fmt(*near));
    if (cursor.error.empty() && !o.cameraPathFile.empty()) {
        Result<std::vector<Camera>> cameras = readCameraPath(o.cameraPathFile);
        if (!cameras) cursor.fail("--" + cameras.error().message);
        else o.cameraPath = std::move(*cameras);
    }
}

std::string commandLineProblem(const SettingsProblem& problem, const RenderOptions& options) {
    const bool anyGiven = std::any_of(problem.settings.begin(), problem.settings.end(),
                                      [&options](const std::string& name) { return options.gave(name); });
    return describe(problem, options.settings, [&](const SettingInfo& info, const SettingValue& value) -> std::string {
        if (anyGiven && !options.gave(info.name)) return {};
        if (info.kind == SettingKind::Switch) return "--" + info.name;
        return "--" + info.name + " " + settingText(info, value);
    });
}

void applyDepthOptions(const Camera& options, Camera& view) {
    view.znear = options.znear;
    view.zfar = options.zfar;
    view.depthRange = options.depthRange;
}

double frameTimeOf(const RenderOptions& options, const Scene& scene, int frame) {
    if (!options.frames && options.time) return *options.time;
    return frameTime(frame, options.fps.value_or(scene.fps));
}

std::string fitSizeToCamera(RenderOptions& options, const Scene& scene) {
    std::optional<int> index = options.camera.sceneCamera;
    if (!index && !options.camera.eye && options.cameraPath.empty() && !scene.cameras.empty()) index = 0;
    if (!index || *index < 0 || *index >= int(scene.cameras.size())) return {};
    const SceneCamera& camera = scene.cameras[std::size_t(*index)];
    const float aspect = camera.fileAspect();
    if (!(aspect > 0.0f) || !std::isfinite(aspect)) return {};
    Settings& s = options.settings;
    if (!options.gave("size")) sizeForAspect(aspect, kLongSide, s.width, s.height);
    if (!aspectDiffers(aspect, s.width, s.height)) return {};
    return options.scene + ": camera " + std::to_string(*index) + quotedName(camera.name) + " has aspect ratio " +
           fmt(aspect) + ", the image " + fmt(double(s.width) / s.height) + " (" + std::to_string(s.width) + "x" +
           std::to_string(s.height) +
           "): drawn with the camera's vertical " + (camera.perspective ? "field of view" : "extent (ymag)") +
           " and the image's aspect ratio, not stretched";
}

Result<Scene> loadForRender(RenderOptions& options, std::ostream& err) {
    Result<Scene> scene = loadScene(options.scene, options.load);
    if (!scene) return scene;
    const std::string aspectWarning = fitSizeToCamera(options, *scene);
    // Check the first frame's camera before a backend is opened, so a bad camera is the only line.
    const int first = options.frames ? options.frames->first : 0;
    const Settings& s = options.settings;
    if (Result<View> view = resolveView(*scene, cameraOf(options, first), frameTimeOf(options, *scene, first), s.width,
                                        s.height, s.depthFormat);
        !view)
        return Error{options.scene + ": " + view.error().message};
    for (const std::string& warning : scene->warnings) err << "warning: " << warning << "\n";
    if (!aspectWarning.empty()) err << "warning: " << aspectWarning << "\n";
    if (!scene->unsupported.empty()) {
        std::string names;
        for (const std::string& name : scene->unsupported) names += (names.empty() ? "" : ", ") + name;
        err << "warning: " << options.scene << ": not modelled, drawn without: " << names << "\n";
    }
    return scene;
}

Result<std::vector<ReportView>> viewsAround(const RenderOptions& options, const Scene& scene, int count, double time) {
    const Bounds bounds = scene.bounds(time);
    if (bounds.empty()) return Error{options.scene + ": the scene has no geometry to view"};
    std::vector<ReportView> views = reportViews(bounds.center(), bounds.radius(), count,
                                                options.camera.yfovDegrees.value_or(40.0f),
                                                float(options.settings.width) / float(options.settings.height));
    for (ReportView& view : views) applyDepthOptions(options.camera, view.camera);
    return views;
}

bool oneCamera(const RenderOptions& options) {
    return options.camera.sceneCamera || options.camera.eye || options.camera.target;
}

Camera cameraOf(const RenderOptions& options, int frame) {
    if (options.cameraPath.empty()) return options.camera;
    const int first = options.frames ? options.frames->first : 0;
    const int last = int(options.cameraPath.size()) - 1;
    Camera camera = options.cameraPath[std::size_t(std::clamp(frame - first, 0, last))];
    applyDepthOptions(options.camera, camera);
    return camera;
}

FrameSetupOf frameSetups(const RenderOptions& options, const Scene& scene, bool writeIds) {
    const Settings& s = options.settings;
    FrameSetupOf setups = frugal::frameSetups(scene, options.scene,
                                              [&options, &scene](int frame) {
                                                  return AskedFrame{cameraOf(options, frame),
                                                                    frameTimeOf(options, scene, frame)};
                                              },
                                              s.width, s.height, writeIds, s.depthFormat);
    return [setups = std::move(setups), s](int frame) -> Result<FrameSetup> {
        Result<FrameSetup> setup = setups(frame);
        if (setup) applyShading(s, setup->params);
        return setup;
    };
}

}  // namespace frugal
