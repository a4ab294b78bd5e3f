#include "app/Flags.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "app/Options.h"
#include "base/Format.h"

namespace frugal {

namespace {

// The flag's spellings: "-o, --output" → {"-o", "--output"}.
std::vector<std::string> spellings(const std::string& name) {
    std::vector<std::string> out;
    std::stringstream in(name);
    std::string part;
    while (std::getline(in, part, ',')) {
        part.erase(0, part.find_first_not_of(' '));
        if (!part.empty()) out.push_back(part);
    }
    return out;
}

bool parseWhole(std::string_view text, int& out) {
    auto [stop, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    return !text.empty() && ec == std::errc() && stop == text.data() + text.size();
}

bool parseFinite(std::string_view text, double& out) {
    const char* begin = text.data();
    const char* end = begin + text.size();
    if (begin != end && *begin == '+') ++begin;
    auto [stop, ec] = std::from_chars(begin, end, out);
    return begin != end && ec == std::errc() && stop == end && std::isfinite(out);
}

// Comma-separated finite numbers, exactly `count` of them.
bool parseNumbers(const std::string& text, std::size_t count, std::vector<double>& out) {
    out.clear();
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        double v = 0.0;
        if (!parseFinite(std::string_view(text).substr(start, comma == std::string::npos ? std::string::npos : comma - start), v))
            return false;
        out.push_back(v);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return out.size() == count;
}

std::string range(double lo, double hi) { return "from " + fmt(lo) + " to " + fmt(hi); }

}  // namespace

bool Flag::matches(const std::string& spelling) const {
    const std::vector<std::string> names = spellings(name);
    return std::find(names.begin(), names.end(), spelling) != names.end();
}

std::string Flag::canonical() const { return spellings(name).back(); }

namespace {

// `words` wrapped at column kWidth after `line` (which the first words continue), the lines after
// it indented by `indent`. A word too long for a line (a JSON shape) breaks after its commas.
constexpr std::size_t kColumn = 24, kWidth = 100;
std::string wrap(std::string line, const std::string& words, std::size_t indent) {
    std::string out;
    std::stringstream in(words);
    std::string word;
    bool first = true;
    while (in >> word) {
        std::size_t start = 0;
        while (start < word.size()) {
            std::size_t end = word.size();
            if (end - start > kWidth - indent) {
                const std::size_t comma = word.rfind(',', start + (kWidth - indent) - 1);
                if (comma != std::string::npos && comma >= start) end = comma + 1;
            }
            const std::string piece = word.substr(start, end - start);
            const bool glued = start > 0;  // continues the word: no space before it
            if (!first && line.size() + (glued ? 0 : 1) + piece.size() > kWidth) {
                out += line + "\n";
                line = std::string(indent, ' ');
                first = true;
            }
            line += (first || glued ? "" : " ") + piece;
            first = false;
            start = end;
        }
    }
    return out + line + "\n";
}

}  // namespace

std::string flagsHelp(const std::vector<FlagGroup>& groups) {
    std::string out;
    for (const FlagGroup& group : groups) {
        if (group.flags.empty()) continue;
        out += "\n" + (group.title.empty() ? "" : group.title + ":\n");
        for (const Flag& f : group.flags) {
            std::string line = "  " + f.name + (f.value.empty() ? "" : " " + f.value);
            // A name longer than the column puts the help on the next line.
            if (line.size() + 2 > kColumn) {
                out += line + "\n";
                line.clear();
            }
            line.resize(kColumn, ' ');
            if (f.help.find('\n') != std::string::npos) {
                // Laid out by hand: each line as it is, at the column.
                std::stringstream lines(f.help);
                std::string text;
                for (bool first = true; std::getline(lines, text); first = false)
                    out += (first ? line : std::string(kColumn, ' ')) + text + "\n";
            } else {
                // A list of values follows the words after a colon.
                const bool colon = !f.choices.empty() && !f.help.empty() && f.help.back() != ':';
                out += wrap(line, f.help + (colon ? ":" : ""), kColumn);
            }
            // The values it takes, one a line: the name, then what it is, wrapped beside it.
            std::size_t nameWidth = 0;
            for (const ChoiceInfo& c : f.choices) nameWidth = std::max(nameWidth, c.name.size());
            for (const ChoiceInfo& c : f.choices) {
                std::string head = std::string(kColumn + 2, ' ') + std::string(c.name);
                head.resize(kColumn + 2 + nameWidth + 2, ' ');
                out += wrap(head, std::string(c.summary), kColumn + 2 + nameWidth + 2);
            }
        }
    }
    return out;
}

Flag settingFlag(std::string_view name, Settings& settings, std::vector<std::string>& given, std::string help) {
    const SettingInfo* info = findSetting(name);
    if (!info) throw std::logic_error("settingFlag: no setting '" + std::string(name) + "'");
    Flag f{"--" + info->name, info->kind == SettingKind::Switch ? "" : info->metavar,
           help.empty() ? info->help : std::move(help),
           [info, &settings, &given](const std::string& text) -> std::string {
               const std::optional<SettingValue> value =
                   info->kind == SettingKind::Switch ? SettingValue(true) : parseSettingText(*info, text);
               std::string why = value ? setSetting(settings, *info, *value) : "is not " + expected(*info);
               if (why.empty() && std::find(given.begin(), given.end(), info->name) == given.end())
                   given.push_back(info->name);
               return why;
           }};
    f.choices = info->choices;
    return f;
}

namespace flag {

Flag on(std::string name, std::string help, bool& target, bool value) {
    return {std::move(name), "", std::move(help), [&target, value](const std::string&) -> std::string {
                target = value;
                return {};
            }};
}

std::string readWhole(const std::string& text, long long lo, long long hi, long long& v) {
    auto [stop, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc() || stop != text.data() + text.size() || v < lo || v > hi)
        return "is not a whole number from " + std::to_string(lo) + " to " + std::to_string(hi);
    return {};
}

namespace {
// Reads a number in [lo, hi] into `v`: "" or why not.
std::string readNumber(const std::string& text, double lo, double hi, double& v) {
    if (!parseFinite(text, v) || v < lo || v > hi) return "is not a number " + range(lo, hi);
    return {};
}
}  // namespace

namespace {
// A number in [lo, hi], handed to `set` when it is one.
Flag numberInto(std::string name, std::string value, std::string help, double lo, double hi,
                std::function<void(double)> set) {
    return {std::move(name), std::move(value), std::move(help), [set = std::move(set), lo, hi](const std::string& text) {
                double v = 0.0;
                std::string why = readNumber(text, lo, hi, v);
                if (why.empty()) set(v);
                return why;
            }};
}
}  // namespace

Flag number(std::string name, std::string value, std::string help, double& target, double lo, double hi) {
    return numberInto(std::move(name), std::move(value), std::move(help), lo, hi, [&target](double v) { target = v; });
}
Flag number(std::string name, std::string value, std::string help, std::optional<double>& target, double lo, double hi) {
    return numberInto(std::move(name), std::move(value), std::move(help), lo, hi, [&target](double v) { target = v; });
}
Flag number(std::string name, std::string value, std::string help, std::optional<float>& target, double lo, double hi) {
    return numberInto(std::move(name), std::move(value), std::move(help), lo, hi,
                      [&target](double v) { target = float(v); });
}

Flag text(std::string name, std::string value, std::string help, std::string& target, std::string noun) {
    return {std::move(name), std::move(value), std::move(help),
            [&target, noun = std::move(noun)](const std::string& text) -> std::string {
                if (text.empty()) return "is not " + noun;
                target = text;
                return {};
            }};
}

Flag size(std::string name, std::string value, std::string help, int& width, int& height, int max, bool* given) {
    return {std::move(name), std::move(value), std::move(help),
            [&width, &height, max, given](const std::string& text) -> std::string {
                int w = 0, h = 0;
                if (!parseIntPair(text, w, h) || w < 1 || h < 1 || w > max || h > max)
                    return "is not a size (WxH, each 1 to " + std::to_string(max) + ")";
                width = w;
                height = h;
                if (given) *given = true;
                return {};
            }};
}

Flag point(std::string name, std::string value, std::string help, std::optional<glm::vec3>& target) {
    return {std::move(name), std::move(value), std::move(help), [&target](const std::string& text) -> std::string {
                std::vector<double> v;
                if (!parseNumbers(text, 3, v)) return "is not a point (x,y,z: three finite numbers)";
                target = glm::vec3(float(v[0]), float(v[1]), float(v[2]));
                return {};
            }};
}

Flag point(std::string name, std::string value, std::string help, glm::vec3& target) {
    return {std::move(name), std::move(value), std::move(help), [&target](const std::string& text) -> std::string {
                std::vector<double> v;
                if (!parseNumbers(text, 3, v)) return "is not a point (x,y,z: three finite numbers)";
                target = glm::vec3(float(v[0]), float(v[1]), float(v[2]));
                return {};
            }};
}

Flag wholeList(std::string name, std::string value, std::string help, std::vector<int>& target, int lo, int hi) {
    return {std::move(name), std::move(value), std::move(help), [&target, lo, hi](const std::string& text) -> std::string {
                std::vector<int> values;
                std::size_t start = 0;
                while (true) {
                    const std::size_t comma = text.find(',', start);
                    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
                    long long v = 0;
                    if (!readWhole(item, lo, hi, v).empty())
                        return "is not a list of whole numbers from " + std::to_string(lo) + " to " + std::to_string(hi);
                    values.push_back(int(v));
                    if (comma == std::string::npos) break;
                    start = comma + 1;
                }
                target = std::move(values);
                return {};
            }};
}

Flag two(std::string name, std::string value, std::string help, std::string& first, std::string& second,
         std::string why) {
    Flag f{std::move(name), std::move(value), std::move(help),
           [&first, &second, why = std::move(why)](const std::string& text) -> std::string {
               const std::size_t split = text.find('\0');
               const std::string a = text.substr(0, split);
               const std::string b = split == std::string::npos ? std::string() : text.substr(split + 1);
               if (a.empty() || b.empty() || b[0] == '-') return why;
               first = a;
               second = b;
               return {};
           }};
    f.arity = 2;
    return f;
}

Flag frames(std::string name, std::string help, std::optional<FrameRange>& target) {
    return {std::move(name), "A:B", std::move(help), [&target](const std::string& text) -> std::string {
                const std::size_t colon = text.find(':');
                FrameRange r;
                r.sequence = true;
                if (colon == std::string::npos || !parseWhole(std::string_view(text).substr(0, colon), r.first) ||
                    !parseWhole(std::string_view(text).substr(colon + 1), r.last) || r.first < 0 || r.last < r.first ||
                    r.last - r.first >= 1000000)
                    return "is not a frame range (A:B, first and last frame: 0 <= A <= B, at most 1000000 frames)";
                target = r;
                return {};
            }};
}

}  // namespace flag

}  // namespace frugal
