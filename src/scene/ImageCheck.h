// Encoded images checked before a decoder sees them. stb_image, which decodes glTF textures (through
// tinygltf) and the PNGs `frugal compare` reads (io/ImageIO.h), sizes its buffers from what a file
// claims before it reads the data: a PNG chunk that claims 2 GB, or a header that claims a huge
// image, makes it allocate that much for a file of a few bytes. So the claims are checked against
// the data first.
#pragma once

#include <cstdint>
#include <span>

#include <frugal/Result.h>

namespace frugal {

// 16384 x 16384: the largest image frugal renders, and the texture size GL 4.5 guarantees.
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t(1) << 28;

struct ImageSize {
    int width = 0, height = 0;
};

// A PNG: its signature; chunks that fit the data, IHDR first, up to IEND; a size within
// kMaxImagePixels; and IDAT data that can fill it (deflate expands at most 1032:1). Errors say what
// and how much, without a file name: "not a PNG: ...", "truncated PNG: ...", "corrupt PNG: ...".
Result<ImageSize> checkPng(std::span<const std::uint8_t> bytes);

// A glTF image: a PNG as checkPng has it, or a JPEG whose frame header declares a size within
// kMaxImagePixels and whose data after that header can hold it: a byte for every 512 pixels at least,
// each 8x8 block's DC code being a bit or more (the two formats glTF 2.0 allows).
Result<ImageSize> checkTextureImage(std::span<const std::uint8_t> bytes);

}  // namespace frugal
