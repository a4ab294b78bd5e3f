// Helpers shared by the test suites.
#pragma once

#include <filesystem>
#include <string>

namespace frugal::test {

// Folder for images and other files a test writes (actual/expected/diff on failure).
std::filesystem::path outputDir();
// A fresh empty folder under outputDir() for one test.
std::filesystem::path freshDir(const std::string& name);
// Writes `text` to `path` (creating folders).
void writeFile(const std::filesystem::path& path, const std::string& text);

}  // namespace frugal::test
