// `frugal span-bench`: the bit-level model of paper 001's shading engine (src/software/span/):
// Fig. 11 reproduced, the schemes it rules out, the error tables of midpoint subdivision, of the
// same tree truncating at each level, of a DDA and of double evaluation against the exact line, and
// the model's spans per second beside the paper's 59,000; with --scene, the software backend's
// --interp modes on whole scenes (how span and dda depart from exact, and the slow path's speed).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "app/Options.h"
#include "app/ReportOutputs.h"
#include "lab/ErrorTable.h"
#include "lab/Fig11.h"
#include "render/Frame.h"
#include "render/SceneRenderer.h"
#include "scene/Load.h"
#include "software/SoftwareBackend.h"

namespace frugal {

const char* spanBenchHelp() {
    return R"(usage: frugal span-bench [options]

The shading engine of paper 001 (Bang, Bae, Kyung 1990) modelled bit by bit: 64-pixel engines, the
L/R multipliers f(XL), f(XR), the midpoint-subdivision tree, the Edge Painting Tree, the LSB-first
z comparator. Prints Fig. 11 as the model computes it (and which rounding schemes contradict the
figure), then the error of each interpolator against the exact line, rounded to nearest:
  span        the paper's engine: ends rounded, exact subdivision, pixels rounded (<= 1 LSB)
  span_trunc  the same tree truncating at every level (PIPE's add-and-shift-right)
  dda         add-and-shift: the slope accumulated per pixel in a --dda-bits register
  exact       double evaluation, rounded
and the spans per second of the model on this machine beside the paper's one span per 17 us.
With --scene, also renders each scene's frame 0 on the software backend (one thread) with
--interp exact, span and dda, and reports how span and dda depart from the exact render and how
fast the slow path runs.
)";
}

namespace {

using namespace span;

struct SpeedRow {
    Method method;
    int length;
    double spansPerSecond;
};

// One scene rendered in one --interp mode, against the same scene in exact.
struct RenderRow {
    std::string scene;
    int width = 0, height = 0;
    span::Interp mode = span::Interp::Exact;
    std::size_t colourPx = 0;        // pixels whose colour differs from exact
    std::size_t idPx = 0;            // pixels another triangle won
    std::uint32_t worstLsb = 0;      // depth, over covered pixels (exact's ids not 0)
    double meanLsb = 0.0;            // depth, over covered pixels
    std::size_t depthChangedPx = 0;  // pixels whose depth differs, anywhere
    std::uint64_t overflow = 0;      // slow-path calls that overflowed, one frame
    std::uint64_t spans = 0;         // slow-path calls (fillSpan), one frame
    double frameMs = 0.0;            // best of kRenderRepeats
    double exactFrameMs = 0.0;
    double spansPerSecond = 0.0;     // spans / (frameMs / 1000)
};

constexpr int kRenderRepeats = 5;
constexpr int kMaxRenderSize = 16384;  // the software backend's largest target

struct Report {
    ErrorTableSettings settings;
    std::vector<Fig11Result> fig11;
    std::vector<ErrorRow> errors;
    std::optional<double> engineSpeed;
    std::vector<SpeedRow> speeds;
    std::vector<RenderRow> render;
};

// A loaded scene and its frame 0, ready to draw.
struct SceneCase {
    std::string spec;
    Scene scene;
    FrameSetup setup;
};

// Loads a --scene (OBJ single-sided) and sets up its frame 0; the error is "<scene>: <why>".
Result<SceneCase> loadSceneCase(const std::string& spec, int width, int height) {
    LoadOptions load;
    load.objDoubleSided = false;
    Result<Scene> scene = loadScene(spec, load);
    const auto named = [&spec](const std::string& why) {
        return why.rfind(spec + ":", 0) == 0 ? why : spec + ": " + why;
    };
    if (!scene) return Error{named(scene.error())};
    // The camera's own planes, not fitted to the scene (render/Camera.h): the engine's error grows
    // with the depth's slope across a span, which the fit makes steeper (builtin:cubes: worst 14 LSB
    // against 2), and this reports the engine as paper 001 measured it.
    Camera camera;
    camera.depthRange = DepthRange::File;
    Result<FrameSetup> setup = setUpFrame(*scene, camera, 0.0, width, height, true);
    if (!setup) return Error{named(setup.error())};
    return SceneCase{spec, std::move(*scene), std::move(*setup)};
}

struct ModeRender {
    Buffers image;
    double bestSeconds = 0.0;
    InterpStats frame;  // the slow path's counters of one frame
};

// kRenderRepeats frames of `c` in `mode` on a one-thread software backend: the last image, the best
// time (draw and rasterization: renderFrame and finish, not the readBack) and one frame's counters.
Result<ModeRender> renderMode(const SceneCase& c, span::Interp mode, int width, int height) {
    SoftwareOptions options;
    options.threads = 1;
    options.interp = mode;
    const std::unique_ptr<Backend> backend = makeSoftwareBackend(options);
    const TargetHandle target = backend->createTarget(width, height);
    if (target == kNoHandle)
        return Error{c.spec + ": the software backend cannot make a " + std::to_string(width) + "x" + std::to_string(height) + " target"};
    Result<SceneRenderer> renderer = SceneRenderer::create(*backend, c.scene);
    if (!renderer) return Error{c.spec + ": " + renderer.error()};
    const glm::vec4 background{0.12f, 0.13f, 0.15f, 1.0f};
    ModeRender out;
    out.bestSeconds = 1e30;
    for (int r = 0; r < kRenderRepeats; ++r) {
        const auto start = std::chrono::steady_clock::now();
        renderer->renderFrame(target, width, height, c.setup.params, c.setup.world, background);
        backend->finish();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        out.bestSeconds = std::min(out.bestSeconds, seconds);
        if (r == 0) {
            out.image = backend->readBack(target);
            out.frame = softwareInterpStats(*backend).value_or(InterpStats{});
        }
    }
    backend->destroyTarget(target);
    return out;
}

// How `other` departs from `exact` (the same scene and size).
void departure(const Buffers& exact, const Buffers& other, RenderRow& row) {
    std::uint64_t sum = 0;
    std::size_t covered = 0;
    for (std::size_t i = 0; i < exact.pixelCount(); ++i) {
        const std::uint32_t e = exact.depth[i] > other.depth[i] ? exact.depth[i] - other.depth[i] : other.depth[i] - exact.depth[i];
        row.depthChangedPx += e != 0;
        if (exact.ids[i] != 0) {
            row.worstLsb = std::max(row.worstLsb, e);
            sum += e;
            ++covered;
        }
        row.idPx += exact.ids[i] != other.ids[i];
        row.colourPx += !std::equal(exact.rgba.begin() + std::ptrdiff_t(4 * i), exact.rgba.begin() + std::ptrdiff_t(4 * i + 4),
                                    other.rgba.begin() + std::ptrdiff_t(4 * i));
    }
    row.meanLsb = covered > 0 ? double(sum) / double(covered) : 0.0;
}

// The three rows of one scene: exact, span, dda.
Result<std::vector<RenderRow>> renderScene(const SceneCase& c, int width, int height) {
    std::vector<RenderRow> rows;
    std::optional<ModeRender> exact;
    for (span::Interp mode : {span::Interp::Exact, span::Interp::Span, span::Interp::Dda}) {
        Result<ModeRender> done = renderMode(c, mode, width, height);
        if (!done) return Error{done.error()};
        if (mode == span::Interp::Exact) exact = std::move(*done);
        const ModeRender& m = mode == span::Interp::Exact ? *exact : *done;
        RenderRow row;
        row.scene = c.spec;
        row.width = width;
        row.height = height;
        row.mode = mode;
        departure(exact->image, m.image, row);
        row.overflow = m.frame.overflow;
        row.spans = m.frame.spans;
        row.frameMs = m.bestSeconds * 1e3;
        row.exactFrameMs = exact->bestSeconds * 1e3;
        row.spansPerSecond = m.bestSeconds > 0.0 ? double(row.spans) / m.bestSeconds : 0.0;
        rows.push_back(row);
    }
    return rows;
}

nlohmann::json channelJson(const Fig11Channel& ch) {
    nlohmann::json printed = nlohmann::json::array();
    for (const Fig11Printed& p : ch.printed) printed.push_back({{"x", p.x}, {"value", p.value}, {"doubtful", p.doubtful}});
    return {{"width", ch.width}, {"from", ch.from}, {"to", ch.to}, {"values", ch.values}, {"hex", fig11Hex(ch)},
            {"printed", printed}, {"mismatches", ch.mismatches}, {"doubtful_mismatches", ch.doubtfulMismatches}};
}

std::string reportJson(const Report& r) {
    nlohmann::json j;
    const Fig11Result& model = r.fig11.front();
    nlohmann::json channels;
    for (const Fig11Channel& ch : model.channels) channels[ch.name] = channelJson(ch);
    nlohmann::json schemes = nlohmann::json::array();
    for (const Fig11Result& s : r.fig11)
        schemes.push_back({{"scheme", s.scheme.name}, {"mismatches", s.mismatches}, {"z", fig11Hex(s.channels[0])},
                           {"blue", fig11Hex(s.channels[3])}});
    j["fig11"] = {{"engine", {0, 64}}, {"span", {kFig11Xl, kFig11Xr}}, {"scheme", model.scheme.name},
                  {"channels", channels}, {"mask", model.mask}, {"write_enable", model.writeEnable},
                  {"mismatches", model.mismatches}, {"schemes", schemes}};
    nlohmann::json errors = nlohmann::json::array();
    for (const ErrorRow& e : r.errors)
        errors.push_back({{"width", e.width}, {"length", e.length}, {"method", methodName(e.method)},
                          {"worst_lsb", e.worstLsb}, {"mean_lsb", e.meanLsb}, {"spans", e.spans}, {"pixels", e.pixels},
                          {"overflow_spans", e.overflowSpans}});
    j["errors"] = errors;
    j["settings"] = {{"lengths", r.settings.lengths}, {"widths", r.settings.widths}, {"spans", r.settings.spans},
                     {"seed", r.settings.seed}, {"dda_bits", r.settings.accumulatorBits}};
    nlohmann::json speed;
    speed["paper"] = kPaperSpansPerSecond;
    speed["note"] = "spans of z (24 bits) and R, G, B (16 bits); measured on this machine, never asserted";
    if (r.engineSpeed) {
        speed["engine_model"] = *r.engineSpeed;
        nlohmann::json fills = nlohmann::json::array();
        for (const SpeedRow& s : r.speeds)
            fills.push_back({{"method", methodName(s.method)}, {"length", s.length}, {"spans_per_second", s.spansPerSecond}});
        speed["fill_span"] = fills;
    } else {
        speed["engine_model"] = nullptr;
        speed["fill_span"] = nlohmann::json::array();
    }
    j["spans_per_second"] = speed;
    nlohmann::json render = nlohmann::json::array();
    for (const RenderRow& row : r.render)
        render.push_back({{"scene", row.scene},
                          {"size", {row.width, row.height}},
                          {"mode", toString(row.mode)},
                          {"colour_px", row.colourPx},
                          {"id_px", row.idPx},
                          {"worst_lsb", row.worstLsb},
                          {"mean_lsb", row.meanLsb},
                          {"depth_changed_px", row.depthChangedPx},
                          {"overflow", row.overflow},
                          {"spans", row.spans},
                          {"frame_ms", row.frameMs},
                          {"exact_frame_ms", row.exactFrameMs},
                          {"spans_per_second", row.spansPerSecond}});
    j["render"] = render;
    return j.dump(2) + "\n";
}

std::string reportCsv(const Report& r) {
    std::string text = "width,length,method,worst_lsb,mean_lsb,spans,pixels,overflow_spans\n";
    for (const ErrorRow& e : r.errors) {
        char line[160];
        std::snprintf(line, sizeof line, "%d,%d,%s,%lld,%.6f,%d,%lld,%d\n", e.width, e.length, methodName(e.method),
                      static_cast<long long>(e.worstLsb), e.meanLsb, e.spans, static_cast<long long>(e.pixels), e.overflowSpans);
        text += line;
    }
    return text;
}

std::string reportGnuplot(const Report& r, const std::string& csvPath, const std::string& svgPath) {
    std::string s;
    s += "# frugal span-bench: error of each interpolator against the exact line (LSB), by span length.\n";
    s += "set terminal svg size 960,420 dynamic enhanced\nset output '" + svgPath + "'\n";
    s += "set datafile separator ','\nset logscale x 2\nset xlabel 'span length (pixels)'\nset grid\n";
    s += "set key top left\nset multiplot layout 1,2\n";
    for (int panel = 0; panel < 2; ++panel) {
        const int column = panel == 0 ? 4 : 5;
        s += panel == 0 ? "set title 'worst error'\nset ylabel 'LSB'\nset logscale y 2\nset yrange [0.5:*]\n"
                        : "set title 'mean error'\nset ylabel 'LSB'\nunset logscale y\nset yrange [0:*]\n";
        s += "plot ";
        bool first = true;
        for (int width : r.settings.widths)
            for (Method m : r.settings.methods) {
                if (!first) s += ", \\\n     ";
                first = false;
                const std::string name = methodName(m);
                // Worst errors of 0 are drawn at 0.5 on the log axis, below the 1-LSB line.
                const std::string value = panel == 0 ? "($" + std::to_string(column) + " > 0 ? $" + std::to_string(column) + " : 0.5)"
                                                     : "$" + std::to_string(column);
                s += "'" + csvPath + "' every ::1 using 2:(($1 == " + std::to_string(width) + " && strcol(3) eq '" + name +
                     "') ? " + value + " : NaN) with linespoints title '" + name + " " + std::to_string(width) + "-bit'";
            }
        s += "\n";
    }
    s += "unset multiplot\n";
    return s;
}

void printFig11(std::ostream& out, const Report& r) {
    const Fig11Result& m = r.fig11.front();
    out << "Fig. 11 (section IV): engine (XL, XR) = (0, 64), span (Xl, Xr) = (2, 9), old z all ones\n";
    out << "  scheme: " << m.scheme.name << "\n";
    out << "  X       ";
    for (int x = kFig11Xl; x <= kFig11Xr; ++x) out << "  " << (x < 10 ? " " : "") << x << " ";
    out << "\n";
    for (const Fig11Channel& ch : m.channels) {
        char head[32];
        std::snprintf(head, sizeof head, "  %-7s", ch.name);
        out << head;
        for (std::int64_t v : ch.values) {
            char cell[16];
            std::snprintf(cell, sizeof cell, ch.width == 24 ? "  %03llX" : "  %3llX", static_cast<unsigned long long>(v));
            out << cell;
        }
        out << "   printed:";
        for (const Fig11Printed& p : ch.printed) {
            char cell[24];
            std::snprintf(cell, sizeof cell, ch.width == 24 ? " %03X" : " %X", unsigned(p.value));
            out << cell << (p.doubtful ? "?" : "");
        }
        out << "\n";
    }
    char masks[96];
    std::snprintf(masks, sizeof masks, "  EPT mask 0x%llX, write enable 0x%llX\n", static_cast<unsigned long long>(m.mask),
                  static_cast<unsigned long long>(m.writeEnable));
    out << masks;
    out << "  (? red at X = 3 reads 2 in the paper's text; a 0 -> 7 ramp over 7 pixels has 1 there)\n";
    out << "schemes tried (printed values missed, of 15; z and blue at X = 2..9):\n";
    for (const Fig11Result& s : r.fig11) {
        char line[256];
        std::snprintf(line, sizeof line, "  %2d  %-68s z %s  blue %s\n", s.mismatches, s.scheme.name.c_str(),
                      fig11Hex(s.channels[0]).c_str(), fig11Hex(s.channels[3]).c_str());
        out << line;
    }
}

void printErrors(std::ostream& out, const Report& r) {
    out << "\nerror against the exact line rounded to nearest (LSB): " << r.settings.spans << " spans per row, seed "
        << r.settings.seed << ", DDA register " << r.settings.accumulatorBits << " bits\n";
    out << "  width  length  method        worst     mean  overflow spans\n";
    for (const ErrorRow& e : r.errors) {
        char line[128];
        std::snprintf(line, sizeof line, "  %5d  %6d  %-10s  %8lld  %7.4f  %d\n", e.width, e.length, methodName(e.method),
                      static_cast<long long>(e.worstLsb), e.meanLsb, e.overflowSpans);
        out << line;
    }
}

void printSpeed(std::ostream& out, const Report& r) {
    out << "\nspans per second (a span: z 24 bits + R, G, B 16 bits):\n";
    char line[160];
    std::snprintf(line, sizeof line, "  %-46s %14.0f\n", "paper, hardware (one span per 17 us, 10 MHz)", kPaperSpansPerSecond);
    out << line;
    if (!r.engineSpeed) {
        out << "  (not measured: --speed-ms 0)\n";
        return;
    }
    std::snprintf(line, sizeof line, "  %-46s %14.0f\n", "engine model (one engine, all blocks, <= 9 px)", *r.engineSpeed);
    out << line;
    for (const SpeedRow& s : r.speeds) {
        const std::string what = std::string("fillSpan ") + methodName(s.method) + ", " + std::to_string(s.length) + " px";
        std::snprintf(line, sizeof line, "  %-46s %14.0f\n", what.c_str(), s.spansPerSecond);
        out << line;
    }
}

void printRender(std::ostream& out, const Report& r) {
    if (r.render.empty()) return;
    out << "\nsoftware backend, --interp: frame 0, one thread, best of " << kRenderRepeats
        << " frames (draw and rasterization);\n"
        << "departures from the exact render, depth error in 24-bit LSB over covered pixels:\n";
    out << "  mode   colour px    id px  worst     mean  depth px  overflow  spans/frame  frame ms  exact ms       spans/s\n";
    for (std::size_t i = 0; i < r.render.size(); ++i) {
        const RenderRow& row = r.render[i];
        if (i == 0 || row.scene != r.render[i - 1].scene)
            out << "  " << row.scene << " " << row.width << "x" << row.height << "\n";
        char line[200];
        std::snprintf(line, sizeof line, "  %-5s  %9zu  %7zu  %5u  %7.4f  %8zu  %8llu  %11llu  %8.2f  %8.2f  %12.0f\n",
                      toString(row.mode), row.colourPx, row.idPx, row.worstLsb, row.meanLsb, row.depthChangedPx,
                      static_cast<unsigned long long>(row.overflow), static_cast<unsigned long long>(row.spans),
                      row.frameMs, row.exactFrameMs, row.spansPerSecond);
        out << line;
    }
}

}  // namespace

int runSpanBench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    Report report;
    ErrorTableSettings& settings = report.settings;
    ReportPaths outputs;
    int speedMs = 100;
    std::vector<std::string> scenes;
    int renderWidth = 800, renderHeight = 600;
    CommandLine command{"span-bench", spanBenchHelp()};
    command.flags = {{"", {
        flag::wholeList("--lengths", "L,L,...", "span lengths in pixels (default 8,64,512,8192)", settings.lengths, 2,
                        kMaxColumn + 1 - 4096),
        flag::wholeList("--widths", "W,W,...", "channel widths in bits (default 16,24: colour and z)", settings.widths,
                        1, kMaxWidth),
        flag::whole("--spans", "N", "random spans per width, length and method (default 2000); a quarter of them the "
                    "steepest ramp (0 to the top, or back)", settings.spans, 1, 1000000),
        flag::whole("--seed", "S", "seed of the random spans (default 1)", settings.seed, 0, 2147483647),
        flag::whole("--dda-bits", "N", "the DDA's register: N bits, N − width of them fraction bits; wider than every "
                    "width (default 32)", settings.accumulatorBits, 2, 62),
        flag::whole("--speed-ms", "N", "time each spans-per-second figure for N ms; 0 skips the measurement (default "
                    "100)", speedMs, 0, 60000),
        {"--scene", "SCENE", "a scene as the other commands take it (builtin:cubes, a .obj, .gltf or .glb file); may be "
         "given several times. OBJ files are drawn single-sided (as with --cull-backfaces). For each, frame 0 at "
         "--render-size on the software backend with one thread, in exact, span and dda; per mode: pixels whose colour "
         "differs from exact, pixels another triangle won (ids differ), worst and mean depth error in 24-bit LSB over "
         "covered pixels, pixels whose depth changed, overflowing spans, spans per frame, the frame time (best of 5, "
         "rasterization included) beside exact's, and spans per second (spans per frame / best frame time). Timings "
         "are printed, never asserted",
         [&scenes](const std::string& text) -> std::string {
             if (text.empty()) return "is not a scene (builtin:NAME or a file)";
             scenes.push_back(text);
             return {};
         }},
        flag::size("--render-size", "WxH", "image size of every --scene (default 800x600)", renderWidth, renderHeight,
                   kMaxRenderSize),
    }}};
    for (Flag& f : reportFlags(outputs,
                               "{\"fig11\":{...},\"errors\":[{width,length,method,worst_lsb,mean_lsb,spans,...}],"
                               "\"spans_per_second\":{...},\"render\":[{scene,size,mode,colour_px,id_px,worst_lsb,"
                               "mean_lsb,depth_changed_px,overflow,spans,frame_ms,exact_frame_ms,spans_per_second}]}",
                               "the error table, one row per width, length and method",
                               "worst and mean error against span length, drawn by gnuplot from the CSV (--csv, or "
                               "FILE.csv beside the plot); the script is written as FILE.gp"))
        command.flags[0].flags.push_back(std::move(f));
    command.finish = [&](ArgCursor& cursor) {
        int widest = 0;
        for (int w : settings.widths) widest = std::max(widest, w);
        if (settings.accumulatorBits <= widest)
            cursor.fail("--dda-bits " + std::to_string(settings.accumulatorBits) + ": the DDA register must be wider than every width (" +
                        std::to_string(widest) + " bits) to hold a fraction");
        else if (const std::string problem = plotProblem(outputs); !problem.empty())
            cursor.fail(problem);
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;

    // Every scene loads before anything is measured: a bad one is the only line, and no file is written.
    std::vector<SceneCase> cases;
    for (const std::string& spec : scenes) {
        Result<SceneCase> c = loadSceneCase(spec, renderWidth, renderHeight);
        if (!c) {
            err << "error: " << c.error() << "\n";
            return kExitError;
        }
        cases.push_back(std::move(*c));
    }
    for (const SceneCase& c : cases) {
        Result<std::vector<RenderRow>> rows = renderScene(c, renderWidth, renderHeight);
        if (!rows) {
            err << "error: " << rows.error() << "\n";
            return kExitError;
        }
        report.render.insert(report.render.end(), rows->begin(), rows->end());
    }

    for (const Fig11Scheme& scheme : fig11Schemes()) report.fig11.push_back(runFig11(scheme));
    report.errors = errorTable(settings);
    if (speedMs > 0) {
        const double seconds = speedMs / 1000.0;
        report.engineSpeed = engineSpansPerSecond(seconds, settings.seed);
        for (Method m : settings.methods)
            for (int length : settings.lengths)
                report.speeds.push_back({m, length, fillSpansPerSecond(m, length, settings.accumulatorBits, seconds, settings.seed)});
    }

    const ReportTexts texts{[&report] { return reportJson(report); }, [&report] { return reportCsv(report); },
                            [&report](const std::string& csvPath, const std::string& svgPath) {
                                return reportGnuplot(report, csvPath, svgPath);
                            }};
    if (const int status = writeReportFiles(outputs, texts, err); status != kExitOk) return status;

    printFig11(out, report);
    printErrors(out, report);
    printSpeed(out, report);
    printRender(out, report);
    return kExitOk;
}

}  // namespace frugal
