// The backends the command line can name: the GL choices (gl/GlBackend.h) and the software
// reference (software/SoftwareBackend.h), opened through one factory so that every command that
// renders (render, bench, diff) accepts the same --backend values.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "gl/GlBackend.h"
#include "render/Backend.h"
#include "base/Result.h"

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
Result<std::unique_ptr<Backend>> openBackend(const BackendSelection& selection,
                                             std::vector<std::string>* log = nullptr, int threads = 0);

}  // namespace frugal
