// Opening a backend by its kind (frugal/Settings.h BackendKind): the GL choices (gl/GlBackend.h)
// and the software reference (software/SoftwareBackend.h), through one factory. And the memory this
// process may still take, checked before a target is made.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <frugal/Result.h>
#include <frugal/Settings.h>

#include "pipeline/Backend.h"

namespace frugal {

// Opens a backend of `kind`. `log` receives one line per context tried (GL) or "software: ok".
// Errors (ErrorKind::BackendUnavailable) are GL context failures ("no usable GL context:
// egl-surfaceless: ..."); the software backend always opens. `threads` > 0 sets the rasterizer
// threads: the software backend's pool, and LP_NUM_THREADS for llvmpipe (read when Mesa creates its
// screen, i.e. the first GL context of the process). `interp` is the software backend's depth
// interpolation; a GL backend has no such choice and is refused for anything but Exact (BadInput):
// "interp span: only the software backend models the span interpolator".
Result<std::unique_ptr<Backend>> openBackend(BackendKind kind, std::vector<std::string>* log = nullptr, int threads = 0,
                                             DepthInterp interp = DepthInterp::Exact);

// Memory, checked before a target is made: a frame larger than the memory this process may still
// take is refused with the numbers, not left to a failed allocation or the OOM killer.
//
// A frame holds its target (colour RGBA8, depth, ids: 12 bytes a pixel on either backend), the
// read-back (12) and, while its colour PNG is encoded, the flipped rows, the filtered rows and
// zlib's output (12). The peak resident memory of a large render, measured on both backends, stays
// just under the 36 bytes a pixel (docs/gl/README.md, "Outside the GL backend").
inline constexpr std::uint64_t kTargetBytesPerPixel = 12;  // a target alone: colour, depth, ids
inline constexpr std::uint64_t kFrameBytesPerPixel = 36;
// A linear frame (Settings::linear) adds 12 to its target (RGBA32F colour) and 28 more to the frame:
// the float read-back (16) and a PFM's rows (12).
inline constexpr std::uint64_t targetBytesPerPixel(bool linear) { return kTargetBytesPerPixel + (linear ? 12 : 0); }
inline constexpr std::uint64_t frameBytesPerPixel(bool linear) { return kFrameBytesPerPixel + (linear ? 40 : 0); }
// The colour format a target of `settings` has.
inline ColorFormat colorFormat(const Settings& settings) {
    return settings.linear ? ColorFormat::Rgba32F : ColorFormat::Rgba8;
}

// What this process may still take: the least of the address space left under `ulimit -v`
// (RLIMIT_AS less VmSize), the data left under `ulimit -d` (RLIMIT_DATA less VmData), the
// machine's MemAvailable + SwapFree, and what its cgroup and the cgroups above it leave (memory.max
// less memory.current; cgroup v1: memory.limit_in_bytes less memory.usage_in_bytes).
struct MemoryLeft {
    std::uint64_t bytes = 0;
    std::string under;  // which: "ulimit -v", "ulimit -d", "MemAvailable + SwapFree", "cgroup /path memory.max"
};
std::optional<MemoryLeft> memoryLeft();  // nothing when no limit could be read

// Bytes as messages give them: "9.7 GB".
std::string gigabytes(std::uint64_t bytes);

// Why `bytes` more do not fit: "more than the 3.2 GB left (ulimit -v)"; nothing when they fit or
// nothing is known.
std::optional<std::string> memoryProblem(std::uint64_t bytes);

// Why a frame of width×height does not fit: "needs about 9.7 GB (36 bytes a pixel: target,
// read-back, PNG encoding), more than the 3.2 GB left (ulimit -v)"; nothing when it fits or nothing
// is known.
std::optional<std::string> frameMemoryProblem(int width, int height, int samples = 1, bool linear = false);

}  // namespace frugal
