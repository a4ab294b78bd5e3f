#include "lab/Gnuplot.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace frugal {

namespace {

// Whether an executable gnuplot is on PATH. Looked up here rather than with std::system("command -v"):
// system() ignores SIGINT in this process while its shell runs, so a Ctrl-C then was lost (and read
// as "gnuplot not found"). popen() below leaves the signals to the handler: a Ctrl-C ends the
// command with its one line.
bool gnuplotOnPath() {
    const char* path = std::getenv("PATH");
    std::string_view dirs = path != nullptr ? path : "/usr/bin:/bin";
    while (true) {
        const std::size_t colon = dirs.find(':');
        const std::string_view dir = dirs.substr(0, colon);
        const std::string file = (dir.empty() ? std::string(".") : std::string(dir)) + "/gnuplot";
        struct stat info {};
        if (::stat(file.c_str(), &info) == 0 && S_ISREG(info.st_mode) && ::access(file.c_str(), X_OK) == 0) return true;
        if (colon == std::string_view::npos) return false;
        dirs.remove_prefix(colon + 1);
    }
}

}  // namespace

std::string runGnuplot(const std::string& script) {
    if (!gnuplotOnPath()) return "gnuplot not found (Debian: apt-get install gnuplot-nox)";
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
