#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtx/component_wise.hpp>

#include <frugal/Scene.h>

#include "scene/Posing.h"

namespace frugal {

glm::mat4 localMatrix(const Node& node) {
    if (node.hasMatrix) return node.matrix;
    glm::mat4 m = glm::translate(glm::mat4(1.0f), node.translation);
    m *= glm::mat4_cast(node.rotation);
    return glm::scale(m, node.scale);
}

void Scene::buildInstances() {
    instances.clear();
    envelope = computeEnvelope();
    std::uint32_t nextId = 1;
    for (int n = 0; n < int(nodes.size()); ++n) {
        for (int mesh : nodes[n].meshes) {
            instances.push_back({n, mesh, nextId});
            // Ids are given per source primitive, so the range is the source count, which equals the
            // primitive count after loading (dropped primitives keep their ids unused). A mesh
            // without triangleSource has source t for primitive t (pipeline/Backend.h).
            const Mesh& m = meshes[mesh];
            auto sourceCount = std::uint32_t(m.triangleSource.empty() ? m.primitiveCount() : 0);
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

std::size_t Scene::primitiveCount() const {
    std::size_t count = 0;
    for (const Instance& instance : instances) count += meshes[instance.mesh].primitiveCount();
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

std::vector<float> sampleWeights(const AnimChannel& channel, double time) {
    const std::size_t count = std::size_t(std::max(channel.weightCount, 0));
    const std::vector<float>& times = channel.times;
    const bool cubic = channel.interpolation == Interp::CubicSpline;
    const std::size_t stride = cubic ? 3 : 1;
    // Element i of key k's value (cubic: of its in-tangent -1, value 0, out-tangent +1).
    auto at = [&](std::size_t key, std::size_t i, int part = 0) {
        return channel.weights[(key * stride + (cubic ? std::size_t(1 + part) : 0)) * count + i];
    };
    std::vector<float> out(count, 0.0f);
    if (times.empty() || channel.weights.size() < times.size() * stride * count) return out;
    const float when = float(time);
    std::size_t held = times.size();  // a key whose value holds, if any
    if (!(when > times.front()) || times.size() == 1)
        held = 0;
    else if (when >= times.back())
        held = times.size() - 1;
    if (held < times.size()) {
        for (std::size_t i = 0; i < count; ++i) out[i] = at(held, i);
        return out;
    }
    const std::size_t k1 = std::size_t(std::upper_bound(times.begin(), times.end(), when) - times.begin());
    const std::size_t k0 = k1 - 1;
    const double dt = double(times[k1]) - double(times[k0]);
    const float t = float((double(when) - double(times[k0])) / dt);
    const float t2 = t * t, t3 = t2 * t;
    for (std::size_t i = 0; i < count; ++i) {
        switch (channel.interpolation) {
            case Interp::Step:
                out[i] = at(k0, i);
                break;
            case Interp::Linear:
                out[i] = at(k0, i) == at(k1, i) ? at(k0, i) : glm::mix(at(k0, i), at(k1, i), t);
                break;
            case Interp::CubicSpline: {
                const float m0 = at(k0, i, 1) * float(dt), m1 = at(k1, i, -1) * float(dt);
                out[i] = (2 * t3 - 3 * t2 + 1) * at(k0, i) + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * at(k1, i) +
                         (t3 - t2) * m1;
                break;
            }
        }
    }
    return out;
}

Posing::Posing(const Mesh& mesh, const std::vector<float>& weights, const std::vector<glm::mat4>& joints,
               PosedVertices& out, bool frames)
    : mesh_(mesh), weights_(weights), joints_(joints), out_(out) {
    const std::size_t n = mesh.positions.size();
    out.positions.resize(n);
    out.normals.resize(frames ? mesh.normals.size() : 0);
    out.tangents.resize(frames ? mesh.tangents.size() : 0);
    for (std::size_t t = 0; t < mesh.targets.size() && t < weights.size(); ++t)
        renormalise_ = renormalise_ || (weights[t] != 0.0f && !out.normals.empty() && !mesh.targets[t].normals.empty());
    skinning_ = !joints.empty() && mesh.skinned();
    renormalise_ = renormalise_ || skinning_;
    if (skinning_ && frames) {
        normalMatrices_.resize(joints.size());
        for (std::size_t j = 0; j < joints.size(); ++j)
            normalMatrices_[j] = glm::transpose(glm::inverse(glm::mat3(joints[j])));
    }
}

void Posing::run(std::size_t begin, std::size_t end) const {
    const Mesh& mesh = mesh_;
    PosedVertices& out = out_;
    const std::vector<glm::mat4>& joints = joints_;
    for (std::size_t v = begin; v < end; ++v) {
        glm::vec3 position = mesh.positions[v];
        const bool hasNormal = v < out.normals.size(), hasTangent = v < out.tangents.size();
        glm::vec3 normal = hasNormal ? mesh.normals[v] : glm::vec3(0.0f);
        glm::vec4 tangent = hasTangent ? mesh.tangents[v] : glm::vec4(0.0f);
        // The targets in order, each displacement times its weight.
        for (std::size_t t = 0; t < mesh.targets.size() && t < weights_.size(); ++t) {
            const float w = weights_[t];
            const MorphTarget& target = mesh.targets[t];
            if (w == 0.0f) continue;
            if (v < target.positions.size()) position += w * target.positions[v];
            if (hasNormal && v < target.normals.size()) normal += w * target.normals[v];
            if (hasTangent && v < target.tangents.size()) tangent += glm::vec4(w * target.tangents[v], 0.0f);
        }
        if (skinning_) {
            glm::vec3 p(0.0f), n(0.0f), d(0.0f);
            for (const Mesh::Influences& set : mesh.influences)
                for (int k = 0; k < 4; ++k) {
                    const float w = set.weights[v][k];
                    const std::uint32_t j = set.joints[v][k];
                    if (w == 0.0f || j >= joints.size()) continue;
                    // glm's J · (position, 1), (c0·x + c1·y) + (c2·z + c3·1), without its fourth row.
                    const glm::mat4& J = joints[j];
                    p += w * ((glm::vec3(J[0]) * position.x + glm::vec3(J[1]) * position.y) +
                              (glm::vec3(J[2]) * position.z + glm::vec3(J[3])));
                    if (hasNormal) n += w * (normalMatrices_[j] * normal);
                    if (hasTangent) d += w * (glm::mat3(J) * glm::vec3(tangent));
                }
            position = p;
            normal = n;
            tangent = glm::vec4(d, tangent.w);
        }
        out.positions[v] = position;
        if (hasNormal) {
            const float length = glm::length(normal);
            out.normals[v] = !renormalise_                            ? normal
                             : length > 0.0f && std::isfinite(length) ? normal / length
                                                                      : mesh.normals[v];
        }
        if (hasTangent) out.tangents[v] = tangent;
    }
}

void poseVertices(const Mesh& mesh, const std::vector<float>& weights, const std::vector<glm::mat4>& joints,
                  PosedVertices& out, bool frames) {
    const Posing posing(mesh, weights, joints, out, frames);
    posing.run(0, posing.vertices());
}

Mesh withPose(const Mesh& mesh, PosedVertices&& posed) {
    Mesh out = mesh;
    out.targets.clear();
    out.influences.clear();
    out.positions = std::move(posed.positions);
    out.normals = std::move(posed.normals);
    out.tangents = std::move(posed.tangents);
    return out;
}

Mesh posedMesh(const Mesh& mesh, const std::vector<float>& weights, const std::vector<glm::mat4>& joints) {
    PosedVertices posed;
    poseVertices(mesh, weights, joints, posed);
    return withPose(mesh, std::move(posed));
}

bool Scene::deforms(const Instance& instance) const {
    const Mesh& mesh = meshes[std::size_t(instance.mesh)];
    return mesh.morphs() || (mesh.skinned() && nodes[std::size_t(instance.node)].skin >= 0);
}

bool Scene::deforms() const {
    for (const Instance& instance : instances)
        if (deforms(instance)) return true;
    return false;
}

std::vector<glm::mat4> Scene::jointMatrices(const Instance& instance, const std::vector<glm::mat4>& world) const {
    const int s = nodes[std::size_t(instance.node)].skin;
    if (s < 0 || !meshes[std::size_t(instance.mesh)].skinned()) return {};
    const Skin& skin = skins[std::size_t(s)];
    const glm::mat4 toNode = glm::inverse(world[std::size_t(instance.node)]);
    std::vector<glm::mat4> out(skin.joints.size());
    for (std::size_t j = 0; j < skin.joints.size(); ++j)
        out[j] = toNode * world[std::size_t(skin.joints[j])] *
                 (j < skin.inverseBindMatrices.size() ? skin.inverseBindMatrices[j] : glm::mat4(1.0f));
    return out;
}

std::vector<std::vector<float>> Scene::morphWeights(double time) const {
    std::vector<std::vector<float>> out(nodes.size());
    for (std::size_t n = 0; n < nodes.size(); ++n)
        for (int m : nodes[n].meshes)
            if (meshes[std::size_t(m)].morphs()) {
                const Mesh& mesh = meshes[std::size_t(m)];
                out[n] = !nodes[n].weights.empty() ? nodes[n].weights
                         : !mesh.weights.empty()   ? mesh.weights
                                                   : std::vector<float>(mesh.targets.size(), 0.0f);
                break;
            }
    for (const Animation& animation : animations)
        for (const AnimChannel& channel : animation.channels)
            if (channel.path == AnimPath::Weights && channel.node >= 0 && channel.node < int(nodes.size()) &&
                !out[std::size_t(channel.node)].empty())
                out[std::size_t(channel.node)] = sampleWeights(channel, time);
    return out;
}

std::vector<glm::mat4> Scene::worldTransforms(double time) const {
    std::vector<Node> posed = nodes;
    for (const Animation& animation : animations) {
        for (const AnimChannel& channel : animation.channels) {
            if (channel.node < 0 || channel.node >= int(posed.size()) || channel.path == AnimPath::Weights) continue;
            Node& node = posed[channel.node];
            const glm::vec4 v = sampleChannel(channel, time);
            // glTF animates only TRS nodes; the loaders reject an animated node that has a matrix.
            switch (channel.path) {
            case AnimPath::Translation: node.translation = glm::vec3(v); break;
            case AnimPath::Rotation: node.rotation = toQuat(v); break;
            case AnimPath::Scale: node.scale = glm::vec3(v); break;
            case AnimPath::Weights: break;
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
    // Posed only where something deforms: a static scene's bounds cost what they did.
    const bool deforming = deforms();
    const std::vector<std::vector<float>> weights = deforming ? morphWeights(time) : std::vector<std::vector<float>>{};
    Bounds bounds;
    PosedVertices posed;
    for (const Instance& instance : instances) {
        const Mesh& mesh = meshes[instance.mesh];
        const bool posing = deforming && deforms(instance);
        if (posing)
            poseVertices(mesh, mesh.morphs() ? weights[std::size_t(instance.node)] : std::vector<float>{},
                         jointMatrices(instance, world), posed, /*frames=*/false);
        const std::vector<glm::vec3>& positions = posing ? posed.positions : mesh.positions;
        const glm::mat4& m = world[instance.node];
        // Only vertices that triangles use count (dropped triangles may leave unused vertices).
        for (std::uint32_t index : mesh.indices) bounds.add(glm::vec3(m * glm::vec4(positions[index], 1.0f)));
    }
    return bounds;
}

namespace {

// A box in double, for the envelope's arithmetic.
struct Box {
    glm::dvec3 min{INFINITY}, max{-INFINITY};
    bool empty() const { return min.x > max.x; }
    void add(const glm::dvec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void add(const Box& b) {
        if (!b.empty()) add(b.min), add(b.max);
    }
    glm::dvec3 center() const { return (min + max) * 0.5; }
    double halfDiagonal() const { return glm::length(max - min) * 0.5; }
};

Box transformed(const glm::mat4& m, const Box& b) {
    Box out;
    if (b.empty()) return out;
    const glm::dmat4 d(m);
    for (int corner = 0; corner < 8; ++corner)
        out.add(glm::dvec3(d * glm::dvec4(corner & 1 ? b.max.x : b.min.x, corner & 2 ? b.max.y : b.min.y,
                                          corner & 4 ? b.max.z : b.min.z, 1.0)));
    return out;
}

// Every value a channel takes at any time lies in the box of its keys: linear and step pieces stay
// between their keys (a slerp's are unit quaternions, not boxed here), a cubic Hermite piece inside
// its Bezier control points p0, p0 + m0/3, p1 - m1/3, p1 (m scaled by the key interval, glTF
// appendix C), and times outside the keys hold the first or last value.
void addChannelValues(const AnimChannel& channel, Box& box) {
    if (channel.interpolation != Interp::CubicSpline) {
        for (const glm::vec4& v : channel.values) box.add(glm::dvec3(v));
        return;
    }
    const std::size_t keys = channel.times.size();
    for (std::size_t k = 0; k < keys && 3 * k + 2 < channel.values.size(); ++k) {
        const glm::dvec3 p(channel.values[3 * k + 1]);
        box.add(p);
        if (k + 1 < keys) {
            const double dt = double(channel.times[k + 1]) - double(channel.times[k]);
            box.add(p + glm::dvec3(channel.values[3 * k + 2]) * (dt / 3.0));
            box.add(glm::dvec3(channel.values[3 * (k + 1) + 1]) - glm::dvec3(channel.values[3 * (k + 1)]) * (dt / 3.0));
        }
    }
}

// What the animations can do to one node's local transform T·R·S.
struct NodeMotion {
    bool animated = false, rotates = false;
    Box translation, scale;  // the values each takes (the node's own when not animated)
};

// A ball that holds some content: what a sweep makes, kept as a ball up the hierarchy (a box
// around a ball is √3 times wider across its diagonal, which over a chain of animated joints would
// grow the envelope by √3 a level).
struct Ball {
    glm::dvec3 c{0.0};
    double r = -1.0;  // < 0: none
    bool empty() const { return r < 0.0; }
};

Ball ballOf(const Box& box) { return box.empty() ? Ball{} : Ball{box.center(), box.halfDiagonal()}; }

// The smallest ball holding both.
Ball merged(const Ball& a, const Ball& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    const double d = glm::length(b.c - a.c);
    if (d + b.r <= a.r) return a;
    if (d + a.r <= b.r) return b;
    const double r = (d + a.r + b.r) * 0.5;
    return Ball{a.c + (b.c - a.c) * ((r - a.r) / d), r};
}

// The box, in the parent's frame, of `content` (in the node's frame) under every local transform
// the node can take: the content becomes a ball (centre c, radius r), scaling moves c within a box
// and grows r by the largest scale, a rotation turns the ball about the origin (any rotation: the
// ball about the origin that holds it), and the translations move it within their box.
// `ball`, when not empty, also holds the content and is used when it is the smaller; `swept`
// receives the result as a ball.
Box sweep(const Node& node, const NodeMotion& motion, const Box& content, const Ball& ball, Ball& swept) {
    if (content.empty()) return content;
    const bool byBall = !ball.empty() && ball.r < content.halfDiagonal();
    const glm::dvec3 c = byBall ? ball.c : content.center();
    const double r = byBall ? ball.r : content.halfDiagonal();
    Box scaled;
    double largestScale = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
        const double a = c[axis] * motion.scale.min[axis], b = c[axis] * motion.scale.max[axis];
        scaled.min[axis] = std::min(a, b);
        scaled.max[axis] = std::max(a, b);
        largestScale = std::max({largestScale, std::abs(motion.scale.min[axis]), std::abs(motion.scale.max[axis])});
    }
    glm::dvec3 centre = scaled.center();
    double radius = r * largestScale + scaled.halfDiagonal();
    if (motion.rotates) {
        radius += glm::length(centre);
        centre = glm::dvec3(0.0);
    } else {
        centre = glm::dmat3(glm::mat3_cast(node.rotation)) * centre;
    }
    centre += motion.translation.center();
    radius += motion.translation.halfDiagonal();
    Box out;
    out.add(centre - glm::dvec3(radius));
    out.add(centre + glm::dvec3(radius));
    swept = Ball{centre, radius};
    return out;
}

}  // namespace

namespace {

struct Range {
    double low = 0.0, high = 0.0;
    void add(double v) {
        low = std::min(low, v);
        high = std::max(high, v);
    }
};

// Per mesh, per target: the weights it can take over every node that draws it and every time
// (0 included; a cubic channel's Hermite pieces within their control points, as addChannelValues).
std::vector<std::vector<Range>> morphWeightRanges(const Scene& scene) {
    std::vector<std::vector<Range>> out(scene.meshes.size());
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        out[m].resize(scene.meshes[m].targets.size());
        for (std::size_t t = 0; t < out[m].size() && t < scene.meshes[m].weights.size(); ++t)
            out[m][t].add(scene.meshes[m].weights[t]);
    }
    const auto addToNode = [&](int node, const std::vector<float>& values, std::size_t count) {
        if (count == 0) return;
        for (int m : scene.nodes[std::size_t(node)].meshes)
            for (std::size_t i = 0; i < values.size(); ++i)
                if (i % count < out[std::size_t(m)].size()) out[std::size_t(m)][i % count].add(values[i]);
    };
    for (int n = 0; n < int(scene.nodes.size()); ++n)
        addToNode(n, scene.nodes[std::size_t(n)].weights, scene.nodes[std::size_t(n)].weights.size());
    for (const Animation& animation : scene.animations)
        for (const AnimChannel& channel : animation.channels) {
            if (channel.path != AnimPath::Weights || channel.node < 0 || channel.node >= int(scene.nodes.size()))
                continue;
            const std::size_t count = std::size_t(std::max(channel.weightCount, 0));
            if (channel.interpolation != Interp::CubicSpline) {
                addToNode(channel.node, channel.weights, count);
                continue;
            }
            // Values, and each piece's inner control points p0 + m0/3 and p1 − m1/3.
            const std::size_t keys = channel.times.size();
            for (int m : scene.nodes[std::size_t(channel.node)].meshes)
                for (std::size_t k = 0; k < keys && (3 * k + 3) * count <= channel.weights.size(); ++k)
                    for (std::size_t i = 0; i < count && i < out[std::size_t(m)].size(); ++i) {
                        const double p = channel.weights[(3 * k + 1) * count + i];
                        out[std::size_t(m)][i].add(p);
                        if (k + 1 < keys && (3 * k + 6) * count <= channel.weights.size()) {
                            const double dt = double(channel.times[k + 1]) - double(channel.times[k]);
                            out[std::size_t(m)][i].add(p + channel.weights[(3 * k + 2) * count + i] * dt / 3.0);
                            out[std::size_t(m)][i].add(channel.weights[(3 * k + 4) * count + i] -
                                                       channel.weights[(3 * k + 3) * count + i] * dt / 3.0);
                        }
                    }
        }
    return out;
}

}  // namespace

Bounds Scene::computeEnvelope() const {
    const std::size_t n = nodes.size();
    std::vector<NodeMotion> motion(n);
    for (std::size_t i = 0; i < n; ++i) {
        motion[i].translation.add(glm::dvec3(nodes[i].translation));
        motion[i].scale.add(glm::dvec3(nodes[i].scale));
    }
    // A channel replaces the node's own value at every time (worldTransforms), so an animated path
    // takes only its channels' values.
    std::vector<std::uint8_t> replaced(n * 3, 0);
    for (const Animation& animation : animations)
        for (const AnimChannel& channel : animation.channels) {
            if (channel.node < 0 || channel.node >= int(n) || channel.values.empty()) continue;
            NodeMotion& m = motion[std::size_t(channel.node)];
            m.animated = true;
            const int path = int(channel.path);
            if (channel.path == AnimPath::Rotation) {
                m.rotates = true;
                continue;
            }
            Box& box = channel.path == AnimPath::Translation ? m.translation : m.scale;
            if (!replaced[std::size_t(channel.node) * 3 + path]) box = Box{};
            replaced[std::size_t(channel.node) * 3 + path] = 1;
            addChannelValues(channel, box);
        }

    // A non-finite vertex draws nothing (its triangles' clip distances are not finite): left out.
    // A morphing vertex moves within the box of its position plus each target's displacement times
    // every weight the target can take (morphWeightRanges).
    const std::vector<std::vector<Range>> ranges = morphWeightRanges(*this);
    const auto vertexBox = [&](std::size_t m, std::uint32_t index) {
        Box box;
        const glm::vec3& p = meshes[m].positions[index];
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) return box;
        glm::dvec3 low(p), high(p);
        for (std::size_t t = 0; t < meshes[m].targets.size() && t < ranges[m].size(); ++t) {
            if (index >= meshes[m].targets[t].positions.size()) continue;
            const glm::dvec3 d(meshes[m].targets[t].positions[index]);
            const glm::dvec3 a = d * ranges[m][t].low, b = d * ranges[m][t].high;
            low += glm::min(a, b);
            high += glm::max(a, b);
        }
        // The posed position is a float sum, rounded at each step: a margin of a few of its ulps.
        const glm::dvec3 slack = meshes[m].morphs() ? (glm::abs(low) + glm::abs(high)) * 1e-6 : glm::dvec3(0.0);
        box.add(low - slack);
        box.add(high + slack);
        return box;
    };
    std::vector<Box> meshBoxes(meshes.size());
    for (std::size_t m = 0; m < meshes.size(); ++m)
        for (std::uint32_t index : meshes[m].indices) meshBoxes[m].add(vertexBox(m, index));

    // A skinned instance's vertices follow its joints: each vertex is in the box of its joints'
    // poses of it (weights at least 0 summing to 1); its box in each joint's frame is added to the
    // joint's content. Weights of another sum widen the world box below.
    std::vector<Box> jointContent(n);
    double weightSum = 1.0;                         // the largest Σ|w| of a skinned vertex
    std::vector<bool> affine(meshes.size(), true);  // every vertex's weights at least 0, summing to 1
    std::vector<std::vector<Box>> perJoint(meshes.size());
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        if (!meshes[m].skinned()) continue;
        for (std::uint32_t index : meshes[m].indices) {
            double sum = 0.0, absolute = 0.0;
            for (const Mesh::Influences& set : meshes[m].influences)
                for (int k = 0; k < 4; ++k) {
                    const float w = set.weights[index][k];
                    if (w == 0.0f) continue;
                    sum += w;
                    absolute += std::abs(double(w));
                    const std::size_t j = set.joints[index][k];
                    if (perJoint[m].size() <= j) perJoint[m].resize(j + 1);
                    perJoint[m][j].add(vertexBox(m, index));
                }
            weightSum = std::max(weightSum, absolute);
            if (std::abs(sum - 1.0) > 1e-6 || absolute > sum + 1e-6) affine[m] = false;
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (nodes[i].skin < 0) continue;
        const Skin& skin = skins[std::size_t(nodes[i].skin)];
        for (int mesh : nodes[i].meshes) {
            // Weights that are no affine combination pull a vertex towards the node's origin too
            // (its matrix applies to the sum with w = 1): the origin joins the node's content.
            if (meshes[std::size_t(mesh)].skinned() && !affine[std::size_t(mesh)]) jointContent[i].add(glm::dvec3(0.0));
            for (std::size_t j = 0; j < perJoint[std::size_t(mesh)].size() && j < skin.joints.size(); ++j)
                jointContent[std::size_t(skin.joints[j])].add(
                    transformed(j < skin.inverseBindMatrices.size() ? skin.inverseBindMatrices[j] : glm::mat4(1.0f),
                                perJoint[std::size_t(mesh)][j]));
        }
    }
    const bool notAffine = std::find(affine.begin(), affine.end(), false) != affine.end();

    // Parents before children (loaders reject cycles), then each node's content, children first.
    std::vector<int> order, stack;
    for (int i = 0; i < int(n); ++i)
        if (nodes[i].parent < 0) stack.push_back(i);
    while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        order.push_back(i);
        for (int child : nodes[i].children) stack.push_back(child);
    }
    std::vector<Box> content(n), swept(n);
    std::vector<Ball> sweptBalls(n);
    Box world;
    for (auto it = order.rbegin(); it != order.rend(); ++it) {
        const std::size_t i = std::size_t(*it);
        for (int mesh : nodes[i].meshes)
            if (nodes[i].skin < 0 || !meshes[std::size_t(mesh)].skinned()) content[i].add(meshBoxes[std::size_t(mesh)]);
        content[i].add(jointContent[i]);
        Ball ball = ballOf(content[i]);  // the node's own content, then its children's balls
        for (int child : nodes[i].children) {
            content[i].add(swept[std::size_t(child)]);
            ball = merged(ball, sweptBalls[std::size_t(child)].empty() ? ballOf(swept[std::size_t(child)])
                                                                       : sweptBalls[std::size_t(child)]);
        }
        if (motion[i].animated && !nodes[i].hasMatrix) {
            swept[i] = sweep(nodes[i], motion[i], content[i], ball, sweptBalls[i]);
        } else {
            swept[i] = transformed(localMatrix(nodes[i]), content[i]);
            // The ball under the node's matrix: its centre moved, its radius times the largest
            // stretch (column length); kept when smaller than the box's.
            const glm::dmat4 m(localMatrix(nodes[i]));
            const double stretch =
                std::max({glm::length(glm::dvec3(m[0])), glm::length(glm::dvec3(m[1])), glm::length(glm::dvec3(m[2]))});
            const Ball moved = ball.empty() ? Ball{} : Ball{glm::dvec3(m * glm::dvec4(ball.c, 1.0)), ball.r * stretch};
            const Ball boxed = ballOf(swept[i]);
            sweptBalls[i] = !moved.empty() && moved.r < boxed.r ? moved : boxed;
        }
        if (nodes[i].parent < 0) world.add(swept[i]);
    }
    // Skin weights that are no affine combination: a vertex is Σ wᵢ·Xᵢ + (1 − Σ wᵢ)·T with Xᵢ its
    // joints' poses of it and T its node's origin, all in the box so far: within (2·Σ|w| + 1) times
    // the box's largest coordinate, either side.
    if (!world.empty() && notAffine) {
        const double reach =
            (2.0 * weightSum + 1.0) * std::max(glm::compMax(glm::abs(world.min)), glm::compMax(glm::abs(world.max)));
        world.add(glm::dvec3(-reach));
        world.add(glm::dvec3(reach));
    }
    Bounds out;
    const bool finite =
        std::isfinite(world.min.x + world.min.y + world.min.z + world.max.x + world.max.y + world.max.z);
    if (world.empty() || !finite) return out;  // nothing drawn, or transforms beyond float: no fit
    // Rounded outward to float.
    for (int axis = 0; axis < 3; ++axis) {
        out.min[axis] = std::nextafter(float(world.min[axis]), -INFINITY);
        out.max[axis] = std::nextafter(float(world.max[axis]), INFINITY);
    }
    return out;
}

}  // namespace frugal
