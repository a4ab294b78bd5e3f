#include "app/Gnuplot.h"

#include <cstdio>
#include <cstdlib>

namespace frugal {

std::string runGnuplot(const std::string& script) {
    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
        return "gnuplot not found (Debian: apt-get install gnuplot-nox)";
    const std::string command = "gnuplot '" + script + "' 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) return "cannot run gnuplot";
    std::string output;
    char buffer[512];
    while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
    const int status = pclose(pipe);
    if (status != 0) {
        std::string first = output.substr(0, output.find('\n'));
        return "gnuplot failed on " + script + (first.empty() ? "" : ": " + first);
    }
    return {};
}

bool hasSingleQuote(const std::string& path) { return path.find('\'') != std::string::npos; }

}  // namespace frugal
