// Reading the JSON files the command-line tests check. Header-only, because only the suites that
// link nlohmann_json include it.
#pragma once

#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestSupport.h"

namespace frugal::test {

// The file parsed; a missing or empty file is a test failure, and a file that does not parse gives
// a discarded value (is_discarded()) rather than an exception.
inline nlohmann::json readJson(const std::filesystem::path& path) {
    const std::string text = readAll(path);
    EXPECT_FALSE(text.empty()) << path << " missing or empty";
    return nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
}

}  // namespace frugal::test
