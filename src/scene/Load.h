// The loaders behind loadScene (frugal/Scene.h), one by one and on bytes in memory. Every function
// returns an error instead of throwing or aborting on bad input.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <frugal/Scene.h>

namespace frugal {

Result<Scene> loadGltf(const std::string& path, const LoadOptions& options = {});
Result<Scene> loadObj(const std::string& path, const LoadOptions& options = {});
Result<Scene> makeBuiltin(const std::string& spec, const LoadOptions& options = {});

// The file loaders on bytes already in memory (the fuzz targets use them). `name` stands for the
// file: messages start with it, a .glb extension means binary glTF as for a path, and its folder is
// where a .gltf's buffer and image URIs and an OBJ's material libraries are looked up.
Result<Scene> loadGltfFromMemory(std::string_view bytes, const std::string& name, const LoadOptions& options = {});
Result<Scene> loadObjFromMemory(std::string_view bytes, const std::string& name, const LoadOptions& options = {});

}  // namespace frugal
