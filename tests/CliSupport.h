// Checking command lines that must fail, the same way in every command-line suite, and reading
// the image a command line renders. Header-only, like JsonSupport.h, because only the suites that
// run the binary include it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "io/ImageIO.h"

namespace frugal::test {

// Runs `frugal ARGS -o NAME.png -q` in `dir`, expecting it to succeed, and returns the PNG's RGBA8
// pixels (empty, with the failure recorded, when it did not).
inline std::vector<std::uint8_t> renderedPixels(const std::filesystem::path& dir, const std::string& name,
                                                std::vector<std::string> args) {
    args.insert(args.end(), {"-o", name + ".png", "-q"});
    const CliRun run = runFrugal(dir, args);
    EXPECT_EQ(run.status, 0) << joined(args) << ": " << run.err;
    Result<DecodedImage> image = readPng((dir / (name + ".png")).string());
    EXPECT_TRUE(image) << name;
    return image ? image->pixels8 : std::vector<std::uint8_t>{};
}

// A command line that must fail with `status` and one error line: `line`, or when it is empty any
// line that starts "error: " (for messages that name a system's own words).
struct FailingRun {
    std::vector<std::string> args;
    std::string line;
    int status = 2;
};

// Runs each in `dir`: the exit status, exactly one line on stderr, nothing on stdout, and no file
// left in `dir`.
inline void expectOneErrorLine(const std::filesystem::path& dir, const std::vector<FailingRun>& runs) {
    for (const FailingRun& r : runs) {
        SCOPED_TRACE(joined(r.args));
        const CliRun run = runFrugal(dir, r.args);
        EXPECT_EQ(run.status, r.status) << run.err;
        const std::vector<std::string> errLines = run.errLines();
        ASSERT_EQ(errLines.size(), 1u) << run.err;
        if (r.line.empty()) {
            EXPECT_EQ(errLines[0].rfind("error: ", 0), 0u) << errLines[0];
        } else {
            EXPECT_EQ(errLines[0], r.line);
        }
        EXPECT_EQ(run.out, "");
        EXPECT_TRUE(filesIn(dir).empty());
    }
}

}  // namespace frugal::test
