#include "scene/Scene.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace frugal {

glm::mat4 localMatrix(const Node& node) {
    if (node.hasMatrix) return node.matrix;
    glm::mat4 m = glm::translate(glm::mat4(1.0f), node.translation);
    m *= glm::mat4_cast(node.rotation);
    return glm::scale(m, node.scale);
}

void Scene::buildInstances() {
    instances.clear();
    std::uint32_t nextId = 1;
    for (int n = 0; n < int(nodes.size()); ++n) {
        for (int mesh : nodes[n].meshes) {
            instances.push_back({n, mesh, nextId});
            // Ids are given per source primitive, so the range is the source count, which equals the
            // triangle count after loading (dropped triangles keep their ids unused). A mesh without
            // triangleSource has source t for triangle t (render/Backend.h).
            const Mesh& m = meshes[mesh];
            auto sourceCount = std::uint32_t(m.triangleSource.empty() ? m.triangleCount() : 0);
            for (std::uint32_t s : m.triangleSource) sourceCount = std::max(sourceCount, s + 1);
            nextId += sourceCount;
        }
    }
}

std::size_t Scene::triangleCount() const {
    std::size_t count = 0;
    for (const Instance& instance : instances) count += meshes[instance.mesh].triangleCount();
    return count;
}

double Scene::duration() const {
    double end = 0.0;
    for (const Animation& animation : animations)
        for (const AnimChannel& channel : animation.channels)
            if (!channel.times.empty()) end = std::max(end, double(channel.times.back()));
    return end;
}

namespace {

glm::quat toQuat(const glm::vec4& v) { return glm::quat(v.w, v.x, v.y, v.z); }
glm::vec4 fromQuat(const glm::quat& q) { return glm::vec4(q.x, q.y, q.z, q.w); }

}  // namespace

glm::vec4 sampleChannel(const AnimChannel& channel, double time) {
    const std::vector<float>& times = channel.times;
    const bool cubic = channel.interpolation == Interp::CubicSpline;
    const std::size_t stride = cubic ? 3 : 1;
    auto value = [&](std::size_t key) { return channel.values[key * stride + (cubic ? 1 : 0)]; };
    // Key times are float (glTF); compare in float too, so a time that equals a key samples it exactly.
    const float at = float(time);
    if (times.empty()) return glm::vec4(0.0f);
    if (!(at > times.front()) || times.size() == 1) return value(0);
    if (at >= times.back()) return value(times.size() - 1);

    // First key strictly after `at`; keys are strictly increasing (validated by the loaders).
    const std::size_t k1 = std::size_t(std::upper_bound(times.begin(), times.end(), at) - times.begin());
    const std::size_t k0 = k1 - 1;
    const double dt = double(times[k1]) - double(times[k0]);
    const float t = float((double(at) - double(times[k0])) / dt);
    const bool rotation = channel.path == AnimPath::Rotation;

    switch (channel.interpolation) {
    case Interp::Step:
        return value(k0);
    case Interp::Linear:
        // Between two equal keys the value is held exactly (mix would round it by an ulp or so):
        // a held pose stays bit-identical, which is what temporal reuse takes for "static".
        if (value(k0) == value(k1)) return value(k0);
        if (rotation) return fromQuat(glm::slerp(toQuat(value(k0)), toQuat(value(k1)), t));
        return glm::mix(value(k0), value(k1), t);
    case Interp::CubicSpline: {
        // glTF 2.0 appendix C: Hermite spline with tangents scaled by the key interval.
        const glm::vec4 p0 = value(k0), p1 = value(k1);
        const glm::vec4 m0 = channel.values[k0 * 3 + 2] * float(dt);
        const glm::vec4 m1 = channel.values[k1 * 3 + 0] * float(dt);
        const float t2 = t * t, t3 = t2 * t;
        glm::vec4 v = (2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * p1 +
                      (t3 - t2) * m1;
        if (rotation) {
            const float len = glm::length(v);
            v = len > 0.0f ? v / len : value(k0);
        }
        return v;
    }
    }
    return value(k0);
}

std::vector<glm::mat4> Scene::worldTransforms(double time) const {
    std::vector<Node> posed = nodes;
    for (const Animation& animation : animations) {
        for (const AnimChannel& channel : animation.channels) {
            if (channel.node < 0 || channel.node >= int(posed.size())) continue;
            Node& node = posed[channel.node];
            const glm::vec4 v = sampleChannel(channel, time);
            // glTF animates only TRS nodes; the loaders reject an animated node that has a matrix.
            switch (channel.path) {
            case AnimPath::Translation: node.translation = glm::vec3(v); break;
            case AnimPath::Rotation: node.rotation = toQuat(v); break;
            case AnimPath::Scale: node.scale = glm::vec3(v); break;
            }
        }
    }

    // Nodes are not necessarily ordered parents-first: walk down from the roots. Loaders reject
    // cycles, so every node is reached at most once.
    std::vector<glm::mat4> world(nodes.size(), glm::mat4(1.0f));
    std::vector<int> stack;
    for (int n = 0; n < int(nodes.size()); ++n)
        if (nodes[n].parent < 0) stack.push_back(n);
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        const glm::mat4 parent = nodes[n].parent >= 0 ? world[nodes[n].parent] : glm::mat4(1.0f);
        world[n] = parent * localMatrix(posed[n]);
        for (int child : nodes[n].children) stack.push_back(child);
    }
    return world;
}

Bounds Scene::bounds(double time) const {
    const std::vector<glm::mat4> world = worldTransforms(time);
    Bounds bounds;
    for (const Instance& instance : instances) {
        const Mesh& mesh = meshes[instance.mesh];
        const glm::mat4& m = world[instance.node];
        // Only vertices that triangles use count (dropped triangles may leave unused vertices).
        for (std::uint32_t index : mesh.indices) bounds.add(glm::vec3(m * glm::vec4(mesh.positions[index], 1.0f)));
    }
    return bounds;
}

}  // namespace frugal
