// Overlap flags (src/hsr/Flags.h): cases by hand (inclusive pixels, closed depth ranges), and the
// grid version against the paper's all-pairs test on thousands of random sets, degenerate ones
// included: empty and single sets, zero-width boxes, identical extents, boxes and depth ranges that
// touch at exactly one value, whole-screen boxes, sets where everything overlaps.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "hsr/Flags.h"

namespace frugal::hsr {
namespace {

using Flags = std::vector<std::uint8_t>;

Extent box(std::int32_t x0, std::int32_t x1, std::int32_t y0, std::int32_t y1, float z0, float z1) {
    return Extent{x0, y0, x1, y1, z0, z1};
}

// Both versions, checked equal; returns the flags.
Flags flagsOf(const std::vector<Extent>& extents) {
    const Flags reference = flagOverlapsAllPairs(extents);
    const Flags fast = flagOverlaps(extents);
    EXPECT_EQ(fast, reference);
    return reference;
}

TEST(HsrFlags, EmptyAndSingleSetsFlagNothing) {
    EXPECT_TRUE(flagsOf({}).empty());
    EXPECT_EQ(flagsOf({box(0, 9, 0, 9, 0.2f, 0.4f)}), Flags{0});
}

TEST(HsrFlags, PixelsAreInclusive) {
    // x ranges [0, 5] and [5, 9] share pixel column 5: an overlap (the paper's vertex test would say
    // no, see Order.h); [0, 5] and [6, 9] share nothing.
    EXPECT_EQ(flagsOf({box(0, 5, 0, 9, 0.2f, 0.4f), box(5, 9, 0, 9, 0.3f, 0.5f)}), (Flags{1, 1}));
    EXPECT_EQ(flagsOf({box(0, 5, 0, 9, 0.2f, 0.4f), box(6, 9, 0, 9, 0.3f, 0.5f)}), (Flags{0, 0}));
    EXPECT_EQ(flagsOf({box(0, 9, 0, 5, 0.2f, 0.4f), box(0, 9, 5, 9, 0.3f, 0.5f)}), (Flags{1, 1}));
    EXPECT_EQ(flagsOf({box(0, 9, 0, 5, 0.2f, 0.4f), box(0, 9, 6, 9, 0.3f, 0.5f)}), (Flags{0, 0}));
    // One pixel each, the same pixel.
    EXPECT_EQ(flagsOf({box(3, 3, 4, 4, 0.5f, 0.5f), box(3, 3, 4, 4, 0.5f, 0.5f)}), (Flags{1, 1}));
    // Corners touching diagonally share a pixel only when both x and y touch.
    EXPECT_EQ(flagsOf({box(0, 4, 0, 4, 0.5f, 0.5f), box(4, 8, 4, 8, 0.5f, 0.5f)}), (Flags{1, 1}));
    EXPECT_EQ(flagsOf({box(0, 4, 0, 4, 0.5f, 0.5f), box(5, 8, 4, 8, 0.5f, 0.5f)}), (Flags{0, 0}));
}

TEST(HsrFlags, DepthRangesAreClosed) {
    EXPECT_EQ(flagsOf({box(0, 9, 0, 9, 0.2f, 0.4f), box(0, 9, 0, 9, 0.4f, 0.6f)}), (Flags{1, 1}));
    EXPECT_EQ(flagsOf({box(0, 9, 0, 9, 0.2f, 0.4f), box(0, 9, 0, 9, std::nextafter(0.4f, 1.0f), 0.6f)}),
              (Flags{0, 0}));
}

TEST(HsrFlags, PapersFigureSix) {
    // Fig. 6: every y range overlaps; A and B overlap in x, not in z; B and C in z, not in x; G meets
    // A, B and C in x, never in z; D, E and F overlap in x, y and z. Flagged: D, E, F only.
    const std::vector<Extent> extents{
        box(0, 20, 0, 50, 0.80f, 0.90f),   // A
        box(15, 35, 0, 50, 0.50f, 0.60f),  // B
        box(40, 60, 0, 50, 0.55f, 0.65f),  // C
        box(70, 90, 0, 50, 0.30f, 0.45f),  // D
        box(80, 95, 0, 50, 0.40f, 0.50f),  // E
        box(85, 99, 0, 50, 0.35f, 0.42f),  // F
        box(0, 60, 0, 50, 0.05f, 0.10f),   // G
    };
    EXPECT_EQ(flagsOf(extents), (Flags{0, 0, 0, 1, 1, 1, 0}));
}

TEST(HsrFlags, OneOverlapFlagsBothAndOnlyThem) {
    const std::vector<Extent> extents{box(0, 10, 0, 10, 0.1f, 0.2f), box(100, 110, 0, 10, 0.1f, 0.2f),
                                      box(105, 120, 5, 20, 0.15f, 0.3f), box(0, 10, 0, 10, 0.5f, 0.6f)};
    EXPECT_EQ(flagsOf(extents), (Flags{0, 1, 1, 0}));
}

// Random sets of `n` extents in a `span` × `span` pixel area with sides up to `side` pixels and
// depths drawn from `levels` values (few levels: many ranges touch at exactly one value).
std::vector<Extent> randomSet(std::mt19937& rng, int n, int span, int side, int levels, double wholeShare) {
    std::uniform_int_distribution<int> pos(0, span - 1), size(0, side), level(0, levels);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Extent> set;
    for (int i = 0; i < n; ++i) {
        if (!set.empty() && unit(rng) < 0.05) {  // an identical copy of an earlier extent
            set.push_back(set[std::size_t(rng() % set.size())]);
            continue;
        }
        Extent e;
        if (unit(rng) < wholeShare) {
            e = box(0, span - 1, 0, span - 1, 0.0f, 1.0f);
        } else {
            e.x0 = pos(rng);
            e.y0 = pos(rng);
            e.x1 = e.x0 + size(rng);  // size 0: a one-pixel-wide box (a zero-area triangle's)
            e.y1 = e.y0 + size(rng);
            const float a = float(level(rng)) / float(levels), b = float(level(rng)) / float(levels);
            e.z0 = std::min(a, b);
            e.z1 = std::max(a, b);
        }
        set.push_back(e);
    }
    return set;
}

TEST(HsrFlags, GridAgreesWithAllPairsOnRandomSets) {
    std::mt19937 rng(2024);
    std::size_t sets = 0, flagged = 0, total = 0;
    for (int round = 0; round < 4000; ++round) {
        const int n = int(rng() % 200);
        const int span = 1 + int(rng() % 300);
        const int side = int(rng() % (round % 4 == 0 ? 300 : 20));
        const int levels = 1 + int(rng() % (round % 3 == 0 ? 4 : 1000));
        const double whole = round % 10 == 0 ? 0.02 : 0.0;
        const std::vector<Extent> set = randomSet(rng, n, span, side, levels, whole);
        const Flags reference = flagOverlapsAllPairs(set);
        ASSERT_EQ(flagOverlaps(set), reference) << "round " << round << ", " << n << " extents";
        ++sets;
        total += set.size();
        flagged += std::size_t(std::count(reference.begin(), reference.end(), 1));
    }
    // Both the flagged and the unflagged case must be well represented for the agreement to mean much.
    EXPECT_GT(flagged, total / 5);
    EXPECT_LT(flagged, total * 4 / 5);
    EXPECT_EQ(sets, 4000u);
}

TEST(HsrFlags, GroupsExemptPairsWithinAGroupOnly) {
    // Two overlapping extents in one group are not flagged; a third overlapping both, in no group,
    // flags all three. The grid agrees with all pairs on random sets with random groups.
    const std::vector<Extent> pair{{0, 0, 9, 9, 0.1f, 0.5f}, {5, 5, 14, 14, 0.2f, 0.6f}};
    const std::vector<std::int32_t> same{3, 3}, apart{3, 4}, none{-1, -1};
    EXPECT_EQ(flagOverlaps(pair, same), (Flags{0, 0}));
    EXPECT_EQ(flagOverlaps(pair, apart), (Flags{1, 1}));
    EXPECT_EQ(flagOverlaps(pair, none), (Flags{1, 1}));
    std::vector<Extent> three = pair;
    three.push_back({7, 7, 8, 8, 0.0f, 1.0f});
    EXPECT_EQ(flagOverlaps(three, std::vector<std::int32_t>{3, 3, -1}), (Flags{1, 1, 1}));
    EXPECT_EQ(flagOverlapsAllPairs(three, std::vector<std::int32_t>{3, 3, -1}), (Flags{1, 1, 1}));
    std::mt19937 rng(99);
    for (int round = 0; round < 500; ++round) {
        const std::vector<Extent> set = randomSet(rng, int(rng() % 150), 1 + int(rng() % 200), int(rng() % 40),
                                                  1 + int(rng() % 50), 0.0);
        std::vector<std::int32_t> groups(set.size());
        for (std::int32_t& g : groups) g = std::int32_t(rng() % 8) - 2;  // −2, −1: no group (any negative)
        for (std::int32_t& g : groups) g = std::max(g, -1);
        ASSERT_EQ(flagOverlaps(set, groups), flagOverlapsAllPairs(set, groups)) << "round " << round;
    }
}

TEST(HsrFlags, GridAgreesWithAllPairsOnLargeSets) {
    std::mt19937 rng(7);
    // Sparse small boxes on a full HD frame, then dense ones, then everything on top of each other.
    for (const auto& [n, span, side, levels] : {std::tuple{5000, 1920, 12, 100000}, std::tuple{5000, 400, 30, 1000},
                                                std::tuple{3000, 50, 50, 3}}) {
        const std::vector<Extent> set = randomSet(rng, n, span, side, levels, 0.0);
        EXPECT_EQ(flagOverlaps(set), flagOverlapsAllPairs(set)) << n << " extents on " << span << " px";
    }
}

TEST(HsrFlags, FarCoordinatesAndWideBoxes) {
    // The grid covers the boxes' union wherever it lies, negative or far from the origin.
    const std::vector<Extent> set{box(-2000000000, -1999999990, 5, 5, 0.0f, 1.0f),
                                  box(-1999999990, 2000000000, 0, 10, 0.5f, 0.5f),
                                  box(2000000000, 2000000000, 11, 20, 0.0f, 1.0f),
                                  box(1999999000, 1999999001, -7, -1, 0.0f, 1.0f)};
    EXPECT_EQ(flagsOf(set), (Flags{1, 1, 0, 0}));
}

}  // namespace
}  // namespace frugal::hsr
