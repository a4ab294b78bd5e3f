// The Radiance .hdr reader behind --environment-map, and the prefiltering of what it reads.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "FuzzSupport.h"
#include "pipeline/Environment.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string name = "input.hdr";
    const frugal::Result<frugal::HdrImage> image = frugal::decodeRadianceHdr(std::span(data, size), name);
    frugal::fuzz::checkError(image, name);
    if (!image) return 0;
    if (image->width < 1 || image->height < 1 ||
        image->rgb.size() != std::size_t(image->width) * std::size_t(image->height) * 3)
        frugal::fuzz::broken("decoded image does not match its size");
    for (const float v : image->rgb)
        if (!(v >= 0.0f) || !std::isfinite(v)) frugal::fuzz::broken("a decoded value is negative or not finite");
    // Small images are prefiltered too (every texel finite), on one thread.
    if (image->rgb.size() <= 3 * 64 * 64) {
        const auto map = frugal::prefilterEnvironment(*image, name, 1);
        for (const frugal::EnvironmentMap::Level& level : map->specular)
            for (const float v : level.rgba)
                if (!std::isfinite(v)) frugal::fuzz::broken("a prefiltered texel is not finite");
    }
    return 0;
}
