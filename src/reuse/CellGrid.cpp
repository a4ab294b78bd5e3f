#include "reuse/CellGrid.h"

#include <algorithm>
#include <cassert>

namespace frugal::reuse {

CellGrid::CellGrid(int width, int height, int cell)
    : width_(width), height_(height), cell_(std::max(1, cell)),
      columns_((width + cell_ - 1) / cell_), rows_((height + cell_ - 1) / cell_),
      bits_(std::size_t(columns_) * std::size_t(rows_), 0) {
    for (auto& sums : sums_) sums.assign(std::size_t(columns_ + 1) * std::size_t(rows_ + 1), 0);
}

void CellGrid::reset() {
    if (any_) std::fill(bits_.begin(), bits_.end(), std::uint8_t(0));
    any_ = false;
}

void CellGrid::mark(const Box& box, std::uint8_t bits) {
    if (box.empty()) return;
    any_ = true;
    const int c0 = box.x0 / cell_, c1 = (box.x1 - 1) / cell_;
    const int r0 = box.y0 / cell_, r1 = (box.y1 - 1) / cell_;
    for (int r = r0; r <= r1; ++r) {
        std::uint8_t* row = bits_.data() + std::size_t(r) * std::size_t(columns_);
        for (int c = c0; c <= c1; ++c) row[c] |= bits;
    }
}

void CellGrid::seal(int slot, std::uint8_t mask) {
    assert(slot == 0 || slot == 1);
    std::vector<std::int32_t>& sums = sums_[slot];
    const std::size_t stride = std::size_t(columns_) + 1;
    for (int r = 0; r < rows_; ++r) {
        std::int32_t run = 0;
        const std::uint8_t* row = bits_.data() + std::size_t(r) * std::size_t(columns_);
        std::int32_t* above = sums.data() + std::size_t(r) * stride;
        std::int32_t* out = above + stride;
        for (int c = 0; c < columns_; ++c) {
            run += (row[c] & mask) != 0 ? 1 : 0;
            out[c + 1] = above[c + 1] + run;
        }
    }
}

bool CellGrid::meets(int slot, const Box& box) const {
    if (box.empty() || !any_) return false;
    const std::vector<std::int32_t>& sums = sums_[slot];
    const std::size_t stride = std::size_t(columns_) + 1;
    const std::size_t c0 = std::size_t(box.x0 / cell_), c1 = std::size_t((box.x1 - 1) / cell_) + 1;
    const std::size_t r0 = std::size_t(box.y0 / cell_), r1 = std::size_t((box.y1 - 1) / cell_) + 1;
    return sums[r1 * stride + c1] - sums[r0 * stride + c1] - sums[r1 * stride + c0] + sums[r0 * stride + c0] > 0;
}

std::vector<Rect> CellGrid::rects(std::uint8_t mask, std::uint8_t exclude, std::int64_t& pixels) const {
    std::vector<Rect> out;
    pixels = 0;
    if (!any_) return out;
    struct Open {
        int c0, c1, r0;
    };
    std::vector<Open> open, next;
    const auto close = [&](const Open& o, int r1) {
        Rect rect{o.c0 * cell_, o.r0 * cell_, 0, 0};
        rect.width = std::min(o.c1 * cell_, width_) - rect.x;
        rect.height = std::min(r1 * cell_, height_) - rect.y;
        pixels += std::int64_t(rect.width) * rect.height;
        out.push_back(rect);
    };
    for (int r = 0; r <= rows_; ++r) {
        next.clear();
        std::size_t k = 0;  // open rectangles are sorted by c0, as are this row's runs
        const std::uint8_t* row = r < rows_ ? bits_.data() + std::size_t(r) * std::size_t(columns_) : nullptr;
        int c = 0;
        while (row != nullptr && c < columns_) {
            if ((row[c] & mask) == 0 || (row[c] & exclude) != 0) { ++c; continue; }
            const int c0 = c;
            while (c < columns_ && (row[c] & mask) != 0 && (row[c] & exclude) == 0) ++c;
            // Close the open rectangles that end before this run, extend the one that matches it.
            while (k < open.size() && open[k].c0 < c0) close(open[k++], r);
            if (k < open.size() && open[k].c0 == c0 && open[k].c1 == c) next.push_back(open[k++]);
            else next.push_back({c0, c, r});
        }
        while (k < open.size()) close(open[k++], r);
        open.swap(next);
    }
    return out;
}

}  // namespace frugal::reuse
