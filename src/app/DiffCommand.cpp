// `frugal diff SCENE`: the same frames rendered on a GL backend and on the software reference,
// compared colour, ids and depth (report/ImageCompare.h). The GL image is the "actual", the
// software image the "reference".
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "app/Backends.h"
#include "app/Cli.h"
#include "app/Commands.h"
#include "app/Options.h"
#include "render/ImageIO.h"
#include "render/SceneRenderer.h"
#include "report/ImageCompare.h"

namespace frugal {

namespace {

// The software backend follows llvmpipe's rasterization rules (../shared/LLVMPIPE-RULES.md). On
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

  --tolerance N         per-channel tolerance in 8-bit steps, 0 to 255 (default 2); a pixel fails
                        when any channel, alpha included, differs by more
  --out DIR             write actual (GL), reference (software) and mask PNGs of every frame to DIR
                        (default: only frames that fail, into ./frugal-diff/). Names: actual.png,
                        reference.png, mask.png; with --frames actual_0003.png, ...
                        The mask is red where a pixel fails, the reference in grey elsewhere
  --json FILE           per-frame metrics as JSON
)";
}

int runDiff(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    RenderOptions options;
    CompareOptions compare;
    compare.tolerance = kDefaultTolerance;
    std::string outDir, jsonPath;
    bool sceneGiven = false;
    ArgCursor cursor(args);
    while (!cursor.done() && cursor.error.empty()) {
        const std::string flag = cursor.next();
        if (flag == "-h" || flag == "--help") {
            out << diffHelp() << sharedOptionsHelp();
            return kExitOk;
        }
        if (parseSharedOption(flag, cursor, options)) continue;
        if (flag == "--tolerance") {
            if (std::optional<int> n = wholeNumber(flag, cursor, 0, 255)) compare.tolerance = *n;
        } else if (flag == "--out" || flag == "--json") {
            const std::optional<std::string> path = cursor.value(flag);
            if (!path) break;
            if (path->empty()) cursor.fail(flag + ": empty " + (flag == "--out" ? "folder" : "file") + " name");
            else (flag == "--out" ? outDir : jsonPath) = *path;
        } else if (!flag.empty() && flag[0] == '-') {
            cursor.fail(flag + ": unknown option (see 'frugal help diff')");
        } else if (!sceneGiven) {
            options.scene = flag;
            sceneGiven = true;
        } else {
            cursor.fail("unexpected argument '" + flag + "' (one SCENE only)");
        }
    }
    if (cursor.error.empty() && options.backend.software)
        cursor.fail("--backend software: diff compares a GL backend with the software reference; choose auto, egl, "
                    "egl-device, egl-surfaceless or osmesa");
    if (!cursor.error.empty()) {
        err << "error: " << cursor.error << "\n";
        return kExitUsage;
    }
    compare.background = colorBytes(options.background);

    Result<Scene> loaded = loadForRender(options, err);
    if (!loaded) {
        err << "error: " << loaded.error() << "\n";
        return kExitError;
    }
    const Scene& scene = *loaded;
    const FrameRange range = options.frames.value_or(FrameRange{});

    std::vector<std::string> log;
    Result<std::unique_ptr<Backend>> gl = openBackend(options.backend, &log, options.threads);
    if (!gl) {
        err << "error: --backend " << options.backendName << ": " << gl.error() << "\n";
        return kExitNoBackend;
    }
    Result<std::unique_ptr<Backend>> software = openBackend(BackendSelection{true, BackendChoice::Auto}, nullptr, options.threads);
    if (!software) {
        err << "error: software reference: " << software.error() << "\n";
        return kExitNoBackend;
    }
    Backend* backends[2] = {gl->get(), software->get()};
    if (!options.quiet) {
        err << "backend: " << backends[0]->name() << " (" << backends[0]->renderer() << ")\n";
        err << "reference: " << backends[1]->name() << " (" << backends[1]->renderer() << ")\n";
    }
    TargetHandle targets[2] = {kNoHandle, kNoHandle};
    for (int k = 0; k < 2; ++k) {
        targets[k] = createTargetOrReport(*backends[k], options, err);
        if (targets[k] == kNoHandle) return kExitError;
    }
    SceneRenderer glRenderer(*backends[0], scene);
    SceneRenderer softwareRenderer(*backends[1], scene);
    SceneRenderer* renderers[2] = {&glRenderer, &softwareRenderer};

    const std::string actualName = backends[0]->name(), referenceName = backends[1]->name();
    const bool writeAll = !outDir.empty();
    const std::string imageDir = writeAll ? outDir : kDefaultFailureDir;
    nlohmann::ordered_json frames = nlohmann::ordered_json::array();
    int failedFrames = 0;
    for (int frame = range.first; frame <= range.last; ++frame) {
        Result<FrameSetup> setup = setUpFrame(options, scene, frame, true);
        if (!setup) {
            err << "error: " << setup.error() << "\n";
            return kExitError;
        }
        const double time = setup->time;
        Buffers images[2];
        for (int k = 0; k < 2; ++k) {
            renderers[k]->renderFrame(targets[k], options.width, options.height, setup->params, setup->world,
                                      options.background);
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
