#include "scene/ImageCheck.h"

#include <algorithm>
#include <string>

#include "scene/LoadSupport.h"

namespace frugal {

namespace {

using load::cat;

std::uint32_t be16(std::span<const std::uint8_t> bytes, std::size_t at) {
    return std::uint32_t(bytes[at]) << 8 | bytes[at + 1];
}
std::uint32_t be32(std::span<const std::uint8_t> bytes, std::size_t at) {
    return be16(bytes, at) << 16 | be16(bytes, at + 2);
}

Result<ImageSize> withinLimit(const char* format, std::uint32_t width, std::uint32_t height) {
    if (width == 0 || height == 0) return Error{cat("corrupt ", format, ": size ", width, "x", height)};
    if (std::uint64_t(width) * height > kMaxImagePixels)
        return Error{cat(format, " of ", width, "x", height, " pixels, more than frugal's limit of ", kMaxImagePixels,
                         " (16384x16384)")};
    return ImageSize{int(width), int(height)};
}

bool isJpeg(std::span<const std::uint8_t> bytes) {
    return bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
}

Result<ImageSize> checkJpeg(std::span<const std::uint8_t> bytes) {
    // Segments up to the frame header (SOF0-SOF15, less DHT C4, JPG C8 and DAC CC): FF, marker, length.
    std::size_t at = 2;
    while (true) {
        while (at < bytes.size() && bytes[at] == 0xFF) ++at;  // fill bytes
        if (at + 3 > bytes.size()) return Error{"truncated JPEG: no frame header"};
        const std::uint8_t marker = bytes[at];
        const std::uint32_t length = be16(bytes, at + 1);
        if (marker == 0xD9 || marker == 0xDA) return Error{"corrupt JPEG: no frame header before the image data"};
        if (length < 2 || length > bytes.size() - at - 1)
            return Error{cat("truncated JPEG: segment at byte ", at - 1, " declares ", length, " bytes, ",
                             bytes.size() - at - 1, " remain")};
        if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC) {
            if (length < 8) return Error{cat("corrupt JPEG: a frame header of ", length, " bytes")};
            Result<ImageSize> size = withinLimit("JPEG", be16(bytes, at + 6), be16(bytes, at + 4));
            if (!size) return size;
            // stb_image decodes a truncated scan as if zero bits followed, so a few bytes could make a
            // full-size image. Every 8x8 block of the first component codes its DC coefficient with a
            // Huffman code of one bit or more (baseline and progressive alike; stb_image decodes no
            // arithmetic coding), so a real image has at least one byte after its frame header for
            // every 512 pixels.
            const std::uint64_t pixels = std::uint64_t(size->width) * std::uint64_t(size->height);
            const std::uint64_t after = bytes.size() - at - 1 - length;
            if (pixels > 512 * after)
                return Error{cat("corrupt JPEG: ", size->width, "x", size->height, " pixels need at least ",
                                 (pixels + 511) / 512, " bytes of coded data (a bit per 8x8 block), ", after,
                                 " bytes follow its frame header")};
            return size;
        }
        at += 1 + length;
    }
}

}  // namespace

Result<ImageSize> checkPng(std::span<const std::uint8_t> bytes) {
    static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (bytes.size() < 8 || !std::equal(kSignature, kSignature + 8, bytes.begin()))
        return Error{"not a PNG: the file does not start with the PNG signature"};
    std::uint32_t width = 0, height = 0, bitsPerPixel = 0;
    std::uint64_t idat = 0;
    std::size_t at = 8;
    for (int chunk = 0;; ++chunk) {
        // Length, type, data, CRC.
        if (bytes.size() - at < 8)
            return Error{cat("truncated PNG: the data ends at byte ", bytes.size(), " before IEND")};
        const std::uint32_t length = be32(bytes, at);
        const std::string type(reinterpret_cast<const char*>(&bytes[at + 4]), 4);
        if (bytes.size() - at - 8 < std::uint64_t(length) + 4)
            return Error{cat("truncated PNG: chunk ", chunk, " ('", oneLine(type), "') at byte ", at, " declares ",
                             length, " bytes and a CRC, ", bytes.size() - at - 8, " bytes follow")};
        if (chunk == 0) {
            if (type != "IHDR" || length != 13) return Error{"corrupt PNG: the first chunk is not a 13-byte IHDR"};
            width = be32(bytes, at + 8);
            height = be32(bytes, at + 12);
            const std::uint32_t depth = bytes[at + 16], colourType = bytes[at + 17];
            // Samples a pixel by colour type: grey, -, RGB, palette index, grey + alpha, -, RGBA.
            static constexpr std::uint32_t kSamples[7] = {1, 0, 3, 1, 2, 0, 4};
            const bool depthValid = depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
            if (colourType > 6 || kSamples[colourType] == 0 || !depthValid)
                return Error{cat("corrupt PNG: colour type ", colourType, " with bit depth ", depth)};
            bitsPerPixel = kSamples[colourType] * depth;
        }
        // stb_image copies a first IDAT into a buffer it has not allocated yet when that IDAT is empty.
        if (type == "IDAT" && idat == 0 && length == 0)
            return Error{cat("unsupported PNG: chunk ", chunk, " is an empty IDAT before the image data")};
        if (type == "IDAT") idat += length;
        if (type == "IEND") break;
        at += 12 + std::size_t(length);
    }
    Result<ImageSize> size = withinLimit("PNG", width, height);
    if (!size) return size;
    // Each row is at least its pixels' bits; deflate cannot expand data more than 1032 times.
    const std::uint64_t raw = std::uint64_t(height) * ((std::uint64_t(width) * bitsPerPixel + 7) / 8);
    if (raw > 1032 * idat)
        return Error{cat("corrupt PNG: ", width, "x", height, " pixels of ", bitsPerPixel, " bits need ", raw,
                         " bytes, which its ", idat,
                         " bytes of image data cannot hold (deflate expands at most 1032:1)")};
    return size;
}

Result<ImageSize> checkTextureImage(std::span<const std::uint8_t> bytes) {
    if (isJpeg(bytes)) return checkJpeg(bytes);
    if (bytes.size() >= 4 && bytes[0] == 0x89 && bytes[1] == 'P') return checkPng(bytes);
    return Error{"neither PNG nor JPEG, the formats glTF 2.0 allows"};
}

}  // namespace frugal
