#include "scene/Load.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "scene/LoadSupport.h"

namespace frugal {

namespace {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace

Result<Scene> loadScene(const std::string& spec, const LoadOptions& options) {
    if (spec.rfind("builtin:", 0) == 0) return makeBuiltin(spec, options);
    const std::string ext = lowerExtension(spec);
    if (ext == ".gltf" || ext == ".glb") return loadGltf(spec, options);
    if (ext == ".obj") return loadObj(spec, options);
    std::error_code ec;
    if (!std::filesystem::exists(spec, ec)) return Error{load::shownPath(spec) + ": no such file"};
    return Error{load::shownPath(spec) + ": unknown scene format '" + oneLine(ext) +
                 "' (frugal reads .gltf, .glb, .obj and builtin:NAME)"};
}

}  // namespace frugal
