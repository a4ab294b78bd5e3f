#include "hsr/Plan.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include "hsr/Flags.h"
#include "hsr/Order.h"

namespace frugal::hsr {

Planner::Planner(const Scene& scene) : scene_(&scene) {
    polygons_.reserve(scene.meshes.size());
    for (const Mesh& mesh : scene.meshes) polygons_.push_back(groupPolygons(mesh));
    std::uint32_t next = 0;
    for (const Instance& instance : scene.instances) {
        firstPolygon_.push_back(next);
        next += polygons_[std::size_t(instance.mesh)].count;
    }
}

std::size_t Planner::polygonCount() const {
    std::size_t count = 0;
    for (const Instance& instance : scene_->instances) count += polygons_[std::size_t(instance.mesh)].count;
    return count;
}

std::size_t Planner::bytes() const {
    std::size_t total = firstPolygon_.size() * sizeof(std::uint32_t);
    for (const MeshPolygons& p : polygons_) total += p.polygonOf.size() * sizeof(std::uint32_t);
    return total;
}

DrawList Planner::plan(Mode mode, const FrameParams& frame, const std::vector<glm::mat4>& world, const DrawList& list,
                       int width, int height, PlanStats* stats) const {
    const auto start = std::chrono::steady_clock::now();
    PlanStats local;
    if (mode == Mode::ZBuffer) {
        local.draws = list.size();
        if (stats) *stats = local;
        return list;
    }

    // adaptive-convex's group of a polygon of `instance` (before its facing is known).
    const auto exemptInstance = [&](int instance) {
        if (mode != Mode::AdaptiveConvex) return -1;
        const Mesh& mesh = scene_->meshes[std::size_t(scene_->instances[std::size_t(instance)].mesh)];
        const bool singleSided = mesh.material < 0 || !scene_->materials[std::size_t(mesh.material)].doubleSided;
        return singleSided && polygons_[std::size_t(scene_->instances[std::size_t(instance)].mesh)].convexSolid ? instance : -1;
    };

    // Blended instances (AlphaMode::Blend) are drawn after the rest, as listed, depth-tested
    // (SceneRenderer::draw orders them): their polygons take part in the flags only, with the whole
    // depth range, so that every polygon sharing a pixel with one of them writes its depth.
    const bool blending = anyBlended(*scene_) && std::any_of(list.begin(), list.end(), [&](const DrawCommand& c) {
        return blendedInstance(*scene_, c.instance);
    });

    // The listed triangles, then their polygons in the order of their first listed triangle.
    const ScreenTriangles screen = screenTriangles(*scene_, frame, world, list, width, height);
    std::vector<std::uint32_t> slot(polygonCount(), ~0u);  // global polygon → listed polygon
    std::vector<std::uint32_t> polygonOfListed(screen.size());
    std::vector<Extent> extents;
    std::vector<float> depthSum;
    std::vector<std::uint32_t> triangleCount;
    std::vector<std::int32_t> group;  // adaptive-convex: the instance, for front faces of a convex solid; else −1
    std::vector<std::uint8_t> blended;  // the polygon's instance is blended
    for (std::size_t i = 0; i < screen.size(); ++i) {
        const TriangleRef& ref = screen.refs[i];
        const Instance& instance = scene_->instances[std::size_t(ref.instance)];
        const std::uint32_t global =
            firstPolygon_[std::size_t(ref.instance)] + polygons_[std::size_t(instance.mesh)].polygonOf[ref.triangle];
        const Extent& e = screen.extents[i];
        if (slot[global] == ~0u) {
            slot[global] = std::uint32_t(extents.size());
            extents.push_back(e);
            depthSum.push_back(0.0f);
            triangleCount.push_back(0);
            group.push_back(exemptInstance(ref.instance));
            blended.push_back(blending && blendedInstance(*scene_, ref.instance) ? 1 : 0);
        }
        const std::uint32_t p = slot[global];
        polygonOfListed[i] = p;
        Extent& u = extents[p];
        u = Extent{std::min(u.x0, e.x0), std::min(u.y0, e.y0), std::max(u.x1, e.x1), std::max(u.y1, e.y1),
                   std::min(u.z0, e.z0), std::max(u.z1, e.z1)};
        depthSum[p] += screen.depth[i];
        if (!screen.front[i]) group[p] = -1;
        ++triangleCount[p];
    }
    const std::size_t polygons = extents.size();
    std::vector<float> depth(polygons);
    for (std::size_t p = 0; p < polygons; ++p) depth[p] = depthSum[p] / float(triangleCount[p]);
    std::vector<std::uint32_t> order = backToFront(depth);
    std::vector<std::uint8_t> flags;
    if (blending) {
        // depthsort flags only what meets a blended polygon: its other polygons share one group.
        for (std::size_t p = 0; p < polygons; ++p) {
            if (blended[p]) {
                extents[p].z0 = -std::numeric_limits<float>::max();
                extents[p].z1 = std::numeric_limits<float>::max();
                group[p] = -1;
            } else if (mode == Mode::DepthSort) {
                group[p] = 0;
            }
        }
    }
    if (mode == Mode::Adaptive || mode == Mode::AdaptiveConvex || blending) {
        flags = mode == Mode::Adaptive ? flagOverlaps(extents) : flagOverlaps(extents, group);
        // Each run of consecutive flagged polygons in submission order (Plan.h: ties).
        for (auto run = order.begin(); run != order.end();) {
            if (!flags[*run]) {
                ++run;
                continue;
            }
            const auto end = std::find_if(run, order.end(), [&](std::uint32_t p) { return !flags[p]; });
            std::sort(run, end);
            run = end;
        }
    }

    // Each polygon's listed triangles, in draw order (a counting sort by polygon).
    std::vector<std::uint32_t> firstOf(polygons + 1, 0);
    for (std::uint32_t p : polygonOfListed) ++firstOf[p + 1];
    for (std::size_t p = 0; p < polygons; ++p) firstOf[p + 1] += firstOf[p];
    std::vector<std::uint32_t> members(screen.size());
    {
        std::vector<std::uint32_t> fill(firstOf.begin(), firstOf.end() - 1);
        for (std::uint32_t i = 0; i < screen.size(); ++i) members[fill[polygonOfListed[i]]++] = i;
    }

    // The list: polygons in order; consecutive triangles of one instance and depth mode share a
    // command, consecutive triangle numbers a range.
    DrawList out;
    for (std::uint32_t p : order) {
        if (blending && blended[p]) {  // drawn whole below, depth-tested
            ++local.flagged;
            continue;
        }
        const DepthMode depthMode = !flags.empty() && flags[p] ? DepthMode::Test : DepthMode::Off;
        local.flagged += depthMode == DepthMode::Test ? 1 : 0;
        for (std::uint32_t k = firstOf[p]; k < firstOf[p + 1]; ++k) {
            const TriangleRef& ref = screen.refs[members[k]];
            if (out.empty() || out.back().instance != ref.instance || out.back().depth != depthMode)
                out.push_back(DrawCommand{ref.instance, {}, depthMode});
            std::vector<IndexRange>& ranges = out.back().ranges;
            if (!ranges.empty() && ranges.back().firstTriangle + ranges.back().triangleCount == ref.triangle)
                ++ranges.back().triangleCount;
            else
                ranges.push_back(IndexRange{ref.triangle, 1});
        }
    }
    if (blending)
        for (const DrawCommand& command : list)
            if (blendedInstance(*scene_, command.instance))
                out.push_back(DrawCommand{command.instance, command.ranges, DepthMode::Test});
    local.polygons = polygons;
    local.draws = out.size();
    local.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (stats) *stats = local;
    return out;
}

}  // namespace frugal::hsr
