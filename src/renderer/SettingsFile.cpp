// Settings files (frugal/Settings.h): the settings by their command-line names, in JSON.
#include <charconv>
#include <functional>

#include <nlohmann/json.hpp>

#include <frugal/Settings.h>

#include "io/ImageIO.h"

namespace frugal {
namespace {

using Json = nlohmann::json;

// Sets one field from a JSON value: "" or why not (the end of "key 'cull': <why>").
using Setter = std::function<std::string(Settings&, const Json&)>;

std::string shown(const Json& value) { return value.dump(); }

template <class T, std::size_t N>
Setter choice(T Settings::*field, const std::array<T, N>& values, const char* noun) {
    return [field, &values, noun](Settings& s, const Json& v) -> std::string {
        if (v.is_string())
            if (const std::optional<T> parsed = fromString(v.get<std::string>(), values)) {
                s.*field = *parsed;
                return {};
            }
        return shown(v) + " is not " + noun + " (" + namesOf(values) + ")";
    };
}

// A whole number into `to`.
std::string whole(const Json& v, int& to) {
    if (!v.is_number_integer() || v.get<long long>() < -(1LL << 30) || v.get<long long>() > (1LL << 30))
        return shown(v) + " is not a whole number";
    to = int(v.get<long long>());
    return {};
}

std::string flag(const Json& v, bool& to) {
    if (!v.is_boolean()) return shown(v) + " is not true or false";
    to = v.get<bool>();
    return {};
}

// [a, b] or "AxB".
std::string pair(const Json& v, int& a, int& b, const char* form) {
    const std::string why = shown(v) + " is not " + form;
    if (v.is_array() && v.size() == 2) return whole(v[0], a).empty() && whole(v[1], b).empty() ? "" : why;
    if (!v.is_string()) return why;
    const std::string text = v.get<std::string>();
    const std::size_t x = text.find('x');
    if (x == std::string::npos) return why;
    const auto read = [&text](std::size_t from, std::size_t to, int& out) {
        const auto [end, error] = std::from_chars(text.data() + from, text.data() + to, out);
        return error == std::errc() && end == text.data() + to && to > from;
    };
    return read(0, x, a) && read(x + 1, text.size(), b) ? "" : why;
}

std::string colour(const Json& v, glm::vec4& to) {
    const std::string why = shown(v) + " is not a colour ([r, g, b] or [r, g, b, a], each 0 to 1)";
    if (!v.is_array() || (v.size() != 3 && v.size() != 4)) return why;
    glm::vec4 c(1.0f);
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (!v[i].is_number() || !(v[i].get<double>() >= 0.0 && v[i].get<double>() <= 1.0)) return why;
        c[int(i)] = float(v[i].get<double>());
    }
    to = c;
    return {};
}

// One setter a name of kSettingNames (a test checks they are the same).
const std::vector<std::pair<std::string, Setter>>& setters() {
    static const std::vector<std::pair<std::string, Setter>> table = {
        {"size", [](Settings& s, const Json& v) { return pair(v, s.width, s.height, "[width, height] or \"WxH\""); }},
        {"backend", choice(&Settings::backend, kBackendKinds, "a backend")},
        {"threads", [](Settings& s, const Json& v) { return whole(v, s.threads); }},
        {"interp", choice(&Settings::interp, kDepthInterps, "a mode")},
        {"cull", choice(&Settings::cull, kCulls, "a method")},
        {"cull-bins",
         [](Settings& s, const Json& v) {
             return pair(v, s.cullBinsTheta, s.cullBinsPhi, "[polar, azimuthal] or \"TxP\"");
         }},
        {"order", choice(&Settings::order, kOrders, "an order")},
        {"refine-costs", [](Settings& s, const Json& v) { return whole(v, s.refineCosts); }},
        {"reuse", [](Settings& s, const Json& v) { return flag(v, s.reuse); }},
        {"reuse-grain", [](Settings& s, const Json& v) { return whole(v, s.reuseSettings.grain); }},
        {"reuse-cell", [](Settings& s, const Json& v) { return whole(v, s.reuseSettings.cell); }},
        {"no-fallback",
         [](Settings& s, const Json& v) {
             bool off = !s.reuseSettings.fallback;
             const std::string why = flag(v, off);
             s.reuseSettings.fallback = !off;
             return why;
         }},
        {"exact-static", [](Settings& s, const Json& v) { return flag(v, s.reuseSettings.exactStatic); }},
        {"hsr", choice(&Settings::hsr, kHsrs, "a mode")},
        {"depth-format", choice(&Settings::depthFormat, kDepthFormats, "a format")},
        {"background", [](Settings& s, const Json& v) { return colour(v, s.background); }},
        {"ids", [](Settings& s, const Json& v) { return flag(v, s.ids); }},
    };
    return table;
}

Error problem(const std::string& name, const std::string& why, ErrorKind kind = ErrorKind::BadInput) {
    return Error{"settings " + name + ": " + why, kind, true};
}

}  // namespace

Result<SettingsFile> parseSettingsJson(std::string_view text, const std::string& name, const Settings& base) {
    Json doc;
    try {
        doc = Json::parse(text);
    } catch (const Json::exception& e) {
        return problem(name, "not JSON (" + std::string(e.what()) + ")");
    }
    if (!doc.is_object()) return problem(name, "expected a JSON object of settings, got " + std::string(doc.type_name()));
    SettingsFile file{base, {}};
    for (const auto& [key, value] : doc.items()) {
        const auto setter = std::find_if(setters().begin(), setters().end(),
                                         [&key = key](const auto& entry) { return entry.first == key; });
        if (setter == setters().end()) {
            std::string names;
            for (const char* known : kSettingNames) names += (names.empty() ? "" : ", ") + std::string(known);
            return problem(name, "'" + key + "' is not a setting (" + names + ")");
        }
        if (const std::string why = setter->second(file.settings, value); !why.empty())
            return problem(name, "key '" + key + "': " + why);
        file.keys.push_back(key);
    }
    return file;
}

Result<SettingsFile> readSettingsFile(const std::string& path, const Settings& base) {
    const std::optional<std::string> text = readWholeFile(path);
    if (!text) return problem(path, "cannot read the file", ErrorKind::Io);
    return parseSettingsJson(*text, path, base);
}

std::string settingsJson(const Settings& s) {
    const auto number = [](float v) {
        char buffer[32];
        const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, v);  // shortest, round-trips
        return std::string(buffer, error == std::errc() ? end : buffer);
    };
    const auto line = [](const char* key, const std::string& value) { return "  \"" + std::string(key) + "\": " + value; };
    const auto text = [](const char* v) { return "\"" + std::string(v) + "\""; };
    const auto truth = [](bool v) { return std::string(v ? "true" : "false"); };
    const std::vector<std::string> lines = {
        line("size", "[" + std::to_string(s.width) + ", " + std::to_string(s.height) + "]"),
        line("backend", text(toString(s.backend))),
        line("threads", std::to_string(s.threads)),
        line("interp", text(toString(s.interp))),
        line("cull", text(toString(s.cull))),
        line("cull-bins", "[" + std::to_string(s.cullBinsTheta) + ", " + std::to_string(s.cullBinsPhi) + "]"),
        line("order", text(toString(s.order))),
        line("refine-costs", std::to_string(s.refineCosts)),
        line("reuse", truth(s.reuse)),
        line("reuse-grain", std::to_string(s.reuseSettings.grain)),
        line("reuse-cell", std::to_string(s.reuseSettings.cell)),
        line("no-fallback", truth(!s.reuseSettings.fallback)),
        line("exact-static", truth(s.reuseSettings.exactStatic)),
        line("hsr", text(toString(s.hsr))),
        line("depth-format", text(toString(s.depthFormat))),
        line("background", "[" + number(s.background.r) + ", " + number(s.background.g) + ", " + number(s.background.b) +
                               ", " + number(s.background.a) + "]"),
        line("ids", truth(s.ids)),
    };
    std::string out = "{\n";
    for (std::size_t i = 0; i < lines.size(); ++i) out += lines[i] + (i + 1 < lines.size() ? ",\n" : "\n");
    return out + "}\n";
}

}  // namespace frugal
