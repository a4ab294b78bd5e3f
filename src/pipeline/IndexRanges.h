// Index ranges as a draw executes them. Both backends, and plans that build ranges (culling), use
// these so that "which triangles, in which order" means the same thing everywhere.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pipeline/Backend.h"

namespace frugal {

// The ranges of one draw in the order given, each clamped to the mesh's `meshTriangles`, empty ones
// dropped, and a range that starts where the previous one ended merged into it. The triangle order
// is unchanged, so `out` draws exactly what `ranges` names. A range past the end of the mesh is the
// caller's bug (asserted in debug builds, clamped otherwise). `out` is overwritten; returns the
// number of triangles in it.
std::uint64_t normalizeRanges(std::span<const IndexRange> ranges, std::uint32_t meshTriangles,
                              std::vector<IndexRange>& out);

// Calls f(at, length) for each run of set bits of `bits`, lowest first: bits [at, at + length) are
// set, the bits around them are not. The plans that keep triangles by 64-bit masks (culling) turn
// them into ranges with it.
template <class F>
inline void forEachRun(std::uint64_t bits, F&& f) {
    while (bits != 0) {
        const int at = __builtin_ctzll(bits);
        const std::uint64_t rest = ~(bits >> at);  // 0 when the run reaches bit 63
        const int length = rest == 0 ? 64 - at : __builtin_ctzll(rest);
        bits &= length + at >= 64 ? 0 : ~std::uint64_t(0) << (at + length);
        f(std::uint32_t(at), std::uint32_t(length));
    }
}

// A mesh's triangle → source-primitive table (pipeline/Backend.h, DrawParams::firstId): its own
// triangleSource, or t for triangle t when it has none.
std::vector<std::uint32_t> triangleSources(const Mesh& mesh);

}  // namespace frugal
