// glTF 2.0, JSON or binary: the extension says .gltf, so a file is read as GLB only when it starts
// with the GLB magic, as the loader decides for any path.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "FuzzSupport.h"
#include "scene/Load.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string name = frugal::fuzz::inputName(".gltf");
    const frugal::Result<frugal::Scene> scene =
        frugal::loadGltfFromMemory(std::string_view(reinterpret_cast<const char*>(data), size), name);
    frugal::fuzz::checkError(scene, name);
    if (scene) frugal::fuzz::checkScene(*scene);
    return 0;
}
