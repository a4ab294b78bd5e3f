// Scene::add* and setTransform: a scene built in memory, checked as a loader checks a file.
#include <cmath>
#include <string>
#include <utility>

#include <frugal/Scene.h>

#include "base/Format.h"
#include "scene/ImageCheck.h"
#include "scene/LightCheck.h"
#include "scene/MeshBuild.h"

namespace frugal {

namespace {

Error bad(std::string message) { return Error{std::move(message), ErrorKind::BadInput}; }

template <int N>
std::string text(const glm::vec<N, float>& v) {
    std::string out = "(";
    for (int k = 0; k < N; ++k) out += (k ? ", " : "") + fmt(double(v[k]));
    return out + ")";
}

// "<what> <i> is (nan, 0, 1), not finite" for the first value that is not, else "".
template <int N>
std::string firstNotFinite(const char* what, const std::vector<glm::vec<N, float>>& values) {
    for (std::size_t i = 0; i < values.size(); ++i)
        if (!isFinite(values[i])) return std::string(what) + " " + std::to_string(i) + " is " + text(values[i]) + ", not finite";
    return {};
}

std::string matrixProblem(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r]))
                return "row " + std::to_string(r) + ", column " + std::to_string(c) + " is " + fmt(double(m[c][r])) +
                       ", not finite";
    return {};
}

// A new root node of `scene` with `transform` (checked) as its local matrix: what an instance and a
// light are placed by.
Node& addRoot(Scene& scene, const glm::mat4& transform, std::string name) {
    Node& node = scene.nodes.emplace_back();
    node.name = std::move(name);
    node.hasMatrix = true;
    node.matrix = transform;
    scene.roots.push_back(int(scene.nodes.size()) - 1);
    return node;
}

std::string meshProblem(const Mesh& mesh, std::size_t materials) {
    const std::size_t vertices = mesh.positions.size();
    const std::size_t corners = verticesPerPrimitive(mesh.topology);
    const char* primitive = mesh.triangles() ? "triangle" : mesh.topology == Topology::Lines ? "segment" : "point";
    if (std::size_t(mesh.topology) >= std::size(kTopologyNames))
        return "topology " + std::to_string(int(mesh.topology)) + " is not triangles, lines or points";
    if (mesh.indices.size() % corners != 0)
        return std::to_string(mesh.indices.size()) + " indices are not whole " + primitive + "s (" +
               std::to_string(corners) + " a " + primitive + ")";
    for (std::size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= vertices)
            return "index " + std::to_string(mesh.indices[i]) + " (" + primitive + " " + std::to_string(i / corners) +
                   ") is past the " + std::to_string(vertices) + " vertices";
    const auto count = [&](const char* what, std::size_t n) -> std::string {
        if (n == 0 || n == vertices) return {};
        return std::to_string(n) + " " + what + " for " + std::to_string(vertices) + " vertices (one a vertex, or none)";
    };
    for (const std::string& problem : {count("normals", mesh.normals.size()), count("colours", mesh.colors.size()),
                                       count("uvs", mesh.uvs.size()), count("tangents", mesh.tangents.size()),
                                       firstNotFinite("position", mesh.positions),
                                       firstNotFinite("normal", mesh.normals), firstNotFinite("colour", mesh.colors),
                                       firstNotFinite("uv", mesh.uvs), firstNotFinite("tangent", mesh.tangents)})
        if (!problem.empty()) return problem;
    if (mesh.material < -1 || mesh.material >= int(materials))
        return "material " + std::to_string(mesh.material) + " does not exist (the scene has " +
               std::to_string(materials) + ")";
    for (std::size_t t = 0; t < mesh.targets.size(); ++t) {
        const MorphTarget& target = mesh.targets[t];
        const std::string which = "morph target " + std::to_string(t) + " ";
        for (const std::string& problem :
             {count("position displacements", target.positions.size()),
              count("normal displacements", target.normals.size()),
              count("tangent displacements", target.tangents.size()), firstNotFinite("position", target.positions),
              firstNotFinite("normal", target.normals), firstNotFinite("tangent", target.tangents)})
            if (!problem.empty()) return which + problem;
    }
    if (!mesh.weights.empty() && mesh.weights.size() != mesh.targets.size())
        return std::to_string(mesh.weights.size()) + " morph weights for " + std::to_string(mesh.targets.size()) +
               " targets";
    for (std::size_t w = 0; w < mesh.weights.size(); ++w)
        if (!std::isfinite(mesh.weights[w]))
            return "morph weight " + std::to_string(w) + " is " + fmt(double(mesh.weights[w])) + ", not finite";
    if (!mesh.triangleSource.empty() && mesh.triangleSource.size() != mesh.primitiveCount())
        return std::to_string(mesh.triangleSource.size()) + " triangle sources for " +
               std::to_string(mesh.primitiveCount()) + " " + primitive + "s";
    return {};
}

}  // namespace

Result<int> Scene::addTexture(Texture texture) {
    const std::uint64_t pixels = std::uint64_t(std::max(texture.width, 0)) * std::uint64_t(std::max(texture.height, 0));
    const std::string size = std::to_string(texture.width) + "x" + std::to_string(texture.height);
    if (texture.width < 1 || texture.height < 1) return bad("texture: " + size + ": width and height must be at least 1");
    if (pixels > kMaxImagePixels)
        return bad("texture: " + size + " is more than the " + std::to_string(kMaxImagePixels) + " pixels frugal reads");
    if (texture.rgba.size() != pixels * 4)
        return bad("texture: " + std::to_string(texture.rgba.size()) + " bytes for " + size + " RGBA (" +
                   std::to_string(pixels * 4) + " expected)");
    textures.push_back(std::move(texture));
    return int(textures.size()) - 1;
}

Result<int> Scene::addMaterial(Material material) {
    if (!isFinite(material.baseColorFactor))
        return bad("material: base colour " + text(material.baseColorFactor) + " is not finite");
    if (!isFinite(material.emissiveFactor) || glm::any(glm::lessThan(material.emissiveFactor, glm::vec3(0.0f))))
        return bad("material: emissive " + text(material.emissiveFactor) + " is not finite and at least 0");
    for (const MaterialMap& map : kMaterialMaps)
        if (const int index = material.*map.texture; index < -1 || index >= int(textures.size()))
            return bad(std::string("material: ") + map.name + " " + std::to_string(index) +
                       " does not exist (the scene has " + std::to_string(textures.size()) + ")");
    const auto factorProblem = [](const char* name, float value) -> std::string {
        if (value >= 0.0f && value <= 1.0f) return {};
        return std::string("material: ") + name + " " + fmt(double(value)) + " is not in [0, 1]";
    };
    for (const std::string& problem :
         {factorProblem("metallic", material.metallicFactor), factorProblem("roughness", material.roughnessFactor),
          factorProblem("occlusion strength", material.occlusionStrength),
          factorProblem("glossiness", material.glossinessFactor),
          factorProblem("specular red", material.specularFactor.r),
          factorProblem("specular green", material.specularFactor.g),
          factorProblem("specular blue", material.specularFactor.b),
          factorProblem("clear coat", material.clearcoatFactor),
          factorProblem("clear-coat roughness", material.clearcoatRoughnessFactor)})
        if (!problem.empty()) return bad(problem);
    if (!std::isfinite(material.normalScale))
        return bad("material: normal scale " + fmt(double(material.normalScale)) + " is not finite");
    if (!std::isfinite(material.clearcoatNormalScale))
        return bad("material: clear-coat normal scale " + fmt(double(material.clearcoatNormalScale)) +
                   " is not finite");
    if (!(material.alphaCutoff >= 0.0f && std::isfinite(material.alphaCutoff)))
        return bad("material: alpha cutoff " + fmt(double(material.alphaCutoff)) + " is not finite and at least 0");
    if (int(material.alphaMode) > int(AlphaMode::Blend))
        return bad("material: alpha mode " + std::to_string(int(material.alphaMode)) + " is not opaque, mask or blend");
    materials.push_back(std::move(material));
    return int(materials.size()) - 1;
}

Result<int> Scene::addMesh(Mesh mesh, bool optimizeOrder) {
    if (const std::string problem = meshProblem(mesh, materials.size()); !problem.empty())
        return bad("mesh" + quotedName(mesh.name) + ": " + problem);
    finalizeMesh(mesh, optimizeOrder);  // nothing to drop: every position is finite
    if (mesh.weights.empty()) mesh.weights.assign(mesh.targets.size(), 0.0f);
    meshes.push_back(std::move(mesh));
    return int(meshes.size()) - 1;
}

Result<int> Scene::addInstance(int mesh, const glm::mat4& transform, std::string name) {
    if (mesh < 0 || mesh >= int(meshes.size()))
        return bad("instance: mesh " + std::to_string(mesh) + " does not exist (the scene has " +
                   std::to_string(meshes.size()) + ")");
    if (const std::string problem = matrixProblem(transform); !problem.empty())
        return bad("instance: transform: " + problem);
    Node& node = addRoot(*this, transform, std::move(name));
    node.meshes = {mesh};
    return int(nodes.size()) - 1;
}

Result<int> Scene::addLight(PunctualLight light, const glm::mat4& transform, std::string name) {
    const std::string what = "light" + quotedName(light.name);
    if (int(light.type) > int(LightType::Spot))
        return bad(what + ": type " + std::to_string(int(light.type)) + " is not directional, point or spot");
    if (const std::optional<LightProblem> problem = lightProblem(light)) {
        const auto value = [](float v) { return fmt(double(v)); };
        switch (problem->value) {
            case LightValue::Color:
                return bad(what + ": colour " + value(light.color[problem->channel]) + " is not finite and at least 0");
            case LightValue::Intensity:
                return bad(what + ": intensity " + value(light.intensity) + " is not finite and at least 0");
            case LightValue::Range:
                return bad(what + ": range " + value(light.range) + " is not finite and at least 0 (0 = unbounded)");
            case LightValue::OuterCone:
                return bad(what + ": outer cone angle " + value(light.outerConeAngle) + " is not in (0, pi/2]");
            case LightValue::InnerCone:
                return bad(what + ": inner cone angle " + value(light.innerConeAngle) +
                           " is not in [0, the outer angle " + value(light.outerConeAngle) + ")");
        }
    }
    if (const std::string problem = matrixProblem(transform); !problem.empty())
        return bad(what + ": transform: " + problem);
    lights.push_back(std::move(light));
    addRoot(*this, transform, std::move(name)).light = int(lights.size()) - 1;
    return int(nodes.size()) - 1;
}

Result<bool> Scene::setTransform(int node, const glm::mat4& transform) {
    if (node < 0 || node >= int(nodes.size()))
        return bad("node " + std::to_string(node) + " does not exist (the scene has " + std::to_string(nodes.size()) +
                   ")");
    if (const std::string problem = matrixProblem(transform); !problem.empty())
        return bad("node " + std::to_string(node) + ": transform: " + problem);
    for (const Animation& animation : animations)
        for (const AnimChannel& channel : animation.channels)
            if (channel.node == node)
                return bad("node " + std::to_string(node) + quotedName(nodes[std::size_t(node)].name) +
                           " is animated (animation" + quotedName(animation.name) +
                           "): its transform is the animation's");
    Node& n = nodes[std::size_t(node)];
    n.hasMatrix = true;
    n.matrix = transform;
    return true;
}

}  // namespace frugal
