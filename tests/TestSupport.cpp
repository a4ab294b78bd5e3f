#include "TestSupport.h"

#include <fstream>

namespace frugal::test {

std::filesystem::path outputDir() {
    std::filesystem::path dir = FRUGAL_TEST_OUTPUT_DIR;
    std::filesystem::create_directories(dir);
    return dir;
}

std::filesystem::path freshDir(const std::string& name) {
    std::filesystem::path dir = outputDir() / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

void writeFile(const std::filesystem::path& path, const std::string& text) {
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

}  // namespace frugal::test
