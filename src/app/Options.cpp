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
    return {"", {
        flag::size("--size", "WxH", "image size in pixels (default 800x600, or the scene camera's aspect ratio with the "
                   "longer side 800)", o.width, o.height, 65536, &o.sizeGiven),
        flag::choice("--backend", "NAME", "a backend",
                     "auto (default: EGL device if it is a GPU, EGL surfaceless, then OSMesa), egl, egl-device, "
                     "egl-surfaceless, osmesa, or software (the CPU reference rasterizer, llvmpipe's rules, no GL)",
                     o.backend, kBackendKinds),
        flag::whole("--threads", "N", "rasterizer threads: the software backend's, and llvmpipe's (LP_NUM_THREADS); "
                    "default every core", o.threads, 1, 256),
        flag::choice("--interp", "MODE", "an interpolation mode",
                     "depth along each scan-line span, software backend only: exact (default, llvmpipe's bits), span "
                     "(paper 001's midpoint-subdivision engine, within 1 LSB of the line through the span's ends) or "
                     "dda (add-and-shift, 8 fraction bits: the error grows along the span); a slow path. Colour is "
                     "shaded per fragment in every mode (not Gouraud): it changes only where a depth test flips",
                     o.interp, kDepthInterps),
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
        flag::choice("--depth-format", "F", "a depth format",
                     "d24 (default): 24-bit depth; d32f: 32-bit float with reversed Z (glClipControl zero-to-one, 1 "
                     "near, 0 far), which separates depths about 1e-7 of their distance apart at any near/far ratio. "
                     "See 'frugal info SCENE'",
                     o.depthFormat, kDepthFormats),
        flag::number("--time", "SECONDS", "animation time of the frame (default 0)", o.time, -1e9, 1e9),
        flag::frames("--frames", "frames A to B inclusive, at --fps (default the scene's, 30)", o.frames),
        flag::number("--fps", "N", "frames per second of --frames (default the scene's)", o.fps, 1e-3, 1e6),
        flag::colour("--background", "R,G,B[,A]", "clear colour in [0,1] (default 0.12,0.13,0.15)", o.background),
        flag::on("--cull-backfaces", "draw OBJ files single-sided (OBJ is double-sided by default; glTF follows each "
                 "material's doubleSided)", o.load.objDoubleSided, false),
        flag::on("--file-order", "keep the file's triangle order (default: reordered for the vertex cache)",
                 o.load.optimizeOrder, false),
        flag::on("-q, --quiet", "no progress lines", o.quiet),
    }};
}

FlagGroup someFlags(const FlagGroup& group, const std::vector<std::string>& names) {
    FlagGroup out{group.title, {}};
    for (const Flag& f : group.flags)
        if (std::find(names.begin(), names.end(), f.canonical()) != names.end()) out.flags.push_back(f);
    return out;
}

void checkSharedOptions(RenderOptions& o, ArgCursor& cursor) {
    if (o.backend != BackendKind::Software && o.interp != DepthInterp::Exact)
        cursor.fail(std::string("--interp ") + toString(o.interp) +
                    ": only the software backend models the span interpolator (use --backend software)");
    if (o.interp != DepthInterp::Exact && o.depthFormat == DepthFormat::D32F)
        cursor.fail(std::string("--interp ") + toString(o.interp) +
                    " with --depth-format d32f: the span engine interpolates a 24-bit depth; use --depth-format d24");
    const std::optional<float>& near = o.camera.znear;
    const std::optional<float>& far = o.camera.zfar;
    if (near && far && *far != 0.0f && !(*far > *near))
        cursor.fail("--far " + fmt(*far) + ": must exceed --near " + fmt(*near));
    if (cursor.error.empty() && !o.cameraPathFile.empty()) {
        Result<std::vector<Camera>> cameras = readCameraPath(o.cameraPathFile);
        if (!cameras) cursor.fail("--" + cameras.error());
        else o.cameraPath = std::move(*cameras);
    }
}

Flag orderFlag(Order& order, std::string help) {
    if (help.empty())
        help = "the draw order: submit (default), key (texture, program, mesh, as bgfx sorts), or by state-change "
               "costs measured on the backend at start (about a second; see 'frugal info --state-costs'): paper "
               "(paper 004's id sort over the 3 costliest kinds), greedy (cheapest next change) or best (the optimum "
               "over the distinct state sets, Held-Karp up to 16, else local search). Consecutive draws of one mesh go "
               "out as one instanced draw. Only pixels where two surfaces tie exactly in depth can change (first drawn "
               "wins). Not applied with --reuse, which draws in its own order (the static pair, then what changed)";
    return flag::choice("--order", "ORDER", "an order", std::move(help), order, kOrders);
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
    if (!options.sizeGiven) sizeForAspect(aspect, kLongSide, options.width, options.height);
    if (!aspectDiffers(aspect, options.width, options.height)) return {};
    return options.scene + ": camera " + std::to_string(*index) + quotedName(camera.name) + " has aspect ratio " +
           fmt(aspect) + ", the image " + fmt(double(options.width) / options.height) + " (" +
           std::to_string(options.width) + "x" + std::to_string(options.height) +
           "): drawn with the camera's vertical " + (camera.perspective ? "field of view" : "extent (ymag)") +
           " and the image's aspect ratio, not stretched";
}

Result<Scene> loadForRender(RenderOptions& options, std::ostream& err) {
    Result<Scene> scene = loadScene(options.scene, options.load);
    if (!scene) return scene;
    const std::string aspectWarning = fitSizeToCamera(options, *scene);
    // Check the first frame's camera before a backend is opened, so a bad camera is the only line.
    const int first = options.frames ? options.frames->first : 0;
    if (Result<FrameSetup> setup = setUpFrame(options, *scene, first, false); !setup) return Error{setup.error()};
    for (const std::string& warning : scene->warnings) err << "warning: " << warning << "\n";
    if (!aspectWarning.empty()) err << "warning: " << aspectWarning << "\n";
    if (!scene->unsupported.empty()) {
        std::string names;
        for (const std::string& name : scene->unsupported) names += (names.empty() ? "" : ", ") + name;
        err << "warning: " << options.scene << ": not modelled, drawn without: " << names << "\n";
    }
    return scene;
}

Settings rendererSettings(const RenderOptions& options) {
    Settings s;
    s.width = options.width;
    s.height = options.height;
    s.backend = options.backend;
    s.threads = options.threads;
    s.interp = options.interp;
    s.depthFormat = options.depthFormat;
    s.background = options.background;
    return s;
}

Result<std::vector<ReportView>> viewsAround(const RenderOptions& options, const Scene& scene, int count, double time) {
    const Bounds bounds = scene.bounds(time);
    if (bounds.empty()) return Error{options.scene + ": the scene has no geometry to view"};
    std::vector<ReportView> views = reportViews(bounds.center(), bounds.radius(), count,
                                                options.camera.yfovDegrees.value_or(40.0f),
                                                float(options.width) / float(options.height));
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

Result<FrameSetup> setUpFrame(const RenderOptions& options, const Scene& scene, int frame, bool writeIds) {
    const Camera camera = cameraOf(options, frame);
    Result<FrameSetup> setup = frugal::setUpFrame(scene, camera, frameTimeOf(options, scene, frame), options.width,
                                                  options.height, writeIds, options.depthFormat);
    if (!setup) return Error{options.scene + ": " + setup.error()};
    return setup;
}

}  // namespace frugal
