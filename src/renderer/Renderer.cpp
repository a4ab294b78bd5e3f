#include <chrono>
#include <cmath>
#include <optional>
#include <utility>

#include <frugal/Renderer.h>

#include "cull/CullAhead.h"
#include "cull/Culling.h"
#include "hsr/Plan.h"
#include "pipeline/Frame.h"
#include "pipeline/SceneRenderer.h"
#include "renderer/Backends.h"
#include "renderer/DrawFingerprint.h"
#include "renderer/Oracle.h"
#include "renderer/Stage.h"
#include "renderer/StateOrder.h"
#include "reuse/Reuse.h"
#include "software/SoftwareBackend.h"

namespace frugal {

namespace {

using Clock = std::chrono::steady_clock;
double msBetween(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

std::string sizeText(const Settings& s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

// Colour with alpha. The target keeps it premultiplied (associated): the blend (rgb·a + dst·(1 − a))
// and the resolve of a multisampled pixel (the samples' mean) are right for premultiplied colour,
// so a background whose alpha is below 1 is cleared as (rgb·a, a). A frame's colour image is
// straight (unassociated) alpha, as PNG defines it and viewers composite it: rgb ÷ a where a is
// between 0 and 1 (rounded, at most 255), 0 where a is 0. With an opaque background (the default)
// every pixel has alpha 1 and neither step changes a byte.
glm::vec4 premultiplied(const glm::vec4& c) { return {c.r * c.a, c.g * c.a, c.b * c.a, c.a}; }

// What a frame's target is cleared to: the background, premultiplied. The background is a display
// colour, written into an 8-bit target as it is; a linear target (Settings::linear) gets its linear
// value rgb^2.2, whose display encoding gives the same bytes back.
glm::vec4 clearColor(const Settings& s) {
    glm::vec4 c = s.background;
    if (s.linear)
        for (int i = 0; i < 3; ++i) c[i] = c[i] > 0.0f ? float(std::pow(double(c[i]), 2.2)) : 0.0f;
    return premultiplied(c);
}

// A linear frame's colour (Settings::linear) the same way, in float, before its display encoding.
void unpremultiply(std::vector<float>& rgba) {
    for (std::size_t i = 0; i + 3 < rgba.size(); i += 4) {
        const float a = rgba[i + 3];
        if (a >= 1.0f) continue;
        for (int c = 0; c < 3; ++c) rgba[i + std::size_t(c)] = a > 0.0f ? rgba[i + std::size_t(c)] / a : 0.0f;
    }
}

void unpremultiply(std::vector<std::uint8_t>& rgba) {
    for (std::size_t i = 0; i + 3 < rgba.size(); i += 4) {
        const unsigned a = rgba[i + 3];
        if (a == 255) continue;
        for (int c = 0; c < 3; ++c)
            rgba[i + c] = a == 0 ? 0 : std::uint8_t(std::min(255u, (rgba[i + c] * 255u + a / 2) / a));
    }
}

}  // namespace

// Members in the order they are made; they go in reverse, the backend last.
struct Renderer::Impl {
    Settings settings;
    std::unique_ptr<Scene> scene;  // stable address: the uploads and planners point to it
    std::optional<SceneCuller> culler;
    std::optional<Renderer::CullPreparation> cullPreparation;
    std::optional<hsr::Planner> planner;
    std::optional<Stage> stage;  // the backend, the target and the uploads
    Backend* backend = nullptr;  // the stage's, for short
    TargetHandle target = kNoHandle;
    SceneRenderer* renderer = nullptr;
    std::optional<OrderCosts> orderCosts;
    TargetHandle staticTarget = kNoHandle;
    std::optional<TemporalReuse> reuse;
    InterpCounters interpSeen;  // the software backend's counters after the previous frame
    int framesDone = 0;
    bool moved = false;  // setTransform since the last frame: the envelope may have to grow
    // A scene without animations has the same bounds at every time: kept from the first frame that
    // needs them (automatic views, default targets) until a node moves.
    std::optional<Bounds> stillBounds;
    // cull occlusion-ahead: the frame after this one (setNextFrame), and its plan, made while this
    // one draws and waited for before render() returns. Declared last: destroyed first.
    std::optional<std::pair<Camera, double>> nextFrame;
    CullAhead ahead;
    // What draw() asked the backend to do in this frame, kept (moved, not copied) until the clock
    // has stopped, when render() takes its fingerprint: reuse's plan, or the list drawn after a full
    // clear. A plan's steps point only to lists the reuse planner keeps.
    FramePlan drawnPlan;
    DrawList drawnList;
    bool drewPlan = false;

    ~Impl() {
        if (backend && staticTarget != kNoHandle) backend->destroyTarget(staticTarget);
    }

    Result<bool> open();
    void draw(const FrameSetup& setup, const DrawList& submitted, FrameStats& stats);
    Result<bool> render(const Camera& camera, double seconds, Frame& frame, Renderer::ReadBack readBack);
    void growEnvelope();
};

Result<bool> Renderer::Impl::open() {
    const Settings& s = settings;
    // Values out of their range, and settings that may not go together (frugal/Settings.h).
    if (const std::optional<SettingsProblem> problem = settingsProblem(s))
        return Error{describe(*problem, s), ErrorKind::BadInput, true};
    // The hidden-surface modes plan from the meshes' shapes, which morph targets and skins change.
    if (traitsOf(s.hsr).plans && scene->deforms())
        return Error{std::string("hsr ") + toString(s.hsr) + ": '" + scene->source +
                         "' has meshes that deform (morph targets, skins), and the hidden-surface modes need "
                         "meshes of a fixed shape (zbuffer draws it)",
                     ErrorKind::BadInput, true};
    if (traitsOf(s.hsr).plans)
        for (const Instance& instance : scene->instances)
            if (const Mesh& mesh = scene->meshes[std::size_t(instance.mesh)]; !mesh.triangles())
                return Error{std::string("hsr ") + toString(s.hsr) + ": '" + scene->source + "' has " +
                                 topologyName(mesh.topology) + " (mesh " + std::to_string(instance.mesh) +
                                 (mesh.name.empty() ? std::string() : " '" + mesh.name + "'") +
                                 "), and the hidden-surface modes order polygons (zbuffer draws it)",
                             ErrorKind::BadInput, true};
    const CullTraits& cull = traitsOf(s.cull);
    if (cull.prepares) {
        MapParams bins{s.cullBinsTheta, s.cullBinsPhi};
        bins.hull = cull.hull;
        culler = SceneCuller::prepare(*scene, bins);  // reorders the meshes: before the upload
        const PrepStats totals = culler->totals();
        cullPreparation = CullPreparation{totals.sphereMs, totals.mapMs,     totals.clusterMs,
                                          totals.hullMs,   totals.totalMs(), bins.hull,
                                          totals.mapBytes + totals.accessBytes + totals.hullBytes};
    }
    if (traitsOf(s.hsr).plans) planner.emplace(*scene);

    Result<Stage> opened = Stage::open(s);
    if (!opened) return opened.error();
    stage.emplace(std::move(*opened));
    backend = &stage->backend();
    target = stage->target();
    if (Result<bool> uploaded = stage->upload(*scene); !uploaded) return uploaded.error();
    renderer = &stage->renderer();

    // paper, greedy and best order by costs measured on this backend, refined between frames.
    Result<OrderCosts> costs = OrderCosts::start(s.order, *backend, s.refineCosts);
    if (!costs)
        return Error{std::string("order ") + toString(s.order) + ": " + costs.error().message, ErrorKind::BadInput, true};
    orderCosts.emplace(std::move(*costs));

    if (s.reuse) {
        // The pair (a target's bytes, kTargetBytesPerPixel; the measured figure is in docs/gl/README.md)
        // and what a frame still allocates after its target (the read-back and the PNG encoding): the
        // first frame comes after it.
        const std::uint64_t pixels = std::uint64_t(s.width) * std::uint64_t(s.height);
        const std::uint64_t pairBytes =
            targetBytesPerPixel(s.linear) * std::uint64_t(s.samples > 1 ? s.samples + 1 : 1);
        const std::uint64_t needed =
            pixels * pairBytes + pixels * (frameBytesPerPixel(s.linear) - targetBytesPerPixel(s.linear));
        if (const std::optional<std::string> problem = memoryProblem(needed))
            return Error{"reuse: " + sizeText(s) + " needs about " + gigabytes(needed) + " more (a static pair of " +
                             std::to_string(pairBytes) +
                             " bytes a pixel, then the frame's read-back and PNG encoding), " + *problem,
                         ErrorKind::OutOfMemory, true};
        staticTarget = backend->createTarget(s.width, s.height, s.depthFormat, s.samples, colorFormat(s));
        if (staticTarget == kNoHandle)
            return Error{"reuse: " + backend->name() + " could not create the static pair (" + sizeText(s) + ", " +
                             std::to_string(pixels * pairBytes) + " bytes)",
                         ErrorKind::OutOfMemory, true};
        reuse.emplace(*scene, s.width, s.height, reuseOptionsFrom(s.reuseSettings));
    }
    if (const std::optional<InterpCounters> counters = softwareInterpStats(*backend)) interpSeen = *counters;
    return true;
}

// Draws the frame's list: ordered, then planned in the hidden-surface mode (the plan is timed with
// the frame), or through temporal reuse.
void Renderer::Impl::draw(const FrameSetup& setup, const DrawList& submitted, FrameStats& stats) {
    const Settings& s = settings;
    const glm::vec4 clear = clearColor(s);
    if (reuse) {
        // A culled list, or the whole scene (the planner's own, faster list).
        FramePlan plan = culler ? reuse->plan(setup.params, setup.world, submitted, clear)
                                : reuse->plan(setup.params, setup.world, clear);
        renderer->execute(plan, target, staticTarget, setup.params, setup.world, clear);
        stats.reuse = reuse->stats();
        drawnPlan = std::move(plan);
        drewPlan = true;
        return;
    }
    drewPlan = false;
    DrawList list = orderFrameDraws(*scene, submitted, s.order, orderCosts->costsUs());
    if (!planner) {
        renderer->renderFrame(target, s.width, s.height, setup.params, setup.world, clear, list);
        drawnList = std::move(list);
        return;
    }
    HsrStats hsrStats;
    DrawList planned = planner->plan(s.hsr, setup.params, setup.world, list, s.width, s.height, &hsrStats);
    stats.hsr = hsrStats;
    renderer->renderFrame(target, s.width, s.height, setup.params, setup.world, clear, planned);
    drawnList = std::move(planned);
}

// After setTransform: the envelope grows to hold where the moved instances are now (and can go,
// for animated ones below a moved node); unchanged while they stay inside it, so the fitted depth
// range, and with it reuse's static pair, stays valid.
void Renderer::Impl::growEnvelope() {
    moved = false;
    const Bounds now = scene->computeEnvelope();
    if (now.empty()) return;
    Bounds& envelope = scene->envelope;
    if (!envelope.empty() && glm::all(glm::greaterThanEqual(now.min, envelope.min)) &&
        glm::all(glm::lessThanEqual(now.max, envelope.max)))
        return;
    envelope.add(now.min);
    envelope.add(now.max);
}

Result<bool> Renderer::Impl::render(const Camera& camera, double seconds, Frame& frame, Renderer::ReadBack readBack) {
    const Settings& s = settings;
    const glm::vec4 clear = clearColor(s);
    if (moved) growEnvelope();
    if (!stillBounds && scene->animations.empty() && (!camera.eye || !camera.target))
        stillBounds = scene->bounds(0.0);
    Result<FrameSetup> setup = setUpFrame(*scene, camera, seconds, s.width, s.height, s.ids, s.depthFormat,
                                          stillBounds ? &*stillBounds : nullptr);
    if (!setup) return Error{scene->source + ": " + setup.error().message};
    applyShading(s, setup->params);
    frame.stats = FrameStats{};
    FrameStats& stats = frame.stats;
    stats.time = seconds;

    // Between two frames, outside every timing: one more cost round when due; this frame and those
    // after it are ordered by the refined costs.
    const auto refineStart = Clock::now();
    if (framesDone > 0 && orderCosts->refine(framesDone)) {
        stats.refinedCostsUs = orderCosts->costsUs();
        stats.refineMs = msBetween(refineStart, Clock::now());
    }

    const StateChanges changesBefore = backend->stateChanges();
    // The list the cull gave (or the whole scene's), kept for its fingerprint after the clock stops.
    DrawList culled;
    const DrawList* submitted = &renderer->fullList();
    auto t0 = Clock::now();
    if (traitsOf(s.cull).idPass) {
        // The id pass and the oracle's own index buffers come before the clock starts.
        Result<Oracle> oracle = makeOracle(*renderer, target, s.width, s.height, setup->params, setup->world, clear);
        if (!oracle) return Error{scene->source + ": " + oracle.error().message};
        stats.cull = CullStats{scene->primitiveCount(), oracle->rvs.count, oracle->ms, 0, std::nullopt};
        t0 = Clock::now();
        oracle->renderer->renderFrame(target, s.width, s.height, setup->params, setup->world, clear);
    } else if (culler) {
        const OcclusionTarget cullTarget = occlusionTarget(*backend, s);
        std::optional<DrawList> madeAhead = ahead.take(s.cull, setup->world, setup->view, cullTarget);
        culled = madeAhead ? std::move(*madeAhead) : culler->cull(s.cull, *scene, setup->world, setup->view, cullTarget);
        const DrawList& list = culled;
        submitted = &culled;
        const double cullMs = msBetween(t0, Clock::now());
        std::size_t ranges = 0;
        for (const DrawCommand& command : list) ranges += command.ranges.size();
        stats.cull = CullStats{scene->primitiveCount(), submittedTriangles(*scene, list), cullMs, ranges, std::nullopt};
        if (traitsOf(s.cull).occlusion) {
            const OcclusionStats& o = culler->occlusion().stats();
            stats.cull->occlusion = OcclusionFrameStats{o.ran, o.ms, o.trianglesHidden, madeAhead.has_value(), 0.0};
        }
        // The next frame's plan, made while this one draws (its set-up is this thread's: the same
        // calls render() makes; a frame that cannot be set up is culled, and its error given, then).
        if (traitsOf(s.cull).ahead && nextFrame) {
            Result<FrameSetup> next = setUpFrame(*scene, nextFrame->first, nextFrame->second, s.width, s.height, s.ids,
                                                 s.depthFormat, stillBounds ? &*stillBounds : nullptr);
            if (next) ahead.start(*culler, s.cull, *scene, std::move(next->world), next->view, aheadTarget(cullTarget));
        }
        nextFrame.reset();
        draw(*setup, list, stats);
    } else {
        draw(*setup, renderer->fullList(), stats);
    }
    backend->finish();
    if (ahead.pending()) {
        // The next frame's plan, made while this one drew: the frame ends when both are done (its
        // time holds the wait), and no thread of it outlives render().
        const auto waitStart = Clock::now();
        ahead.wait();
        stats.cull->occlusion->aheadWaitMs = msBetween(waitStart, Clock::now());
    }
    const auto t1 = Clock::now();
    // The frame's own vectors, read into and given back (their memory used again).
    Buffers buffers;
    buffers.rgba = std::move(frame.color.rgba);
    buffers.linear = std::move(frame.linear.rgba);
    buffers.depth = std::move(frame.depth.values);
    buffers.ids = std::move(frame.ids.ids);
    backend->readBackInto(target, buffers, {.depth = readBack.depth, .ids = s.ids});
    const auto t2 = Clock::now();
    stats.renderMs = msBetween(t0, t1);
    stats.readbackMs = msBetween(t1, t2);
    stats.stateChanges = backend->stateChanges() - changesBefore;
    if (!traitsOf(s.cull).idPass) {
        // The interpolator changes how the backend draws the same calls (software backend).
        const auto seed = std::uint64_t(s.interp);
        stats.drawFingerprint = drewPlan ? drawFingerprint(drawnPlan, seed)
                                         : drawFingerprint(drawnList, s.width, s.height, seed);
        stats.culledFingerprint = drawFingerprint(*submitted, s.width, s.height, std::uint64_t(DepthInterp::Exact));
    }
    if (s.interp != DepthInterp::Exact)
        if (const std::optional<InterpCounters> counters = softwareInterpStats(*backend)) {
            // The backend's counters run from its start: per frame, the difference.
            stats.interp = InterpStats{counters->spans - interpSeen.spans, counters->pixels - interpSeen.pixels,
                                       counters->overflow - interpSeen.overflow};
            interpSeen = *counters;
        }
    ++framesDone;

    if (s.background.a < 1.0f && s.linear) {  // only a translucent background leaves a < 1
        unpremultiply(buffers.linear);
        encodeLinear(buffers);
    } else if (s.background.a < 1.0f) {
        unpremultiply(buffers.rgba);
    }
    const View& view = setup->view;
    frame.color = ColorImage{buffers.width, buffers.height, std::move(buffers.rgba)};
    frame.depth = DepthImage{buffers.width, buffers.height, std::move(buffers.depth), buffers.depthFormat,
                             view.znear,    view.zfar,      view.perspective};
    frame.ids = s.ids ? IdImage{buffers.width, buffers.height, std::move(buffers.ids)} : IdImage{};
    frame.linear = s.linear ? LinearImage{buffers.width, buffers.height, std::move(buffers.linear)} : LinearImage{};
    frame.view = view;
    return true;
}

Result<Renderer> Renderer::create(Scene scene, const Settings& settings) {
    auto impl = std::make_unique<Impl>();
    impl->settings = settings;
    impl->scene = std::make_unique<Scene>(std::move(scene));
    if (Result<bool> opened = impl->open(); !opened) return opened.error();
    return Renderer(std::move(impl));
}

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::Renderer(Renderer&& other) noexcept = default;
Renderer& Renderer::operator=(Renderer&& other) noexcept = default;
Renderer::~Renderer() = default;

Result<Frame> Renderer::render(const Camera& camera, double seconds) {
    Frame frame;
    if (Result<bool> rendered = impl_->render(camera, seconds, frame, {}); !rendered) return rendered.error();
    return frame;
}
Result<bool> Renderer::render(const Camera& camera, double seconds, Frame& frame) {
    return impl_->render(camera, seconds, frame, {});
}
Result<bool> Renderer::render(const Camera& camera, double seconds, Frame& frame, ReadBack readBack) {
    return impl_->render(camera, seconds, frame, readBack);
}
void Renderer::setNextFrame(const Camera& camera, double seconds) {
    if (traitsOf(impl_->settings.cull).ahead) impl_->nextFrame.emplace(camera, seconds);
}

Result<bool> Renderer::setTransform(int node, const glm::mat4& transform) {
    Result<bool> set = impl_->scene->setTransform(node, transform);
    if (set) {
        impl_->moved = true;
        impl_->stillBounds.reset();
    }
    return set;
}
void Renderer::releaseThread() { impl_->backend->releaseThread(); }
const Scene& Renderer::scene() const { return *impl_->scene; }
const Settings& Renderer::settings() const { return impl_->settings; }
std::string Renderer::backendName() const { return impl_->backend->name(); }
std::string Renderer::backendRenderer() const { return impl_->backend->renderer(); }
const std::vector<std::string>& Renderer::backendLog() const { return impl_->stage->log(); }
std::optional<Renderer::CullPreparation> Renderer::cullPreparation() const { return impl_->cullPreparation; }
std::optional<Renderer::EnvironmentPreparation> Renderer::environmentPreparation() const {
    if (impl_->settings.environmentMap.empty()) return std::nullopt;
    const Result<std::shared_ptr<const EnvironmentMap>> map = loadEnvironmentMap(impl_->settings.environmentMap);
    if (!map) return std::nullopt;  // (the renderer opened with it: loaded and kept)
    return EnvironmentPreparation{(*map)->sourceWidth, (*map)->sourceHeight, (*map)->prefilterMs};
}
std::optional<StateCosts> Renderer::stateCosts() const { return impl_->orderCosts->report(); }
std::uint64_t Renderer::staticPairBytes() const {
    return impl_->reuse ? std::uint64_t(impl_->settings.width) * std::uint64_t(impl_->settings.height) *
                              targetBytesPerPixel(impl_->settings.linear)
                        : 0;
}
std::uint64_t Renderer::extraBytes() const {
    return staticPairBytes() + (impl_->cullPreparation ? impl_->cullPreparation->bytes : 0) +
           (impl_->culler ? impl_->culler->occlusion().bytes() : 0) + (impl_->planner ? impl_->planner->bytes() : 0);
}

}  // namespace frugal
