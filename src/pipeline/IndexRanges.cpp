#include "pipeline/IndexRanges.h"

#include <algorithm>
#include <cassert>
#include <numeric>

namespace frugal {

std::uint64_t normalizeRanges(std::span<const IndexRange> ranges, std::uint32_t meshTriangles,
                              std::vector<IndexRange>& out) {
    out.clear();
    std::uint64_t triangles = 0;
    for (const IndexRange& range : ranges) {
        assert(std::uint64_t(range.firstTriangle) + range.triangleCount <= meshTriangles &&
               "draw: index range past the end of the mesh");
        const std::uint32_t first = std::min(range.firstTriangle, meshTriangles);
        const std::uint32_t count = std::min(range.triangleCount, meshTriangles - first);
        if (count == 0) continue;
        triangles += count;
        if (!out.empty() && out.back().firstTriangle + out.back().triangleCount == first)
            out.back().triangleCount += count;
        else
            out.push_back({first, count});
    }
    return triangles;
}

std::vector<std::uint32_t> triangleSources(const Mesh& mesh) {
    if (!mesh.triangleSource.empty()) return mesh.triangleSource;
    std::vector<std::uint32_t> sources(mesh.primitiveCount());
    std::iota(sources.begin(), sources.end(), 0u);
    return sources;
}

}  // namespace frugal
