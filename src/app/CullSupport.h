// The command-line side of culling, shared by `frugal render --cull` and `frugal cull-report`:
// the options, and pre-processing with its progress line.
#pragma once

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <frugal/Renderer.h>

#include "app/Options.h"
#include "cull/Culling.h"
#include "lab/CullMeasure.h"
#include "render/SceneRenderer.h"

namespace frugal {

struct CullOptions {
    std::optional<Cull> method;        // render: --cull (absent = none, nothing prepared)
    MapParams bins;                    // --cull-bins TxP
};

// --cull METHOD (when `withMethod`) and --cull-bins TxP.
std::vector<Flag> cullFlags(CullOptions& options, bool withMethod);

}  // namespace frugal
