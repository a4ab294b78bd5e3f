// frugal.Renderer's keyword arguments, read and written through the library's schema
// (frugal/Settings.h): each kind of value once, every setting from the table.
#include "Settings.h"

#include <string>

#include "Arrays.h"
#include "Bindings.h"

namespace frugal::python {

namespace {

std::string shown(const py::handle& value) { return py::repr(value).cast<std::string>(); }

// A Python value as the setting's value, by its kind alone (nothing: not of the kind). Pairs are
// (a, b), [a, b] or "AxB"; colours a sequence of 3 or 4 numbers.
std::optional<SettingValue> valueOf(const SettingInfo& info, const py::handle& v) {
    const auto isInt = [](const py::handle& x) { return py::isinstance<py::int_>(x) && !py::isinstance<py::bool_>(x); };
    const auto wholeOf = [](const py::handle& x) -> std::optional<long long> {
        try {
            return x.cast<long long>();
        } catch (const py::cast_error&) {
            return std::nullopt;  // beyond 64 bits: out of every range
        }
    };
    switch (info.kind) {
        case SettingKind::Switch:
            if (py::isinstance<py::bool_>(v)) return v.cast<bool>();
            break;
        case SettingKind::Whole:
            if (isInt(v))
                if (const std::optional<long long> w = wholeOf(v)) return *w;
            break;
        case SettingKind::Pair:
            if (py::isinstance<py::str>(v)) return parseSettingText(info, v.cast<std::string>());
            if (py::isinstance<py::sequence>(v) && py::len(v) == 2) {
                const py::sequence items = py::reinterpret_borrow<py::sequence>(v);
                if (isInt(items[0]) && isInt(items[1]))
                    if (const auto a = wholeOf(items[0]), b = wholeOf(items[1]); a && b)
                        return std::array<long long, 2>{*a, *b};
            }
            break;
        case SettingKind::Choice:
            if (py::isinstance<py::str>(v)) return v.cast<std::string>();
            break;
        case SettingKind::Colour:
            if (py::isinstance<py::sequence>(v) && !py::isinstance<py::str>(v)) {
                std::vector<double> c;
                for (const py::handle x : py::reinterpret_borrow<py::sequence>(v)) {
                    if (py::isinstance<py::bool_>(x) || !(py::isinstance<py::int_>(x) || py::isinstance<py::float_>(x)))
                        return std::nullopt;
                    c.push_back(x.cast<double>());
                }
                return c;
            }
            break;
        case SettingKind::Real:
            if (py::isinstance<py::float_>(v) || isInt(v)) return v.cast<double>();
            break;
        case SettingKind::Text:
            if (py::isinstance<py::str>(v)) return v.cast<std::string>();
            if (py::hasattr(v, "__fspath__")) return py::str(v.attr("__fspath__")()).cast<std::string>();
            break;
    }
    return std::nullopt;
}

py::object pythonValue(const SettingValue& value) {
    return std::visit(
        [](const auto& v) -> py::object {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, std::array<long long, 2>>) return py::make_tuple(v[0], v[1]);
            else if constexpr (std::is_same_v<V, std::vector<double>>) {
                py::tuple t(v.size());
                for (std::size_t i = 0; i < v.size(); ++i) t[i] = py::float_(double(float(v[i])));
                return t;
            } else if constexpr (std::is_same_v<V, double>) return py::float_(double(float(v)));
            else return py::cast(v);
        },
        value);
}

// A setting as Python spells it: "cull='oracle'", "reuse=True".
std::string pythonSpelling(const SettingInfo& info, const SettingValue& value) {
    return info.pythonName() + "=" + shown(pythonValue(value));
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
        const SettingInfo* info = findSetting(name);
        if (!info || info->pythonName() != name) {
            std::string names;
            for (const SettingInfo& known : settingInfos()) {  // appended, not `a + b`: GCC 12's LTO warns of
                if (!names.empty()) names += ", ";               // that (-Wstringop-overflow, a false alarm)
                names += known.pythonName();
            }
            throw InputError{"unknown setting '" + name + "' (" + names + ")"};
        }
        const std::optional<SettingValue> v = valueOf(*info, value);
        if (const std::string why = v ? setSetting(settings, *info, *v) : "is not " + expected(*info); !why.empty())
            throw InputError{name + ": " + shown(value) + " " + why};
    }
    if (const std::optional<SettingsProblem> problem = settingsProblem(settings))
        throw InputError{describe(*problem, settings, pythonSpelling)};
    return settings;
}

py::list settingsSchema() {
    const char* const kinds[] = {"switch", "whole", "pair", "choice", "colour", "real", "text"};
    const Settings defaults;
    py::list out;
    for (const SettingInfo& info : settingInfos()) {
        py::dict d;
        d["name"] = info.pythonName();
        d["option"] = info.flag ? py::object(py::str("--" + info.name)) : py::object(py::none());
        d["key"] = info.name;
        d["kind"] = kinds[std::size_t(info.kind)];
        d["default"] = pythonValue(info.get(defaults));
        d["help"] = info.help;
        py::list choices;
        for (const ChoiceInfo& c : info.choices) choices.append(py::str(std::string(c.name)));
        d["choices"] = choices;
        d["range"] = info.kind == SettingKind::Whole || info.kind == SettingKind::Pair
                         ? py::object(py::make_tuple(info.min, info.max))
                     : info.kind == SettingKind::Real ? py::object(py::make_tuple(info.low, info.high))
                                                      : py::object(py::none());
        d["expected"] = expected(info);
        py::list conflicts;
        for (const SettingsConflict& c : settingsConflicts())
            if (c.first == info.name || c.second == info.name)
                conflicts.append(py::str(findSetting(c.first == info.name ? c.second : c.first)->pythonName()));
        d["conflicts"] = conflicts;
        out.append(d);
    }
    return out;
}

py::dict settingsDict(const Settings& s) {
    py::dict d;
    for (const SettingInfo& info : settingInfos()) d[py::str(info.pythonName())] = pythonValue(info.get(s));
    return d;
}

}  // namespace frugal::python
