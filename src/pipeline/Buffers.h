// What a backend's target is read back as, all planes at once (Buffers), and the rectangles plans
// clear and copy (Rect, clipRect). The public images (frugal/Image.h: ColorImage, DepthImage,
// IdImage) are what a Renderer hands out; these are the backends' and the comparisons' own.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <frugal/Image.h>

namespace frugal {

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

// The three planes of a target as read back at once (the comparisons and reports read them so).
struct Buffers {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;  // 4 bytes a pixel
    // A Rgba32F target's colour (LinearImage: 4 floats a pixel); `rgba` is then its display
    // encoding (encodeLinear). Empty for an 8-bit target.
    std::vector<float> linear;
    // D24: the 24-bit values. D32F: the floats' bits; window z is never negative, so these order as
    // the floats do and their difference counts the floats between two values (ULPs).
    std::vector<std::uint32_t> depth;
    std::vector<std::uint32_t> ids;  // triangle ids
    DepthFormat depthFormat = DepthFormat::D24;

    std::size_t pixelCount() const { return std::size_t(width) * std::size_t(height); }
    // Window z of pixel i, in [0, 1].
    float windowDepth(std::size_t i) const { return frugal::windowDepth(depthFormat, depth[i]); }
};

// Fills out.rgba from out.linear: displayLevel for rgb, alphaLevel for alpha (frugal/Image.h).
void encodeLinear(Buffers& out);

}  // namespace frugal
