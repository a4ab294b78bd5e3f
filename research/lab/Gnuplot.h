// Running gnuplot on a script the reports wrote (cull-report, reuse-bench --plot).
#pragma once

#include <string>

namespace frugal {

// Runs gnuplot on `script`: "" on success, or why it failed ("gnuplot not found (Debian: apt-get
// install gnuplot-nox)", "gnuplot failed on F: <its first line of output>").
std::string runGnuplot(const std::string& script);

// gnuplot gets its script's path inside single quotes on a shell line: such a path cannot be passed.
bool hasSingleQuote(const std::string& path);

}  // namespace frugal
