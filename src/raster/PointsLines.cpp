#include "raster/PointsLines.h"

#include <algorithm>
#include <cmath>
#include <utility>

#if !defined(__clang__)  // Clang: -ffp-contract=off (CMakeLists.txt)
#pragma GCC optimize("fp-contract=off")
#endif

namespace frugal::raster {

namespace {

// util_iround on x86-64: half away from zero, the add rounded in float (3.).
int iround(float f) { return f >= 0.0f ? int(f + 0.5f) : int(f - 0.5f); }
int snap(float a) { return iround(256.0f * a); }
bool sign(float x) { return x >= 0.0f; }
float fract(float f) { return f - std::floor(f); }

// The box [x0, x1] × [y0, y1] within the target; false when it is empty or outside (u_rect's test).
bool clampBox(int& x0, int& y0, int& x1, int& y1, const Viewport& viewport) {
    if (x1 < x0 || y1 < y0 || x1 < 0 || y1 < 0 || x0 > viewport.width - 1 || y0 > viewport.height - 1) return false;
    x0 = std::max(x0, 0), y0 = std::max(y0, 0);
    x1 = std::min(x1, viewport.width - 1), y1 = std::min(y1, viewport.height - 1);
    return true;
}

}  // namespace

bool setupPoint(const SetupVertex& v, const Viewport& viewport, ShapeSetup* out) {
    const float po = pixelOffset(viewport);
    const int fw = 256;  // max(256, snap(1))
    const int x0 = snap(v.x - po) - fw / 2, y0 = snap(v.y - po) - fw / 2;
    const int x1 = x0 + fw, y1 = y0 + fw;
    ShapeSetup& s = *out;
    s.x0 = x0 >> 8, s.y0 = y0 >> 8, s.x1 = ((x1 + 255) >> 8) - 1, s.y1 = ((y1 + 255) >> 8) - 1;
    if (!clampBox(s.x0, s.y0, s.x1, s.y1, viewport)) return false;
    s.planes[0] = {-std::int64_t(std::max(x0, s.x0 << 8)) + 1, -1, 0};
    s.planes[1] = {std::int64_t(std::min(x1, (s.x1 + 1) << 8)), 1, 0};
    s.planes[2] = {-std::int64_t(std::max(y0, s.y0 << 8)) + 1, 0, 1};
    s.planes[3] = {std::int64_t(std::min(y1, (s.y1 + 1) << 8)), 0, -1};
    s.z0 = v.z, s.dzdx = 0.0f, s.dzdy = 0.0f;
    return true;
}

bool setupSegment(const SetupVertex& a, const SetupVertex& b, const Viewport& viewport, ShapeSetup* out) {
    SetupVertex v1 = a, v2 = b;
    float dx = v1.x - v2.x, dy = v1.y - v2.y;
    const float area = dx * dx + dy * dy;
    if (area == 0.0f) return false;
    float infoDx = dx, infoDy = dy;
    const float oneOverArea = 1.0f / area;
    const bool multisampled = viewport.samples > 1;
    const float po = pixelOffset(viewport);
    ShapeSetup& s = *out;
    s.xMajor = std::fabs(dx) >= std::fabs(dy);
    int x[4], y[4];
    if (multisampled) {
        const float scale = 0.5f / std::sqrt(area);
        const int tx = snap(-dy * scale), ty = snap(dx * scale);
        const int x1 = snap(v1.x - po), x2 = snap(v2.x - po), y1 = snap(v1.y - po), y2 = snap(v2.y - po);
        x[0] = x1 - tx, x[1] = x2 - tx, x[2] = x2 + tx, x[3] = x1 + tx;
        y[0] = y1 - ty, y[1] = y2 - ty, y[2] = y2 + ty, y[3] = y1 + ty;
    } else {
        float xOffset = 0, yOffset = 0, xOffsetEnd = 0, yOffsetEnd = 0;
        const float x1diff = v1.x - std::floor(v1.x) - 0.5f, y1diff = v1.y - std::floor(v1.y) - 0.5f;
        float x2diff = v2.x - std::floor(v2.x) - 0.5f, y2diff = v2.y - std::floor(v2.y) - 0.5f;
        constexpr int halfWidth = 128;  // round(width) · 256 / 2
        bool drawStart, drawEnd;
        if (s.xMajor) {
            const float dydx = dy / dx;
            if (y2diff == -0.5f && dy < 0) y2diff = 0.5f;
            if (std::fabs(x1diff) + std::fabs(y1diff) < 0.5f)
                drawStart = true;
            else if (sign(x1diff) == sign(-dx))
                drawStart = false;
            else if (sign(-y1diff) != sign(dy))
                drawStart = true;
            else {
                const float yi = fract(v1.y) + x1diff * dydx;
                drawStart = yi < 1.0f && yi > 0.0f;
            }
            if (std::fabs(x2diff) + std::fabs(y2diff) < 0.5f)
                drawEnd = false;
            else if (sign(x2diff) != sign(-dx))
                drawEnd = false;
            else if (sign(-y2diff) == sign(dy))
                drawEnd = true;
            else {
                const float yi = fract(v2.y) + x2diff * dydx;
                drawEnd = yi < 1.0f && yi > 0.0f;
            }
            const bool willDrawStart = sign(-x1diff) != sign(dx);
            const bool willDrawEnd = sign(x2diff) == sign(-dx) || x2diff == 0.0f;
            infoDx *= 1.0f + dydx * dydx;
            infoDy = 0.0f;
            if (dx < 0) {
                std::swap(v1, v2);
                dx = -dx, dy = -dy;
                if (willDrawStart != drawStart) xOffsetEnd = -x1diff - 0.5f, yOffsetEnd = xOffsetEnd * dydx;
                if (willDrawEnd != drawEnd) xOffset = -x2diff - 0.5f, yOffset = xOffset * dydx;
            } else {
                if (willDrawStart != drawStart) xOffset = -x1diff + 0.5f, yOffset = xOffset * dydx;
                if (willDrawEnd != drawEnd) xOffsetEnd = -x2diff + 0.5f, yOffsetEnd = xOffsetEnd * dydx;
            }
            x[0] = x[3] = snap(v1.x + xOffset - po);
            x[1] = x[2] = snap(v2.x + xOffsetEnd - po);
            y[0] = snap(v1.y + yOffset - po) - halfWidth, y[3] = snap(v1.y + yOffset - po) + halfWidth;
            y[1] = snap(v2.y + yOffsetEnd - po) - halfWidth, y[2] = snap(v2.y + yOffsetEnd - po) + halfWidth;
        } else {
            const float dxdy = dx / dy;
            if (x2diff == -0.5f && dx < 0) x2diff = 0.5f;
            if (std::fabs(x1diff) + std::fabs(y1diff) < 0.5f)
                drawStart = true;
            else if (sign(-y1diff) == sign(dy))
                drawStart = false;
            else if (sign(x1diff) != sign(-dx))
                drawStart = true;
            else {
                const float xi = fract(v1.x) + y1diff * dxdy;
                drawStart = xi < 1.0f && xi > 0.0f;
            }
            if (std::fabs(x2diff) + std::fabs(y2diff) < 0.5f)
                drawEnd = false;
            else if (sign(-y2diff) != sign(dy))
                drawEnd = false;
            else if (sign(x2diff) == sign(-dx))
                drawEnd = true;
            else {
                const float xi = fract(v2.x) + y2diff * dxdy;
                drawEnd = xi < 1.0f && xi >= 0.0f;
            }
            const bool willDrawStart = sign(y1diff) == sign(dy);
            const bool willDrawEnd = sign(-y2diff) == sign(dy) || y2diff == 0.0f;
            infoDx = 0.0f;
            infoDy *= 1.0f + dxdy * dxdy;
            if (dy > 0) {
                std::swap(v1, v2);
                dx = -dx, dy = -dy;
                if (willDrawStart != drawStart) yOffsetEnd = -y1diff + 0.5f, xOffsetEnd = yOffsetEnd * dxdy;
                if (willDrawEnd != drawEnd) yOffset = -y2diff + 0.5f, xOffset = yOffset * dxdy;
            } else {
                if (willDrawStart != drawStart) yOffset = -y1diff - 0.5f, xOffset = yOffset * dxdy;
                if (willDrawEnd != drawEnd) yOffsetEnd = -y2diff - 0.5f, xOffsetEnd = yOffsetEnd * dxdy;
            }
            x[0] = snap(v1.x + xOffset - po) - halfWidth, x[3] = snap(v1.x + xOffset - po) + halfWidth;
            x[1] = snap(v2.x + xOffsetEnd - po) - halfWidth, x[2] = snap(v2.x + xOffsetEnd - po) + halfWidth;
            y[0] = y[3] = snap(v1.y + yOffset - po);
            y[1] = y[2] = snap(v2.y + yOffsetEnd - po);
        }
    }
    // The bounding box (bottom_edge_rule 0) within the target; empty or outside: dropped (6.).
    s.x0 = (std::min({x[0], x[1], x[2], x[3]}) + 255) >> 8;
    s.x1 = ((std::max({x[0], x[1], x[2], x[3]}) + 255) >> 8) - 1;
    s.y0 = (std::min({y[0], y[1], y[2], y[3]}) + 255) >> 8;
    s.y1 = ((std::max({y[0], y[1], y[2], y[3]}) + 255) >> 8) - 1;
    if (!clampBox(s.x0, s.y0, s.x1, s.y1, viewport)) return false;
    if (multisampled) {  // whole 64×64 tiles are tested (6.)
        s.x0 &= ~(kTileSize - 1), s.y0 &= ~(kTileSize - 1);
        s.x1 = std::min(s.x1 | (kTileSize - 1), viewport.width - 1);
        s.y1 = std::min(s.y1 | (kTileSize - 1), viewport.height - 1);
    }
    for (int i = 0; i < 4; ++i) {
        const int j = (i + 1) & 3;
        ShapeSetup::Plane& p = s.planes[i];
        p.dcdy = std::int64_t(x[i]) - x[j];
        p.dcdx = std::int64_t(y[i]) - y[j];
        p.c = p.dcdx * x[i] - p.dcdy * y[i];
        if (p.dcdx < 0 || (p.dcdx == 0 && p.dcdy > 0)) ++p.c;  // top-left rule
    }
    // The depth plane, from the ends as given (7.).
    const float dz = a.z - b.z;
    s.dzdx = dz * infoDx * oneOverArea;
    s.dzdy = dz * infoDy * oneOverArea;
    s.z0 = a.z - (s.dzdx * (a.x - 0.5f) + s.dzdy * (a.y - 0.5f));
    return true;
}

bool clipSegment(const glm::vec4& c0, const glm::vec4& c1, unsigned mask0, unsigned mask1, bool halfZ, float* t0,
                 float* t1) {
    *t0 = *t1 = 0.0f;
    if ((mask0 | mask1) == 0) return true;
    if ((mask0 & mask1) != 0) return false;
    const glm::vec4 planes[6] = {
        {-1, 0, 0, 1}, {1, 0, 0, 1}, {0, -1, 0, 1}, {0, 1, 0, 1}, halfZ ? glm::vec4(0, 0, 1, 0) : glm::vec4(0, 0, 1, 1),
        {0, 0, -1, 1}};
    const auto dot = [](const glm::vec4& v, const glm::vec4& p) {
        return ((v.x * p.x + v.y * p.y) + v.z * p.z) + v.w * p.w;
    };
    for (unsigned mask = mask0 | mask1; mask != 0; mask &= mask - 1) {
        const glm::vec4& plane = planes[__builtin_ctz(mask)];
        const float dp0 = dot(c0, plane), dp1 = dot(c1, plane);
        if (!std::isfinite(dp0) || !std::isfinite(dp1)) return false;
        if (dp1 < 0.0f) *t1 = std::max(*t1, dp1 / (dp1 - dp0));
        if (dp0 < 0.0f) *t0 = std::max(*t0, dp0 / (dp0 - dp1));
        if (*t0 + *t1 >= 1.0f) return false;
    }
    return true;
}

}  // namespace frugal::raster
