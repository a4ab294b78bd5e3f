#include <chrono>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <regex>

#include <nlohmann/json.hpp>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "app/CullSupport.h"
#include "app/HsrSupport.h"
#include "app/OrderSupport.h"
#include "app/ReuseSupport.h"
#include "io/ImageIO.h"
#include "io/Interrupt.h"
#include "render/SceneRenderer.h"
#include "software/SoftwareBackend.h"

namespace frugal {

const char* renderHelp() {
    static const std::string text =
        std::string(
            R"(usage: frugal render [SCENE] [-o FILE.png] [options]

Renders SCENE (default builtin:default) offscreen and writes the colour image.

outputs (each written to a temporary file and renamed, never left half-written):
  -o, --output FILE     colour PNG (default frame.png). With --frames, FILE may hold a printf
                        number such as out_%04d.png; otherwise _%04d is put before the extension
  --depth FILE          depth: .png = 16-bit grey, 0 near, 65535 far (d24: the top 16 of its 24
                        bits), with the format and planes in its text chunks; .pfm = float32
                        window z, exact (d32f: reversed, 1 near, 0 far)
  --ids FILE            triangle ids: PNG whose RGBA bytes are the 32-bit id, little-endian
                        (R = low byte); 0 = background
  --json FILE           metadata: scene counts, camera (the planes drawn with and the given ones,
                        the aspect ratios, the depth format), backend, GL renderer, per-frame timings
                        (with --cull: per-frame tos, pvs and cull_ms too), and per frame the
                        state changes the backend issued, by kind ("state_changes": draws,
                        programs, meshes, textures, toggles, uniforms; software: draws only)

culling (only the triangles that may be visible are submitted; src/cull/Culling.h):
  --cull METHOD         none (default), sphere, backface, cones, paper, conservative or oracle.
                        conservative never drops a triangle that owns a pixel; paper reproduces
                        paper 002 and misses some; oracle draws exactly the visible set found by an
                        id pass (a lower bound, not a shortcut). See 'frugal cull-report'.
)"
            "  --cull-bins TxP       bins of the spherical barycenter map: T polar by P azimuthal (default 16x32)\n"
            R"(
  --order ORDER         the draw order: submit (default), key (texture, program, mesh, as bgfx
                        sorts), or by state-change costs measured on the backend at start (about
                        a second; see 'frugal info --state-costs'): paper (paper 004's id sort over
                        the 3 costliest kinds), greedy (cheapest next change) or best (the optimum
                        over the distinct state sets, Held-Karp up to 16, else local search).
                        Consecutive draws of one mesh go out as one instanced draw. Only pixels
                        where two surfaces tie exactly in depth can change (first drawn wins)
  --refine-costs N      with paper, greedy or best: every N frames of a sequence, one more round
                        of the cost measurement between two frames (a few ms), averaged with the
                        last 32 rounds, so the order follows the backend (default 10; 0 = never)
  --reuse               temporal reuse: with the camera still, copy what static instances render
                        from a static pair (one more target) and redraw only what changed; the
                        images are the same, byte for byte. The JSON gets per-frame state counts.
)") + reuseOptionsHelp() +
        "\n" + hsrOptionHelp();
    return text.c_str();
}

namespace {

struct Outputs {
    std::string color = "frame.png";
    std::string depth, ids, json;
};

bool hasExtension(const std::string& path, const std::string& ext) {
    std::string e = std::filesystem::path(path).extension().string();
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e == ext;
}

// The file name of frame `frame`: the pattern's single %d/%0Nd, or "_%04d" before the extension.
std::string framePath(const std::string& pattern, int frame, bool sequence) {
    if (!sequence) return pattern;
    char number[32];
    static const std::regex kSpec("%(0?[0-9]*)d");
    std::smatch match;
    if (std::regex_search(pattern, match, kSpec)) {
        const int width = match[1].length() ? std::stoi(match[1].str()) : 0;
        std::snprintf(number, sizeof number, "%0*d", width, frame);
        return match.prefix().str() + number + match.suffix().str();
    }
    std::snprintf(number, sizeof number, "_%04d", frame);
    const std::filesystem::path p(pattern);
    return (p.parent_path() / (p.stem().string() + number + p.extension().string())).string();
}

std::string checkPattern(const std::string& flag, const std::string& path) {
    const auto percents = std::count(path.begin(), path.end(), '%');
    static const std::regex kOnly("[^%]*%0?[0-9]*d[^%]*");
    if (percents > 1 || (percents == 1 && !std::regex_match(path, kOnly)))
        return flag + " " + path + ": at most one %d (or %0Nd) and no other % in a file name";
    return {};
}

nlohmann::json vec(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// One frame with temporal reuse: the plan, executed; its statistics as JSON.
nlohmann::json renderReused(TemporalReuse& reuse, SceneRenderer& renderer, TargetHandle target, TargetHandle staticTarget,
                            const FrameSetup& setup, const DrawList* list, const glm::vec4& background) {
    // Without a list: the whole scene.
    const FramePlan plan = list ? reuse.plan(setup.params, setup.world, *list, background)
                                : reuse.plan(setup.params, setup.world, background);
    renderer.execute(plan, target, staticTarget, setup.params, setup.world, background);
    return reuseStatsJson(reuse.stats());
}

}  // namespace

int runRender(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    Outputs outputs;
    CullOptions cull;
    ReuseCliOptions reuseOptions;
    hsr::Mode hsrMode = hsr::Mode::ZBuffer;
    DrawOrder drawOrder = DrawOrder::Submit;
    int refineCostsEvery = 10;
    CommandLine command{"render", renderHelp(), &options};
    command.option = [&outputs, &cull, &reuseOptions, &options, &hsrMode, &drawOrder, &refineCostsEvery](
                         const std::string& flag, ArgCursor& cursor) {
        if (parseCullOption(flag, cursor, cull, true)) return true;
        if (parseHsrOption(flag, cursor, hsrMode)) return true;
        if (parseDrawOrderOption(flag, cursor, drawOrder)) return true;
        if (flag == "--refine-costs") {
            if (const std::optional<int> every = wholeNumber(flag, cursor, 0, 1000000)) refineCostsEvery = *every;
            return true;
        }
        if (parseReuseOption(flag, cursor, reuseOptions, options, true)) return true;
        if (flag != "-o" && flag != "--output" && flag != "--depth" && flag != "--ids" && flag != "--json") return false;
        const std::optional<std::string> path = cursor.value(flag);
        if (!path) return true;
        if (path->empty()) cursor.fail(flag + ": empty file name");
        else if (flag == "--depth") outputs.depth = *path;
        else if (flag == "--ids") outputs.ids = *path;
        else if (flag == "--json") outputs.json = *path;
        else outputs.color = *path;
        return true;
    };
    command.positional = sceneArgument(options);
    command.finish = [&outputs, &options, &cull, &reuseOptions, &hsrMode](ArgCursor& cursor) {
        if (reuseOptions.enabled && cull.method == CullMethod::Oracle)
            cursor.fail("--reuse with --cull oracle: the oracle is an id pass of each frame, not a plan to reuse");
        else if (hsrMode != hsr::Mode::ZBuffer && reuseOptions.enabled)
            cursor.fail(std::string("--hsr ") + hsr::modeName(hsrMode) +
                        " with --reuse: reuse redraws what moved with the z-buffer over the static image; use one");
        else if (hsrMode != hsr::Mode::ZBuffer && cull.method == CullMethod::Oracle)
            cursor.fail(std::string("--hsr ") + hsr::modeName(hsrMode) +
                        " with --cull oracle: the oracle draws its own scene; use --cull with a method");
        else if (!hasExtension(outputs.color, ".png"))
            cursor.fail("-o " + outputs.color + ": the colour image is written as PNG; name it .png");
        else if (!outputs.depth.empty() && !hasExtension(outputs.depth, ".png") && !hasExtension(outputs.depth, ".pfm"))
            cursor.fail("--depth " + outputs.depth + ": name it .png (16-bit) or .pfm (float32)");
        else if (!outputs.ids.empty() && !hasExtension(outputs.ids, ".png"))
            cursor.fail("--ids " + outputs.ids + ": the id image is written as PNG; name it .png");
        else if (options.frames)
            for (const auto& [flag, path] : {std::pair{"-o", outputs.color}, {"--depth", outputs.depth}, {"--ids", outputs.ids}})
                if (!path.empty()) {
                    const std::string problem = checkPattern(flag, path);
                    if (!problem.empty()) cursor.fail(problem);
                }
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;

    Result<Scene> loaded = loadForRender(options, err);
    if (!loaded) {
        err << "error: " << loaded.error() << "\n";
        return kExitError;
    }
    Scene& scene = *loaded;
    const CullMethod method = cull.method.value_or(CullMethod::None);
    std::optional<SceneCuller> culler = prepareCullOption(scene, cull, err, options.quiet);  // before the upload

    const FrameRange range = options.frames.value_or(FrameRange{});
    std::optional<hsr::Planner> planner;
    if (hsrMode != hsr::Mode::ZBuffer) planner.emplace(scene);

    std::variant<Session, int> started = startSession(options, scene, err);
    if (const int* status = std::get_if<int>(&started)) return *status;
    Session& session = std::get<Session>(started);
    Backend& backend = *session.backend;
    SceneRenderer& renderer = *session.renderer;
    const TargetHandle target = session.target;
    const std::vector<std::string>& log = session.log;

    // paper, greedy and best order by costs measured on this backend, refined between frames.
    Result<OrderCosts> orderCosts = OrderCosts::start(drawOrder, backend, refineCostsEvery, err, options.quiet);
    if (!orderCosts) {
        err << "error: --order " << drawOrderName(drawOrder) << ": " << orderCosts.error() << "\n";
        return kExitError;
    }

    // Temporal reuse: the static pair is one more target of the same size.
    TargetHandle staticTarget = kNoHandle;
    std::optional<TemporalReuse> reuse;
    if (reuseOptions.enabled) {
        // The pair (a target's bytes; measured 11.8 a pixel at 8192x8192) and what a frame still
        // allocates after its target (the read-back and the PNG encoding): the first frame comes after it.
        const std::uint64_t pixels = std::uint64_t(options.width) * std::uint64_t(options.height);
        const std::uint64_t needed =
            staticPairBytes(options.width, options.height) + pixels * (kFrameBytesPerPixel - kTargetBytesPerPixel);
        if (const std::optional<std::string> problem = memoryProblem(needed)) {
            err << "error: --reuse: " << options.width << "x" << options.height << " needs about " << gigabytes(needed)
                << " more (a static pair of 12 bytes a pixel, then the frame's read-back and PNG encoding), "
                << *problem << "\n";
            return kExitError;
        }
        staticTarget = backend.createTarget(options.width, options.height, options.camera.depthFormat);
        if (staticTarget == kNoHandle) {
            err << "error: --reuse: " << backend.name() << " could not create the static pair (" << options.width << "x"
                << options.height << ", " << staticPairBytes(options.width, options.height) << " bytes)\n";
            return kExitError;
        }
        reuse.emplace(scene, options.width, options.height, reuseOptions.settings);
    }
    const ScopedTarget staticPair(backend, staticTarget);

    const int frameCount = range.last - range.first + 1;
    nlohmann::json frames = nlohmann::json::array();
    InterpStats interpSeen;  // --interp: the software backend's counters after the previous frame
    nlohmann::json cameraJson;
    using Clock = std::chrono::steady_clock;
    auto ms = [](Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); };

    // SIGINT, SIGTERM and SIGHUP stop the sequence between frames: the frames written stay, the
    // JSON is not written (io/Interrupt.h).
    InterruptPoints interrupts;
    for (int frame = range.first; frame <= range.last; ++frame) {
        if (const int caught = interrupts.arrived()) {
            err << "error: " << interruptedAfter(caught, frame - range.first, frameCount) << "\n";
            return kExitError;
        }
        Result<FrameSetup> setup = setUpFrame(options, scene, frame, !outputs.ids.empty());
        if (!setup) {
            err << "error: " << setup.error() << "\n";
            return kExitError;
        }
        const double time = setup->time;
        const View& view = setup->view;

        nlohmann::json cullJson, reuseJson, hsrFrameJson;
        const StateChanges changesBefore = backend.stateChanges();
        // The frame's list as drawn: in the --hsr mode's order and depth modes (the plan is timed).
        const auto drawList = [&](const DrawList& submitted) {
            const DrawList list = orderFrameDraws(scene, submitted, drawOrder, orderCosts->costsUs());
            if (!planner) {
                renderer.renderFrame(target, options.width, options.height, setup->params, setup->world,
                                     options.background, list);
                return;
            }
            hsr::PlanStats stats;
            const DrawList planned =
                planner->plan(hsrMode, setup->params, setup->world, list, options.width, options.height, &stats);
            hsrFrameJson = hsrJson(hsrMode, stats);
            renderer.renderFrame(target, options.width, options.height, setup->params, setup->world,
                                 options.background, planned);
        };
        auto t0 = Clock::now();
        if (method == CullMethod::Oracle) {
            // The id pass and the oracle's own index buffers come before the clock starts.
            Result<Oracle> oracle = makeOracle(renderer, target, options.width, options.height, setup->params,
                                               setup->world, options.background);
            if (!oracle) {
                err << "error: " << options.scene << ": " << oracle.error() << "\n";
                return kExitError;
            }
            cullJson = {{"tos", scene.triangleCount()}, {"pvs", oracle->rvs.count}, {"cull_ms", oracle->ms}};
            t0 = Clock::now();
            oracle->renderer->renderFrame(target, options.width, options.height, setup->params, setup->world,
                                          options.background);
        } else if (culler) {
            const DrawList list = culler->cull(method, scene, setup->world, view);
            const double cullMs = ms(Clock::now() - t0);
            std::size_t ranges = 0;
            for (const DrawCommand& draw : list) ranges += draw.ranges.size();
            cullJson = {{"tos", scene.triangleCount()}, {"pvs", submittedTriangles(scene, list)}, {"cull_ms", cullMs},
                        {"ranges", ranges}};
            if (reuse)
                reuseJson = renderReused(*reuse, renderer, target, staticTarget, *setup, &list, options.background);
            else
                drawList(list);
        } else if (reuse) {
            reuseJson = renderReused(*reuse, renderer, target, staticTarget, *setup, nullptr, options.background);
        } else {
            drawList(renderer.fullList());
        }
        backend.finish();
        const auto t1 = Clock::now();
        const Buffers buffers = backend.readBack(target);
        const auto t2 = Clock::now();

        OutputSet files;
        const bool sequence = range.sequence;
        files.add(framePath(outputs.color, frame, sequence), encodeColorPng(buffers));
        if (!outputs.depth.empty())
            files.add(framePath(outputs.depth, frame, sequence),
                      hasExtension(outputs.depth, ".pfm")
                          ? encodeDepthPfm(buffers)
                          : encodeDepthPng(buffers, DepthInfo{view.znear, view.zfar, view.perspective}));
        if (!outputs.ids.empty()) files.add(framePath(outputs.ids, frame, sequence), encodeIdPng(buffers));
        Result<bool> written = files.commit();
        if (!written) {
            err << "error: " << written.error() << "\n";
            return kExitError;
        }
        const auto t3 = Clock::now();

        if (frame == range.first) {
            cameraJson = {{"source", view.source},
                          {"eye", vec(view.eye)},
                          {"forward", vec(view.forward)},
                          {"perspective", view.perspective},
                          {"yfov_degrees", glm::degrees(view.yfov)},
                          {"znear", view.znear},
                          {"zfar", view.zfar},
                          {"depth_range", depthRangeName(view.depthRange)},
                          {"given_znear", view.givenNear},
                          {"given_zfar", view.givenFar},
                          {"depth_format", depthFormatName(view.depthFormat)},
                          {"aspect_ratio", view.aspect},
                          {"file_aspect_ratio",
                           view.fileAspect > 0.0f ? nlohmann::json(view.fileAspect) : nlohmann::json(nullptr)},
                          {"aspect_ratio_differs", aspectDiffers(view.fileAspect, options.width, options.height)}};
        }
        frames.push_back({{"frame", frame}, {"time", time}, {"render_ms", ms(t1 - t0)}, {"readback_ms", ms(t2 - t1)},
                          {"write_ms", ms(t3 - t2)}, {"file", framePath(outputs.color, frame, sequence)}});
        if (!cullJson.is_null()) frames.back().update(cullJson);
        if (!reuseJson.is_null()) frames.back()["reuse"] = reuseJson;
        if (!hsrFrameJson.is_null()) frames.back()["hsr"] = hsrFrameJson;
        frames.back()["state_changes"] = stateChangesJson(backend.stateChanges() - changesBefore);
        if (options.interp != span::Interp::Exact)
            if (const std::optional<InterpStats> interp = softwareInterpStats(backend)) {
                // The backend's counters run from its start: per frame, the difference.
                frames.back()["interp"] = {{"mode", span::interpName(options.interp)},
                                           {"spans", interp->spans - interpSeen.spans},
                                           {"overflow", interp->overflow - interpSeen.overflow}};
                interpSeen = *interp;
            }
        // Between frames, outside every timing above: one more cost round when due; the frames after
        // this one are ordered by the refined costs.
        const auto refineStart = Clock::now();
        if (frame < range.last && orderCosts->refine(frame - range.first + 1)) {
            frames.back()["refined_state_costs_us"] = orderCosts->costsUs();
            frames.back()["refine_ms"] = ms(Clock::now() - refineStart);
        }
        if (!options.quiet) {
            err << "frame " << frame << " (" << (frame - range.first + 1) << "/" << frameCount << "): "
                << fmt(ms(t1 - t0)) << " ms";
            if (!cullJson.is_null())
                err << " (" << cullMethodName(method) << ": " << cullJson["pvs"].get<std::size_t>() << " of "
                    << scene.triangleCount() << " triangles)";
            if (!hsrFrameJson.is_null())
                err << " (" << hsr::modeName(hsrMode) << ": " << hsrFrameJson["zbuffered_polygons"].get<std::size_t>()
                    << " of " << hsrFrameJson["polygons"].get<std::size_t>() << " polygons depth-tested)";
            if (reuse) {
                const ReuseFrameStats& stats = reuse->stats();
                err << " (" << reuseModeName(stats.mode) << ": " << stats.redrawnTris << " of " << stats.drawnTris
                    << " triangles drawn";
                if (stats.mode == ReuseMode::Full) err << "; " << stats.reason;
                err << ")";
            }
            err << " -> " << framePath(outputs.color, frame, sequence) << "\n";
        }
    }

    if (interpSeen.overflow > 0)
        err << "warning: --interp " << span::interpName(options.interp) << ": " << interpSeen.overflow
            << " spans overflowed the 24-bit depth and were clamped (see the JSON's per-frame \"interp\")\n";
    if (!outputs.json.empty()) {
        nlohmann::json meta = {
            {"scene", options.scene},
            {"counts", {{"nodes", scene.nodes.size()}, {"meshes", scene.meshes.size()}, {"instances", scene.instances.size()},
                        {"triangles", scene.triangleCount()}, {"materials", scene.materials.size()},
                        {"textures", scene.textures.size()}, {"animations", scene.animations.size()}}},
            {"unsupported", scene.unsupported},
            {"size", {options.width, options.height}},
            {"backend", backend.name()},
            {"renderer", backend.renderer()},
            {"backend_log", log},
            {"camera", cameraJson},
            {"cull", cullMethodName(method)},
            {"hsr", hsr::modeName(hsrMode)},
            {"draw_order", drawOrderName(drawOrder)},
            {"state_costs", orderCosts->json()},
            {"reuse", reuse ? nlohmann::json{{"grain", reuseOptions.settings.grain}, {"cell", reuseOptions.settings.cell},
                                             {"fallback", reuseOptions.settings.fallback},
                                             {"static_pair_bytes", staticPairBytes(options.width, options.height)}}
                            : nlohmann::json(nullptr)},
            {"frames", frames},
        };
        const std::string text = meta.dump(2) + "\n";
        Result<bool> written = writeFileAtomic(outputs.json, Bytes(text.begin(), text.end()));
        if (!written) {
            err << "error: " << written.error() << "\n";
            return kExitError;
        }
    }
    if (!options.quiet && !range.sequence) out << "wrote " << outputs.color << "\n";
    return kExitOk;
}

}  // namespace frugal
