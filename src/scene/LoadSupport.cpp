#include "scene/LoadSupport.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace frugal::load {

std::string oneLine(std::string_view text, std::size_t maxLength) {
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

std::string readFile(const std::string& path) {
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (status.type() == std::filesystem::file_type::not_found) fail("no such file");
    if (ec) fail("cannot access (", ec.message(), ")");
    if (std::filesystem::is_directory(status)) fail("is a directory, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("cannot open for reading (", std::strerror(errno), ")");
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0) fail("cannot read (not a regular file?)");
    in.seekg(0, std::ios::beg);
    std::string bytes(static_cast<std::size_t>(size), '\0');
    if (!in.read(bytes.data(), size)) fail("read error after ", in.gcount(), " of ", size, " bytes");
    return bytes;
}

}  // namespace frugal::load
