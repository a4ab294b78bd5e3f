#include "cull/VisibleSet.h"

#include <algorithm>
#include <cassert>
#include <limits>
#include <string>

namespace frugal {

namespace {

constexpr std::uint32_t kNoTriangle = std::numeric_limits<std::uint32_t>::max();

bool validMesh(const Scene& scene, const Instance& instance) {
    return instance.mesh >= 0 && std::size_t(instance.mesh) < scene.meshes.size();
}

std::size_t trianglesOf(const Scene& scene, const Instance& instance) {
    return validMesh(scene, instance) ? scene.meshes[std::size_t(instance.mesh)].primitiveCount() : 0;
}

// A mesh's source → triangle table: inverse[s] = t with triangleSource[t] = s, kNoTriangle for a
// source no triangle has. Without triangleSource, source t is triangle t.
std::vector<std::uint32_t> inverseSources(const Mesh& mesh) {
    const std::size_t triangles = mesh.primitiveCount();
    if (mesh.triangleSource.empty()) {
        std::vector<std::uint32_t> inverse(triangles);
        for (std::size_t t = 0; t < triangles; ++t) inverse[t] = std::uint32_t(t);
        return inverse;
    }
    // Only the sources of real triangles count (a longer triangleSource breaks the upload contract).
    const std::size_t n = std::min(triangles, mesh.triangleSource.size());
    std::uint32_t sourceCount = 0;
    for (std::size_t t = 0; t < n; ++t) sourceCount = std::max(sourceCount, mesh.triangleSource[t] + 1);
    std::vector<std::uint32_t> inverse(sourceCount, kNoTriangle);
    for (std::size_t t = 0; t < n; ++t) {
        std::uint32_t& slot = inverse[mesh.triangleSource[t]];
        if (slot == kNoTriangle) slot = std::uint32_t(t);  // a repeated source keeps its first triangle
    }
    return inverse;
}

// One instance's id range [first, end) and where its sources map.
struct IdRange {
    std::uint32_t first = 0;
    std::uint64_t end = 0;
    std::size_t instance = 0;
    const std::vector<std::uint32_t>* inverse = nullptr;
};

}  // namespace

TriangleSet emptySet(const Scene& scene) {
    TriangleSet set;
    set.perInstance.resize(scene.instances.size());
    for (std::size_t i = 0; i < scene.instances.size(); ++i)
        set.perInstance[i].assign(trianglesOf(scene, scene.instances[i]), 0);
    return set;
}

TriangleSet drawnSet(const Scene& scene, const DrawList& list) {
    TriangleSet set = emptySet(scene);
    for (const DrawCommand& command : list) {
        assert(command.instance >= 0 && std::size_t(command.instance) < scene.instances.size() &&
               "drawnSet: draw command for an instance the scene does not have");
        if (command.instance < 0 || std::size_t(command.instance) >= scene.instances.size()) continue;
        std::vector<std::uint8_t>& members = set.perInstance[std::size_t(command.instance)];
        const std::uint64_t triangles = members.size();
        for (const IndexRange& range : command.ranges) {
            // Clamped to the mesh as the backends do (pipeline/IndexRanges.h).
            const std::uint64_t first = std::min<std::uint64_t>(range.firstTriangle, triangles);
            const std::uint64_t end = std::min<std::uint64_t>(first + range.triangleCount, triangles);
            for (std::uint64_t t = first; t < end; ++t) {
                set.count += members[t] == 0;
                members[t] = 1;
            }
        }
    }
    return set;
}

Result<TriangleSet> visibleSet(const Scene& scene, const Buffers& buffers) {
    const std::size_t pixels = buffers.pixelCount();
    if (buffers.ids.empty() && pixels > 0) return Error{"the frame has no id image"};
    if (buffers.ids.size() != pixels)
        return Error{"the frame's id image has " + std::to_string(buffers.ids.size()) + " ids for " +
                     std::to_string(buffers.width) + "x" + std::to_string(buffers.height) + " pixels"};

    // Source → triangle tables, once per mesh (instances share meshes).
    std::vector<std::vector<std::uint32_t>> inverses(scene.meshes.size());
    std::vector<bool> built(scene.meshes.size(), false);
    std::vector<IdRange> ranges;
    ranges.reserve(scene.instances.size());
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        if (!validMesh(scene, instance)) continue;
        const auto m = std::size_t(instance.mesh);
        if (!built[m]) {
            inverses[m] = inverseSources(scene.meshes[m]);
            built[m] = true;
        }
        if (inverses[m].empty()) continue;
        ranges.push_back({instance.firstId, std::uint64_t(instance.firstId) + inverses[m].size(), i, &inverses[m]});
    }
    std::sort(ranges.begin(), ranges.end(), [](const IdRange& a, const IdRange& b) { return a.first < b.first; });

    TriangleSet set = emptySet(scene);
    // Neighbouring pixels mostly share a triangle: the last id looked up is remembered.
    std::uint32_t lastId = 0;
    for (std::size_t p = 0; p < pixels; ++p) {
        const std::uint32_t id = buffers.ids[p];
        if (id == 0 || id == lastId) continue;
        const auto next = std::upper_bound(ranges.begin(), ranges.end(), id,
                                           [](std::uint32_t v, const IdRange& r) { return v < r.first; });
        std::uint32_t t = kNoTriangle;
        const IdRange* range = nullptr;
        if (next != ranges.begin()) {
            range = &*(next - 1);
            if (id < range->end) t = (*range->inverse)[id - range->first];
        }
        if (t == kNoTriangle) {
            const auto x = p % std::size_t(buffers.width);
            const auto y = std::size_t(buffers.height) - 1 - p / std::size_t(buffers.width);  // top row is 0
            return Error{"id " + std::to_string(id) + " at pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                         ") belongs to no triangle of the scene"};
        }
        std::uint8_t& member = set.perInstance[range->instance][t];
        set.count += member == 0;
        member = 1;
        lastId = id;
    }
    return set;
}

SetCounts compareSets(const Scene& scene, const TriangleSet& pvs, const TriangleSet& rvs) {
    assert(pvs.perInstance.size() == scene.instances.size() && rvs.perInstance.size() == scene.instances.size() &&
           "compareSets: sets shaped like another scene");
    SetCounts counts;
    static const std::vector<std::uint8_t> none;
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const std::size_t triangles = trianglesOf(scene, scene.instances[i]);
        counts.tos += triangles;
        const std::vector<std::uint8_t>& p = i < pvs.perInstance.size() ? pvs.perInstance[i] : none;
        const std::vector<std::uint8_t>& r = i < rvs.perInstance.size() ? rvs.perInstance[i] : none;
        assert(p.size() == triangles && r.size() == triangles && "compareSets: sets shaped like another scene");
        for (std::size_t t = 0; t < triangles; ++t) {
            const bool inP = t < p.size() && p[t] != 0;
            const bool inR = t < r.size() && r[t] != 0;
            counts.pvs += inP;
            counts.rvs += inR;
            counts.misses += inR && !inP;
            counts.waste += inP && !inR;
        }
    }
    return counts;
}

Scene oracleScene(const Scene& scene, const TriangleSet& set) {
    assert(set.perInstance.size() == scene.instances.size() && "oracleScene: set shaped like another scene");
    // Everything is copied (nodes, materials, textures, cameras, animations, ...); only the meshes
    // and the instances are replaced.
    Scene oracle = scene;
    oracle.meshes.clear();
    oracle.instances.clear();

    // Nodes name the new meshes, so the copy stays consistent (instance i of node n draws mesh i).
    for (Node& node : oracle.nodes) node.meshes.clear();
    oracle.meshes.reserve(scene.instances.size());
    oracle.instances.reserve(scene.instances.size());
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        Mesh mesh;
        if (validMesh(scene, instance)) {
            const Mesh& from = scene.meshes[std::size_t(instance.mesh)];
            mesh.name = from.name + " (visible)";
            mesh.positions = from.positions;
            mesh.normals = from.normals;
            mesh.colors = from.colors;
            mesh.uvs = from.uvs;
            mesh.tangents = from.tangents;
            mesh.material = from.material;
            mesh.topology = from.topology;
            const std::size_t triangles = from.primitiveCount(), corners = verticesPerPrimitive(from.topology);
            static const std::vector<std::uint8_t> none;
            const std::vector<std::uint8_t>& members = i < set.perInstance.size() ? set.perInstance[i] : none;
            std::size_t kept = 0;
            for (std::size_t t = 0; t < triangles && t < members.size(); ++t) kept += members[t] != 0;
            mesh.indices.reserve(corners * kept);
            mesh.triangleSource.reserve(kept);
            for (std::size_t t = 0; t < triangles && t < members.size(); ++t) {
                if (members[t] == 0) continue;
                mesh.indices.insert(mesh.indices.end(), from.indices.begin() + std::ptrdiff_t(corners * t),
                                    from.indices.begin() + std::ptrdiff_t(corners * (t + 1)));
                mesh.triangleSource.push_back(from.triangleSource.empty() ? std::uint32_t(t) : from.triangleSource[t]);
            }
        }
        const int meshIndex = int(oracle.meshes.size());
        oracle.meshes.push_back(std::move(mesh));
        oracle.instances.push_back({instance.node, meshIndex, instance.firstId});
        if (instance.node >= 0 && std::size_t(instance.node) < oracle.nodes.size())
            oracle.nodes[std::size_t(instance.node)].meshes.push_back(meshIndex);
    }
    return oracle;
}

}  // namespace frugal
