// The backends the command line can name: the GL choices (gl/GlBackend.h) and the software
// reference (software/SoftwareBackend.h), opened through one factory so that every command that
// renders (render, bench, diff) accepts the same --backend values.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gl/GlBackend.h"
#include "render/Backend.h"
#include "base/Result.h"
#include "software/span/Interp.h"

namespace frugal {

struct BackendSelection {
    bool software = false;
    BackendChoice gl = BackendChoice::Auto;  // when !software
};

// The names --backend accepts, in the order help lists them.
inline constexpr const char* kBackendNames = "auto, egl, egl-device, egl-surfaceless, osmesa or software";

// Parses "software" or a GL choice. Error: "unknown backend 'x' (expected <kBackendNames>)".
Result<BackendSelection> parseBackendSelection(const std::string& text);

// The canonical name of a selection ("auto", "egl-surfaceless", "software", ...).
std::string backendSelectionName(const BackendSelection& selection);

// Opens the selected backend. `log` receives one line per context tried (GL) or "software: ok".
// Errors are GL context failures ("egl-surfaceless: ..."); the software backend always opens.
// `threads` > 0 sets the rasterizer threads: the software backend's pool, and LP_NUM_THREADS for
// llvmpipe (read when Mesa creates its screen, i.e. the first GL context of the process).
// `interp` is the software backend's depth interpolation (SoftwareOptions::interp); a GL backend
// has no such choice and is refused for anything but Exact: "--interp span: only the software
// backend models the span interpolator (use --backend software)".
Result<std::unique_ptr<Backend>> openBackend(const BackendSelection& selection,
                                             std::vector<std::string>* log = nullptr, int threads = 0,
                                             span::Interp interp = span::Interp::Exact);

// Memory, checked before a target is made: a frame larger than the memory this process may still
// take is refused with the numbers, not left to a failed allocation or the OOM killer.
//
// A frame holds its target (colour RGBA8, depth, ids: 12 bytes a pixel on either backend), the
// read-back (12) and, while its colour PNG is encoded, the flipped rows, the filtered rows and
// zlib's output (12). Measured peak resident memory of `frugal render --size 16384x16384`: 9.50 GB
// on the software backend, 9.60 GB on egl-surfaceless (35.4 and 35.8 bytes a pixel).
inline constexpr std::uint64_t kTargetBytesPerPixel = 12;  // a target alone: colour, depth, ids
inline constexpr std::uint64_t kFrameBytesPerPixel = 36;

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
std::optional<std::string> frameMemoryProblem(int width, int height);

// The message for an allocation that failed all the same (std::bad_alloc): "out of memory: an
// allocation failed (ulimit -v: 3.8 GB left once the command's memory was freed)".
std::string outOfMemoryMessage();

// The names --interp accepts, and the parse: "--interp wat: not a mode (exact, span or dda)".
inline constexpr const char* kInterpNames = "exact, span or dda";
Result<span::Interp> parseInterp(const std::string& text);
// The error above for a GL selection with an interp other than Exact; nothing when they go together.
std::optional<std::string> interpConflict(const BackendSelection& selection, span::Interp interp);

}  // namespace frugal
