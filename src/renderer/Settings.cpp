// The settings schema (frugal/Settings.h): every setting once, the checks of a whole Settings, and
// settings files, all read from the one table below.
#include <algorithm>
#include <charconv>
#include <cmath>

#include <nlohmann/json.hpp>

#include <frugal/Settings.h>

#include "io/ImageIO.h"

namespace frugal {

namespace {

using Json = nlohmann::json;

// Builders of the table's entries. `field` is a generic lambda giving the member (const or not):
// [](auto& s) -> auto& { return s.threads; }.

SettingInfo entry(std::string name, SettingKind kind, std::string metavar, std::string topic, std::string help) {
    SettingInfo info;
    info.name = std::move(name);
    info.kind = kind;
    info.metavar = std::move(metavar);
    info.topic = std::move(topic);
    info.help = std::move(help);
    return info;
}

template <class Field>
SettingInfo whole(std::string name, std::string metavar, std::string topic, std::string help, long long min,
                  long long max, Field field) {
    SettingInfo info = entry(std::move(name), SettingKind::Whole, std::move(metavar), std::move(topic), std::move(help));
    info.min = min;
    info.max = max;
    info.get = [field](const Settings& s) { return SettingValue(static_cast<long long>(field(s))); };
    info.put = [field](Settings& s, const SettingValue& v) { field(s) = static_cast<int>(std::get<long long>(v)); };
    return info;
}

// A real number in [low, high] (a float member).
template <class Field>
SettingInfo real(std::string name, std::string metavar, std::string topic, std::string help, double low, double high,
                 Field field) {
    SettingInfo info = entry(std::move(name), SettingKind::Real, std::move(metavar), std::move(topic), std::move(help));
    info.low = low;
    info.high = high;
    info.get = [field](const Settings& s) { return SettingValue(double(field(s))); };
    info.put = [field](Settings& s, const SettingValue& v) { field(s) = float(std::get<double>(v)); };
    return info;
}

// A file's path (a std::string member; "" = none).
template <class Field>
SettingInfo path(std::string name, std::string metavar, std::string topic, std::string help, Field field) {
    SettingInfo info = entry(std::move(name), SettingKind::Text, std::move(metavar), std::move(topic), std::move(help));
    info.get = [field](const Settings& s) { return SettingValue(field(s)); };
    info.put = [field](Settings& s, const SettingValue& v) { field(s) = std::get<std::string>(v); };
    return info;
}

// Two whole numbers; `first` and `second` give the members.
template <class First, class Second>
SettingInfo pair(std::string name, std::string metavar, std::string noun, std::string topic, std::string help,
                 long long min, long long max, First first, Second second) {
    SettingInfo info = entry(std::move(name), SettingKind::Pair, std::move(metavar), std::move(topic), std::move(help));
    info.noun = std::move(noun);
    info.min = min;
    info.max = max;
    info.get = [first, second](const Settings& s) {
        return SettingValue(std::array<long long, 2>{first(s), second(s)});
    };
    info.put = [first, second](Settings& s, const SettingValue& v) {
        const auto& p = std::get<std::array<long long, 2>>(v);
        first(s) = static_cast<int>(p[0]);
        second(s) = static_cast<int>(p[1]);
    };
    return info;
}

// A switch; `inverted`: the member holds the opposite (no-fallback sets fallback = false).
template <class Field>
SettingInfo toggle(std::string name, std::string topic, std::string help, Field field, bool inverted = false) {
    SettingInfo info = entry(std::move(name), SettingKind::Switch, "", std::move(topic), std::move(help));
    info.get = [field, inverted](const Settings& s) { return SettingValue(field(s) != inverted); };
    info.put = [field, inverted](Settings& s, const SettingValue& v) { field(s) = std::get<bool>(v) != inverted; };
    return info;
}

// One of an enum's values, by name. A value outside the enum (a cast) reads as its number, which
// the check refuses.
template <class Field>
SettingInfo choice(std::string name, std::string metavar, std::string noun, std::string topic, std::string help,
                   Field field) {
    SettingInfo info = entry(std::move(name), SettingKind::Choice, std::move(metavar), std::move(topic), std::move(help));
    info.noun = std::move(noun);
    using T = std::remove_cvref_t<decltype(field(std::declval<Settings&>()))>;
    for (const T v : values<T>()) info.choices.push_back(infoOf(v));
    info.get = [field](const Settings& s) {
        const T v = field(s);
        return std::size_t(v) < values<T>().size() ? SettingValue(std::string(toString(v)))
                                                   : SettingValue(std::to_string(int(v)));
    };
    info.put = [field](Settings& s, const SettingValue& v) {
        field(s) = *fromString(std::get<std::string>(v), values<T>());
    };
    return info;
}

const char* const kImage = "image";
const char* const kCulling = "culling";
const char* const kOrder = "order";
const char* const kReuse = "reuse";
const char* const kHsr = "hsr";
const char* const kOutputs = "outputs";

std::vector<SettingInfo> makeTable() {
    std::vector<SettingInfo> t;
    t.push_back(pair("size", "WxH", "a size", kImage,
                     "image size in pixels (default 800x600; the command line, given no size, takes the aspect ratio "
                     "of the scene camera it draws with, the longer side 800)",
                     1, 65536, [](auto& s) -> auto& { return s.width; }, [](auto& s) -> auto& { return s.height; }));
    t.push_back(choice("backend", "NAME", "a backend", kImage, "where frames are drawn",
                       [](auto& s) -> auto& { return s.backend; }));
    t.push_back(whole("threads", "N", kImage,
                      "rasterizer threads: the software backend's, and llvmpipe's (LP_NUM_THREADS); 0 (default) = "
                      "every core",
                      0, 256, [](auto& s) -> auto& { return s.threads; }));
    t.push_back(choice("interp", "MODE", "an interpolation mode", kImage,
                       "depth along each scan-line span, software backend only; span and dda are a slow path. Colour "
                       "is shaded per fragment in every mode (not Gouraud): it changes only where a depth test flips",
                       [](auto& s) -> auto& { return s.interp; }));
    t.push_back(choice("cull", "METHOD", "a method", kCulling,
                       "which triangles are submitted; all but paper keep every triangle that owns a pixel (see "
                       "'frugal cull-report' and docs/occlusion.md)",
                       [](auto& s) -> auto& { return s.cull; }));
    t.push_back(pair("cull-bins", "TxP", "a bin grid", kCulling,
                     "bins of the spherical barycenter map: T polar by P azimuthal (default 16x32)", 1, 1024,
                     [](auto& s) -> auto& { return s.cullBinsTheta; }, [](auto& s) -> auto& { return s.cullBinsPhi; }));
    t.push_back(choice("order", "ORDER", "an order", kOrder,
                       "the draw order; paper, greedy and best measure state-change costs on the backend at start "
                       "(about a second; see 'frugal info --state-costs'). Consecutive draws of one mesh go out as one "
                       "instanced draw. Only pixels where two surfaces tie exactly in depth can change (first drawn "
                       "wins). Not applied with reuse, which draws in its own order (the static pair, then what changed)",
                       [](auto& s) -> auto& { return s.order; }));
    t.push_back(whole("refine-costs", "N", kOrder,
                      "with paper, greedy or best: every N frames of a sequence, one more round of the cost measurement "
                      "between two frames (a few ms), averaged with the last 32 rounds, so the order follows the backend "
                      "(default 10; 0 = never)",
                      0, 1000000, [](auto& s) -> auto& { return s.refineCosts; }));
    t.push_back(toggle("reuse", kReuse,
                       "temporal reuse: with the camera still, copy what static instances render from a static pair "
                       "(one more target) and redraw only what changed; the images are the same, byte for byte",
                       [](auto& s) -> auto& { return s.reuse; }));
    t.push_back(whole("reuse-grain", "N", kReuse,
                      "triangles per extent: N consecutive triangles of a mesh share one screen rectangle (default 16; "
                      "1 = per triangle as in the paper; 0 = per instance)",
                      0, 1 << 30, [](auto& s) -> auto& { return s.reuseSettings.grain; }));
    t.push_back(whole("reuse-cell", "PX", kReuse,
                      "side of the screen-grid cells that copies and clears are made of (default 16)", 1, 4096,
                      [](auto& s) -> auto& { return s.reuseSettings.cell; }));
    t.push_back(toggle("no-fallback", kReuse, "never fall back to a full render while the camera is still (for measuring)",
                       [](auto& s) -> auto& { return s.reuseSettings.fallback; }, true));
    t.push_back(toggle("exact-static", kReuse,
                       "keep the static pair exactly the static instances' render (clear and redraw around instances "
                       "that come to rest) instead of paper 000's steps, with which a depth tie lost while moving can "
                       "outlive its frame",
                       [](auto& s) -> auto& { return s.reuseSettings.exactStatic; }));
    t.push_back(choice("hsr", "MODE", "a mode", kHsr,
                       "hidden-surface removal (paper 003). Besides zbuffer, the depth image holds only the "
                       "depth-tested polygons. See 'frugal-lab hsr-bench'",
                       [](auto& s) -> auto& { return s.hsr; }));
    t.push_back(choice("depth-format", "F", "a depth format", kImage,
                       "the depth buffer (see 'frugal info SCENE' for the depth resolution each gives)",
                       [](auto& s) -> auto& { return s.depthFormat; }));
    t.push_back(choice("tonemap", "OP", "a tone-mapping operator", kImage,
                       "how linear colour is mapped before its display encoding, as the Khronos glTF Sample Renderer "
                       "maps it (the background is not)",
                       [](auto& s) -> auto& { return s.tonemap; }));
    t.push_back(choice("shading", "MODEL", "a shading model", kImage, "how lit materials are shaded",
                       [](auto& s) -> auto& { return s.shading; }));
    t.push_back(toggle("no-mipmaps", kImage,
                       "sample every texture from its base level, whatever its sampler asks: no mipmaps are made "
                       "(faster to upload and to sample; minified textures alias)",
                       [](auto& s) -> auto& { return s.mipmaps; }, true));
    t.push_back(choice("light", "L", "a light", kImage, "the light of a scene without lights of its own",
                       [](auto& s) -> auto& { return s.light; }));
    t.push_back(real("environment", "L", kImage,
                     "radiance of the uniform white environment that lights every material, diffusely and "
                     "specularly, as image-based light (default 0.3: a white matte surface reflects 0.3 of it in "
                     "any orientation; 0 = none)",
                     0.0, 1e6, [](auto& s) -> auto& { return s.environment; }));
    t.push_back(path("environment-map", "FILE", kImage,
                     "an equirectangular Radiance .hdr image (+Y its top row) lights every material instead of "
                     "the uniform environment, diffusely and specularly, prefiltered once when loaded as the "
                     "Khronos glTF Sample Renderer prefilters its environments",
                     [](auto& s) -> auto& { return s.environmentMap; }));
    t.push_back(toggle("no-environment-specular", kImage,
                       "the environment lights each material's diffuse lobe alone: no specular reflection of it "
                       "(metals then reflect only the lights; faster to shade)",
                       [](auto& s) -> auto& { return s.environmentSpecular; }, true));
    SettingInfo samples = whole("samples", "N", kImage,
                                "samples a pixel (multisampling, resolved to one colour each): 1 (default), 2, 4 "
                                "or 8, at least as many as the backend has (llvmpipe and the software backend: 4 for "
                                "2 and 4; 8 needs a GPU). The depth and id images hold each pixel's first sample",
                                1, 8, [](auto& s) -> auto& { return s.samples; });
    samples.only = {1, 2, 4, 8};
    t.push_back(std::move(samples));
    SettingInfo background = entry("background", SettingKind::Colour, "R,G,B[,A]", kImage,
                                   "clear colour in [0,1] (default 0.12,0.13,0.15); an alpha below 1 makes the image "
                                   "translucent there, written with straight alpha as PNG defines it");
    background.get = [](const Settings& s) {
        return SettingValue(std::vector<double>{s.background.r, s.background.g, s.background.b, s.background.a});
    };
    background.put = [](Settings& s, const SettingValue& v) {
        const auto& c = std::get<std::vector<double>>(v);
        s.background = glm::vec4(float(c[0]), float(c[1]), float(c[2]), c.size() == 4 ? float(c[3]) : 1.0f);
    };
    t.push_back(std::move(background));
    SettingInfo ids = toggle("ids", kOutputs, "draw triangle ids too (an id pass; without it the frame holds no ids)",
                             [](auto& s) -> auto& { return s.ids; });
    ids.flag = false;  // `render --ids FILE` draws them
    t.push_back(std::move(ids));
    SettingInfo linear = toggle(
        "linear", kOutputs,
        "draw the colour in linear light into a float target (after tone mapping, before the display "
        "encoding, unclamped; blended surfaces and multisampled edges mix in linear light): the frame holds it as "
        "float32, and its "
        "colour image is its display encoding",
        [](auto& s) -> auto& { return s.linear; });
    linear.flag = false;  // `render --linear FILE` draws it
    t.push_back(std::move(linear));
    return t;
}

// The pairs that may not go together: the check, and what the documentation says of it.
struct ConflictRule {
    SettingsConflict doc;
    std::function<std::string_view(const Settings&)> why;  // empty when they go together
};

const std::vector<ConflictRule>& conflictRules() {
    static const std::vector<ConflictRule> rules = {
        {{"reuse", "cull", "with a method that is an id pass (oracle) or culls against what moving parts hide "
                           "(occlusion, occlusion-ahead)"},
         [](const Settings& s) { return s.reuse ? traitsOf(s.cull).notWithReuse : std::string_view(); }},
        {{"hsr", "reuse", "with any mode but zbuffer"},
         [](const Settings& s) {
             return traitsOf(s.hsr).plans && s.reuse ? "reuse redraws what moved with the z-buffer over the static image"
                                                     : std::string_view();
         }},
        {{"hsr", "cull", "with any mode but zbuffer, and cull oracle"},
         [](const Settings& s) { return traitsOf(s.hsr).plans ? traitsOf(s.cull).notWithHsr : std::string_view(); }},
        {{"interp", "backend", "span and dda with any backend but software"},
         [](const Settings& s) {
             return s.interp != DepthInterp::Exact && s.backend != BackendKind::Software
                        ? "only the software backend models the span interpolator"
                        : std::string_view();
         }},
        {{"samples", "interp", "more than 1 with span and dda"},
         [](const Settings& s) {
             return s.samples > 1 && s.interp != DepthInterp::Exact ? "the span engine models one sample a pixel"
                                                                    : std::string_view();
         }},
        {{"samples", "cull", "more than 1 with occlusion, occlusion-ahead and oracle"},
         [](const Settings& s) {
             const CullTraits& cull = traitsOf(s.cull);
             return s.samples > 1 && (cull.occlusion || cull.idPass)
                        ? "they find what is visible at pixel centres, and a multisampled pixel is seen at 4 samples"
                        : std::string_view();
         }},
        {{"environment", "environment-map", "another radiance than the default 0.3 with a map"},
         [](const Settings& s) {
             return !s.environmentMap.empty() && s.environment != Settings{}.environment
                        ? "a map gives the environment's radiance itself"
                        : std::string_view();
         }},
        {{"interp", "depth-format", "span and dda with d32f"},
         [](const Settings& s) {
             return s.interp != DepthInterp::Exact && s.depthFormat == DepthFormat::D32F
                        ? "the span engine interpolates a 24-bit depth"
                        : std::string_view();
         }},
    };
    return rules;
}

bool parseWhole(std::string_view text, long long& out) {
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), out);
    return !text.empty() && error == std::errc() && end == text.data() + text.size();
}

bool parseFinite(std::string_view text, double& out) {
    const char* begin = text.data();
    const char* end = begin + text.size();
    if (begin != end && *begin == '+') ++begin;
    const auto [stop, error] = std::from_chars(begin, end, out);
    return begin != end && error == std::errc() && stop == end && std::isfinite(out);
}

// The shortest text that reads back as the same float.
std::string floatText(double v) {
    char buffer[32];
    const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, float(v));
    return std::string(buffer, error == std::errc() ? end : buffer);
}

// "" when `value` is of `info`'s kind and within its range, else why not ("is not ...").
std::string check(const SettingInfo& info, const SettingValue& value) {
    const std::string refused = "is not " + expected(info);
    switch (info.kind) {
        case SettingKind::Switch:
            return std::holds_alternative<bool>(value) ? "" : refused;
        case SettingKind::Whole: {
            const long long* v = std::get_if<long long>(&value);
            const bool allowed = v && (info.only.empty() || std::find(info.only.begin(), info.only.end(), *v) !=
                                                                 info.only.end());
            return allowed && *v >= info.min && *v <= info.max ? "" : refused;
        }
        case SettingKind::Pair: {
            const auto* v = std::get_if<std::array<long long, 2>>(&value);
            const auto in = [&info](long long x) { return x >= info.min && x <= info.max; };
            return v && in((*v)[0]) && in((*v)[1]) ? "" : refused;
        }
        case SettingKind::Choice: {
            const std::string* v = std::get_if<std::string>(&value);
            const bool known = v && std::any_of(info.choices.begin(), info.choices.end(),
                                                [v](const ChoiceInfo& c) { return c.name == *v; });
            return known ? "" : refused;
        }
        case SettingKind::Colour: {
            const auto* v = std::get_if<std::vector<double>>(&value);
            const bool ok = v && (v->size() == 3 || v->size() == 4) &&
                            std::all_of(v->begin(), v->end(), [](double x) { return x >= 0.0 && x <= 1.0; });
            return ok ? "" : refused;
        }
        case SettingKind::Real: {
            const double* v = std::get_if<double>(&value);
            return v && std::isfinite(*v) && *v >= info.low && *v <= info.high ? "" : refused;
        }
        case SettingKind::Text: {
            const std::string* v = std::get_if<std::string>(&value);
            return v && v->find('\0') == std::string::npos ? "" : refused;
        }
    }
    return refused;
}

// A JSON value as the setting's value, by its kind alone (nothing: not of the kind).
std::optional<SettingValue> fromJson(const SettingInfo& info, const Json& v) {
    switch (info.kind) {
        case SettingKind::Switch:
            if (v.is_boolean()) return v.get<bool>();
            break;
        case SettingKind::Whole:
            if (v.is_number_integer()) return v.get<long long>();
            break;
        case SettingKind::Pair:
            if (v.is_string()) return parseSettingText(info, v.get<std::string>());
            if (v.is_array() && v.size() == 2 && v[0].is_number_integer() && v[1].is_number_integer())
                return std::array<long long, 2>{v[0].get<long long>(), v[1].get<long long>()};
            break;
        case SettingKind::Choice:
            if (v.is_string()) return v.get<std::string>();
            break;
        case SettingKind::Colour:
            if (v.is_array() && std::all_of(v.begin(), v.end(), [](const Json& x) { return x.is_number(); })) {
                std::vector<double> c;
                for (const Json& x : v) c.push_back(x.get<double>());
                return c;
            }
            break;
        case SettingKind::Real:
            if (v.is_number()) return v.get<double>();
            break;
        case SettingKind::Text:
            if (v.is_string()) return v.get<std::string>();
            break;
    }
    return std::nullopt;
}

std::string jsonText(const SettingValue& value) {
    return std::visit(
        [](const auto& v) -> std::string {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, bool>) return v ? "true" : "false";
            else if constexpr (std::is_same_v<V, long long>) return std::to_string(v);
            else if constexpr (std::is_same_v<V, std::array<long long, 2>>)
                return "[" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + "]";
            else if constexpr (std::is_same_v<V, std::string>) return Json(v).dump();
            else if constexpr (std::is_same_v<V, double>) return floatText(v);
            else {
                std::string out;
                for (const double x : v) out += (out.empty() ? "[" : ", ") + floatText(x);
                return out + "]";
            }
        },
        value);
}

Error fileProblem(const std::string& name, const std::string& why, ErrorKind kind = ErrorKind::BadInput) {
    return Error{"settings " + name + ": " + why, kind, true};
}

}  // namespace

std::string SettingInfo::pythonName() const {
    std::string out = name;
    std::replace(out.begin(), out.end(), '-', '_');
    return out;
}

const std::vector<SettingInfo>& settingInfos() {
    static const std::vector<SettingInfo> table = makeTable();
    return table;
}

const SettingInfo* findSetting(std::string_view name) {
    for (const SettingInfo& info : settingInfos())
        if (info.name == name || info.pythonName() == name) return &info;
    return nullptr;
}

std::string expected(const SettingInfo& info) {
    const std::string range = std::to_string(info.min) + " to " + std::to_string(info.max);
    switch (info.kind) {
        case SettingKind::Switch:
            return "true or false";
        case SettingKind::Whole: {
            if (info.only.empty()) return "a whole number from " + range;
            std::string values;
            for (std::size_t i = 0; i < info.only.size(); ++i)
                values += (i == 0 ? "" : i + 1 == info.only.size() ? " or " : ", ") + std::to_string(info.only[i]);
            return values;
        }
        case SettingKind::Pair:
            return info.noun + " (" + info.metavar + ", each " + range + ")";
        case SettingKind::Choice: {
            std::string names;
            for (const ChoiceInfo& c : info.choices) names += (names.empty() ? "" : ", ") + std::string(c.name);
            return info.noun + " (" + names + ")";
        }
        case SettingKind::Colour:
            return "a colour (r,g,b or r,g,b,a, each 0 to 1)";
        case SettingKind::Real: {
            const auto bound = [](double v) {  // 1000000, not 1e+06
                return v == std::floor(v) && std::fabs(v) < 1e15 ? std::to_string(static_cast<long long>(v))
                                                                 : floatText(v);
            };
            return "a number from " + bound(info.low) + " to " + bound(info.high);
        }
        case SettingKind::Text:
            return "a path";
    }
    return {};
}

std::string setSetting(Settings& settings, const SettingInfo& info, const SettingValue& value) {
    std::string why = check(info, value);
    if (why.empty()) info.put(settings, value);
    return why;
}

std::optional<SettingValue> parseSettingText(const SettingInfo& info, std::string_view text) {
    switch (info.kind) {
        case SettingKind::Switch:
            if (text == "true" || text == "false") return text == "true";
            break;
        case SettingKind::Whole:
            if (long long v = 0; parseWhole(text, v)) return v;
            break;
        case SettingKind::Pair: {
            const std::size_t x = text.find('x');
            long long a = 0, b = 0;
            if (x != std::string_view::npos && parseWhole(text.substr(0, x), a) && parseWhole(text.substr(x + 1), b))
                return std::array<long long, 2>{a, b};
            break;
        }
        case SettingKind::Choice:
            return std::string(text);
        case SettingKind::Colour: {
            std::vector<double> c;
            std::size_t start = 0;
            while (true) {
                const std::size_t comma = text.find(',', start);
                double v = 0.0;
                if (!parseFinite(text.substr(start, comma == std::string_view::npos ? text.npos : comma - start), v))
                    return std::nullopt;
                c.push_back(v);
                if (comma == std::string_view::npos) break;
                start = comma + 1;
            }
            return c;
        }
        case SettingKind::Real:
            if (double v = 0.0; parseFinite(text, v)) return v;
            break;
        case SettingKind::Text:
            return std::string(text);
    }
    return std::nullopt;
}

std::string settingText(const SettingInfo& info, const SettingValue& value) {
    (void)info;
    return std::visit(
        [](const auto& v) -> std::string {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, bool>) return v ? "true" : "false";
            else if constexpr (std::is_same_v<V, long long>) return std::to_string(v);
            else if constexpr (std::is_same_v<V, std::array<long long, 2>>)
                return std::to_string(v[0]) + "x" + std::to_string(v[1]);
            else if constexpr (std::is_same_v<V, std::string>) return v;
            else if constexpr (std::is_same_v<V, double>) return floatText(v);
            else {
                std::string out;
                for (const double x : v) out += (out.empty() ? "" : ",") + floatText(x);
                return out;
            }
        },
        value);
}

const std::vector<SettingsConflict>& settingsConflicts() {
    static const std::vector<SettingsConflict> conflicts = [] {
        std::vector<SettingsConflict> out;
        for (const ConflictRule& rule : conflictRules()) out.push_back(rule.doc);
        return out;
    }();
    return conflicts;
}

std::optional<SettingsProblem> settingsProblem(const Settings& settings) {
    for (const SettingInfo& info : settingInfos())
        if (std::string why = check(info, info.get(settings)); !why.empty())
            return SettingsProblem{{info.name}, std::move(why), true};
    for (const ConflictRule& rule : conflictRules())
        if (const std::string_view why = rule.why(settings); !why.empty())
            return SettingsProblem{{rule.doc.first, rule.doc.second}, std::string(why), false};
    return std::nullopt;
}

std::string librarySpelling(const SettingInfo& info, const SettingValue& value) {
    if (info.kind == SettingKind::Switch && std::get<bool>(value)) return info.name;
    return info.name + " " + settingText(info, value);
}

std::string describe(const SettingsProblem& problem, const Settings& settings, const SettingSpelling& spell) {
    std::string head;
    for (const std::string& name : problem.settings) {
        const SettingInfo* info = findSetting(name);
        const std::string spelt = info ? spell(*info, info->get(settings)) : name;
        if (!spelt.empty()) head += (head.empty() ? "" : " with ") + spelt;  // a front end may leave one out
    }
    return head + (problem.value ? " " : ": ") + problem.why;
}

std::string setSettingJson(Settings& settings, const SettingInfo& info, std::string_view json) {
    Json value;
    try {
        value = Json::parse(json);
    } catch (const Json::exception&) {
        return std::string(json) + " is not JSON";
    }
    const std::optional<SettingValue> v = fromJson(info, value);
    const std::string why = v ? setSetting(settings, info, *v) : "is not " + expected(info);
    return why.empty() ? why : value.dump() + " " + why;
}

Result<SettingsFile> parseSettingsJson(std::string_view text, const std::string& name, const Settings& base) {
    Json doc;
    try {
        doc = Json::parse(text);
    } catch (const Json::exception& e) {
        return fileProblem(name, "not JSON (" + std::string(e.what()) + ")");
    }
    if (!doc.is_object())
        return fileProblem(name, "expected a JSON object of settings, got " + std::string(doc.type_name()));
    SettingsFile file{base, {}};
    for (const auto& [key, value] : doc.items()) {
        const auto info = std::find_if(settingInfos().begin(), settingInfos().end(),
                                       [&key = key](const SettingInfo& i) { return i.name == key; });
        if (info == settingInfos().end()) {
            std::string names;
            for (const SettingInfo& known : settingInfos()) names += (names.empty() ? "" : ", ") + known.name;
            return fileProblem(name, "'" + key + "' is not a setting (" + names + ")");
        }
        if (const std::string why = setSettingJson(file.settings, *info, value.dump()); !why.empty())
            return fileProblem(name, "key '" + key + "': " + why);
        file.keys.push_back(key);
    }
    return file;
}

Result<SettingsFile> readSettingsFile(const std::string& path, const Settings& base) {
    const std::optional<std::string> text = readFile(path);
    if (!text) return fileProblem(path, "cannot read the file", ErrorKind::Io);
    return parseSettingsJson(*text, path, base);
}

std::string settingsJson(const Settings& settings) {
    std::string out = "{\n";
    const std::vector<SettingInfo>& infos = settingInfos();
    for (std::size_t i = 0; i < infos.size(); ++i)
        out += "  \"" + infos[i].name + "\": " + jsonText(infos[i].get(settings)) + (i + 1 < infos.size() ? ",\n" : "\n");
    return out + "}\n";
}

}  // namespace frugal
