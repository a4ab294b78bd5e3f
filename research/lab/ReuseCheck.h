// A reuse frame judged against the full render of the same frame (src/reuse/Reuse.h): every pixel
// must match in colour, depth and id, except where a static and a dynamic triangle tie in depth and
// the draw order (static first under reuse, scene order in a full render) picked the other one.
#pragma once

#include <cstddef>

#include <frugal/Image.h>
#include "renderer/Research.h"

namespace frugal {

struct FrameMatch {
    std::size_t pixels = 0;
    std::size_t differing = 0;  // colour, depth or id differs
    std::size_t ties = 0;       // of those: equal depth, another triangle (id or colour differs)
    std::size_t errors() const { return differing - ties; }  // depth differs: never allowed
};

// `reuse` and `full` must have the same size; ids and depth are compared when both have them
// (without depth on either side every difference counts as an error).
FrameMatch matchFrames(const Buffers& reuse, const Buffers& full);

}  // namespace frugal
