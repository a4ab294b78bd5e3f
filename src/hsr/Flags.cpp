#include "hsr/Flags.h"

#include <algorithm>
#include <cmath>

namespace frugal::hsr {
namespace {

// A triangle's extent in a cell's list, copied so that a cell's scan reads memory in order.
struct Entry {
    Extent extent;
    std::uint32_t index = 0;
};

// The grid over the boxes' union: cells of 2^shift pixels a side, cell (cx, cy) at cy · cols + cx.
struct Grid {
    std::int64_t x0 = 0, y0 = 0;  // pixel at the corner of cell (0, 0)
    int shift = 0;
    std::int64_t cols = 1, rows = 1;

    std::int64_t col(std::int64_t x) const { return (x - x0) >> shift; }
    std::int64_t row(std::int64_t y) const { return (y - y0) >> shift; }
    std::int64_t entries(const Extent& e) const { return (col(e.x1) - col(e.x0) + 1) * (row(e.y1) - row(e.y0) + 1); }
};

Grid chooseGrid(std::span<const Extent> extents) {
    Grid grid;
    std::int64_t x1 = extents[0].x1, y1 = extents[0].y1;
    grid.x0 = extents[0].x0;
    grid.y0 = extents[0].y0;
    double sides = 0.0;
    for (const Extent& e : extents) {
        grid.x0 = std::min<std::int64_t>(grid.x0, e.x0);
        grid.y0 = std::min<std::int64_t>(grid.y0, e.y0);
        x1 = std::max<std::int64_t>(x1, e.x1);
        y1 = std::max<std::int64_t>(y1, e.y1);
        sides += 0.5 * (double(e.x1) - e.x0 + 1.0) + 0.5 * (double(e.y1) - e.y0 + 1.0);
    }
    const std::int64_t n = std::int64_t(extents.size());
    grid.shift = std::max(0, int(std::ceil(std::log2(sides / double(n)))));
    for (;; ++grid.shift) {
        grid.cols = grid.col(x1) + 1;
        grid.rows = grid.row(y1) + 1;
        if (grid.cols * grid.rows > 2 * n) continue;
        std::int64_t total = 0;
        for (const Extent& e : extents) total += grid.entries(e);
        if (total <= 8 * n) return grid;
    }
}

bool sameGroup(std::span<const std::int32_t> groups, std::size_t a, std::size_t b) {
    return !groups.empty() && groups[a] >= 0 && groups[a] == groups[b];
}

}  // namespace

std::vector<std::uint8_t> flagOverlapsAllPairs(std::span<const Extent> extents, std::span<const std::int32_t> groups) {
    std::vector<std::uint8_t> flags(extents.size(), 0);
    for (std::size_t f = 0; f < extents.size(); ++f)
        for (std::size_t s = f + 1; s < extents.size(); ++s)
            if (overlaps(extents[f], extents[s]) && !sameGroup(groups, f, s)) flags[f] = flags[s] = 1;
    return flags;
}

std::vector<std::uint8_t> flagOverlaps(std::span<const Extent> extents, std::span<const std::int32_t> groups) {
    std::vector<std::uint8_t> flags(extents.size(), 0);
    if (extents.size() < 2) return flags;
    const Grid grid = chooseGrid(extents);

    // Triangles by x0 (then index), as one sort of 64-bit keys: x0 relative to the grid's corner
    // fits 32 bits because extents are 32-bit coordinates.
    std::vector<std::uint64_t> byX(extents.size());
    for (std::size_t i = 0; i < extents.size(); ++i)
        byX[i] = (std::uint64_t(std::int64_t(extents[i].x0) - grid.x0) << 32) | i;
    std::sort(byX.begin(), byX.end());

    // Cell lists, bucketed in x0 order: a count, a prefix sum, a fill.
    const std::size_t cells = std::size_t(grid.cols * grid.rows);
    std::vector<std::uint32_t> start(cells + 1, 0);
    const auto forCells = [&](const Extent& e, auto&& visit) {
        for (std::int64_t cy = grid.row(e.y0); cy <= grid.row(e.y1); ++cy)
            for (std::int64_t cx = grid.col(e.x0); cx <= grid.col(e.x1); ++cx) visit(std::size_t(cy * grid.cols + cx));
    };
    for (const Extent& e : extents) forCells(e, [&](std::size_t cell) { ++start[cell + 1]; });
    for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
    std::vector<Entry> entries(start[cells]);
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (const std::uint64_t key : byX) {
        const std::uint32_t i = std::uint32_t(key & 0xFFFFFFFFu);
        forCells(extents[i], [&](std::size_t cell) { entries[fill[cell]++] = Entry{extents[i], i}; });
    }

    // In each cell, every triangle against the ones after it that start before it ends in x.
    for (std::size_t c = 0; c < cells; ++c) {
        const std::uint32_t end = start[c + 1];
        for (std::uint32_t i = start[c]; i < end; ++i) {
            const Extent& a = entries[i].extent;
            const std::uint32_t ai = entries[i].index;
            for (std::uint32_t j = i + 1; j < end && entries[j].extent.x0 <= a.x1; ++j) {
                const Extent& b = entries[j].extent;
                const std::uint32_t bi = entries[j].index;
                if (flags[ai] && flags[bi]) continue;
                if (a.y0 <= b.y1 && b.y0 <= a.y1 && a.z0 <= b.z1 && b.z0 <= a.z1 && !sameGroup(groups, ai, bi))
                    flags[ai] = flags[bi] = 1;
            }
        }
    }
    return flags;
}

}  // namespace frugal::hsr
