// CPU-side images read back from a render target.
//
// Window convention: row 0 is the bottom row (GL window origin bottom-left). Images are flipped once,
// when written to a file (see io/ImageIO.h).
// Depth: 24-bit unsigned integers, 0 = near, 0xFFFFFF = far (window z in [0,1] × 16777215); both
// backends render into a 24-bit depth buffer, so values compare exactly.
// Triangle ids: 32-bit, 0 = background (see scene/Scene.h for how ids are formed).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace frugal {

inline constexpr std::uint32_t kDepthMax = 0xFFFFFFu;

struct Rect {
    int x = 0, y = 0, width = 0, height = 0;  // window coordinates, origin bottom-left
    bool empty() const { return width <= 0 || height <= 0; }
};

// The part of `rect` inside a width × height target (empty when they do not meet).
inline Rect clipRect(const Rect& rect, int width, int height) {
    const int x0 = std::max(rect.x, 0), y0 = std::max(rect.y, 0);
    const int x1 = std::min(rect.x + std::max(rect.width, 0), width);
    const int y1 = std::min(rect.y + std::max(rect.height, 0), height);
    return Rect{x0, y0, std::max(x1 - x0, 0), std::max(y1 - y0, 0)};
}

struct Buffers {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;     // 4 bytes a pixel
    std::vector<std::uint32_t> depth;   // 24-bit values
    std::vector<std::uint32_t> ids;     // triangle ids

    std::size_t pixelCount() const { return std::size_t(width) * std::size_t(height); }
};

}  // namespace frugal
