// Numbers and text as every message quotes them: printf's "%g" (six significant digits, no trailing
// zeros), so a value reads the same in a library error, a CLI line and a report; and text from a
// file or the command line made fit for a one-line message.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace frugal {

inline std::string fmt(double value) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", value);
    return buf;
}

// An object's optional name as messages quote it after its index: " 'name'", or nothing.
inline std::string quotedName(const std::string& name) { return name.empty() ? std::string() : " '" + name + "'"; }

// Text from a file or a user (names, URIs, library messages) in a one-line message: control
// characters become spaces, bytes that are not UTF-8 become '?', runs of spaces collapse, and it is
// capped at `maxLength` bytes ("..." marks a cut).
inline std::string oneLine(std::string_view text, std::size_t maxLength = 200) {
    std::string out;
    std::size_t i = 0;
    while (i < text.size() && out.size() < maxLength) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x80) {
            const char ch = (c < 0x20 || c == 0x7f) ? ' ' : char(c);
            if (!(ch == ' ' && (out.empty() || out.back() == ' '))) out += ch;
            ++i;
            continue;
        }
        const std::size_t length = (c >= 0xC2 && c <= 0xDF)   ? 2
                                   : (c >= 0xE0 && c <= 0xEF) ? 3
                                   : (c >= 0xF0 && c <= 0xF4) ? 4
                                                              : 0;
        bool valid = length > 0 && i + length <= text.size();
        for (std::size_t k = 1; valid && k < length; ++k)
            valid = (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80;
        if (valid) {
            out.append(text.substr(i, length));
            i += length;
        } else {
            out += '?';
            ++i;
        }
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    if (i < text.size()) out += "...";
    return out;
}

}  // namespace frugal
