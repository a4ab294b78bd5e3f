// A command's flags as one declarative table: each flag's name, the value it takes, its help, and
// how it sets its value. The argument loop (app/Command.h) parses with it and the help is printed
// from it, so every command refuses a bad value with the same shape of line,
//
//   error: --cull: 'x' is not a method (none, sphere, backface, cones, paper, conservative, occlusion, occlusion-ahead, oracle)
//
// and lists its flags the same way. Why not CLI11 (Debian libcli11-dev): a parser made with it
// compiles many times slower and its object is many times larger (docs/architecture.md), and its
// messages ("--cull: wat not in {none,sphere,...}" and a second line) would each
// need a validator and a formatter of our own to get this shape.
#pragma once

#include <array>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Settings.h>

namespace frugal {

struct FrameRange;

// One flag. `set` gets the value (a switch gets "") and returns "" or why it is refused, as the end
// of "error: <name>: '<value>' <why>" ("is not a method (none, sphere, ...)").
struct Flag {
    std::string name;   // "--cull", or "-o, --output" (every spelling, the last the one messages use)
    std::string value;  // what it takes, "METHOD"; empty for a switch
    std::string help;   // one paragraph, wrapped when printed; with '\n' in it, lines laid out by hand
    std::function<std::string(const std::string& value)> set;
    // Values it takes (--ids A B: 2). With 2, `set` gets both joined by '\0' (no argument holds one)
    // and a refusal reads "error: <name>: <why>".
    int arity = 1;
    // The names it takes, each listed under the help with what it is (a setting's choices).
    std::vector<ChoiceInfo> choices = {};

    bool matches(const std::string& spelling) const;
    std::string canonical() const;  // the last spelling: "--output"
};

struct FlagGroup {
    std::string title;  // "culling (only the triangles that may be visible are submitted)", or "" for none
    std::vector<Flag> flags;
};

// The help of `groups`: each flag on its line, "  --cull METHOD         <help wrapped at 100
// columns, continued at column 24>", groups headed by their titles.
std::string flagsHelp(const std::vector<FlagGroup>& groups);

// The flag of setting `name` (frugal/Settings.h's schema: `--<name>`, its value, help and choices),
// setting it in `settings` and adding the name to `given` (which settings the command line gave).
// `help`, when given, replaces the schema's paragraph (a command that uses the setting its own way);
// a refused value reads "error: --<name>: '<value>' is not <expected(info)>".
Flag settingFlag(std::string_view name, Settings& settings, std::vector<std::string>& given, std::string help = {});

// Builders of the usual kinds. Each sets `target` from the value or refuses it:
namespace flag {

// A switch: sets `target` to `value`.
Flag on(std::string name, std::string help, bool& target, bool value = true);

// One of `values` by its name (toString), into `target` (a T or an optional<T>): "'x' is not a
// <noun> (a, b, c)".
template <class Target, class T, std::size_t N>
Flag choice(std::string name, std::string value, std::string noun, std::string help, Target& target,
            const std::array<T, N>& values) {
    return {std::move(name), std::move(value), std::move(help),
            [&target, &values, noun = std::move(noun)](const std::string& text) -> std::string {
                if (const std::optional<T> v = fromString(text, values)) {
                    target = *v;
                    return {};
                }
                return "is not " + noun + " (" + namesOf(values) + ")";
            }};
}

// Reads a whole number in [lo, hi] into `v`: "" or why not ("is not a whole number from lo to hi").
std::string readWhole(const std::string& text, long long lo, long long hi, long long& v);

template <class T> struct WholeOf { using type = T; };
template <class T> struct WholeOf<std::optional<T>> { using type = T; };

// A whole number in [lo, hi] into an integer or an optional one: "'x' is not a whole number from lo to hi".
// `given`, when set, becomes true once the flag is seen (a command whose flags exclude each other).
template <class T>
Flag whole(std::string name, std::string value, std::string help, T& target, long long lo, long long hi,
           bool* given = nullptr) {
    return {std::move(name), std::move(value), std::move(help), [&target, lo, hi, given](const std::string& text) {
                if (given) *given = true;
                long long v = 0;
                std::string why = readWhole(text, lo, hi, v);
                if (why.empty()) target = static_cast<typename WholeOf<T>::type>(v);
                return why;
            }};
}
// A number in [lo, hi]: "'x' is not a number from lo to hi".
Flag number(std::string name, std::string value, std::string help, double& target, double lo, double hi);
Flag number(std::string name, std::string value, std::string help, std::optional<double>& target, double lo, double hi);
Flag number(std::string name, std::string value, std::string help, std::optional<float>& target, double lo, double hi);
// A non-empty text (a file name, a spec): "'' is not a file name".
Flag text(std::string name, std::string value, std::string help, std::string& target, std::string noun = "a file name");
// Width × height, each in [1, max]: "'x' is not a size (WxH, each 1 to max)".
Flag size(std::string name, std::string value, std::string help, int& width, int& height, int max,
          bool* given = nullptr);
// x,y,z of three finite numbers: "'x' is not a point (x,y,z: three finite numbers)".
Flag point(std::string name, std::string value, std::string help, std::optional<glm::vec3>& target);
Flag point(std::string name, std::string value, std::string help, glm::vec3& target);
// Comma-separated whole numbers, each in [lo, hi]: "'x' is not a list of whole numbers from lo to hi".
Flag wholeList(std::string name, std::string value, std::string help, std::vector<int>& target, int lo, int hi);
// Two non-empty values into `first` and `second` (arity 2); `why` is the refusal.
Flag two(std::string name, std::string value, std::string help, std::string& first, std::string& second,
         std::string why);
// A:B, 0 ≤ A ≤ B, at most 1,000,000 frames: "'x' is not a frame range (A:B, 0 <= A <= B, ...)".
Flag frames(std::string name, std::string help, std::optional<FrameRange>& target);

}  // namespace flag

}  // namespace frugal
