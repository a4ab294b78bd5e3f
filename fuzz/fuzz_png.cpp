// The PNG reader behind `frugal compare` (stb_image), on bytes in memory.
#include <cstddef>
#include <cstdint>
#include <span>

#include "FuzzSupport.h"
#include "io/ImageIO.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string name = "input.png";
    const frugal::Result<frugal::DecodedImage> image = frugal::decodePng(std::span(data, size), name);
    frugal::fuzz::checkError(image, name);
    if (!image) return 0;
    // compare indexes the pixels by the size and format it reports.
    const std::size_t samples = std::size_t(image->width) * std::size_t(image->height) * std::size_t(image->channels);
    const std::size_t have = image->bitDepth == 16 ? image->pixels16.size() : image->pixels8.size();
    if (image->width < 1 || image->height < 1 || image->channels < 1 || image->channels > 4 || have != samples)
        frugal::fuzz::broken("decoded image does not match its size and format");
    return 0;
}
