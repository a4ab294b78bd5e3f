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

// Builds the maps and reorders the scene's meshes (before upload); prints one line unless quiet:
// "cull: 1 mesh, 69666 triangles prepared in 31.2 ms (sphere 2.1, map 9.8, clusters 5.3, hull 14)"
// (the hull only when bins.hull asks for it).
SceneCuller prepareCulling(Scene& scene, const MapParams& bins, std::ostream& err, bool quiet);

// What render and reuse-bench prepare for their --cull: nothing for none (or no --cull), else
// prepareCulling with the hull built for paper alone (the only method that uses it). Call it
// before the upload: the map's triangle order must be in place by then.
std::optional<SceneCuller> prepareCullOption(Scene& scene, const CullOptions& options, std::ostream& err, bool quiet);

}  // namespace frugal
