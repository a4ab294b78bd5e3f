// Extents (paper 000, Fig. 2): integer screen rectangles that contain every pixel a triangle can
// cover, computed on the CPU from the same float model-view-projection the backends use.
//
// Why a rectangle is enough, and when it is the whole screen:
// - A pixel (px, py) is covered only if its centre (px + 0.5, py + 0.5) lies inside the triangle
//   (src/raster/Rasterizer.h, llvmpipe's rules), so inside the bounding box [minX, maxX] ×
//   [minY, maxY] of the projected vertices: px ∈ [floor(minX), ceil(maxX)). One more pixel on each
//   side absorbs the sub-pixel snapping and the last bits by which a vertex shader's float
//   arithmetic (FMA, another association) may differ from ours; a further 1e-5 of the coordinate's
//   magnitude keeps that margin relative for vertices far from the origin of the window.
// - Clipping against the near and far planes adds vertices on edges whose ends both have w > 0, and
//   a perspective projection maps such an edge to the segment between the ends' projections: the
//   clipped polygon stays inside the box of the projected vertices. Only a vertex at w ≤ 0 (at or
//   behind the eye plane, where the near plane's clipping makes the projection unbounded) makes
//   the extent the whole screen. A non-finite vertex does too.
// - A triangle whose three vertices lie outside one clip plane covers nothing: empty extent.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "pipeline/Backend.h"

namespace frugal::reuse {

// A half-open pixel box [x0, x1) × [y0, y1), window coordinates (origin bottom-left), always
// clipped to its target; x0 == x1 or y0 == y1 is empty.
struct Box {
    std::int32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x0 >= x1 || y0 >= y1; }
    std::int64_t area() const { return empty() ? 0 : std::int64_t(x1 - x0) * (y1 - y0); }
    void add(const Box& b) {
        if (b.empty()) return;
        if (empty()) { *this = b; return; }
        x0 = std::min(x0, b.x0); y0 = std::min(y0, b.y0);
        x1 = std::max(x1, b.x1); y1 = std::max(y1, b.y1);
    }
    bool operator==(const Box&) const = default;
};

inline bool overlaps(const Box& a, const Box& b) {
    return !a.empty() && !b.empty() && a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}
inline Rect toRect(const Box& b) { return Rect{b.x0, b.y0, b.x1 - b.x0, b.y1 - b.y0}; }

// Projects positions once: window x, y and a code of what the vertex is (outcodes against the six
// clip planes, and "unbounded" for w ≤ 0 or a non-finite coordinate).
struct ProjectedVertex {
    float x = 0.0f, y = 0.0f;  // window coordinates (only meaningful when bounded)
    std::uint8_t outside = 0;  // bit per clip plane: -x, +x, -y, +y, -z, +z
    bool unbounded = false;
};

class ExtentBuilder {
public:
    ExtentBuilder(int width, int height) : width_(width), height_(height) {}

    // `mvp` = projection × view × model, as the backends form it (float, glm).
    void project(const glm::mat4& mvp, std::span<const glm::vec3> positions);
    // The extent of triangle (a, b, c) of the positions last projected.
    Box triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;
    // The extent of segment (a, b), or of point a when b = a (Mesh::topology): the triangle's box,
    // one pixel wider each side, for a segment's or a point's pixels reach half a pixel beyond its
    // projection (raster/PointsLines.h).
    Box segment(std::uint32_t a, std::uint32_t b) const;

    Box screen() const { return Box{0, 0, width_, height_}; }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    int width_, height_;
    std::vector<ProjectedVertex> vertices_;
};

}  // namespace frugal::reuse
