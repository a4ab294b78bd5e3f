// Wavefront OBJ (tinyobjloader, then frugal's index checks and polygon splitting).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "FuzzSupport.h"
#include "scene/Load.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string name = frugal::fuzz::inputName(".obj");
    const frugal::Result<frugal::Scene> scene =
        frugal::loadObjFromMemory(std::string_view(reinterpret_cast<const char*>(data), size), name);
    frugal::fuzz::checkError(scene, name);
    if (scene) frugal::fuzz::checkScene(*scene);
    return 0;
}
