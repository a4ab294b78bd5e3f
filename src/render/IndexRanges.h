// Index ranges as a draw executes them. Both backends, and plans that build ranges (culling), use
// these so that "which triangles, in which order" means the same thing everywhere.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "render/Backend.h"

namespace frugal {

// The ranges of one draw in the order given, each clamped to the mesh's `meshTriangles`, empty ones
// dropped, and a range that starts where the previous one ended merged into it. The triangle order
// is unchanged, so `out` draws exactly what `ranges` names. A range past the end of the mesh is the
// caller's bug (asserted in debug builds, clamped otherwise). `out` is overwritten; returns the
// number of triangles in it.
std::uint64_t normalizeRanges(std::span<const IndexRange> ranges, std::uint32_t meshTriangles,
                              std::vector<IndexRange>& out);

// A mesh's triangle → source-primitive table (render/Backend.h, DrawParams::firstId): its own
// triangleSource, or t for triangle t when it has none.
std::vector<std::uint32_t> triangleSources(const Mesh& mesh);

}  // namespace frugal
