#include "lab/ReportText.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace frugal::reporttext {

Json number(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

Json number(float value) {
    if (!std::isfinite(value)) return nullptr;
    char buf[32];
    const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf - 1, value);
    *r.ptr = '\0';
    return std::strtod(buf, nullptr);
}

std::string jsonText(const Json& report) { return report.dump(2, ' ', false, Json::error_handler_t::replace) + "\n"; }

std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

std::string csvNumber(double value) {
    if (!std::isfinite(value)) return {};
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", value);
    return buf;
}

std::string gnuplotQuoted(const std::string& text) {
    std::string quoted = "'";
    for (char c : text) quoted += c == '\'' ? std::string("''") : std::string(1, c);
    return quoted + "'";
}

}  // namespace frugal::reporttext
