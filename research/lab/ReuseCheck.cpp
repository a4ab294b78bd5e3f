#include "lab/ReuseCheck.h"

#include <cassert>
#include <cstring>
#include "renderer/Research.h"

namespace frugal {

FrameMatch matchFrames(const Buffers& reuse, const Buffers& full) {
    FrameMatch match;
    assert(reuse.width == full.width && reuse.height == full.height);
    match.pixels = full.pixelCount();
    const bool depth = reuse.depth.size() == match.pixels && full.depth.size() == match.pixels;
    const bool ids = reuse.ids.size() == match.pixels && full.ids.size() == match.pixels;
    for (std::size_t p = 0; p < match.pixels; ++p) {
        const bool colorDiffers = std::memcmp(&reuse.rgba[4 * p], &full.rgba[4 * p], 4) != 0;
        const bool idDiffers = ids && reuse.ids[p] != full.ids[p];
        const bool depthDiffers = depth && reuse.depth[p] != full.depth[p];
        if (!colorDiffers && !idDiffers && !depthDiffers) continue;
        ++match.differing;
        if (depth && !depthDiffers) ++match.ties;
    }
    return match;
}

}  // namespace frugal
