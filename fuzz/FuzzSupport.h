// What the fuzz targets share: the folder inputs pretend to live in, and the oracle a loaded scene
// must pass. A broken promise aborts, so libFuzzer reports it like a crash, with the input.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include <frugal/Result.h>
#include <frugal/Scene.h>

namespace frugal::fuzz {

// Inputs are named as files in a folder that does not exist: relative URIs and mtllib names then
// resolve to nothing (the kernel needs every component of "/nonexistent/../x" to exist), so a run
// depends on its input alone.
inline std::string inputName(const char* extension) {
    return std::string("/nonexistent-frugal-fuzz/input") + extension;
}

[[noreturn]] inline void broken(const std::string& what) {
    std::fprintf(stderr, "fuzz oracle: %s\n", what.c_str());
    std::abort();
}

// An error is one line, "<name>: <why>" (any name when `name` is empty).
template <class T>
void checkError(const Result<T>& result, std::string_view name) {
    if (result) return;
    const std::string& message = result.error().message;
    if (message.empty() || message.find_first_of("\r\n") != std::string::npos)
        broken("error message is not one line: '" + message + "'");
    if (!name.empty() && (message.rfind(std::string(name) + ": ", 0) != 0 || message.size() <= name.size() + 2))
        broken("error message does not name the input and a reason: " + message);
}

// What Scene.h promises every module that reads a scene: indices, counts and references in range,
// key times increasing; then what `frugal info` and every render do first (transforms, bounds) runs.
inline void checkScene(const Scene& scene) {
    const auto inRange = [](auto index, std::size_t size) { return index >= 0 && std::size_t(index) < size; };
    for (const Mesh& mesh : scene.meshes) {
        const std::size_t vertices = mesh.positions.size();
        if (std::size_t(mesh.topology) >= std::size(kTopologyNames)) broken("mesh '" + mesh.name + "': topology");
        if (mesh.indices.size() % verticesPerPrimitive(mesh.topology) != 0)
            broken("mesh '" + mesh.name + "': indices not whole primitives");
        for (std::uint32_t index : mesh.indices)
            if (index >= vertices) broken("mesh '" + mesh.name + "': index out of range");
        // Points and segments may have no normals (drawn unlit); triangles always have them.
        if (mesh.normals.size() != vertices && (mesh.triangles() || !mesh.normals.empty()))
            broken("mesh '" + mesh.name + "': normals not one per vertex");
        if (!mesh.colors.empty() && mesh.colors.size() != vertices) broken("mesh '" + mesh.name + "': colours");
        if (!mesh.uvs.empty() && mesh.uvs.size() != vertices) broken("mesh '" + mesh.name + "': uvs");
        if (mesh.triangleSource.size() != mesh.primitiveCount()) broken("mesh '" + mesh.name + "': triangleSource");
        if (mesh.material != -1 && !inRange(mesh.material, scene.materials.size()))
            broken("mesh '" + mesh.name + "': material out of range");
    }
    for (const Material& material : scene.materials)
        if (material.baseColorTexture != -1 && !inRange(material.baseColorTexture, scene.textures.size()))
            broken("material '" + material.name + "': texture out of range");
    for (const Texture& texture : scene.textures)
        if (texture.width < 1 || texture.height < 1 ||
            texture.rgba.size() != std::size_t(texture.width) * std::size_t(texture.height) * 4)
            broken("texture '" + texture.name + "': size does not match its pixels");
    for (const Node& node : scene.nodes) {
        if (node.parent != -1 && !inRange(node.parent, scene.nodes.size())) broken("node parent out of range");
        for (int child : node.children)
            if (!inRange(child, scene.nodes.size())) broken("node child out of range");
        for (int mesh : node.meshes)
            if (!inRange(mesh, scene.meshes.size())) broken("node mesh out of range");
        if (node.camera != -1 && !inRange(node.camera, scene.cameras.size())) broken("node camera out of range");
    }
    for (int root : scene.roots)
        if (!inRange(root, scene.nodes.size())) broken("root out of range");
    // Morph targets and skins: one value a vertex, joints that exist where a vertex leans on them.
    for (const Mesh& mesh : scene.meshes) {
        const std::size_t vertices = mesh.positions.size();
        const auto sized = [vertices](std::size_t n) { return n == 0 || n == vertices; };
        for (const MorphTarget& target : mesh.targets)
            if (!sized(target.positions.size()) || !sized(target.normals.size()) || !sized(target.tangents.size()))
                broken("morph target arrays not one a vertex");
        if (mesh.weights.size() != mesh.targets.size()) broken("morph weights not one a target");
        for (const Mesh::Influences& set : mesh.influences)
            if (set.joints.size() != vertices || set.weights.size() != vertices)
                broken("skin influences not one a vertex");
    }
    for (const Skin& skin : scene.skins) {
        if (skin.inverseBindMatrices.size() != skin.joints.size()) broken("inverse bind matrices not one a joint");
        for (int joint : skin.joints)
            if (!inRange(joint, scene.nodes.size())) broken("skin joint out of range");
    }
    for (const Node& node : scene.nodes) {
        if (node.skin == -1) continue;
        if (!inRange(node.skin, scene.skins.size())) broken("node skin out of range");
        for (int m : node.meshes)
            for (const Mesh::Influences& set : scene.meshes[std::size_t(m)].influences)
                for (std::size_t v = 0; v < set.joints.size(); ++v)
                    for (int k = 0; k < 4; ++k)
                        if (set.weights[v][k] != 0.0f &&
                            set.joints[v][k] >= scene.skins[std::size_t(node.skin)].joints.size())
                            broken("a vertex leans on a joint its skin does not have");
    }
    for (const SceneCamera& camera : scene.cameras)
        if (!inRange(camera.node, scene.nodes.size())) broken("camera node out of range");
    std::uint64_t ids = 1;  // 0 is the background
    for (const Instance& instance : scene.instances) {
        if (!inRange(instance.node, scene.nodes.size()) || !inRange(instance.mesh, scene.meshes.size()))
            broken("instance out of range");
        if (instance.firstId != ids) broken("instance ids not consecutive (32-bit ids wrapped?)");
        std::uint64_t sources = 0;
        for (std::uint32_t source : scene.meshes[std::size_t(instance.mesh)].triangleSource)
            sources = std::max<std::uint64_t>(sources, source + 1ull);
        ids += sources;
        if (ids - 1 > 0xFFFFFFFFu) broken("triangle ids beyond 32 bits");
    }
    for (const Animation& animation : scene.animations)
        for (const AnimChannel& channel : animation.channels) {
            if (!inRange(channel.node, scene.nodes.size())) broken("animation channel node out of range");
            const std::size_t perKey = channel.interpolation == Interp::CubicSpline ? 3 : 1;
            if (channel.path == AnimPath::Weights) {
                if (channel.weightCount < 1 || !channel.values.empty() ||
                    channel.weights.size() != channel.times.size() * perKey * std::size_t(channel.weightCount))
                    broken("animation weights per key");
            } else if (channel.values.size() != channel.times.size() * perKey) {
                broken("animation values per key");
            }
            for (std::size_t k = 0; k < channel.times.size(); ++k)
                if (!std::isfinite(channel.times[k]) || (k > 0 && !(channel.times[k] > channel.times[k - 1])))
                    broken("animation key times not finite and increasing");
        }
    scene.bounds(0.0);
    scene.bounds(scene.duration());
}

}  // namespace frugal::fuzz
