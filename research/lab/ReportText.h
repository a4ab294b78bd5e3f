// How the reports (CullReport, ReuseReport) write their JSON, CSV and gnuplot text: one definition,
// so a NaN, a comma or a quote comes out the same in every report. Internal to research/lab/, not
// installed.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace frugal::reporttext {

using Json = nlohmann::ordered_json;

// JSON has no infinity or NaN: those are written as null.
Json number(double value);
// A float as the double of its shortest decimal form, so 0.1f is written 0.1 (not 0.10000000149...).
// (Beside the double overload, so a double never reaches it by a narrowing conversion.)
Json number(float value);

// The report as written: indented by 2, a final line break. Invalid UTF-8 in a name (a file path)
// is replaced rather than thrown on.
std::string jsonText(const Json& report);

// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
std::string csvField(const std::string& text);

// Six significant digits; NaN and infinities as an empty field (missing data for gnuplot, NaN for
// most CSV readers).
std::string csvNumber(double value);

// A gnuplot single-quoted string: nothing is special inside but the quote, written twice.
std::string gnuplotQuoted(const std::string& text);

}  // namespace frugal::reporttext

namespace frugal {

// What a one-frame benchmark gives its command (order-bench, shading-bench): the report's JSON and
// CSV, and the lines it prints.
struct BenchTexts {
    std::string json, csv, text;
};

}  // namespace frugal
