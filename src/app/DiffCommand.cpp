// `frugal diff SCENE`: the same frames rendered on a GL backend and on the software reference,
// compared colour, ids and depth (report/ImageCompare.h). The GL image is the "actual", the
// software image the "reference".
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "app/HsrSupport.h"
#include "io/ImageIO.h"
#include "io/Interrupt.h"
#include "render/SceneRenderer.h"
#include "renderer/Backends.h"
#include "renderer/StateOrder.h"
#include "renderer/StatsJson.h"
#include "report/ImageCompare.h"

namespace frugal {

namespace {

// The software backend follows llvmpipe's rasterization rules (src/software/Rasterizer.h). On
// Mesa 22.3.6 llvmpipe it matches bit for bit (colour, ids and depth): builtin:default, 30 frames of
// builtin:cubes, the bunny at 800x600 and every renderable glTF file of assimp-testmodels all have a
// largest channel difference of 0. The default still allows 2 steps, because the shading is the same
// formula in GLSL and in C++, and other GL implementations (a GPU's EGL device, other Mesa versions)
// may round a float differently; pass --tolerance 0 to demand exactness.
constexpr int kDefaultTolerance = 2;

constexpr const char* kDefaultFailureDir = "frugal-diff";

}  // namespace

const char* diffHelp() {
    return R"(usage: frugal diff [SCENE] [options] [--tolerance N] [--out DIR] [--json FILE]

Renders SCENE (default builtin:default) on a GL backend (--backend, default auto) and on the
software reference, and compares them frame by frame: colour (the verdict), coverage, triangle ids
and depth. Prints a summary per frame; exit status 0 when every frame is within tolerance, 1 when
one is not.
)";
}

int runDiff(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    CompareOptions compare;
    compare.tolerance = kDefaultTolerance;
    std::string outDir, jsonPath;
    hsr::Mode hsrMode = hsr::Mode::ZBuffer;
    Order drawOrder = Order::Submit;
    CommandLine command{"diff", diffHelp(), &options};
    command.flags = {{"", {
        flag::whole("--tolerance", "N", "per-channel tolerance in 8-bit steps, 0 to 255 (default 2); a pixel fails "
                    "when any channel, alpha included, differs by more", compare.tolerance, 0, 255),
        flag::text("--out", "DIR", "write actual (GL), reference (software) and mask PNGs of every frame to DIR "
                   "(default: only frames that fail, into ./frugal-diff/). Names: actual.png, reference.png, "
                   "mask.png; with --frames actual_0003.png, ... The mask is red where a pixel fails, the reference "
                   "in grey elsewhere", outDir, "a folder name"),
        flag::text("--json", "FILE", "per-frame metrics as JSON", jsonPath),
        hsrFlag(hsrMode, "both backends draw the frame in this hidden-surface mode: zbuffer (default), depthsort or "
                         "adaptive (see 'frugal help render')"),
        orderFlag(drawOrder, "both backends draw in this order: submit (default), key, paper, greedy or best (see "
                             "'frugal help render'); consecutive draws of one mesh are one instanced draw on GL"),
    }}};
    command.positional = sceneArgument(options);
    command.finish = [&options](ArgCursor& cursor) {
        if (options.backend == BackendKind::Software)
            cursor.fail("--backend software: diff compares a GL backend with the software reference; choose auto, egl, "
                        "egl-device, egl-surfaceless or osmesa");
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;
    compare.background = colorBytes(options.background);

    Result<Scene> loaded = loadForRender(options, err);
    if (!loaded) {
        err << "error: " << loaded.error() << "\n";
        return kExitError;
    }
    const Scene& scene = *loaded;
    const FrameRange range = options.frames.value_or(FrameRange{});
    std::optional<hsr::Planner> planner;  // --hsr: both backends draw the same plan
    if (hsrMode != hsr::Mode::ZBuffer) planner.emplace(scene);

    // The GL backend under test, then the software reference.
    Session sessions[2];
    const BackendKind selections[2] = {options.backend, BackendKind::Software};
    const std::string labels[2] = {std::string("--backend ") + toString(options.backend), "software reference"};
    for (int k = 0; k < 2; ++k) {
        Result<Session> opened = openSession(selections[k], options);
        if (!opened) {
            err << "error: " << labels[k] << ": " << opened.error() << "\n";
            return kExitNoBackend;
        }
        sessions[k] = std::move(*opened);
    }
    Backend* backends[2] = {sessions[0].backend.get(), sessions[1].backend.get()};
    if (!options.quiet) {
        err << "backend: " << backends[0]->name() << " (" << backends[0]->renderer() << ")\n";
        err << "reference: " << backends[1]->name() << " (" << backends[1]->renderer() << ")\n";
    }
    for (Session& session : sessions)
        if (int prepared = prepareSession(session, options, scene, err); prepared != kExitOk) return prepared;
    const TargetHandle targets[2] = {sessions[0].target, sessions[1].target};
    // paper, greedy and best order by the GL backend's measured costs; both backends draw that list.
    Result<OrderCosts> orderCosts = startOrderCosts(drawOrder, *sessions[0].backend, 0, err, options.quiet);
    if (!orderCosts) {
        err << "error: --order " << toString(drawOrder) << ": " << orderCosts.error() << "\n";
        return kExitError;
    }
    SceneRenderer* renderers[2] = {&*sessions[0].renderer, &*sessions[1].renderer};
    const std::vector<std::string>& log = sessions[0].log;

    const std::string actualName = backends[0]->name(), referenceName = backends[1]->name();
    const bool writeAll = !outDir.empty();
    const std::string imageDir = writeAll ? outDir : kDefaultFailureDir;
    nlohmann::ordered_json frames = nlohmann::ordered_json::array();
    int failedFrames = 0;
    // SIGINT, SIGTERM and SIGHUP stop between frames: the images written stay (io/Interrupt.h).
    InterruptPoints interrupts;
    for (int frame = range.first; frame <= range.last; ++frame) {
        if (const int caught = interrupts.arrived()) {
            err << "error: " << interruptedAfter(caught, frame - range.first, range.last - range.first + 1) << "\n";
            return kExitError;
        }
        Result<FrameSetup> setup = setUpFrame(options, scene, frame, true);
        if (!setup) {
            err << "error: " << setup.error() << "\n";
            return kExitError;
        }
        const double time = setup->time;
        Buffers images[2];
        const DrawList ordered = orderFrameDraws(scene, renderers[0]->fullList(), drawOrder, orderCosts->costsUs());
        const DrawList list =
            planner ? planner->plan(hsrMode, setup->params, setup->world, ordered, options.width, options.height) : ordered;
        for (int k = 0; k < 2; ++k) {
            renderers[k]->renderFrame(targets[k], options.width, options.height, setup->params, setup->world,
                                      options.background, list);
            images[k] = backends[k]->readBack(targets[k]);
        }
        Result<ImageComparison> compared = compareBuffers(images[0], images[1], compare);
        if (!compared) {  // both targets were created at the same size: a backend broke its contract
            err << "error: frame " << frame << ": " << compared.error() << "\n";
            return kExitError;
        }
        const ImageComparison& c = *compared;
        if (!c.passed()) ++failedFrames;

        nlohmann::ordered_json files = nullptr;
        if (writeAll || !c.passed()) {
            std::error_code ec;
            std::filesystem::create_directories(imageDir, ec);
            if (ec) {
                err << "error: " << imageDir << ": cannot create the folder: " << ec.message() << "\n";
                return kExitError;
            }
            char suffix[32] = "";
            if (range.sequence) std::snprintf(suffix, sizeof suffix, "_%04d", frame);
            const std::filesystem::path dir(imageDir);
            const std::string names[3] = {(dir / ("actual" + std::string(suffix) + ".png")).string(),
                                          (dir / ("reference" + std::string(suffix) + ".png")).string(),
                                          (dir / ("mask" + std::string(suffix) + ".png")).string()};
            OutputSet set;
            set.add(names[0], encodeColorPng(images[0]));
            set.add(names[1], encodeColorPng(images[1]));
            set.add(names[2], encodeMaskPng(c));
            Result<bool> written = set.commit();
            if (!written) {
                err << "error: " << written.error() << "\n";
                return kExitError;
            }
            files = {{"actual", names[0]}, {"reference", names[1]}, {"mask", names[2]}};
        }

        out << "frame " << frame << " (t=" << fmt(time) << " s): " << (c.passed() ? "PASS" : "FAIL") << ", "
            << actualName << " vs " << referenceName << ", " << c.width << "x" << c.height << "\n"
            << comparisonSummary(c, actualName, referenceName);
        if (!files.is_null())
            out << "  wrote " << files["actual"].get<std::string>() << ", " << files["reference"].get<std::string>()
                << ", " << files["mask"].get<std::string>() << "\n";

        nlohmann::ordered_json entry = {{"frame", frame}, {"time", time}};
        entry.update(nlohmann::ordered_json::parse(comparisonJson(c)));
        entry["files"] = files;
        frames.push_back(std::move(entry));
    }

    const int frameCount = range.last - range.first + 1;
    out << "diff " << options.scene << ": " << (frameCount - failedFrames) << " of " << frameCount
        << (frameCount == 1 ? " frame" : " frames") << " within tolerance " << compare.tolerance << "\n";

    if (!jsonPath.empty()) {
        const nlohmann::ordered_json report = {
            {"command", "diff"},
            {"scene", options.scene},
            {"size", {options.width, options.height}},
            {"tolerance", compare.tolerance},
            {"hsr", toString(hsrMode)},
            {"draw_order", toString(drawOrder)},
            {"passed", failedFrames == 0},
            {"failed_frames", failedFrames},
            {"actual", {{"backend", actualName}, {"renderer", backends[0]->renderer()}, {"backend_log", log}}},
            {"reference", {{"backend", referenceName}, {"renderer", backends[1]->renderer()}}},
            {"frames", frames},
        };
        const std::string text = report.dump(2) + "\n";
        Result<bool> written = writeFileAtomic(jsonPath, Bytes(text.begin(), text.end()));
        if (!written) {
            err << "error: " << written.error() << "\n";
            return kExitError;
        }
    }
    return failedFrames == 0 ? kExitOk : kExitError;
}

}  // namespace frugal
