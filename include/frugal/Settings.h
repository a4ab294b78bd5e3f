// What a Renderer does (frugal/Renderer.h): the choices, with the names the command line gives them
// (`--cull conservative` is Cull::Conservative, toString(Cull::Conservative) is "conservative"), and
// the settings struct that holds one of each.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Camera.h>
#include <frugal/Image.h>
#include <frugal/Result.h>

namespace frugal {

// Where frames are drawn. Auto: the EGL device platform when it is a GPU, else Mesa's EGL
// surfaceless platform, else OSMesa. Egl: the device platform when it is a GPU, else surfaceless.
// EglDevice: the device platform (software devices too). Software: frugal's CPU reference, which
// follows llvmpipe's rules bit for bit.
enum class BackendKind : std::uint8_t { Auto, Egl, EglDevice, EglSurfaceless, OsMesa, Software };

// Depth along each covered run of a triangle, software backend only: exact (llvmpipe's bits), span
// (paper 001's midpoint-subdivision engine), dda (add-and-shift); the last two model 24-bit depth.
enum class DepthInterp : std::uint8_t { Exact, Span, Dda };

// Culling: which triangles are submitted (see the renderer's documentation for each method).
// OcclusionAhead is occlusion's plan, made on a sequence while the frame before draws
// (Renderer::setNextFrame); it comes last so that the others keep their values.
enum class Cull : std::uint8_t { None, Sphere, Backface, Cones, Paper, Conservative, Occlusion, Oracle, OcclusionAhead };

// Draw order: submit (as listed), key (texture, program, mesh, as bgfx sorts), or by state-change
// costs measured on the backend: paper (paper 004's id sort), greedy, best.
enum class Order : std::uint8_t { Submit, Key, Paper, Greedy, Best };

// Hidden-surface mode (paper 003): the z-buffer, depth sort, the adaptive z-buffer, and adaptive
// with a convex solid's own faces unflagged.
enum class Hsr : std::uint8_t { ZBuffer, DepthSort, Adaptive, AdaptiveConvex };

inline constexpr std::array<BackendKind, 6> kBackendKinds{BackendKind::Auto,      BackendKind::Egl,
                                                          BackendKind::EglDevice, BackendKind::EglSurfaceless,
                                                          BackendKind::OsMesa,    BackendKind::Software};
inline constexpr std::array<DepthInterp, 3> kDepthInterps{DepthInterp::Exact, DepthInterp::Span, DepthInterp::Dda};
inline constexpr std::array<Cull, 9> kCulls{Cull::None,         Cull::Sphere,    Cull::Backface,
                                            Cull::Cones,        Cull::Paper,     Cull::Conservative,
                                            Cull::Occlusion,    Cull::OcclusionAhead, Cull::Oracle};
inline constexpr std::array<Order, 5> kOrders{Order::Submit, Order::Key, Order::Paper, Order::Greedy, Order::Best};
inline constexpr std::array<Hsr, 4> kHsrs{Hsr::ZBuffer, Hsr::DepthSort, Hsr::Adaptive, Hsr::AdaptiveConvex};
inline constexpr std::array<DepthRange, 2> kDepthRanges{DepthRange::Fit, DepthRange::File};
inline constexpr std::array<DepthFormat, 2> kDepthFormats{DepthFormat::D24, DepthFormat::D32F};

inline const char* toString(BackendKind v) {
    constexpr const char* names[] = {"auto", "egl", "egl-device", "egl-surfaceless", "osmesa", "software"};
    return names[std::size_t(v)];
}
inline const char* toString(DepthInterp v) {
    constexpr const char* names[] = {"exact", "span", "dda"};
    return names[std::size_t(v)];
}
inline const char* toString(Cull v) {
    constexpr const char* names[] = {"none", "sphere", "backface", "cones", "paper", "conservative", "occlusion", "oracle", "occlusion-ahead"};
    return names[std::size_t(v)];
}
// The methods whose plan the occlusion pass makes.
inline bool usesOcclusion(Cull v) { return v == Cull::Occlusion || v == Cull::OcclusionAhead; }
inline const char* toString(Order v) {
    constexpr const char* names[] = {"submit", "key", "paper", "greedy", "best"};
    return names[std::size_t(v)];
}
inline const char* toString(Hsr v) {
    constexpr const char* names[] = {"zbuffer", "depthsort", "adaptive", "adaptive-convex"};
    return names[std::size_t(v)];
}
inline const char* toString(DepthRange v) { return depthRangeName(v); }
inline const char* toString(DepthFormat v) { return depthFormatName(v); }

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

// Temporal reuse's settings (paper 000): with the camera still, what static instances render is
// kept in a static pair (one more target) and only what changed is drawn again.
struct ReuseSettings {
    int grain = 16;            // triangles an extent covers (1 = per triangle, as the paper; 0 = per instance)
    int cell = 16;             // the screen grid's cell side, in pixels
    bool fallback = true;      // render in full when the plan would cost more than that
    bool exactStatic = false;  // keep the static pair exact (no tie between static and dynamic outlives its frame)
};

// Every setting of a Renderer, with the command line's defaults.
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
    bool ids = false;  // draw triangle ids too (an id pass; Frame::ids stays empty without)
};

// A settings file (settings.json, as `frugal report` writes one): a JSON object whose keys are the
// command line's names of the settings above (the Python module's keyword arguments are these with
// '_' for '-'), each optional:
//   {"size": [800, 600], "backend": "auto", "threads": 0, "interp": "exact", "cull": "conservative",
//    "cull-bins": [16, 32], "order": "key", "refine-costs": 10, "reuse": true, "reuse-grain": 16,
//    "reuse-cell": 16, "no-fallback": false, "exact-static": false, "hsr": "zbuffer",
//    "depth-format": "d24", "background": [0.12, 0.13, 0.15, 1], "ids": false}
// Names as toString gives them; "size" and "cull-bins" also as "800x600"; "background" RGB or RGBA.
inline constexpr std::array<const char*, 17> kSettingNames{
    "size",       "backend",    "threads",     "interp",       "cull", "cull-bins",    "order",      "refine-costs",
    "reuse",      "reuse-grain", "reuse-cell", "no-fallback", "exact-static", "hsr", "depth-format", "background",
    "ids"};

struct SettingsFile {
    Settings settings;               // `base` with the file's values
    std::vector<std::string> keys;   // the keys the file gave, sorted
};
// `base` with the values of the settings file at `path`. Errors, one line starting with
// "settings <path>: " (Error::aboutSetting): the file cannot be read (Io); not JSON, not an object,
// a key that is not a setting (with the names), a value of the wrong kind ("key 'cull': 'x' is not
// a method (none, ...)") (BadInput). Ranges are Renderer::create's to check, as for any Settings.
Result<SettingsFile> readSettingsFile(const std::string& path, const Settings& base = {});
// The same from JSON text; `name` stands for the file in messages.
Result<SettingsFile> parseSettingsJson(std::string_view text, const std::string& name, const Settings& base = {});
// `settings` as a settings file: every key, one a line, in kSettingNames' order.
std::string settingsJson(const Settings& settings);

}  // namespace frugal
