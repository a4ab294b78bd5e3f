// Binary glTF: the .glb extension makes every input a GLB container (header, chunks, JSON, BIN).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "FuzzSupport.h"
#include "scene/Load.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string name = frugal::fuzz::inputName(".glb");
    const frugal::Result<frugal::Scene> scene =
        frugal::loadGltfFromMemory(std::string_view(reinterpret_cast<const char*>(data), size), name);
    frugal::fuzz::checkError(scene, name);
    if (scene) frugal::fuzz::checkScene(*scene);
    return 0;
}
