// The renderer: one object that owns a backend (EGL, OSMesa or the software reference; Auto and its
// fallback), its target, the scene's uploads, and every method that makes a frame cheaper, chained
// in the one right order: culling prepared before the upload, cost-driven orders measured on the
// backend and refined between frames, the hidden-surface plan, temporal reuse's static pair, the
// read-back. A sequence is a loop of render() calls; reuse and the cost refinement work across them.
//
//   Result<Scene> scene = loadScene("robot.glb");
//   Result<Renderer> renderer = Renderer::create(std::move(*scene), {.width = 800, .height = 600});
//   Result<Frame> frame = renderer->render(Camera::fromScene(0), 0.0);
//   writePng("robot.png", frame->color);
//
// Errors come as Result (frugal/Result.h): ErrorKind::BackendUnavailable when no backend of the kind
// asked for runs here, OutOfMemory when a target is larger than the memory the process may still take
// (checked before it is made), BadInput for a scene the backend refuses or a camera that cannot be
// resolved. Nothing is thrown, nothing aborts on bad input.
//
// Threads: a Renderer is used from one thread at a time; two Renderers on two threads run in
// parallel (each has its own backend and context). To hand one to another thread, call
// releaseThread() on the thread that used it last.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <frugal/Camera.h>
#include <frugal/Image.h>
#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>
#include <frugal/Stats.h>

namespace frugal {

// One frame: the images (rows bottom-up: frugal/Image.h) and what it cost. `ids` is empty unless
// Settings::ids, `linear` unless Settings::linear.
struct Frame {
    ColorImage color;
    LinearImage linear;
    DepthImage depth;
    IdImage ids;
    FrameStats stats;
    View view;  // the camera as resolved for this frame: matrices, planes, aspect ratios
};

// The line for an allocation that failed all the same (std::bad_alloc), past the memory checks made
// before a target is made: "out of memory: an allocation failed (ulimit -v: 3.8 GB left once the
// command's memory was freed)". frugal's main prints it.
std::string outOfMemoryMessage();

class Renderer {
public:
    // Opens the backend, prepares what the settings ask for and uploads `scene`, which the renderer
    // keeps (culling reorders its meshes' triangles: scene() is the one drawn). `log`, when given,
    // receives one line per GL context tried ("egl-surfaceless: ok (...)"). Errors, one line each,
    // starting with the setting they are about when there is one (Error::aboutSetting):
    //   "backend auto: no usable GL context: ..."                          BackendUnavailable
    //   "depth-format d32f: osmesa has no glClipControl (GL 4.5 or ARB_clip_control) ..."
    //   "size 16384x16384: needs about 9.7 GB (...), more than the 3.5 GB left (ulimit -v)"  OutOfMemory
    //   "size 20000x10: egl-surfaceless cannot create a target that large (at most 16384 pixels a side)"
    //   "reuse: 8192x8192 needs about 2.4 GB more (...), more than ... left (ulimit -v)"     OutOfMemory
    //   "order best: <why the cost measurement failed>"
    //   "<scene>: mesh 2 'name' (...): <backend> refused it"                BadInput
    static Result<Renderer> create(Scene scene, const Settings& settings);

    Renderer(Renderer&& other) noexcept;
    Renderer& operator=(Renderer&& other) noexcept;
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;
    ~Renderer();

    // The frame at scene time `seconds` (animations sampled there) through `camera`. Errors:
    // "<scene>: camera 3: the scene has 1 camera", and the like (BadInput); "<scene>: <why>" when the
    // oracle's visible set cannot be built.
    Result<Frame> render(const Camera& camera, double seconds);
    // The same into `frame`, whose images' memory is used again when it is large enough: a loop
    // that renders into one Frame allocates nothing a frame (a new 800x600 frame is 5.8 MB of fresh
    // pages, about 0.5 ms of page faults and zeroing on every frame). On an error `frame` holds
    // nothing of use.
    Result<bool> render(const Camera& camera, double seconds, Frame& frame);
    // Which images render() reads back besides the colour: an image no file or caller needs is
    // left out (Frame::depth stays empty), sparing its read-back (the depth of a 1080p frame: a
    // few milliseconds on llvmpipe; docs/writing.md). Ids are read whenever Settings::ids drew them.
    struct ReadBack {
        bool depth = true;
    };
    Result<bool> render(const Camera& camera, double seconds, Frame& frame, ReadBack readBack);

    // The frame render() will be asked for after the next call (a sequence knows it). With cull
    // occlusion-ahead, the next render() makes that frame's plan on a thread of its own while its
    // own frame draws (and waits for it before it returns: no thread outlives a call), and the
    // render() of that frame takes the plan instead of culling. The plan is used only when that
    // frame's transforms and view are exactly the ones it was made for; otherwise the frame is
    // culled as usual, so a wrong guess costs time, never an image. Any other cull ignores it.
    void setNextFrame(const Camera& camera, double seconds);

    // Moves node `node` for the frames that follow: its local transform becomes `transform`
    // (Scene::setTransform, whose errors it returns). Temporal reuse sees the instances it places
    // as moved in the next frame, and only them. The scene's envelope grows to hold them where
    // they leave it (the depth range is fitted to it, so a frame after such a move may have other
    // planes, and reuse then renders it in full); it never shrinks.
    Result<bool> setTransform(int node, const glm::mat4& transform);

    // Lets another thread render next. A GL context is current on one thread at a time: call it on
    // the thread that rendered (or created the renderer) before another thread renders or destroys
    // it. Costs one context switch; nothing on the software backend.
    void releaseThread();

    const Scene& scene() const;
    const Settings& settings() const;
    std::string backendName() const;      // "egl-surfaceless", "osmesa", "software", ...
    std::string backendRenderer() const;  // GL_RENDERER and GL_VERSION, or the software backend's description
    const std::vector<std::string>& backendLog() const;  // one line per context tried, or "software: ok"
    // With Cull other than None: what preparing the culling took (milliseconds: sphere, map,
    // clusters, hull, total) and the bytes it keeps.
    struct CullPreparation {
        double sphereMs = 0, mapMs = 0, clusterMs = 0, hullMs = 0, totalMs = 0;
        bool hull = false;        // built (paper only)
        std::uint64_t bytes = 0;  // the maps (barycenter, memory access, facing planes) and the hull's vertices
    };
    std::optional<CullPreparation> cullPreparation() const;
    // With Settings::environmentMap: the image's size and what reading and prefiltering it took
    // (once a process: later renderers with the same map share it).
    struct EnvironmentPreparation {
        int width = 0, height = 0;
        double ms = 0;
    };
    std::optional<EnvironmentPreparation> environmentPreparation() const;
    // With Order paper, greedy or best: the state costs measured, as refined so far.
    std::optional<StateCosts> stateCosts() const;
    // Bytes of the static pair (with reuse), else 0.
    std::uint64_t staticPairBytes() const;
    // Memory this renderer keeps beyond a plain render's (the default settings'): the static pair,
    // the culling's maps and hull, the hidden-surface planner's polygons. The GPU's copy of the
    // scene is the same for all: culling reorders the index buffer, it does not add one.
    std::uint64_t extraBytes() const;

private:
    struct Impl;
    explicit Renderer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace frugal
