// The Radiance .hdr reader behind --environment-map. (Prefiltering takes about a second whatever the
// image, too slow to fuzz: tests/render/EnvironmentTest.cpp gives it extreme values.)
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
    return 0;
}
