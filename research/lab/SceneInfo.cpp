#include "lab/SceneInfo.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/Research.h"

namespace frugal {

namespace {

// The scene's finer detail: the length that 1 % of its triangles' edges (world space, time 0) are
// shorter than, leaving out edges of length 0. 0 when it has no edge.
double sceneDetail(const Scene& scene) {
    const std::vector<glm::mat4> world = scene.worldTransforms(0.0);
    std::vector<float> lengths;
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[std::size_t(instance.mesh)];
        const glm::mat3 m(world[std::size_t(instance.node)]);
        if (!mesh.triangles()) continue;
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
            for (int k = 0; k < 3; ++k) {
                const glm::vec3 a = mesh.positions[mesh.indices[t + std::size_t(k)]];
                const glm::vec3 b = mesh.positions[mesh.indices[t + std::size_t((k + 1) % 3)]];
                const float length = glm::length(m * (b - a));
                if (length > 0.0f && std::isfinite(length)) lengths.push_back(length);
            }
    }
    if (lengths.empty()) return 0.0;
    const auto at = lengths.begin() + std::ptrdiff_t(lengths.size() / 100);
    std::nth_element(lengths.begin(), at, lengths.end());
    return double(*at);
}

// Where the scene lies along camera `index`'s view (the automatic view when none), and the depth
// each format and range separates at its far side; a warning where that is coarser than `detail`.
void printDepthPrecision(const Scene& scene, std::optional<int> index, double detail, int longSide, std::ostream& out) {
    const std::vector<glm::mat4> world = scene.worldTransforms(0.0);
    int width = 800, height = 600;
    if (index) {
        const float aspect = scene.cameras[std::size_t(*index)].fileAspect();
        if (aspect > 0.0f) sizeForAspect(aspect, longSide, width, height);
    }
    Camera spec;
    spec.sceneCamera = index;
    Result<View> fitted = resolveCamera(scene, world, 0.0, spec, width, height);
    spec.depthRange = DepthRange::File;
    Result<View> given = resolveCamera(scene, world, 0.0, spec, width, height);
    if (!fitted || !given) {
        out << "    " << (fitted ? given.error().message : fitted.error().message) << "\n";
        return;
    }
    const DepthExtent extent = depthExtent(fitted->view, scene.envelope);
    if (scene.envelope.empty() || !(extent.farthest > 0.0)) {
        out << "    the scene is not in front of this camera\n";
        return;
    }
    const auto planes = [](const View& v) {
        return fmt(v.znear) + " to " + (v.zfar > 0.0f ? fmt(v.zfar) : std::string("infinity"));
    };
    // The far side as drawn: no farther than the far plane.
    const double d = given->zfar > 0.0f ? std::min(extent.farthest, double(given->zfar)) : extent.farthest;
    out << "    scene at distance " << fmt(std::max(extent.nearest, 0.0)) << " to " << fmt(extent.farthest)
        << " along the view (its bounds over the whole animation)\n";
    out << "    depth separated at " << fmt(d) << ": fit (" << planes(*fitted) << "), file (" << planes(*given)
        << ")\n";
    std::string coarse;
    for (const DepthFormat format : {DepthFormat::D24, DepthFormat::D32F}) {
        char line[160];
        const double fit = depthResolution(format, fitted->perspective, fitted->znear, fitted->zfar, d);
        const double file = depthResolution(format, given->perspective, given->znear, given->zfar, d);
        std::snprintf(line, sizeof line, "      %-5s fit %-12.4g file %.4g\n", depthFormatName(format), fit, file);
        out << line;
        for (const auto& [range, step] : {std::pair{"fit", fit}, std::pair{"file", file}})
            if (detail > 0.0 && step > detail)
                coarse += (coarse.empty() ? "" : ", ") + std::string(depthFormatName(format)) + " with " + range +
                          " (" + fmt(step) + ")";
    }
    if (!coarse.empty())
        out << "    warning: coarser than the scene's detail (" << fmt(detail) << "): " << coarse
            << "; surfaces closer together than that may z-fight\n";
}

// The shading each drawn mesh asks for: what its program variant reads (the GL backend compiles one
// per combination, GlPrograms.cpp; ids and batching add their own forms per frame), with how many
// meshes use it.
void printShading(const Scene& scene, std::ostream& out) {
    static const Material kDefault{};
    std::map<std::string, int> variants;
    std::vector<bool> drawn(scene.meshes.size(), false);
    for (const Instance& instance : scene.instances) drawn[std::size_t(instance.mesh)] = true;
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        if (!drawn[i]) continue;
        const Mesh& mesh = scene.meshes[i];
        const Material& m = mesh.material >= 0 ? scene.materials[std::size_t(mesh.material)] : kDefault;
        // Points and segments without normals: the base colour plus the emission (Mesh::topology).
        const bool bare = !mesh.triangles() && mesh.normals.empty() && !m.unlit;
        std::string terms = m.unlit ? "unlit"
                            : bare  ? std::string(topologyName(mesh.topology)) + ", unlit: base colour + emission"
                            : m.specularGlossiness ? "specular-glossiness BRDF"
                                                   : "metallic-roughness BRDF";
        if (!mesh.triangles() && !bare) terms += std::string(" (") + topologyName(mesh.topology) + ")";
        if (bare) {
            if (m.baseColorTexture >= 0) terms += ", base colour map";
            if (m.emissiveTexture >= 0) terms += ", emissive map";
            if (!mesh.colors.empty()) terms += ", vertex colours";
            ++variants[terms];
            continue;
        }
        if (!m.unlit) {  // one side of the metal mix alone (pipeline/Backend.h, MetalMix)
            const MetalMix mix = metalMixOf(m.metallicFactor, m.metallicRoughnessTexture >= 0, m.specularGlossiness);
            if (mix == MetalMix::Dielectric) terms += ", dielectric only";
            if (mix == MetalMix::Metal) terms += ", metal only";
        }
        if (m.baseColorTexture >= 0) terms += ", base colour map";
        if (!mesh.colors.empty()) terms += ", vertex colours";
        if (!m.unlit) {
            if (m.metallicRoughnessTexture >= 0 && !m.specularGlossiness) terms += ", metallic-roughness map";
            if (m.specularGlossinessTexture >= 0 && m.specularGlossiness) terms += ", specular-glossiness map";
            if (m.occlusionTexture >= 0) terms += ", occlusion map";
            if (m.emissiveTexture >= 0) terms += ", emissive map";
            // Segments and points read a normal map only with tangents of their own (the Khronos renderer's rule).
            if (m.normalTexture >= 0 && (mesh.triangles() || !mesh.tangents.empty())) terms += ", normal map";
            if (m.clearcoat()) {
                terms += ", clear coat";
                if (m.clearcoatTexture >= 0) terms += ", clear-coat map";
                if (m.clearcoatRoughnessTexture >= 0) terms += ", clear-coat roughness map";
                if (m.clearcoatNormalTexture >= 0) terms += ", clear-coat normal map";
            }
            if (m.tangentSpace() && mesh.tangents.empty() && mesh.triangles()) terms += " (tangents generated)";
        }
        if (m.alphaMode == AlphaMode::Mask) terms += ", alpha mask (cutoff " + fmt(double(m.alphaCutoff)) + ")";
        if (m.alphaMode == AlphaMode::Blend) terms += ", blended (drawn last, far to near)";
        ++variants[terms];
    }
    out << "shading: " << variants.size() << " variant" << (variants.size() == 1 ? "" : "s") << "\n";
    for (const auto& [terms, meshes] : variants)
        out << "  " << terms << ": " << meshes << " mesh" << (meshes == 1 ? "" : "es") << "\n";
}

}  // namespace

std::string sceneInfoText(const Scene& scene, int longSide) {
    std::ostringstream out;

    std::size_t vertices = 0;
    for (const Mesh& mesh : scene.meshes) vertices += mesh.positions.size();
    out << "scene: " << scene.source << "\n";
    out << "nodes: " << scene.nodes.size() << " (" << scene.roots.size() << " roots)\n";
    out << "meshes: " << scene.meshes.size() << " (" << vertices << " vertices)\n";
    out << "instances: " << scene.instances.size() << "\n";
    out << "triangles: " << scene.triangleCount() << " (drawn per frame)\n";
    std::size_t segments = 0, points = 0;
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[std::size_t(instance.mesh)];
        if (mesh.topology == Topology::Lines) segments += mesh.primitiveCount();
        if (mesh.topology == Topology::Points) points += mesh.primitiveCount();
    }
    if (segments + points > 0)
        out << "points and lines: " << segments << (segments == 1 ? " line segment, " : " line segments, ") << points
            << (points == 1 ? " point" : " points") << " (1 pixel wide; culling draws them whole)\n";
    out << "materials: " << scene.materials.size() << "\n";
    for (const Material& m : scene.materials) {
        out << "  '" << m.name << "' base colour " << fmt(m.baseColorFactor.r) << "," << fmt(m.baseColorFactor.g) << ","
            << fmt(m.baseColorFactor.b) << "," << fmt(m.baseColorFactor.a)
            << (m.baseColorTexture >= 0 ? ", texture " + std::to_string(m.baseColorTexture) : std::string())
            << (m.unlit                ? ", unlit"
                : m.specularGlossiness ? ", specular " + fmt(m.specularFactor.r) + "," + fmt(m.specularFactor.g) + "," +
                                             fmt(m.specularFactor.b) + ", glossiness " + fmt(m.glossinessFactor)
                                       : ", metallic " + fmt(m.metallicFactor) + ", roughness " + fmt(m.roughnessFactor))
            << (m.doubleSided ? ", double-sided" : ", single-sided")
            << (m.alphaMode == AlphaMode::Mask    ? ", alpha mask at " + fmt(m.alphaCutoff)
                : m.alphaMode == AlphaMode::Blend ? std::string(", blended")
                                                  : std::string());
        if (!m.unlit) {
            if (m.metallicRoughnessTexture >= 0) out << ", metallic-roughness map " << m.metallicRoughnessTexture;
            if (m.specularGlossinessTexture >= 0) out << ", specular-glossiness map " << m.specularGlossinessTexture;
            if (m.occlusionTexture >= 0)
                out << ", occlusion map " << m.occlusionTexture << " at " << fmt(m.occlusionStrength);
            if (m.emissiveTexture >= 0) out << ", emissive map " << m.emissiveTexture;
            if (m.normalTexture >= 0) out << ", normal map " << m.normalTexture << " at " << fmt(m.normalScale);
            if (m.clearcoat()) {
                out << ", clear coat " << fmt(m.clearcoatFactor) << " of roughness " << fmt(m.clearcoatRoughnessFactor);
                if (m.clearcoatTexture >= 0) out << ", clear-coat map " << m.clearcoatTexture;
                if (m.clearcoatRoughnessTexture >= 0)
                    out << ", clear-coat roughness map " << m.clearcoatRoughnessTexture;
                if (m.clearcoatNormalTexture >= 0)
                    out << ", clear-coat normal map " << m.clearcoatNormalTexture << " at "
                        << fmt(m.clearcoatNormalScale);
            }
            if (m.emissiveFactor != glm::vec3(0.0f))
                out << ", emissive " << fmt(m.emissiveFactor.r) << "," << fmt(m.emissiveFactor.g) << ","
                    << fmt(m.emissiveFactor.b);
        }
        out << "\n";
    }
    printShading(scene, out);
    out << "textures: " << scene.textures.size() << "\n";
    for (const Texture& t : scene.textures) {
        const auto name = [](Filter f) { return f == Filter::Nearest ? "nearest" : "linear"; };
        out << "  '" << t.name << "' " << t.width << "x" << t.height << ", " << name(t.filter) << " filter";
        if (t.minFilter != t.filter) out << " (" << name(t.minFilter) << " minified)";
        if (t.mipmaps == MipFilter::Nearest) out << ", nearest mipmap";
        if (t.mipmaps == MipFilter::Linear) out << ", mipmaps blended";
        out << (t.srgb ? ", sRGB colour" : ", linear data") << "\n";
    }
    const double detail = sceneDetail(scene);
    if (detail > 0.0)
        out << "detail: 1 % of the triangle edges are shorter than " << fmt(detail) << "\n";
    else
        out << "detail: no triangle edge longer than 0\n";
    out << "cameras: " << scene.cameras.size() << "\n";
    for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
        const SceneCamera& c = scene.cameras[i];
        out << "  '" << c.name << "' "
            << (c.perspective ? "perspective yfov " + fmt(glm::degrees(c.yfov)) + " deg" : std::string("orthographic"))
            << (c.perspective && c.aspect > 0.0f ? ", aspect ratio " + fmt(c.aspect) : std::string()) << ", znear "
            << fmt(c.znear) << ", zfar " << (c.zfar > 0 ? fmt(c.zfar) : std::string("infinite")) << "\n";
        printDepthPrecision(scene, int(i), detail, longSide, out);
    }
    if (scene.cameras.empty()) {
        out << "  the automatic view (no camera in the scene):\n";
        printDepthPrecision(scene, std::nullopt, detail, longSide, out);
    }
    // Punctual lights, by the nodes that place them (KHR_lights_punctual); none: the default light.
    std::size_t placed = 0;
    for (const Node& node : scene.nodes) placed += node.light >= 0;
    out << "lights: " << placed;
    if (placed == 0) out << " (the default directional light)";
    if (placed > std::size_t(kMaxLights)) out << " (the first " << kMaxLights << " are drawn)";
    out << "\n";
    for (const Node& node : scene.nodes) {
        if (node.light < 0) continue;
        const PunctualLight& l = scene.lights[std::size_t(node.light)];
        out << "  '" << l.name << "' " << lightTypeName(l.type) << " on node '" << node.name << "', colour "
            << fmt(l.color.r) << "," << fmt(l.color.g) << "," << fmt(l.color.b) << " x " << fmt(l.intensity)
            << (l.type == LightType::Directional ? " lx" : " cd");
        if (l.type != LightType::Directional)
            out << ", range " << (l.range > 0.0f ? fmt(l.range) : std::string("unbounded"));
        if (l.type == LightType::Spot)
            out << ", cone " << fmt(glm::degrees(l.innerConeAngle)) << " to " << fmt(glm::degrees(l.outerConeAngle))
                << " deg";
        out << "\n";
    }
    std::size_t channels = 0;
    for (const Animation& a : scene.animations) channels += a.channels.size();
    out << "animations: " << scene.animations.size() << " (" << channels << " channels, " << fmt(scene.duration())
        << " s at " << fmt(scene.fps) << " fps)\n";
    std::size_t morphing = 0, targets = 0, weightChannels = 0;
    for (const Mesh& m : scene.meshes) morphing += m.morphs(), targets += m.targets.size();
    for (const Animation& a : scene.animations)
        for (const AnimChannel& c : a.channels) weightChannels += c.path == AnimPath::Weights;
    if (morphing > 0)
        out << "morph targets: " << targets << " on " << morphing << (morphing == 1 ? " mesh" : " meshes")
            << ", weights animated by " << weightChannels << (weightChannels == 1 ? " channel" : " channels")
            << " (posed on the CPU; culling draws them whole)\n";
    std::size_t skinned = 0;
    for (const Instance& instance : scene.instances)
        skinned +=
            scene.nodes[std::size_t(instance.node)].skin >= 0 && scene.meshes[std::size_t(instance.mesh)].skinned();
    if (!scene.skins.empty()) {
        std::size_t joints = 0;
        for (const Skin& skin : scene.skins) joints += skin.joints.size();
        out << "skins: " << scene.skins.size() << " (" << joints << " joints), " << skinned
            << (skinned == 1 ? " instance" : " instances") << " skinned (posed on the CPU; culling draws them whole)\n";
    }
    const Bounds b = scene.bounds(0.0);
    if (b.empty()) out << "bounds: empty\n";
    else out << "bounds: min " << fmt(b.min.x) << "," << fmt(b.min.y) << "," << fmt(b.min.z) << " max " << fmt(b.max.x) << ","
             << fmt(b.max.y) << "," << fmt(b.max.z) << " (radius " << fmt(b.radius()) << ")\n";
    for (const Decompression& d : scene.decompressed)
        out << "compressed: " << d.method << ", " << d.items
            << (d.method == "EXT_meshopt_compression" ? (d.items == 1 ? " bufferView" : " bufferViews")
                                                      : (d.items == 1 ? " primitive" : " primitives"))
            << ", " << d.compressedBytes << " bytes decoded to " << d.decodedBytes << " in " << fmt(d.seconds * 1e3)
            << " ms\n";
    out << "not modelled: ";
    if (scene.unsupported.empty()) out << "none\n";
    else {
        std::string names;
        for (const std::string& name : scene.unsupported) names += (names.empty() ? "" : ", ") + name;
        out << names << "\n";
    }
    for (const std::string& warning : scene.warnings) out << "warning: " << warning << "\n";
    return out.str();
}

Result<StateCostsOutput> stateCostsReport(const Settings& settings) {
    Result<std::unique_ptr<Backend>> backend = openBackend(settings.backend, nullptr, settings.threads, settings.interp);
    if (!backend)
        return Error{std::string("backend ") + toString(settings.backend) + ": " + backend.error().message, backend.error().kind,
                     true};
    Result<StateCostReport> measured = measureStateCosts(**backend);
    if (!measured) return measured.error();
    std::ostringstream out;
    const StateCostReport& r = *measured;
    out << "state costs on " << r.backend << " (" << r.renderer << "), " << r.rounds << " rounds of " << r.draws
        << " draws\n";
    char line[160];
    std::snprintf(line, sizeof line, "  %-10s %10.3f us a draw with no change\n", "draw", r.drawUs);
    out << line;
    nlohmann::json costs = nlohmann::json::object();
    for (const StateCost& c : r.costs) {
        std::snprintf(line, sizeof line, "  %-10s %10.3f us a change (%.3f to %.3f)\n", c.kind.c_str(), c.us, c.minUs, c.maxUs);
        out << line;
        costs[c.kind] = {{"us", c.us}, {"min_us", c.minUs}, {"max_us", c.maxUs}};
    }
    std::snprintf(line, sizeof line,
                  "  texture 256x256: upload %.3f ms, first draw %.3f ms, resident draw %.3f ms\n"
                  "  new state combination: first draw %.3f ms, again %.3f ms\n",
                  r.textureUploadMs, r.textureFirstDrawMs, r.textureResidentDrawMs, r.newCombinationMs, r.seenCombinationMs);
    out << line;
    const nlohmann::json json = {
        {"backend", r.backend}, {"renderer", r.renderer}, {"rounds", r.rounds}, {"draws", r.draws}, {"draw_us", r.drawUs},
        {"costs", costs},
        {"texture", {{"upload_ms", r.textureUploadMs}, {"first_draw_ms", r.textureFirstDrawMs},
                     {"resident_draw_ms", r.textureResidentDrawMs}}},
        {"new_combination", {{"first_ms", r.newCombinationMs}, {"again_ms", r.seenCombinationMs}}}};
    return StateCostsOutput{out.str(), json.dump(2) + "\n"};
}


std::string stateCostsLine(Order order, const std::string& backendName, const StateCosts& costs) {
    std::string line = std::string("order ") + toString(order) + ": state costs on " + backendName + " (us):";
    for (std::size_t k = 0; k < costs.us.size(); ++k)
        line += (k ? ", " : " ") + costs.kinds[k] + " " + fmt(costs.us[k]);
    return line;
}

}  // namespace frugal
