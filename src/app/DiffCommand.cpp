// `frugal diff SCENE`: the same frames rendered on a GL backend and on the software reference,
// compared colour, ids and depth (lab/ImageCompare.h). The GL image is the "actual", the
// software image the "reference".
#include <array>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <system_error>

#include <nlohmann/json.hpp>

#include <frugal/Files.h>
#include <frugal/Interrupt.h>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "lab/BackendPair.h"
#include "lab/ImageCompare.h"

namespace frugal {

namespace {

// The software backend follows llvmpipe's rasterization rules (src/raster/Rasterizer.h). On
// Mesa 22.3.6 llvmpipe it matches bit for bit (colour, ids and depth): builtin:default, 30 frames of
// builtin:cubes, the bunny at 800x600 and every renderable glTF file of assimp-testmodels all have a
// largest channel difference of 0. The default still allows 2 steps, because the shading is the same
// formula in GLSL and in C++, and other GL implementations (a GPU's EGL device, other Mesa versions)
// may round a float differently; pass --tolerance 0 to demand exactness.
constexpr int kDefaultTolerance = 2;

constexpr const char* kDefaultFailureDir = "frugal-diff";

// actual, reference and mask PNGs of `frame` into `imageDir` (made when missing), all or none;
// gives their names as the JSON's "files".
Result<nlohmann::ordered_json> writeFrameImages(const std::string& imageDir, const FrameRange& range, int frame,
                                                const std::array<Buffers, 2>& images, const ImageComparison& c) {
    std::error_code ec;
    std::filesystem::create_directories(imageDir, ec);
    if (ec) return Error{imageDir + ": cannot create the folder: " + ec.message(), ErrorKind::Io};
    char suffix[32] = "";
    if (range.sequence) std::snprintf(suffix, sizeof suffix, "_%04d", frame);
    const std::filesystem::path dir(imageDir);
    const std::string names[3] = {(dir / ("actual" + std::string(suffix) + ".png")).string(),
                                  (dir / ("reference" + std::string(suffix) + ".png")).string(),
                                  (dir / ("mask" + std::string(suffix) + ".png")).string()};
    FileSet set;
    set.add(names[0], encodeColorPng(images[0]));
    set.add(names[1], encodeColorPng(images[1]));
    set.add(names[2], encodeMaskPng(c));
    if (Result<bool> written = set.commit(); !written) return written.error();
    return nlohmann::ordered_json{{"actual", names[0]}, {"reference", names[1]}, {"mask", names[2]}};
}

// "frame 3 (t=0.1 s): PASS, egl-surfaceless vs software, 320x240", the comparison's lines, and the
// files written.
std::string frameSummary(const BackendPair& pair, int frame, double time, const ImageComparison& c,
                         const nlohmann::ordered_json& files) {
    const std::string actual = pair.actual().backend().name(), reference = pair.reference().backend().name();
    std::string text = "frame " + std::to_string(frame) + " (t=" + fmt(time) + " s): " + (c.passed() ? "PASS" : "FAIL") +
                       ", " + actual + " vs " + reference + ", " + std::to_string(c.width) + "x" +
                       std::to_string(c.height) + "\n" + comparisonSummary(c, actual, reference);
    if (!files.is_null())
        text += "  wrote " + files["actual"].get<std::string>() + ", " + files["reference"].get<std::string>() + ", " +
                files["mask"].get<std::string>() + "\n";
    return text;
}

// The --json document: the settings, the verdict, both backends and the frames' records.
std::string diffJson(const RenderOptions& options, const Settings& settings, int tolerance, int failedFrames,
                     const BackendPair& pair, const nlohmann::ordered_json& frames) {
    const nlohmann::ordered_json report = {
        {"command", "diff"},
        {"scene", options.scene},
        {"size", {options.settings.width, options.settings.height}},
        {"tolerance", tolerance},
        {"hsr", toString(settings.hsr)},
        {"draw_order", toString(settings.order)},
        {"passed", failedFrames == 0},
        {"failed_frames", failedFrames},
        {"actual",
         {{"backend", pair.actual().backend().name()},
          {"renderer", pair.actual().backend().renderer()},
          {"backend_log", pair.actual().log()}}},
        {"reference",
         {{"backend", pair.reference().backend().name()}, {"renderer", pair.reference().backend().renderer()}}},
        {"frames", frames},
    };
    return report.dump(2) + "\n";
}

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
    CommandLine command{"diff", diffHelp(), &options};
    command.flags = {{"", {
        flag::whole("--tolerance", "N", "per-channel tolerance in 8-bit steps, 0 to 255 (default 2); a pixel fails "
                    "when any channel, alpha included, differs by more", compare.tolerance, 0, 255),
        flag::text("--out", "DIR", "write actual (GL), reference (software) and mask PNGs of every frame to DIR "
                   "(default: only frames that fail, into ./frugal-diff/). Names: actual.png, reference.png, "
                   "mask.png; with --frames actual_0003.png, ... The mask is red where a pixel fails, the reference "
                   "in grey elsewhere", outDir, "a folder name"),
        flag::text("--json", "FILE", "per-frame metrics as JSON", jsonPath),
        settingFlag("hsr", options.settings, options.given,
                    "both backends draw the frame in this hidden-surface mode (see 'frugal help render')"),
        settingFlag("order", options.settings, options.given,
                    "both backends draw in this order (see 'frugal help render'); consecutive draws of one mesh are "
                    "one instanced draw on GL"),
    }}};
    command.positional = sceneArgument(options);
    command.finish = [&options](ArgCursor& cursor) {
        if (options.settings.backend == BackendKind::Software)
            cursor.fail("--backend software: diff compares a GL backend with the software reference; choose auto, egl, "
                        "egl-device, egl-surfaceless or osmesa");
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;
    compare.background = colorBytes(options.settings.background);

    Result<Scene> loaded = loadForRender(options, err);
    if (!loaded) return fail(err, loaded.error());
    const Settings& settings = options.settings;
    Result<BackendPair> pair = BackendPair::open(*loaded, settings, progressTo(err, options.quiet));
    if (!pair) return fail(err, pair.error());

    const FrameRange range = options.frames.value_or(FrameRange{});
    const std::string imageDir = outDir.empty() ? kDefaultFailureDir : outDir;
    nlohmann::ordered_json frames = nlohmann::ordered_json::array();
    int failedFrames = 0;
    // SIGINT, SIGTERM and SIGHUP stop between frames: the images written stay (io/Interrupt.h).
    InterruptPoints interrupts;
    for (int frame = range.first; frame <= range.last; ++frame) {
        if (const int caught = interrupts.arrived())
            return fail(err, Error{interruptedAfter(caught, frame - range.first, range.last - range.first + 1),
                                   ErrorKind::Interrupted});
        Result<FrameSetup> setup = frameSetups(options, *loaded, true)(frame);
        if (!setup) return fail(err, setup.error());
        const std::array<Buffers, 2> images = pair->render(*setup);
        Result<ImageComparison> compared = compareBuffers(images[0], images[1], compare);
        if (!compared)  // both targets were created at the same size: a backend broke its contract
            return fail(err, Error{"frame " + std::to_string(frame) + ": " + compared.error().message});
        const ImageComparison& c = *compared;
        if (!c.passed()) ++failedFrames;
        nlohmann::ordered_json files = nullptr;
        if (!outDir.empty() || !c.passed()) {
            Result<nlohmann::ordered_json> written = writeFrameImages(imageDir, range, frame, images, c);
            if (!written) return fail(err, written.error());
            files = std::move(*written);
        }
        out << frameSummary(*pair, frame, setup->time, c, files);
        nlohmann::ordered_json entry = {{"frame", frame}, {"time", setup->time}};
        entry.update(nlohmann::ordered_json::parse(comparisonJson(c)));
        entry["files"] = files;
        frames.push_back(std::move(entry));
    }

    const int frameCount = range.last - range.first + 1;
    out << "diff " << options.scene << ": " << (frameCount - failedFrames) << " of " << frameCount
        << (frameCount == 1 ? " frame" : " frames") << " within tolerance " << compare.tolerance << "\n";
    if (!jsonPath.empty()) {
        const std::string text = diffJson(options, settings, compare.tolerance, failedFrames, *pair, frames);
        if (Result<bool> written = writeFile(jsonPath, text); !written)
            return fail(err, written.error());
    }
    return failedFrames == 0 ? kExitOk : kExitError;
}

}  // namespace frugal
