// The command-line side of culling, shared by `frugal render --cull` and `frugal cull-report`:
// the options, pre-processing with its progress line, and the oracle (the frame's really visible
// set drawn from index buffers of its own).
#pragma once

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

#include "app/Options.h"
#include "cull/Culling.h"
#include "render/SceneRenderer.h"
#include "report/VisibleSet.h"

namespace frugal {

struct CullOptions {
    std::optional<CullMethod> method;  // render: --cull (absent = none, nothing prepared)
    MapParams bins;                    // --cull-bins TxP
};

// --cull METHOD (when `withMethod`) and --cull-bins TxP. False when `flag` is neither.
bool parseCullOption(const std::string& flag, ArgCursor& cursor, CullOptions& options, bool withMethod);

// Builds the maps and reorders the scene's meshes (before upload); prints one line unless quiet:
// "cull: 1 mesh, 69666 triangles prepared in 31.2 ms (sphere 2.1, map 9.8, clusters 5.3, hull 14)"
// (the hull only when bins.hull asks for it).
SceneCuller prepareCulling(Scene& scene, const MapParams& bins, std::ostream& err, bool quiet);

// What render and reuse-bench prepare for their --cull: nothing for none (or no --cull), else
// prepareCulling with the hull built for paper alone (the only method that uses it). Call it
// before the upload: the map's triangle order must be in place by then.
std::optional<SceneCuller> prepareCullOption(Scene& scene, const CullOptions& options, std::ostream& err, bool quiet);

// One frame's oracle: the id pass of the full render, its visible set, and a scene holding exactly
// that set, uploaded to the same backend.
struct Oracle {
    TriangleSet rvs;
    std::unique_ptr<Scene> scene;  // stable address: the renderer points to it
    std::optional<SceneRenderer> renderer;
    double ms = 0.0;  // id pass + read-back + set + oracle scene (upload excluded)
};

// Draws `frame` whole with ids into `target` (its contents are overwritten), then builds the oracle.
// Error: the visible set's ("id N at pixel ... belongs to no triangle") or a refused upload.
Result<Oracle> makeOracle(SceneRenderer& full, TargetHandle target, int width, int height, FrameParams frame,
                          const std::vector<glm::mat4>& world, const glm::vec4& background);

}  // namespace frugal
