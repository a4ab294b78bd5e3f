// The OpenGL implementation of the Backend interface (pipeline/Backend.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <frugal/Result.h>

#include "gl/GlContext.h"
#include "pipeline/Backend.h"

namespace frugal {

enum class BackendChoice {
    Auto,            // EGL device (hardware), EGL surfaceless, then OSMesa
    Egl,             // EGL device (hardware), then surfaceless
    EglDevice,       // EGL device platform only (software devices allowed)
    EglSurfaceless,
    OsMesa,
};

// Parses "auto", "egl", "egl-device", "egl-surfaceless", "osmesa".
Result<BackendChoice> parseBackendChoice(const std::string& text);

// Creates a context of the chosen kind and a backend on it. `log` receives one line per context
// tried ("egl-surfaceless: ok", "osmesa: not built"), so `auto` can say what it chose and why.
Result<std::unique_ptr<Backend>> createGlBackend(BackendChoice choice,
                                                 std::vector<std::string>* log = nullptr);

// A GL backend on an existing context (takes ownership). Error "<kind>: <reason>" when the context
// lacks an entry point, is older than GL 3.3, or a shader does not compile.
Result<std::unique_ptr<Backend>> makeGlBackend(std::unique_ptr<GlContext> context);

}  // namespace frugal
