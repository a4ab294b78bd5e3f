// Scene loading: glTF 2.0 (.gltf/.glb), OBJ, and built-in procedural scenes ("builtin:NAME?k=v&...").
// Every function returns an error message instead of throwing or aborting on bad input.
#pragma once

#include <string>
#include <string_view>
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

// The file loaders on bytes already in memory (the fuzz targets use them). `name` stands for the
// file: messages start with it, a .glb extension means binary glTF as for a path, and its folder is
// where a .gltf's buffer and image URIs and an OBJ's material libraries are looked up.
Result<Scene> loadGltfFromMemory(std::string_view bytes, const std::string& name, const LoadOptions& options = {});
Result<Scene> loadObjFromMemory(std::string_view bytes, const std::string& name, const LoadOptions& options = {});

// Names and one-line descriptions of the built-in scenes, with their parameters.
std::vector<std::pair<std::string, std::string>> builtinScenes();

}  // namespace frugal
