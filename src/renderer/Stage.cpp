#include "renderer/Stage.h"

#include <algorithm>
#include <optional>

#include "renderer/Backends.h"

namespace frugal {

Stage::Parts::~Parts() {
    renderer.reset();  // the uploads, while the backend lives
    if (backend && target != kNoHandle) backend->destroyTarget(target);
}

Result<Stage> Stage::open(const Settings& s) {
    std::vector<std::string> log;
    Result<std::unique_ptr<Backend>> opened = openBackend(s.backend, &log, s.threads, s.interp);
    if (!opened)
        return Error{std::string("backend ") + toString(s.backend) + ": " + opened.error().message, opened.error().kind, true};
    return on(std::move(*opened), s, std::move(log));
}

Result<std::optional<Stage>> Stage::openIfAvailable(const Settings& s, std::string& unavailable) {
    std::vector<std::string> log;
    Result<std::unique_ptr<Backend>> opened = openBackend(s.backend, &log, s.threads, s.interp);
    if (!opened) {
        unavailable = opened.error().message;
        return std::optional<Stage>();
    }
    Result<Stage> stage = on(std::move(*opened), s, std::move(log));
    if (!stage) return stage.error();
    return std::optional<Stage>(std::move(*stage));
}

Result<Stage> Stage::on(std::unique_ptr<Backend> opened, const Settings& s, std::vector<std::string> log) {
    const std::string size = std::to_string(s.width) + "x" + std::to_string(s.height);
    auto parts = std::make_unique<Parts>();
    parts->log = std::move(log);
    parts->backend = std::move(opened);
    parts->mipmaps = s.mipmaps;
    Backend& backend = *parts->backend;
    // The environment map, read and prefiltered once a process (applyShading finds it loaded).
    if (!s.environmentMap.empty())
        if (Result<std::shared_ptr<const EnvironmentMap>> map = loadEnvironmentMap(s.environmentMap); !map)
            return Error{map.error().message, ErrorKind::BadInput, true};
    if (!backend.supportsDepthFormat(s.depthFormat))
        return Error{std::string("depth-format ") + toString(s.depthFormat) + ": " + backend.name() +
                         " has no glClipControl (GL 4.5 or ARB_clip_control), which reversed Z needs",
                     ErrorKind::BackendUnavailable, true};
    // A size the backend takes but this process's memory does not hold: refused before any of it is made.
    if (std::max(s.width, s.height) <= backend.maxTargetSize())
        if (const std::optional<std::string> problem = frameMemoryProblem(s.width, s.height, s.samples, s.linear))
            return Error{"size " + size + ": " + *problem, ErrorKind::OutOfMemory, true};
    if (s.samples > backend.maxSamples())
        return Error{"samples " + std::to_string(s.samples) + ": " + backend.name() + " has at most " +
                         std::to_string(backend.maxSamples()) + " samples a pixel",
                     ErrorKind::BadInput, true};
    parts->target = backend.createTarget(s.width, s.height, s.depthFormat, s.samples, colorFormat(s));
    if (parts->target == kNoHandle)
        return Error{"size " + size + ": " + backend.name() + " cannot create a target that large (at most " +
                         std::to_string(backend.maxTargetSize()) + " pixels a side)",
                     ErrorKind::BadInput, true};
    return Stage(std::move(parts));
}

void applyShading(const Settings& s, FrameParams& params) {
    params.tonemap = s.tonemap;
    params.shading = s.shading;
    params.lighting.environment = s.environment;
    params.lighting.environmentSpecular = s.environmentSpecular;
    params.lighting.map = nullptr;
    if (!s.environmentMap.empty())  // loaded when the stage was opened (Stage::on refuses a map it cannot load)
        if (Result<std::shared_ptr<const EnvironmentMap>> map = loadEnvironmentMap(s.environmentMap))
            params.lighting.map = *map;
    if (s.light == DefaultLight::Off) params.lighting.light = 0.0f;
}

Result<bool> Stage::upload(const Scene& scene) {
    parts_->renderer.reset();  // released before the next are made (a backend may reuse the names)
    Result<SceneRenderer> uploaded = SceneRenderer::create(*parts_->backend, scene, parts_->mipmaps);
    if (!uploaded) return Error{scene.source + ": " + uploaded.error().message};
    parts_->renderer.emplace(std::move(*uploaded));
    return true;
}

}  // namespace frugal
