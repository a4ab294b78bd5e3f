// Checking command lines that must fail, the same way in every command-line suite. Header-only,
// like JsonSupport.h, because only the suites that run the binary include it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestSupport.h"

namespace frugal::test {

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
