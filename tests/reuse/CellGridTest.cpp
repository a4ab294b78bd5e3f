// The screen grid behind the ⊗ tests (src/reuse/CellGrid.h) against a brute-force reference that
// works pixel by pixel: mark, seal and meets on random boxes; rects() covering exactly the pixels
// of the cells that qualify, without overlap, clipped to the target, with the right pixel count.
// Sizes include targets that are not a multiple of the cell, a cell of 1 and a cell larger than the
// target.
#include <gtest/gtest.h>

#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "reuse/CellGrid.h"

namespace frugal::test {
namespace {

using reuse::Box;
using reuse::CellGrid;

struct Size {
    int width, height, cell;
};

std::string str(const Size& s) {
    return std::to_string(s.width) + "x" + std::to_string(s.height) + " cell " + std::to_string(s.cell);
}

const Size kSizes[] = {{64, 48, 16}, {100, 75, 16}, {37, 23, 8},  {50, 30, 1},  {20, 10, 64}, {1, 1, 1},
                       {1, 1, 16},   {200, 150, 7}, {33, 65, 32}, {96, 72, 256}, {7, 300, 3}};

// The reference: the bits of every cell, and the questions answered pixel by pixel.
class Reference {
public:
    explicit Reference(const Size& s)
        : s_(s), columns_((s.width + s.cell - 1) / s.cell), rows_((s.height + s.cell - 1) / s.cell),
          bits_(std::size_t(columns_) * std::size_t(rows_), 0) {}
    void reset() { std::fill(bits_.begin(), bits_.end(), std::uint8_t(0)); }
    void mark(const Box& b, std::uint8_t bits) {
        for (int y = b.y0; y < b.y1; ++y)
            for (int x = b.x0; x < b.x1; ++x) cellOf(x, y) |= bits;
    }
    std::uint8_t at(int x, int y) const { return bits_[std::size_t(y / s_.cell) * std::size_t(columns_) + std::size_t(x / s_.cell)]; }
    bool meets(std::uint8_t mask, const Box& b) const {
        for (int y = b.y0; y < b.y1; ++y)
            for (int x = b.x0; x < b.x1; ++x)
                if (at(x, y) & mask) return true;
        return false;
    }
    bool selected(int x, int y, std::uint8_t mask, std::uint8_t exclude) const {
        const std::uint8_t b = at(x, y);
        return (b & mask) != 0 && (b & exclude) == 0;
    }
    int columns() const { return columns_; }
    int rows() const { return rows_; }

private:
    std::uint8_t& cellOf(int x, int y) { return bits_[std::size_t(y / s_.cell) * std::size_t(columns_) + std::size_t(x / s_.cell)]; }
    Size s_;
    int columns_, rows_;
    std::vector<std::uint8_t> bits_;
};

// A random box inside the target (empty now and then), small more often than large.
Box randomBox(std::mt19937& rng, int width, int height) {
    std::uniform_int_distribution<int> px(0, width), py(0, height), kind(0, 9);
    const int k = kind(rng);
    if (k == 0) return Box{};  // empty
    int x0 = px(rng), y0 = py(rng);
    int x1 = std::min(width, x0 + std::uniform_int_distribution<int>(0, k < 6 ? 12 : width)(rng));
    int y1 = std::min(height, y0 + std::uniform_int_distribution<int>(0, k < 6 ? 12 : height)(rng));
    if (k == 1) x1 = x0;  // degenerate: empty
    return Box{x0, y0, x1, y1};
}

void checkRects(const CellGrid& grid, const Reference& ref, const Size& s, std::uint8_t mask, std::uint8_t exclude,
                const std::string& label) {
    SCOPED_TRACE(label + " mask " + std::to_string(mask) + " exclude " + std::to_string(exclude));
    std::int64_t pixels = -1;
    const std::vector<Rect> rects = grid.rects(mask, exclude, pixels);
    std::vector<int> covered(std::size_t(s.width) * std::size_t(s.height), 0);
    std::int64_t area = 0;
    for (const Rect& r : rects) {
        ASSERT_FALSE(r.empty()) << "empty rectangle";
        ASSERT_GE(r.x, 0);
        ASSERT_GE(r.y, 0);
        ASSERT_LE(r.x + r.width, s.width);
        ASSERT_LE(r.y + r.height, s.height);
        EXPECT_EQ(r.x % s.cell, 0) << "rectangles start on cell boundaries";
        EXPECT_EQ(r.y % s.cell, 0) << "rectangles start on cell boundaries";
        area += std::int64_t(r.width) * r.height;
        for (int y = r.y; y < r.y + r.height; ++y)
            for (int x = r.x; x < r.x + r.width; ++x) ++covered[std::size_t(y) * std::size_t(s.width) + std::size_t(x)];
    }
    std::int64_t expected = 0;
    std::size_t overlapping = 0, wrong = 0;
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            const int c = covered[std::size_t(y) * std::size_t(s.width) + std::size_t(x)];
            const bool want = ref.selected(x, y, mask, exclude);
            expected += want ? 1 : 0;
            overlapping += c > 1 ? 1 : 0;
            wrong += (c > 0) != want ? 1 : 0;
        }
    EXPECT_EQ(overlapping, 0u) << "pixels covered by two rectangles";
    EXPECT_EQ(wrong, 0u) << "pixels covered that should not be, or not covered that should";
    EXPECT_EQ(pixels, expected);
    EXPECT_EQ(area, expected);
    // Row runs merged downwards: never more rectangles than qualifying cells.
    std::size_t cells = 0;
    for (int r = 0; r < ref.rows(); ++r)
        for (int c = 0; c < ref.columns(); ++c) cells += ref.selected(c * s.cell, r * s.cell, mask, exclude) ? 1 : 0;
    EXPECT_LE(rects.size(), cells);
}

const std::pair<std::uint8_t, std::uint8_t> kMasks[] = {{1, 0}, {2, 1}, {2, 0}, {5, 0}, {7, 0}, {3, 4}, {4, 3}, {6, 1}, {1, 6}};

TEST(ReuseCellGrid, MarkSealMeetsMatchesTheReference) {
    std::mt19937 rng(11);
    for (const Size& s : kSizes) {
        SCOPED_TRACE(str(s));
        CellGrid grid(s.width, s.height, s.cell);
        Reference ref(s);
        EXPECT_EQ(grid.cell(), s.cell);
        EXPECT_EQ(grid.columns(), ref.columns());
        EXPECT_EQ(grid.rows(), ref.rows());
        for (int round = 0; round < 6; ++round) {
            grid.reset();
            ref.reset();
            const int marks = round == 0 ? 0 : 1 + round * 4;
            for (int m = 0; m < marks; ++m) {
                const Box b = randomBox(rng, s.width, s.height);
                const auto bits = std::uint8_t(1u << std::uniform_int_distribution<int>(0, 2)(rng));
                grid.mark(b, bits);
                ref.mark(b, bits);
            }
            // Two masks at once, in the two slots, as TemporalReuse uses them.
            const std::uint8_t maskA = kMasks[std::size_t(round) % std::size(kMasks)].first;
            const std::uint8_t maskB = kMasks[std::size_t(round + 3) % std::size(kMasks)].first;
            grid.seal(0, maskA);
            grid.seal(1, maskB);
            for (int q = 0; q < 200; ++q) {
                const Box b = randomBox(rng, s.width, s.height);
                ASSERT_EQ(grid.meets(0, b), ref.meets(maskA, b))
                    << "round " << round << " slot 0 mask " << int(maskA) << " box [" << b.x0 << "," << b.x1 << ")x["
                    << b.y0 << "," << b.y1 << ")";
                ASSERT_EQ(grid.meets(1, b), ref.meets(maskB, b))
                    << "round " << round << " slot 1 mask " << int(maskB) << " box [" << b.x0 << "," << b.x1 << ")x["
                    << b.y0 << "," << b.y1 << ")";
            }
            // Every single pixel, and the whole target.
            for (int y = 0; y < s.height; y += std::max(1, s.height / 9))
                for (int x = 0; x < s.width; x += std::max(1, s.width / 9)) {
                    const Box pixel{x, y, x + 1, y + 1};
                    ASSERT_EQ(grid.meets(0, pixel), ref.meets(maskA, pixel)) << x << "," << y;
                }
            const Box whole{0, 0, s.width, s.height};
            EXPECT_EQ(grid.meets(0, whole), ref.meets(maskA, whole));
            EXPECT_FALSE(grid.meets(0, Box{}));
            EXPECT_FALSE(grid.meets(1, Box{3, 3, 3, 9}));
        }
    }
}

TEST(ReuseCellGrid, RectsCoverExactlyTheQualifyingCells) {
    std::mt19937 rng(12);
    for (const Size& s : kSizes) {
        SCOPED_TRACE(str(s));
        CellGrid grid(s.width, s.height, s.cell);
        Reference ref(s);
        for (int round = 0; round < 5; ++round) {
            grid.reset();
            ref.reset();
            if (round < 3) {
                // Random boxes of random bits.
                for (int m = 0; m < 3 + 6 * round; ++m) {
                    const Box b = randomBox(rng, s.width, s.height);
                    const auto bits = std::uint8_t(std::uniform_int_distribution<int>(1, 7)(rng));
                    grid.mark(b, bits);
                    ref.mark(b, bits);
                }
            } else {
                // A random pattern cell by cell (checkerboards, holes, ragged runs).
                for (int r = 0; r < ref.rows(); ++r)
                    for (int c = 0; c < ref.columns(); ++c) {
                        const auto bits = std::uint8_t(std::uniform_int_distribution<int>(0, 7)(rng));
                        const Box cell{c * s.cell, r * s.cell, std::min(s.width, (c + 1) * s.cell),
                                       std::min(s.height, (r + 1) * s.cell)};
                        grid.mark(cell, bits);
                        ref.mark(cell, bits);
                    }
            }
            for (const auto& [mask, exclude] : kMasks) checkRects(grid, ref, s, mask, exclude, "round " + std::to_string(round));
        }
    }
}

TEST(ReuseCellGrid, FullAndEmptyRegions) {
    for (const Size& s : kSizes) {
        SCOPED_TRACE(str(s));
        CellGrid grid(s.width, s.height, s.cell);
        Reference ref(s);
        std::int64_t pixels = -1;
        // Nothing marked: nothing meets, no rectangle.
        grid.seal(0, 1);
        EXPECT_FALSE(grid.meets(0, Box{0, 0, s.width, s.height}));
        EXPECT_TRUE(grid.rects(1, 0, pixels).empty());
        EXPECT_EQ(pixels, 0);
        // The whole target: rectangles cover it exactly, one per distinct run (here one).
        grid.mark(Box{0, 0, s.width, s.height}, 2);
        ref.mark(Box{0, 0, s.width, s.height}, 2);
        grid.seal(0, 2);
        EXPECT_TRUE(grid.meets(0, Box{s.width - 1, s.height - 1, s.width, s.height}));
        const std::vector<Rect> all = grid.rects(2, 0, pixels);
        EXPECT_EQ(pixels, std::int64_t(s.width) * s.height);
        ASSERT_EQ(all.size(), 1u);
        EXPECT_EQ(all[0].width, s.width);
        EXPECT_EQ(all[0].height, s.height);
        checkRects(grid, ref, s, 2, 0, "whole");
        // Excluded everywhere: nothing.
        grid.mark(Box{0, 0, s.width, s.height}, 1);
        EXPECT_TRUE(grid.rects(2, 1, pixels).empty());
        EXPECT_EQ(pixels, 0);
        // reset() forgets every bit.
        grid.reset();
        grid.seal(0, 7);
        grid.seal(1, 7);
        EXPECT_FALSE(grid.meets(0, Box{0, 0, s.width, s.height}));
        EXPECT_FALSE(grid.meets(1, Box{0, 0, s.width, s.height}));
        EXPECT_TRUE(grid.rects(7, 0, pixels).empty());
        EXPECT_EQ(pixels, 0);
    }
}

TEST(ReuseCellGrid, MarkingIsPerCellNeverPerPixel) {
    // One pixel marked makes its whole cell (clipped to the target) part of the region: the region
    // is a superset of the extents marked, never smaller.
    CellGrid grid(100, 75, 16);
    grid.mark(Box{97, 70, 98, 71}, 1);  // the last, partial cell (96..100 × 64..75)
    grid.seal(0, 1);
    EXPECT_TRUE(grid.meets(0, Box{96, 64, 97, 65}));
    EXPECT_FALSE(grid.meets(0, Box{0, 0, 96, 75}));
    EXPECT_FALSE(grid.meets(0, Box{0, 0, 100, 64}));
    std::int64_t pixels = 0;
    const std::vector<Rect> rects = grid.rects(1, 0, pixels);
    ASSERT_EQ(rects.size(), 1u);
    EXPECT_EQ(rects[0].x, 96);
    EXPECT_EQ(rects[0].y, 64);
    EXPECT_EQ(rects[0].width, 4);
    EXPECT_EQ(rects[0].height, 11);
    EXPECT_EQ(pixels, 44);
}

}  // namespace
}  // namespace frugal::test
