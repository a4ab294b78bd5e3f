// The screen grid behind the ⊗ tests of temporal reuse: O(n + k) instead of the paper's all-pairs
// loop. Regions (what a frame copies, clears, copies back) are sets of cells of `cell` × `cell`
// pixels; each cell holds a bit per region. Marking an extent sets the bits of the cells it meets,
// so a region is a superset of the extents marked into it, never smaller. After seal(), whether a
// box meets a region is O(1) (a summed-area table per queried mask), and a region is turned into
// few rectangles (row runs merged downwards) for the backend's clear and copy.
//
// Exactness: temporal reuse copies and clears exactly the cells of a region and tests extents
// against exactly those cells, so the cell size trades pixels copied against triangles redrawn,
// never correctness.
#pragma once

#include <cstdint>
#include <vector>

#include "reuse/Extents.h"

namespace frugal::reuse {

class CellGrid {
public:
    CellGrid(int width, int height, int cell);

    void reset();                                 // every bit cleared, nothing sealed
    void mark(const Box& box, std::uint8_t bits);  // sets `bits` in every cell `box` meets
    // Builds the summed-area table of cells with any bit of `mask` set (call once per mask after
    // marking; at most two masks are kept, slots 0 and 1).
    void seal(int slot, std::uint8_t mask);
    // Whether `box` meets a cell counted by slot `slot`'s mask.
    bool meets(int slot, const Box& box) const;

    // The cells whose bits b satisfy (b & mask) != 0 and (b & exclude) == 0, as pixel rectangles
    // clipped to the target (row runs merged with identical runs below them), and their pixel count.
    std::vector<Rect> rects(std::uint8_t mask, std::uint8_t exclude, std::int64_t& pixels) const;

    int cell() const { return cell_; }
    int columns() const { return columns_; }
    int rows() const { return rows_; }

private:
    int width_, height_, cell_, columns_, rows_;
    std::vector<std::uint8_t> bits_;
    std::vector<std::int32_t> sums_[2];  // (columns + 1) × (rows + 1)
    bool any_ = false;
};

}  // namespace frugal::reuse
