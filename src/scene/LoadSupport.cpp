#include "scene/LoadSupport.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace frugal::load {

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
