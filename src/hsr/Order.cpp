#include "hsr/Order.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace frugal::hsr {
namespace {

// A vertex in window space: x, y (pixels), z (window depth), its outcodes against the six clip
// planes, and whether its projection is unbounded (w ≤ 0 or a non-finite coordinate).
struct WindowVertex {
    double x = 0.0, y = 0.0, z = 0.0;
    std::uint8_t outside = 0;  // bit per plane: -x, +x, -y, +y, -z, +z
    bool unbounded = false;
};

WindowVertex toWindow(const glm::mat4& mvp, const glm::vec3& position, int width, int height, bool reversed) {
    const glm::vec4 c = mvp * glm::vec4(position, 1.0f);
    WindowVertex v;
    if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && std::isfinite(c.w))) {
        v.unbounded = true;
        return v;
    }
    // D32F's clip space holds 0 ≤ z ≤ w (near at z = w), D24's −w ≤ z ≤ w.
    v.outside = std::uint8_t((c.x < -c.w ? 1 : 0) | (c.x > c.w ? 2 : 0) | (c.y < -c.w ? 4 : 0) | (c.y > c.w ? 8 : 0) |
                             (c.z < (reversed ? 0.0f : -c.w) ? 16 : 0) | (c.z > c.w ? 32 : 0));
    if (!(c.w > 0.0f)) {
        v.unbounded = true;
        return v;
    }
    // Clamped to a band around the target so that the integer conversions below stay exact.
    const double band = 4.0 * (width + height) + 16.0;
    v.x = std::clamp((double(c.x) / c.w + 1.0) * 0.5 * width, -band, band);
    v.y = std::clamp((double(c.y) / c.w + 1.0) * 0.5 * height, -band, band);
    // Depth as D24 orders it, 0 near and 1 far, in both formats (D32F's window z is 1 near, 0 far).
    v.z = reversed ? 1.0 - double(c.z) / c.w : (double(c.z) / c.w + 1.0) * 0.5;
    return v;
}

// Facing in window space (counter-clockwise is front), see Order.h: −1 clearly back-facing, +1
// clearly front-facing, 0 nearly edge-on.
int facing(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c) {
    const double ux = b.x - a.x, uy = b.y - a.y, vx = c.x - a.x, vy = c.y - a.y;
    const double area2 = ux * vy - uy * vx, margin = 1e-5 * std::hypot(ux, uy) * std::hypot(vx, vy);
    return area2 < -margin ? -1 : area2 > margin ? 1 : 0;
}

}  // namespace

ScreenTriangles screenTriangles(const Scene& scene, const FrameParams& frame, const std::vector<glm::mat4>& world,
                                const DrawList& list, int width, int height) {
    ScreenTriangles out;
    if (width < 1 || height < 1) return out;
    const glm::mat4 viewProjection = frame.projection * frame.view;
    const Extent whole{0, 0, width - 1, height - 1, 0.0f, 1.0f};
    const bool reversed = frame.depthFormat == DepthFormat::D32F;
    const double zMargin = reversed ? kZMarginF32 : kZMargin;
    const auto margin = [](double v) { return 1.0 + 1e-5 * std::abs(v); };
    std::vector<WindowVertex> vertices;
    for (const DrawCommand& command : list) {
        if (command.ranges.empty()) continue;
        const Instance& instance = scene.instances[std::size_t(command.instance)];
        const Mesh& mesh = scene.meshes[std::size_t(instance.mesh)];
        const bool singleSided = mesh.material < 0 || !scene.materials[std::size_t(mesh.material)].doubleSided;
        const glm::mat4 mvp = viewProjection * world[std::size_t(instance.node)];
        vertices.resize(mesh.positions.size());
        for (std::size_t i = 0; i < mesh.positions.size(); ++i)
            vertices[i] = toWindow(mvp, mesh.positions[i], width, height, reversed);
        const std::uint32_t meshTriangles = std::uint32_t(mesh.triangleCount());
        for (const IndexRange& range : command.ranges) {
            const std::uint32_t first = std::min(range.firstTriangle, meshTriangles);
            const std::uint32_t end = first + std::min(range.triangleCount, meshTriangles - first);
            for (std::uint32_t t = first; t < end; ++t) {
                const WindowVertex& a = vertices[mesh.indices[3 * std::size_t(t)]];
                const WindowVertex& b = vertices[mesh.indices[3 * std::size_t(t) + 1]];
                const WindowVertex& c = vertices[mesh.indices[3 * std::size_t(t) + 2]];
                if (a.outside & b.outside & c.outside) continue;
                Extent e = whole;
                float depth = 0.0f;
                int side = 0;
                if (!(a.unbounded || b.unbounded || c.unbounded)) {
                    side = facing(a, b, c);
                    if (singleSided && side < 0) continue;
                    const double minX = std::min({a.x, b.x, c.x}), maxX = std::max({a.x, b.x, c.x});
                    const double minY = std::min({a.y, b.y, c.y}), maxY = std::max({a.y, b.y, c.y});
                    e.x0 = std::max(0, int(std::floor(minX - margin(minX))));
                    e.y0 = std::max(0, int(std::floor(minY - margin(minY))));
                    e.x1 = std::min(width - 1, int(std::ceil(maxX + margin(maxX))) - 1);
                    e.y1 = std::min(height - 1, int(std::ceil(maxY + margin(maxY))) - 1);
                    if (e.x0 > e.x1 || e.y0 > e.y1) continue;
                    const double minZ = std::min({a.z, b.z, c.z}), maxZ = std::max({a.z, b.z, c.z});
                    e.z0 = float(std::clamp(minZ - zMargin, 0.0, 1.0));
                    e.z1 = float(std::clamp(maxZ + zMargin, 0.0, 1.0));
                    depth = float((std::clamp(a.z, 0.0, 1.0) + std::clamp(b.z, 0.0, 1.0) + std::clamp(c.z, 0.0, 1.0)) / 3.0);
                } else {
                    // Only the bounded vertices count; the others sit on the near plane (z 0).
                    for (const WindowVertex* v : {&a, &b, &c})
                        if (!v->unbounded) depth += float(std::clamp(v->z, 0.0, 1.0) / 3.0);
                }
                out.refs.push_back(TriangleRef{command.instance, t});
                out.extents.push_back(e);
                out.depth.push_back(depth);
                out.front.push_back(side > 0 ? 1 : 0);
            }
        }
    }
    return out;
}

std::vector<std::uint32_t> backToFront(std::span<const float> depth) {
    std::vector<std::uint32_t> order(depth.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return depth[a] > depth[b]; });
    return order;
}

}  // namespace frugal::hsr
