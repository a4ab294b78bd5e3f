#include "renderer/Backends.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>

#include <sys/resource.h>

#include "gl/GlBackend.h"
#include "software/SoftwareBackend.h"

namespace frugal {

Result<std::unique_ptr<Backend>> openBackend(BackendKind kind, std::vector<std::string>* log, int threads,
                                             DepthInterp interp) {
    if (kind != BackendKind::Software && interp != DepthInterp::Exact)
        return Error{
            std::string("interp ") + toString(interp) + ": only the software backend models the span interpolator",
            ErrorKind::BadInput, true};
    if (kind != BackendKind::Software) {
        if (threads > 0) setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 1);
        constexpr BackendChoice kChoices[] = {BackendChoice::Auto, BackendChoice::Egl, BackendChoice::EglDevice,
                                              BackendChoice::EglSurfaceless, BackendChoice::OsMesa};
        Result<std::unique_ptr<Backend>> gl = createGlBackend(kChoices[std::size_t(kind)], log);
        if (!gl) return Error{gl.error().message, ErrorKind::BackendUnavailable};
        return gl;
    }
    SoftwareOptions options;
    options.threads = threads;
    options.interp = interp;
    std::unique_ptr<Backend> backend = makeSoftwareBackend(options);
    if (!backend) return Error{"software: could not be created"};
    if (log) log->push_back("software: ok");
    return backend;
}

namespace {

// A "Key:  123 kB" line of a /proc file, in bytes.
std::optional<std::uint64_t> procKilobytes(const char* file, const std::string& key) {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind(key + ":", 0) != 0) continue;
        std::istringstream fields(line.substr(key.size() + 1));
        std::uint64_t kilobytes = 0;
        if (fields >> kilobytes) return kilobytes * 1024;
    }
    return std::nullopt;
}

// A cgroup file holding one number ("max" and v1's "no limit", 2^63 rounded to pages, give nothing).
std::optional<std::uint64_t> cgroupNumber(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::uint64_t value = 0;
    if (!(in >> value) || value >= (std::uint64_t(1) << 62)) return std::nullopt;
    return value;
}

// The tightest cgroup memory limit over this process's cgroup and those above it, as mounted here.
std::optional<MemoryLeft> cgroupMemoryLeft() {
    std::ifstream in("/proc/self/cgroup");
    std::string line;
    std::optional<MemoryLeft> tightest;
    while (std::getline(in, line)) {
        // "0::/path" (v2) or "4:memory:/path" (v1, controllers separated by commas).
        const std::size_t first = line.find(':'), second = line.find(':', first + 1);
        if (first == std::string::npos || second == std::string::npos) continue;
        const std::string controllers = "," + line.substr(first + 1, second - first - 1) + ",";
        const bool v2 = controllers == ",,";
        if (!v2 && controllers.find(",memory,") == std::string::npos) continue;
        const std::filesystem::path root = v2 ? "/sys/fs/cgroup" : "/sys/fs/cgroup/memory";
        const char* limitFile = v2 ? "memory.max" : "memory.limit_in_bytes";
        const char* usageFile = v2 ? "memory.current" : "memory.usage_in_bytes";
        // Inside a cgroup namespace the path may not be visible: then only the root is.
        const std::string relative = line.substr(std::min(line.size(), second + 2));  // after the '/'
        std::filesystem::path dir = relative.empty() ? root : root / relative;
        if (!std::filesystem::exists(dir / usageFile)) dir = root;
        for (;; dir = dir.parent_path()) {
            const std::optional<std::uint64_t> limit = cgroupNumber(dir / limitFile);
            const std::optional<std::uint64_t> usage = cgroupNumber(dir / usageFile);
            if (limit && usage) {
                const std::uint64_t left = *limit > *usage ? *limit - *usage : 0;
                if (!tightest || left < tightest->bytes)
                    tightest = MemoryLeft{left, "cgroup " + dir.string() + " " + limitFile};
            }
            if (dir == root || !dir.has_relative_path()) break;
        }
    }
    return tightest;
}

}  // namespace

std::optional<MemoryLeft> memoryLeft() {
    std::optional<MemoryLeft> tightest;
    const auto consider = [&tightest](std::uint64_t limit, std::uint64_t used, const std::string& under) {
        const std::uint64_t left = limit > used ? limit - used : 0;
        if (!tightest || left < tightest->bytes) tightest = MemoryLeft{left, under};
    };
    // An address-space or data limit, less what the process holds of it already.
    for (const auto& [resource, field, under] :
         {std::tuple{RLIMIT_AS, "VmSize", "ulimit -v"}, std::tuple{RLIMIT_DATA, "VmData", "ulimit -d"}}) {
        rlimit limit{};
        if (getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) continue;
        if (const auto used = procKilobytes("/proc/self/status", field)) consider(limit.rlim_cur, *used, under);
    }
    if (const auto available = procKilobytes("/proc/meminfo", "MemAvailable"))
        consider(*available + procKilobytes("/proc/meminfo", "SwapFree").value_or(0), 0, "MemAvailable + SwapFree");
    if (const std::optional<MemoryLeft> cgroup = cgroupMemoryLeft()) consider(cgroup->bytes, 0, cgroup->under);
    return tightest;
}

std::string gigabytes(std::uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f GB", double(bytes) / 1e9);
    return text;
}

std::optional<std::string> memoryProblem(std::uint64_t bytes) {
    const std::optional<MemoryLeft> left = memoryLeft();
    if (!left || bytes <= left->bytes) return std::nullopt;
    return "more than the " + gigabytes(left->bytes) + " left (" + left->under + ")";
}

std::optional<std::string> frameMemoryProblem(int width, int height, int samples, bool linear) {
    // A multisampled target holds its planes per sample, and a resolved copy besides.
    const std::uint64_t perPixel =
        frameBytesPerPixel(linear) + std::uint64_t(samples > 1 ? samples : 0) * targetBytesPerPixel(linear);
    const std::uint64_t needed = std::uint64_t(width) * std::uint64_t(height) * perPixel;
    const std::optional<std::string> problem = memoryProblem(needed);
    if (!problem) return std::nullopt;
    return "needs about " + gigabytes(needed) + " (" + std::to_string(perPixel) + " bytes a pixel: target" +
           (samples > 1 ? " of " + std::to_string(samples) + " samples" : std::string()) +
           (linear ? " with float colour" : "") + ", read-back, PNG encoding), " + *problem;
}

std::string outOfMemoryMessage() {
    const std::optional<MemoryLeft> left = memoryLeft();
    return "out of memory: an allocation failed" +
           (left ? " (" + left->under + ": " + gigabytes(left->bytes) + " left once the command's memory was freed)"
                 : std::string());
}

}  // namespace frugal
