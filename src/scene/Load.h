// Scene loading: glTF 2.0 (.gltf/.glb), OBJ, and built-in procedural scenes ("builtin:NAME?k=v&...").
// Every function returns an error message instead of throwing or aborting on bad input.
#pragma once

#include <string>
#include <vector>

#include "base/Result.h"
#include "scene/Scene.h"

namespace frugal {

struct LoadOptions {
    bool optimizeOrder = true;   // reorder triangles for the vertex cache (meshoptimizer)
    bool objDoubleSided = true;  // OBJ has no culling flag: drawn double-sided unless told otherwise
};

// Dispatches on the spec: "builtin:..." → makeBuiltin, ".gltf"/".glb" → loadGltf, ".obj" → loadObj.
Result<Scene> loadScene(const std::string& spec, const LoadOptions& options = {});

Result<Scene> loadGltf(const std::string& path, const LoadOptions& options = {});
Result<Scene> loadObj(const std::string& path, const LoadOptions& options = {});
Result<Scene> makeBuiltin(const std::string& spec, const LoadOptions& options = {});

// Names and one-line descriptions of the built-in scenes, with their parameters.
std::vector<std::pair<std::string, std::string>> builtinScenes();

}  // namespace frugal
