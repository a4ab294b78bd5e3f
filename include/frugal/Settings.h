// What a Renderer does (frugal/Renderer.h): the choices and what each method is, the settings
// struct that holds one of each, and the schema every front end reads them through.
//
// The schema (settingInfos()) holds each setting once: its name (`--cull-bins` on the command
// line, "cull-bins" in a settings file, cull_bins in Python), the kind and range of its value, its
// help, and the settings it may conflict with. The command line's flags and their help, the
// settings file's reader and writer, Python's keyword arguments and dict, and the documentation's
// table are all made from it, and settingsProblem() is the one check of a whole Settings. Adding a
// setting is a member below and an entry in src/renderer/Settings.cpp (docs/architecture.md walks
// through one).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Camera.h>
#include <frugal/Image.h>
#include <frugal/Result.h>

namespace frugal {

// ---- The choices, and what each one is ----------------------------------------------------------

// Where frames are drawn. Auto: the EGL device platform when it is a GPU, else Mesa's EGL
// surfaceless platform, else OSMesa. Egl: the device platform when it is a GPU, else surfaceless.
// EglDevice: the device platform (software devices too). Software: frugal's CPU reference, which
// follows llvmpipe's rules bit for bit.
enum class BackendKind : std::uint8_t { Auto, Egl, EglDevice, EglSurfaceless, OsMesa, Software };

// Depth along each covered run of a triangle, software backend only: exact (llvmpipe's bits), span
// (paper 001's midpoint-subdivision engine), dda (add-and-shift); the last two model 24-bit depth.
enum class DepthInterp : std::uint8_t { Exact, Span, Dda };

// Culling: which triangles are submitted (kCullTraits says what each method is).
enum class Cull : std::uint8_t { None, Sphere, Backface, Cones, Paper, Conservative, Occlusion, OcclusionAhead, Oracle };

// Draw order: submit (as listed), key (texture, program, mesh, as bgfx sorts), or by state-change
// costs measured on the backend: paper (paper 004's id sort), greedy, best.
enum class Order : std::uint8_t { Submit, Key, Paper, Greedy, Best };

// Hidden-surface mode (paper 003): the z-buffer, depth sort, the adaptive z-buffer, and adaptive
// with a convex solid's own faces unflagged.
enum class Hsr : std::uint8_t { ZBuffer, DepthSort, Adaptive, AdaptiveConvex };

// A value of one of the enums above (and DepthFormat, frugal/Image.h): its name and one line of
// help. Each enum's table below lists its values in the enum's order (checked where it is written).
struct ChoiceInfo {
    std::string_view name;     // "conservative": what the command line, settings files and Python take
    std::string_view summary;  // what it is, for --help and the documentation
};

// A culling method and what it needs; the renderer, the reports and the checks ask these, not the
// method's name.
struct CullTraits {
    Cull method;
    ChoiceInfo info;
    bool exact;       // submits every triangle that owns a pixel: the same images (proven in tests)
    bool prepares;    // per-mesh maps and clusters, made before the upload, which order each mesh's triangles
                      // by bin (every method but none; the oracle too, so that it draws in the order they do)
    bool hull;        // also each mesh's convex hull (paper's side factors)
    bool occlusion;   // the occlusion pass: culls against the target's pixels (occlusion, occlusion-ahead)
    bool ahead;       // makes the next frame's plan while this one draws (Renderer::setNextFrame)
    bool idPass;      // draws the visible set an id pass of each frame finds: a floor, not a method
    std::string_view notWithReuse;  // why it cannot go with reuse, or empty
    std::string_view notWithHsr;    // why it cannot go with a hidden-surface mode but the z-buffer, or empty
};

inline constexpr std::array<CullTraits, 9> kCullTraits{{
    {Cull::None, {"none", "everything (default)"}, true, false, false, false, false, false, {}, {}},
    {Cull::Sphere, {"sphere", "instances whose bounding sphere meets the frustum"}, true, true, false, false, false, false,
     {}, {}},
    {Cull::Backface, {"backface", "every triangle tested on the CPU: frustum, and facing for single-sided materials"},
     true, true, false, false, false, false, {}, {}},
    {Cull::Cones, {"cones", "meshlets kept whole unless outside the frustum or facing away (normal cones)"}, true, true,
     false, false, false, false, {}, {}},
    {Cull::Paper, {"paper", "paper 002 as written: the spherical barycenter map's bins in view, or between the convex "
                            "hull's side factors; misses some triangles"},
     false, true, true, false, false, false, {}, {}},
    {Cull::Conservative, {"conservative", "clusters culled whole by box and cone, tested triangle by triangle where "
                                          "they cross; never drops a triangle that owns a pixel"},
     true, true, false, false, false, false, {}, {}},
    {Cull::Occlusion, {"occlusion", "conservative less what is hidden behind what is drawn anyway and the triangles "
                                    "that own no pixel centre, found on the CPU by llvmpipe's rules (the same pixels; "
                                    "it skips itself where it does not pay)"},
     true, true, false, true, false, false,
     "a static part hidden behind a moving one would be missing from the static image once it moves away (conservative "
     "culling goes with reuse)",
     {}},
    {Cull::OcclusionAhead, {"occlusion-ahead", "occlusion's plan, made on a sequence on a thread of its own while the "
                                               "frame before draws"},
     true, true, false, true, true, false,
     "a static part hidden behind a moving one would be missing from the static image once it moves away (conservative "
     "culling goes with reuse)",
     {}},
    {Cull::Oracle, {"oracle", "exactly the triangles an id pass of the frame finds visible: the floor of culling, not a "
                              "shortcut"},
     true, true, false, false, false, true, "the oracle is an id pass of each frame, not a plan to reuse",
     "the oracle draws its own scene"},
}};

// A draw order and what it needs.
struct OrderTraits {
    Order order;
    ChoiceInfo info;
    bool measuresCosts;  // state-change costs measured on the backend at start, refined between frames
};

inline constexpr std::array<OrderTraits, 5> kOrderTraits{{
    {Order::Submit, {"submit", "as the scene lists its draws (default)"}, false},
    {Order::Key, {"key", "sorted by texture, program and mesh, as bgfx sorts"}, false},
    {Order::Paper, {"paper", "paper 004's id sort over the 3 costliest kinds of state change"}, true},
    {Order::Greedy, {"greedy", "the cheapest next state change"}, true},
    {Order::Best, {"best", "the optimum over the distinct state sets (Held-Karp up to 16, else local search)"}, true},
}};

// A hidden-surface mode and what it needs.
struct HsrTraits {
    Hsr mode;
    ChoiceInfo info;
    bool plans;  // a hidden-surface plan each frame (every mode but the z-buffer)
    bool exact;  // the z-buffer's colour (but for exact depth ties)
};

inline constexpr std::array<HsrTraits, 4> kHsrTraits{{
    {Hsr::ZBuffer, {"zbuffer", "the exact render (default)"}, false, true},
    {Hsr::DepthSort, {"depthsort", "polygons back to front by average depth, no depth test (the painter's method; not "
                                   "exact)"},
     true, false},
    {Hsr::Adaptive, {"adaptive", "the same order; only polygons whose x, y and z extents overlap another's are "
                                 "depth-tested (exact but for rare depth ties)"},
     true, true},
    {Hsr::AdaptiveConvex, {"adaptive-convex", "adaptive, with the front faces of one convex solid not flagged "
                                              "against each other"},
     true, true},
}};

inline constexpr std::array<ChoiceInfo, 6> kBackendInfos{{
    {"auto", "the EGL device platform if it is a GPU, else EGL surfaceless, else OSMesa (default)"},
    {"egl", "the EGL device platform if it is a GPU, else EGL surfaceless"},
    {"egl-device", "the EGL device platform (software devices too)"},
    {"egl-surfaceless", "Mesa's EGL surfaceless platform"},
    {"osmesa", "Mesa's OSMesa"},
    {"software", "frugal's CPU reference rasterizer: llvmpipe's rules, no GL"},
}};

inline constexpr std::array<ChoiceInfo, 3> kDepthInterpInfos{{
    {"exact", "llvmpipe's bits (default)"},
    {"span", "paper 001's midpoint-subdivision engine, within 1 LSB of the line through the span's ends"},
    {"dda", "add-and-shift with 8 fraction bits: the error grows along the span"},
}};

inline constexpr std::array<ChoiceInfo, 2> kDepthFormatInfos{{
    {"d24", "24-bit depth (default)"},
    {"d32f", "32-bit float with reversed Z (1 near, 0 far), which separates depths about 1e-7 of their distance "
             "apart at any near/far ratio"},
}};

inline constexpr std::array<ChoiceInfo, 3> kToneMapInfos{{
    {"none", "linear colour as it is, clamped at 1 (default)"},
    {"pbr-neutral", "the Khronos PBR Neutral operator: hue and value kept below 0.76, brighter colours compressed "
                    "toward white"},
    {"aces", "Stephen Hill's fit of the ACES filmic curve"},
}};

// The default light: a scene without KHR_lights_punctual lights is lit by the directional light of
// pipeline/Backend.h's Lighting, or by the environment alone.
enum class DefaultLight : std::uint8_t { On, Off };
inline constexpr std::array<ChoiceInfo, 2> kDefaultLightInfos{{
    {"default", "where the scene has no lights of its own, one white directional light from (0.35, 0.8, 0.5) of "
                "intensity 0.7π, as a white surface facing it reflects 0.7 (default)"},
    {"none", "no default light: the environment lights the scene, with the scene's own lights where it has any"},
}};

inline constexpr std::array<ChoiceInfo, 2> kShadingModelInfos{{
    {"full", "glTF's metallic-roughness model as the Khronos glTF Sample Renderer draws it, with every map and "
             "extension the material uses (default)"},
    {"lambert", "a fast approximation: base colour times the diffuse light (environment and lights) plus emission; "
                "no specular, metallic-roughness, occlusion, normal or clear-coat terms"},
}};

constexpr const CullTraits& traitsOf(Cull v) { return kCullTraits[std::size_t(v)]; }
constexpr const OrderTraits& traitsOf(Order v) { return kOrderTraits[std::size_t(v)]; }
constexpr const HsrTraits& traitsOf(Hsr v) { return kHsrTraits[std::size_t(v)]; }

constexpr const ChoiceInfo& infoOf(Cull v) { return traitsOf(v).info; }
constexpr const ChoiceInfo& infoOf(Order v) { return traitsOf(v).info; }
constexpr const ChoiceInfo& infoOf(Hsr v) { return traitsOf(v).info; }
constexpr const ChoiceInfo& infoOf(BackendKind v) { return kBackendInfos[std::size_t(v)]; }
constexpr const ChoiceInfo& infoOf(DepthInterp v) { return kDepthInterpInfos[std::size_t(v)]; }
constexpr const ChoiceInfo& infoOf(DepthFormat v) { return kDepthFormatInfos[std::size_t(v)]; }
constexpr const ChoiceInfo& infoOf(ToneMap v) { return kToneMapInfos[std::size_t(v)]; }
constexpr const ChoiceInfo& infoOf(DefaultLight v) { return kDefaultLightInfos[std::size_t(v)]; }
constexpr const ChoiceInfo& infoOf(ShadingModel v) { return kShadingModelInfos[std::size_t(v)]; }

// Every value of an enum, in its order: values<Cull>() is {None, Sphere, ...}.
template <class T>
constexpr auto values() {
    constexpr std::size_t n = [] {
        if constexpr (std::is_same_v<T, Cull>) return kCullTraits.size();
        else if constexpr (std::is_same_v<T, Order>) return kOrderTraits.size();
        else if constexpr (std::is_same_v<T, Hsr>) return kHsrTraits.size();
        else if constexpr (std::is_same_v<T, BackendKind>) return kBackendInfos.size();
        else if constexpr (std::is_same_v<T, DepthInterp>) return kDepthInterpInfos.size();
        else if constexpr (std::is_same_v<T, ToneMap>) return kToneMapInfos.size();
        else if constexpr (std::is_same_v<T, DefaultLight>) return kDefaultLightInfos.size();
        else if constexpr (std::is_same_v<T, ShadingModel>) return kShadingModelInfos.size();
        else return kDepthFormatInfos.size();
    }();
    std::array<T, n> out{};
    for (std::size_t i = 0; i < n; ++i) out[i] = T(i);
    return out;
}

inline constexpr auto kBackendKinds = values<BackendKind>();
inline constexpr auto kDepthInterps = values<DepthInterp>();
inline constexpr auto kCulls = values<Cull>();
inline constexpr auto kOrders = values<Order>();
inline constexpr auto kHsrs = values<Hsr>();
inline constexpr auto kDepthFormats = values<DepthFormat>();
inline constexpr auto kToneMaps = values<ToneMap>();
inline constexpr auto kDefaultLights = values<DefaultLight>();
inline constexpr auto kShadingModels = values<ShadingModel>();

// The tables hold their enum's values in order, so that traitsOf(v) is v's row.
static_assert([] {
    for (std::size_t i = 0; i < kCullTraits.size(); ++i)
        if (kCullTraits[i].method != Cull(i)) return false;
    for (std::size_t i = 0; i < kOrderTraits.size(); ++i)
        if (kOrderTraits[i].order != Order(i)) return false;
    for (std::size_t i = 0; i < kHsrTraits.size(); ++i)
        if (kHsrTraits[i].mode != Hsr(i)) return false;
    return true;
}());

template <class T>
const char* toString(T v) requires requires { infoOf(v); } {
    return infoOf(v).name.data();  // every name is a literal: NUL-terminated
}
// A camera's depth range (frugal/Camera.h), which the command line takes beside the settings.
inline const char* toString(DepthRange v) { return depthRangeName(v); }
inline constexpr std::array<DepthRange, 2> kDepthRanges{DepthRange::Fit, DepthRange::File};

// The value named `name` among `values` (one of the k... arrays above), or nothing.
template <class T, std::size_t N>
std::optional<T> fromString(std::string_view name, const std::array<T, N>& values) {
    for (const T v : values)
        if (name == toString(v)) return v;
    return std::nullopt;
}

// "none, sphere, backface, ..." for a message.
template <class T, std::size_t N>
std::string namesOf(const std::array<T, N>& values) {
    std::string out;
    for (const T v : values) out += (out.empty() ? "" : ", ") + std::string(toString(v));
    return out;
}

// ---- The settings ---------------------------------------------------------------------------------

// Temporal reuse's settings (paper 000): with the camera still, what static instances render is
// kept in a static pair (one more target) and only what changed is drawn again.
struct ReuseSettings {
    int grain = 16;            // triangles an extent covers (1 = per triangle, as the paper; 0 = per instance)
    int cell = 16;             // the screen grid's cell side, in pixels
    bool fallback = true;      // render in full when the plan would cost more than that
    bool exactStatic = false;  // keep the static pair exact (no tie between static and dynamic outlives its frame)
};

// Every setting of a Renderer, with the command line's defaults. settingInfos() describes each.
struct Settings {
    int width = 800, height = 600;
    BackendKind backend = BackendKind::Auto;
    int threads = 0;  // rasterizer threads (software pool, llvmpipe's LP_NUM_THREADS); 0 = every core
    DepthInterp interp = DepthInterp::Exact;
    Cull cull = Cull::None;
    int cullBinsTheta = 16, cullBinsPhi = 32;  // the spherical barycenter map's bins (polar × azimuthal)
    Order order = Order::Submit;
    int refineCosts = 10;  // paper, greedy, best: one more cost round every N frames (0 = never)
    bool reuse = false;
    ReuseSettings reuseSettings;
    Hsr hsr = Hsr::ZBuffer;
    DepthFormat depthFormat = DepthFormat::D24;
    glm::vec4 background{0.12f, 0.13f, 0.15f, 1.0f};
    ToneMap tonemap = ToneMap::None;  // frugal/Image.h
    int samples = 1;  // multisampling: 1, 2, 4 or 8 samples a pixel (Backend::createTarget)
    DefaultLight light = DefaultLight::On;  // the directional light where the scene has no lights
    float environment = 0.3f;               // the uniform white environment's radiance (0: none)
    std::string environmentMap;       // an equirectangular Radiance .hdr file lighting instead ("" = none)
    bool environmentSpecular = true;  // false: the environment lights the diffuse lobe alone (no reflection of it)
    ShadingModel shading = ShadingModel::Full;  // frugal/Image.h
    bool mipmaps = true;  // false: every texture sampled from its base level (no mipmaps made)
    bool ids = false;  // draw triangle ids too (an id pass; Frame::ids stays empty without)
    // Draw the colour in linear light into a float target as well (Frame::linear, frugal/Image.h):
    // Frame::color is then its display encoding. Blended surfaces and multisampled edges mix in
    // linear light.
    bool linear = false;
};

// ---- The schema -----------------------------------------------------------------------------------

enum class SettingKind : std::uint8_t {
    Switch,  // true or false; on the command line a flag without a value
    Whole,   // a whole number in [min, max]
    Pair,    // two whole numbers, each in [min, max]: "AxB" on the command line, [A, B] in JSON, (A, B) in Python
    Choice,  // one of `choices`, by name
    Colour,  // r,g,b or r,g,b,a, each 0 to 1 (alpha 1 when not given)
    Real,    // a finite number in [low, high]
    Text,    // a string: a file's path ("" = none)
};

// A setting's value as the front ends pass it: Switch bool, Whole long long, Pair two long longs,
// Choice the name, Colour 3 or 4 numbers, Real a double, Text the string.
using SettingValue = std::variant<bool, long long, std::array<long long, 2>, std::string, std::vector<double>, double>;

struct SettingInfo {
    std::string name;       // "cull-bins": the flag (--cull-bins), the settings file's key; Python's keyword cull_bins
    SettingKind kind = SettingKind::Switch;
    std::string metavar;    // the command line's placeholder, "TxP"
    std::string noun;       // what a refused value is not: "a bin grid (TxP, each 1 to 1024)" (see expected())
    std::string help;       // what it does, one paragraph
    std::string topic;      // the group of flags it is listed under: "image", "culling", "order", ...
    long long min = 0, max = 0;        // Whole and Pair: each number's range
    std::vector<long long> only;       // Whole: when not empty, the values allowed (within the range)
    double low = 0.0, high = 0.0;      // Real: its range
    std::vector<ChoiceInfo> choices;   // Choice: every value, in the enum's order
    bool flag = true;       // a flag of the commands that render (ids is not: `render --ids FILE` sets it)
    std::function<SettingValue(const Settings&)> get;
    std::function<void(Settings&, const SettingValue&)> put;  // a value setSetting accepted

    std::string pythonName() const;  // "cull_bins"
};

// Every setting, in the order the settings file writes them.
const std::vector<SettingInfo>& settingInfos();
// The setting named `name` (the command line's "cull-bins" or Python's "cull_bins"), or nullptr.
const SettingInfo* findSetting(std::string_view name);

// What a value of `info` must be, for a refusal: "a whole number from 0 to 256", "1, 2, 4 or 8", "a method (none,
// sphere, ...)", "a size (WxH, each 1 to 65536)", "a colour (r,g,b or r,g,b,a, each 0 to 1)", "true
// or false". Every front end refuses a value as "<the value as it shows it> is not <expected>".
std::string expected(const SettingInfo& info);
// Sets `info`'s setting in `settings` to `value`: "" when done, or why not ("is not a whole number
// from 0 to 256"; `settings` unchanged).
std::string setSetting(Settings& settings, const SettingInfo& info, const SettingValue& value);
// The command line's text of a value ("800x600", "conservative", "0.5,0.2,0.1", "true"), read by
// the kind alone: nothing when it is not of the kind (the range is setSetting's to check).
std::optional<SettingValue> parseSettingText(const SettingInfo& info, std::string_view text);
// The command line's text of a value: "800x600", "conservative", "0.12,0.13,0.15,1", "true".
std::string settingText(const SettingInfo& info, const SettingValue& value);

// A pair of settings that may not go together: what settingsProblem checks, for the documentation.
struct SettingsConflict {
    std::string first, second;  // setting names
    std::string when;           // "with a culling method whose traits say why not (occlusion, oracle)"
};
const std::vector<SettingsConflict>& settingsConflicts();

// What is wrong with a whole Settings: a value out of its range, or two settings that may not go
// together. `settings` are the names it is about, in the order a message names them.
struct SettingsProblem {
    std::vector<std::string> settings;
    std::string why;     // "the oracle is an id pass of each frame, not a plan to reuse"
    bool value = false;  // one value out of range: why is "is not <expected>"
};
std::optional<SettingsProblem> settingsProblem(const Settings& settings);

// How a front end names a setting with its value: the command line "--cull oracle" or "--reuse",
// Python "cull='oracle'". The default, the library's own, is "cull oracle", "reuse".
using SettingSpelling = std::function<std::string(const SettingInfo& info, const SettingValue& value)>;
std::string librarySpelling(const SettingInfo& info, const SettingValue& value);
// The problem as one line: "reuse with cull oracle: the oracle is ...", "threads 999 is not a whole
// number from 0 to 256".
std::string describe(const SettingsProblem& problem, const Settings& settings,
                     const SettingSpelling& spell = librarySpelling);

// ---- Settings files -------------------------------------------------------------------------------

// A settings file (settings.json, as `frugal report` writes one): a JSON object whose keys are
// settings' names, each optional, values as JSON gives them: a Switch true or false, a Whole a
// number, a Pair [A, B] or "AxB", a Choice its name, a Colour [r, g, b] or [r, g, b, a].
struct SettingsFile {
    Settings settings;              // `base` with the file's values
    std::vector<std::string> keys;  // the keys the file gave, sorted
};
// `base` with the values of the settings file at `path`. Errors, one line starting with
// "settings <path>: " (Error::aboutSetting): the file cannot be read (Io); not JSON, not an object,
// a key that is not a setting (with the names), a value that is not what the setting takes ("key
// 'cull': \"x\" is not a method (none, ...)") (BadInput). Settings that may not go together are
// settingsProblem's (Renderer::create) to refuse, after whatever is applied on top.
Result<SettingsFile> readSettingsFile(const std::string& path, const Settings& base = {});
// The same from JSON text; `name` stands for the file in messages.
Result<SettingsFile> parseSettingsJson(std::string_view text, const std::string& name, const Settings& base = {});
// `settings` as a settings file: every key, one a line, in settingInfos()' order.
std::string settingsJson(const Settings& settings);
// One setting's value as a settings file gives it (JSON text: `[640, 480]`, `"auto"`), set in
// `settings`: "" when done, or why not, as the file's reader says it ("\"x\" is not a backend
// (auto, ...)"; also "... is not JSON").
std::string setSettingJson(Settings& settings, const SettingInfo& info, std::string_view json);

}  // namespace frugal
