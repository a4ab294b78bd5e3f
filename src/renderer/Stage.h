// A stage: a backend, one target of a frame's size and a scene uploaded into it. It is what a
// Renderer draws into, and what the research harnesses (research/lab/) time directly when they need the
// lower-level calls (SceneRenderer, Backend) that a Renderer hides. Move-only; it releases the
// uploads, then the target, then the backend.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <frugal/Result.h>
#include <frugal/Settings.h>

#include "pipeline/Backend.h"
#include "pipeline/SceneRenderer.h"

namespace frugal {
// The settings that shade a whole frame, put into its parameters: the shading model, tone mapping, the default light
// (its intensity 0 with DefaultLight::Off), the environment's radiance or map (loaded once a process, by the first
// Stage opened with it) and its specular term. What every front end
// that sets up frames from Settings calls (the Renderer, the command line's sequences).
void applyShading(const Settings& s, FrameParams& params);
}  // namespace frugal

namespace frugal {

class Stage {
public:
    // Opens settings.backend (with settings.threads and settings.interp) and makes its target
    // (settings.width × settings.height, settings.depthFormat), the memory checked before. Errors
    // start with the setting they are about (Error::aboutSetting):
    //   "backend auto: no usable GL context: ..."                                 BackendUnavailable
    //   "depth-format d32f: osmesa has no glClipControl (...), which reversed Z needs"   BackendUnavailable
    //   "size 16384x16384: needs about 9.7 GB (...), more than the 3.5 GB left (ulimit -v)"  OutOfMemory
    //   "size 20000x10: egl-surfaceless cannot create a target that large (at most 16384 pixels a side)"
    static Result<Stage> open(const Settings& settings);
    // The same on a backend already open (openBackend; settings.backend is not read): the errors
    // but the first.
    static Result<Stage> on(std::unique_ptr<Backend> backend, const Settings& settings,
                            std::vector<std::string> log = {});
    // open() where a backend that does not open here is no error (a harness going over several
    // kinds skips it): the result is then empty and `unavailable` gets openBackend's reason ("no
    // usable GL context: ..."). Every other failure is the error, as open() gives it.
    static Result<std::optional<Stage>> openIfAvailable(const Settings& settings, std::string& unavailable);

    // Uploads `scene`, replacing what was uploaded before; the scene must outlive the uploads (the
    // stage, or the next upload); its textures without mipmaps when the settings say no-mipmaps.
    // Error: "<scene.source>: <why the backend refused a mesh>".
    Result<bool> upload(const Scene& scene);

    Backend& backend() const { return *parts_->backend; }
    TargetHandle target() const { return parts_->target; }
    SceneRenderer& renderer() const { return *parts_->renderer; }  // after upload()
    bool uploaded() const { return parts_->renderer.has_value(); }
    // One line per GL context tried ("egl-surfaceless: ok (...)"), or "software: ok".
    const std::vector<std::string>& log() const { return parts_->log; }

private:
    struct Parts {
        std::vector<std::string> log;
        std::unique_ptr<Backend> backend;
        TargetHandle target = kNoHandle;
        std::optional<SceneRenderer> renderer;
        bool mipmaps = true;  // Settings::mipmaps: whether uploads make textures' mipmaps
        Parts() = default;
        Parts(const Parts&) = delete;
        Parts& operator=(const Parts&) = delete;
        ~Parts();
    };
    explicit Stage(std::unique_ptr<Parts> parts) : parts_(std::move(parts)) {}
    std::unique_ptr<Parts> parts_;
};

// A target of `backend` (kNoHandle: none), destroyed when this goes or is reset. It must go before
// the backend: declare it after the stage that owns the backend.
class OwnedTarget {
public:
    explicit OwnedTarget(Backend& backend, TargetHandle handle = kNoHandle) : backend_(backend), handle_(handle) {}
    ~OwnedTarget() { reset(kNoHandle); }
    OwnedTarget(const OwnedTarget&) = delete;
    OwnedTarget& operator=(const OwnedTarget&) = delete;

    TargetHandle get() const { return handle_; }
    void reset(TargetHandle handle) {
        if (handle_ != kNoHandle) backend_.destroyTarget(handle_);
        handle_ = handle;
    }

private:
    Backend& backend_;
    TargetHandle handle_;
};

}  // namespace frugal
