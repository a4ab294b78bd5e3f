#include "Settings.h"

#include <functional>
#include <map>
#include <string>

#include "Arrays.h"
#include "Bindings.h"

namespace frugal::python {

namespace {

std::string shown(const py::handle& value) { return py::repr(value).cast<std::string>(); }

template <class T, std::size_t N>
T choice(const py::handle& value, const char* name, const std::array<T, N>& values, const char* noun) {
    if (!py::isinstance<py::str>(value))
        throw InputError{std::string(name) + ": expected a string, one of " + namesOf(values) + ", got " + shown(value)};
    const std::string text = value.cast<std::string>();
    if (const std::optional<T> v = fromString(text, values)) return *v;
    throw InputError{std::string(name) + ": '" + text + "' is not " + noun + " (" + namesOf(values) + ")"};
}

bool flag(const py::handle& value, const char* name) {
    if (!py::isinstance<py::bool_>(value)) throw InputError{std::string(name) + ": expected True or False, got " + shown(value)};
    return value.cast<bool>();
}

int integer(const py::handle& value, const char* name) {
    if (py::isinstance<py::bool_>(value) || !py::isinstance<py::int_>(value))
        throw InputError{std::string(name) + ": expected an integer, got " + shown(value)};
    const long long v = value.cast<long long>();
    if (v < -(1LL << 30) || v > (1LL << 30)) throw InputError{std::string(name) + ": " + std::to_string(v) + " is out of range"};
    return int(v);
}

// (a, b), [a, b] or "AxB" (as the command line takes it).
std::pair<int, int> pairOf(const py::handle& value, const char* name, const char* form) {
    const std::string expected = std::string(name) + ": expected " + form + ", got " + shown(value);
    if (py::isinstance<py::str>(value)) {
        const std::string text = value.cast<std::string>();
        const std::size_t x = text.find('x');
        try {
            std::size_t used1 = 0, used2 = 0;
            if (x == std::string::npos) throw InputError{expected};
            const int a = std::stoi(text.substr(0, x), &used1), b = std::stoi(text.substr(x + 1), &used2);
            if (used1 != x || used2 != text.size() - x - 1) throw InputError{expected};
            return {a, b};
        } catch (const std::logic_error&) {
            throw InputError{expected};
        }
    }
    if (!py::isinstance<py::sequence>(value) || py::len(value) != 2) throw InputError{expected};
    const py::sequence items = py::reinterpret_borrow<py::sequence>(value);
    return {integer(items[0], name), integer(items[1], name)};
}

using Setter = std::function<void(Settings&, const py::handle&)>;

const std::map<std::string, Setter>& setters() {
    static const std::map<std::string, Setter> table = {
        {"size",
         [](Settings& s, const py::handle& v) { std::tie(s.width, s.height) = pairOf(v, "size", "(width, height) or 'WxH'"); }},
        {"backend", [](Settings& s, const py::handle& v) { s.backend = choice(v, "backend", kBackendKinds, "a backend"); }},
        {"threads", [](Settings& s, const py::handle& v) { s.threads = integer(v, "threads"); }},
        {"interp", [](Settings& s, const py::handle& v) { s.interp = choice(v, "interp", kDepthInterps, "a mode"); }},
        {"cull", [](Settings& s, const py::handle& v) { s.cull = choice(v, "cull", kCulls, "a method"); }},
        {"cull_bins",
         [](Settings& s, const py::handle& v) {
             std::tie(s.cullBinsTheta, s.cullBinsPhi) = pairOf(v, "cull_bins", "(polar, azimuthal) or 'TxP'");
         }},
        {"order", [](Settings& s, const py::handle& v) { s.order = choice(v, "order", kOrders, "an order"); }},
        {"refine_costs", [](Settings& s, const py::handle& v) { s.refineCosts = integer(v, "refine_costs"); }},
        {"reuse", [](Settings& s, const py::handle& v) { s.reuse = flag(v, "reuse"); }},
        {"reuse_grain", [](Settings& s, const py::handle& v) { s.reuseSettings.grain = integer(v, "reuse_grain"); }},
        {"reuse_cell", [](Settings& s, const py::handle& v) { s.reuseSettings.cell = integer(v, "reuse_cell"); }},
        {"no_fallback", [](Settings& s, const py::handle& v) { s.reuseSettings.fallback = !flag(v, "no_fallback"); }},
        {"exact_static", [](Settings& s, const py::handle& v) { s.reuseSettings.exactStatic = flag(v, "exact_static"); }},
        {"hsr", [](Settings& s, const py::handle& v) { s.hsr = choice(v, "hsr", kHsrs, "a mode"); }},
        {"depth_format",
         [](Settings& s, const py::handle& v) { s.depthFormat = choice(v, "depth_format", kDepthFormats, "a format"); }},
        {"background", [](Settings& s, const py::handle& v) { s.background = colorFrom(v, "background"); }},
        {"ids", [](Settings& s, const py::handle& v) { s.ids = flag(v, "ids"); }},
    };
    return table;
}

}  // namespace

Settings settingsFrom(const py::kwargs& kwargs) {
    Settings settings;
    if (kwargs.contains("settings")) {  // a settings file first: the other keyword arguments win
        const py::object path = py::module_::import("os").attr("fspath")(kwargs["settings"]);
        settings = take(readSettingsFile(path.cast<std::string>())).settings;
    }
    for (const auto& [key, value] : kwargs) {
        const std::string name = key.cast<std::string>();
        if (name == "settings") continue;
        const auto setter = setters().find(name);
        if (setter == setters().end()) {
            std::string names;
            for (const auto& [known, unused] : setters()) names += (names.empty() ? "" : ", ") + known;
            throw InputError{"unknown setting '" + name + "' (" + names + ")"};
        }
        setter->second(settings, value);
    }
    return settings;
}

py::dict settingsDict(const Settings& s) {
    py::dict d;
    d["size"] = py::make_tuple(s.width, s.height);
    d["backend"] = toString(s.backend);
    d["threads"] = s.threads;
    d["interp"] = toString(s.interp);
    d["cull"] = toString(s.cull);
    d["cull_bins"] = py::make_tuple(s.cullBinsTheta, s.cullBinsPhi);
    d["order"] = toString(s.order);
    d["refine_costs"] = s.refineCosts;
    d["reuse"] = s.reuse;
    d["reuse_grain"] = s.reuseSettings.grain;
    d["reuse_cell"] = s.reuseSettings.cell;
    d["no_fallback"] = !s.reuseSettings.fallback;
    d["exact_static"] = s.reuseSettings.exactStatic;
    d["hsr"] = toString(s.hsr);
    d["depth_format"] = toString(s.depthFormat);
    d["background"] = py::make_tuple(s.background.r, s.background.g, s.background.b, s.background.a);
    d["ids"] = s.ids;
    return d;
}

}  // namespace frugal::python
