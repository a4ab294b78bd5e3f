// Numbers as every message quotes them: printf's "%g" (six significant digits, no trailing zeros),
// so a value reads the same in a library error, a CLI line and a report.
#pragma once

#include <cstdio>
#include <string>

namespace frugal {

inline std::string fmt(double value) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", value);
    return buf;
}

// An object's optional name as messages quote it after its index: " 'name'", or nothing.
inline std::string quotedName(const std::string& name) { return name.empty() ? std::string() : " '" + name + "'"; }

}  // namespace frugal
