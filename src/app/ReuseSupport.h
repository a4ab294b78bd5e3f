// The command-line side of temporal reuse, shared by `frugal render --reuse` and `frugal reuse-bench`:
// the options and the static pair's size.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "app/Options.h"
#include "reuse/Reuse.h"

namespace frugal {

struct ReuseCliOptions {
    bool enabled = false;    // render: --reuse
    ReuseSettings settings;  // --reuse-grain N, --reuse-cell PX, --no-fallback, --exact-static
};

// --reuse (when `withSwitch`), --reuse-grain, --reuse-cell, --no-fallback and --exact-static; also
// --camera-path FILE into `render.cameraPathFile` (read with the shared options' checks).
std::vector<Flag> reuseFlags(ReuseCliOptions& options, RenderOptions& render, bool withSwitch);

}  // namespace frugal
