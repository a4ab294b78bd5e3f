#include "reuse/Extents.h"

#include <cmath>

namespace frugal::reuse {

void ExtentBuilder::project(const glm::mat4& mvp, std::span<const glm::vec3> positions) {
    vertices_.resize(positions.size());
    const double halfW = 0.5 * width_, halfH = 0.5 * height_;
    for (std::size_t i = 0; i < positions.size(); ++i) {
        const glm::vec4 c = mvp * glm::vec4(positions[i], 1.0f);
        ProjectedVertex& v = vertices_[i];
        v = ProjectedVertex{};
        if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && std::isfinite(c.w))) {
            v.unbounded = true;
            v.outside = 0;
            continue;
        }
        v.outside = std::uint8_t((c.x < -c.w ? 1 : 0) | (c.x > c.w ? 2 : 0) | (c.y < -c.w ? 4 : 0) |
                                 (c.y > c.w ? 8 : 0) | (c.z < -c.w ? 16 : 0) | (c.z > c.w ? 32 : 0));
        if (!(c.w > 0.0f)) {
            v.unbounded = true;
            continue;
        }
        // Window coordinates in double, then clamped to a band around the target so that the
        // float and the integer conversions below stay exact.
        const double x = (double(c.x) / c.w + 1.0) * halfW, y = (double(c.y) / c.w + 1.0) * halfH;
        const double band = 4.0 * (width_ + height_) + 16.0;
        v.x = float(std::clamp(x, -band, band));
        v.y = float(std::clamp(y, -band, band));
    }
}

Box ExtentBuilder::triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    const ProjectedVertex& p = vertices_[a];
    const ProjectedVertex& q = vertices_[b];
    const ProjectedVertex& r = vertices_[c];
    if (p.outside & q.outside & r.outside) return Box{};
    if (p.unbounded || q.unbounded || r.unbounded) return screen();
    const float minX = std::min({p.x, q.x, r.x}), maxX = std::max({p.x, q.x, r.x});
    const float minY = std::min({p.y, q.y, r.y}), maxY = std::max({p.y, q.y, r.y});
    const auto margin = [](float v) { return 1.0f + 1e-5f * std::abs(v); };
    Box box;
    box.x0 = std::max(0, int(std::floor(minX - margin(minX))));
    box.y0 = std::max(0, int(std::floor(minY - margin(minY))));
    box.x1 = std::min(width_, int(std::ceil(maxX + margin(maxX))));
    box.y1 = std::min(height_, int(std::ceil(maxY + margin(maxY))));
    if (box.empty()) return Box{};
    return box;
}

Box ExtentBuilder::segment(std::uint32_t a, std::uint32_t b) const {
    Box box = triangle(a, b, b);
    if (box.empty()) return box;
    box.x0 = std::max(box.x0 - 1, 0), box.y0 = std::max(box.y0 - 1, 0);
    box.x1 = std::min(box.x1 + 1, width_), box.y1 = std::min(box.y1 + 1, height_);
    return box;
}

}  // namespace frugal::reuse
