// Built-in scene specs ("builtin:NAME?key=value&..."), as given on the command line.
#include <cstddef>
#include <cstdint>
#include <string>

#include "FuzzSupport.h"
#include "scene/Load.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string spec(reinterpret_cast<const char*>(data), size);
    // A command-line argument ends at its first NUL.
    if (spec.find('\0') != std::string::npos) return -1;
    const frugal::Result<frugal::Scene> scene = frugal::makeBuiltin(spec);
    frugal::fuzz::checkError(scene, "");  // the scene named by of= names itself in its errors
    if (scene) frugal::fuzz::checkScene(*scene);
    return 0;
}
