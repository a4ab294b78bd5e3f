// A texture's mipmaps: the levels below its base level, made on the CPU once when the texture is
// uploaded, so that the GL backend (which uploads them level by level instead of calling
// glGenerateMipmap, whose filter each driver chooses) and the software reference sample the same
// texels.
//
// Each level halves the one above, rounded down and at least 1 texel (GL's sizes: a 5×3 texture has
// levels 5×3, 2×1, 1×1), down to 1×1. A texel is the average of the area of the level above that it
// covers: the 2×2 box where a size halves exactly, three texels weighted 1/3, 2/3… of their width
// where it was odd, the texel itself along an axis already 1 wide. Colour is averaged as the
// texture's samplers read it: an sRGB texture's rgb in linear light (decoded by the sRGB curve,
// averaged, encoded again: the filter a sampler applies after decoding), alpha and linear data as
// they are. Each value is rounded to the nearest byte. Each level is made from the one above it, as
// GL's glGenerateMipmap makes them.
#pragma once

#include <cstdint>
#include <vector>

#include <frugal/Scene.h>

namespace frugal {

struct MipLevel {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;  // RGBA8, rows as Texture::rgba stores them
};

// How many levels a width × height texture has, its base level included: 1 + ⌊log2(max(w, h))⌋.
int mipLevelCount(int width, int height);

// Levels 1 … mipLevelCount − 1 of `texture` (its rgba is level 0), as above. The texture must be
// valid (a positive size and width × height × 4 bytes). Throws std::bad_alloc when memory runs out.
std::vector<MipLevel> mipLevels(const Texture& texture);

}  // namespace frugal
