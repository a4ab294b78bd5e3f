// The backends the command line can name: the GL choices (gl/GlBackend.h) and the software
// reference (software/SoftwareBackend.h), opened through one factory so that every command that
// renders (render, bench, diff) accepts the same --backend values.
#pragma once

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

// The names --interp accepts, and the parse: "--interp wat: not a mode (exact, span or dda)".
inline constexpr const char* kInterpNames = "exact, span or dda";
Result<span::Interp> parseInterp(const std::string& text);
// The error above for a GL selection with an interp other than Exact; nothing when they go together.
std::optional<std::string> interpConflict(const BackendSelection& selection, span::Interp interp);

}  // namespace frugal
