// Scenes: the model every loader produces and every renderer reads, and loading one from a file or
// a built-in spec. A scene is plain data: build one in memory as well (meshes, materials, textures,
// nodes that place meshes, cameras, animations), then call buildInstances().
//
// Conventions (shared by every module):
// - Right-handed, column vectors, glm; units are whatever the file uses.
// - Texture coordinates follow glTF: (0,0) is the first texel of the first row of the image as stored
//   in the file (its top-left). The OBJ loader flips v to match.
// - A Mesh is one list of primitives with one material (a glTF primitive): triangles (most meshes),
//   line segments or points (Mesh::topology). Its triangles are kept in a vertex-cache-friendly
//   order (meshoptimizer); `triangleSource[t]` names the index that primitive t had in the file, so
//   ids stay stable whatever the order. Segments and points keep the file's order.
// - Global id = instance.firstId + triangleSource[t] (a triangle's, a segment's or a point's); 0 is
//   the background.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <frugal/Result.h>

namespace frugal {

// The value of enum E whose name in `names` (one per value, in the enum's order) is `name`; false
// when none is.
template <class E, std::size_t N>
bool enumNamed(const char* const (&names)[N], std::string_view name, E& value) {
    for (std::size_t i = 0; i < N; ++i)
        if (name == names[i]) {
            value = E(i);
            return true;
        }
    return false;
}

enum class Wrap : std::uint8_t { Repeat, ClampToEdge, MirroredRepeat };
enum class Filter : std::uint8_t { Nearest, Linear };
// How a minified texture uses its mipmaps (Texture::mipmaps): not at all (the base level only), the
// nearest level, or a blend of the two nearest levels (GL's *_MIPMAP_NEAREST and *_MIPMAP_LINEAR).
enum class MipFilter : std::uint8_t { None, Nearest, Linear };
// glTF's alphaMode: how the base colour's alpha is used (Material).
enum class AlphaMode : std::uint8_t { Opaque, Mask, Blend };

// Decoded RGBA8 image, rows in file order (first row = v 0).
struct Texture {
    std::string name;
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;
    Wrap wrapS = Wrap::Repeat;
    Wrap wrapT = Wrap::Repeat;
    // Sampling, as GL's sampler state: `filter` where the texture is magnified (a texel covers more
    // than a pixel), `minFilter` within a level where it is minified, and `mipmaps` between levels
    // there. Mipmaps are made once when the texture is uploaded, each level the average of the area
    // of the level above that its texels cover (in linear light for sRGB colour), the same levels in
    // the GL backend and the software reference. The glTF loader sets all three from the file's
    // sampler, and where the file leaves them undefined, as the Khronos glTF Sample Renderer does:
    // linear, linear, linear (trilinear).
    Filter filter = Filter::Linear;
    Filter minFilter = Filter::Linear;
    MipFilter mipmaps = MipFilter::None;
    // Whether the texels are sRGB-encoded colour (glTF's base colour and emissive textures), decoded
    // to linear before they are filtered; false: linear data. Alpha is always linear.
    bool srgb = true;
};

// glTF 2.0's metallic-roughness material; a default-constructed one is glTF's default material
// (white, metallic 1, roughness 1). Factors are linear. The loaders of formats without these terms
// (OBJ, the built-in scenes) give dielectrics: metallic 0 and a roughness of their own.
struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    int baseColorTexture = -1;  // index into Scene::textures, -1 = none
    bool doubleSided = false;   // false: back faces are culled (glTF); true: both sides lit
    float metallicFactor = 1.0f;   // 0: dielectric (diffuse + 4 % specular), 1: metal; [0, 1]
    float roughnessFactor = 1.0f;  // perceptual roughness, [0, 1]; GGX alpha = roughness²
    bool unlit = false;            // KHR_materials_unlit: the colour is the base colour, no light
    glm::vec3 emissiveFactor{0.0f};  // linear radiance added to the lit colour (× emissive strength)
    // Where the base colour texture is sampled: (u', v') = baseColorTransform · (u, v, 1)
    // (KHR_texture_transform; identity by default). The other maps are sampled there too.
    glm::mat3 baseColorTransform{1.0f};
    // The maps besides the base colour (-1 = none), each read as glTF reads it and each decoded as
    // its Texture says (Texture::srgb: the glTF loader sets it by use):
    int metallicRoughnessTexture = -1;  // blue × metallicFactor, green × roughnessFactor
    int occlusionTexture = -1;          // red: the environment's light × (1 + strength · (red − 1))
    float occlusionStrength = 1.0f;     // [0, 1]
    int emissiveTexture = -1;           // rgb × emissiveFactor
    // Tangent-space normals (rgb · 2 − 1, x and y × normalScale), in the basis of the mesh's
    // tangents (Mesh::tangents; generated when the mesh has none).
    int normalTexture = -1;
    float normalScale = 1.0f;
    // Alpha (the base colour's: factor × vertex colour × texture). Opaque: ignored, the colour
    // written has alpha 1. Mask: a fragment whose alpha is below alphaCutoff is discarded (no
    // colour, depth or id), the others written with alpha 1. Blend: drawn after every opaque and
    // masked surface of the frame, instances far to near by the view depth of their mesh's centroid
    // (the Khronos renderer's order), over what is drawn: rgb·a + dst·(1 − a), alpha a + dst·(1 − a).
    // Blended surfaces test and write depth and ids as the others do (the Khronos renderer and
    // three.js write depth for them too): the depth and id images hold the nearest surface drawn,
    // blended or not; only the colour shows what lies behind.
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;  // Mask only; finite, at least 0 (above 1 discards everything)
    // KHR_materials_pbrSpecularGlossiness, when `specularGlossiness` is set: the base colour (factor,
    // texture) is the diffuse colour, metallic and the metallic-roughness map are not read, the
    // dielectric's reflectance at normal incidence is specularFactor × the map's rgb (instead of
    // 0.04) and roughness is 1 − glossinessFactor × the map's alpha, as the Khronos renderer reads
    // the extension. The glTF loader reads the extension's diffuse and specular-glossiness textures as
    // linear, as the Khronos renderer does (the extension calls their rgb sRGB; Texture::srgb says).
    bool specularGlossiness = false;
    glm::vec3 specularFactor{1.0f};  // each in [0, 1]
    float glossinessFactor = 1.0f;   // [0, 1]
    int specularGlossinessTexture = -1;
    // KHR_materials_clearcoat, as the Khronos renderer draws it, when clearcoatFactor > 0: a
    // dielectric coat (reflectance 0.04 at normal incidence) over the material. With k =
    // clearcoatFactor × the map's red × Fresnel (Schlick, 0.04 to 1, at the coat normal · v), the
    // environment's light becomes env · (1 − k) + radiance · k before occlusion darkens it, each
    // light's becomes light · (1 − k) + the coat's GGX specular (no Fresnel) · k, and emission
    // · (1 − k). The coat's roughness is clearcoatRoughnessFactor × its map's green; its normal is
    // the coat normal map's in the tangent basis (read as normalTexture is, at
    // clearcoatNormalScale, not normalised after the basis, as the Khronos renderer reads it),
    // else the surface's normal without the base normal map. All three maps are linear.
    float clearcoatFactor = 0.0f;           // [0, 1]; 0: no coat
    int clearcoatTexture = -1;              // red × clearcoatFactor
    float clearcoatRoughnessFactor = 0.0f;  // [0, 1]
    int clearcoatRoughnessTexture = -1;     // green × clearcoatRoughnessFactor
    int clearcoatNormalTexture = -1;
    float clearcoatNormalScale = 1.0f;

    bool clearcoat() const { return clearcoatFactor > 0.0f; }
    // Is a tangent basis read (a normal map of the surface or of its coat)?
    bool tangentSpace() const { return normalTexture >= 0 || (clearcoat() && clearcoatNormalTexture >= 0); }
    bool hasTextures() const;  // does it sample any (kMaterialMaps)?

    // Every member equal (floats by value: a NaN is never equal, so it always counts as a change).
    bool operator==(const Material&) const = default;
};

// Every texture a material can sample, in one list (the order of DrawParams' maps and of the GL
// backend's texture units): what messages call it, and its member. `material.*map.texture`.
struct MaterialMap {
    const char* name;
    int Material::*texture;
};
inline constexpr MaterialMap kMaterialMaps[] = {
    {"texture", &Material::baseColorTexture},
    {"metallic-roughness texture", &Material::metallicRoughnessTexture},
    {"occlusion texture", &Material::occlusionTexture},
    {"emissive texture", &Material::emissiveTexture},
    {"normal texture", &Material::normalTexture},
    {"specular-glossiness texture", &Material::specularGlossinessTexture},
    {"clear-coat texture", &Material::clearcoatTexture},
    {"clear-coat roughness texture", &Material::clearcoatRoughnessTexture},
    {"clear-coat normal texture", &Material::clearcoatNormalTexture}};

inline bool Material::hasTextures() const {
    for (const MaterialMap& map : kMaterialMaps)
        if (this->*map.texture >= 0) return true;
    return false;
}

// A morph target (glTF's primitive.targets): displacements added to a mesh's vertices, times the
// target's weight. Each array empty or one value a vertex.
struct MorphTarget {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec3> tangents;  // xyz of the tangent (its w, the handedness, is not displaced)
};

// What a mesh's indices make: triangles (3 indices each), line segments (2) or points (1). The glTF
// loader turns glTF's seven modes into these three lists: strips and fans into triangles, LINE_STRIP
// and LINE_LOOP into segments (a loop's last one closing it), numbered as glTF counts them.
enum class Topology : std::uint8_t { Triangles, Lines, Points };
inline constexpr const char* kTopologyNames[] = {"triangles", "lines", "points"};
inline const char* topologyName(Topology topology) { return kTopologyNames[std::size_t(topology)]; }
// The topology named `name`; false when there is none.
inline bool topologyNamed(std::string_view name, Topology& topology) {
    return enumNamed(kTopologyNames, name, topology);
}
inline constexpr std::size_t verticesPerPrimitive(Topology topology) {
    return topology == Topology::Triangles ? 3 : topology == Topology::Lines ? 2 : 1;
}

struct Mesh {
    std::string name;
    // Triangles are shaded as Material says. Segments and points are drawn one pixel wide (GL's
    // line width and point size 1), lit as triangles are where the mesh has normals (no normal map
    // without tangents, no back face), and without normals given the base colour plus the emission,
    // unlit: how the Khronos glTF Sample Renderer draws glTF's POINTS and LINES.
    Topology topology = Topology::Triangles;
    std::vector<glm::vec3> positions;
    // Triangles: always filled (computed when the file has none). Segments and points: the file's,
    // or empty (unlit, above).
    std::vector<glm::vec3> normals;
    std::vector<glm::vec4> colors;              // empty = white
    std::vector<glm::vec2> uvs;                 // empty = no texture coordinates
    // glTF's TANGENT: xyz the direction of increasing u, w = ±1 the handedness (the bitangent is
    // cross(normal, xyz) · w, toward decreasing v: "up" in the image). Empty = none: a mesh whose
    // material reads a tangent basis (Material::tangentSpace) gets generated ones when it is
    // uploaded (generateTangents).
    std::vector<glm::vec4> tangents;
    std::vector<std::uint32_t> indices;         // verticesPerPrimitive(topology) a primitive; counter-clockwise = front
    std::vector<std::uint32_t> triangleSource;  // per primitive: its index in the file (ids)
    int material = -1;                          // -1 = default material (white, single-sided)
    // Morph targets and their default weights (glTF's mesh.weights; one per target, 0 where the file
    // gives none). A drawn vertex is position + Σ weightᵢ · targetᵢ.position, its normal the same sum
    // normalised, its tangent's xyz likewise (posedMesh): weights come from the node, else these, and
    // an animation's "weights" channel replaces them (Scene::morphWeights).
    std::vector<MorphTarget> targets;
    std::vector<float> weights;
    // Skinning (glTF's JOINTS_n and WEIGHTS_n; up to two sets): per vertex four joints, indices
    // into Skin::joints of the skin of the node that draws the mesh, and their weights, used as
    // given (glTF says they sum to 1; frugal does not renormalise, nor does the Khronos renderer).
    // Empty: not skinned. A node without a skin draws the mesh unskinned.
    struct Influences {
        std::vector<glm::uvec4> joints;
        std::vector<glm::vec4> weights;
    };
    std::vector<Influences> influences;

    // Triangles, segments or points, as topology says; triangleCount() is 0 but for triangles.
    std::size_t primitiveCount() const { return indices.size() / verticesPerPrimitive(topology); }
    std::size_t triangleCount() const { return topology == Topology::Triangles ? indices.size() / 3 : 0; }
    bool triangles() const { return topology == Topology::Triangles; }
    bool morphs() const { return !targets.empty(); }
    bool skinned() const { return !influences.empty(); }
};

// KHR_lights_punctual's kinds of light, and their names there ("directional", "point", "spot"): what
// the loader reads, Python's add_light takes and frugal info prints.
enum class LightType : std::uint8_t { Directional, Point, Spot };
inline constexpr const char* kLightTypeNames[] = {"directional", "point", "spot"};
inline const char* lightTypeName(LightType type) { return kLightTypeNames[std::size_t(type)]; }
// The type named `name`; false when there is none.
inline bool lightTypeNamed(std::string_view name, LightType& type) { return enumNamed(kLightTypeNames, name, type); }

// A punctual light (KHR_lights_punctual), placed by the nodes that refer to it (Node::light): at the
// node's origin, shining down the node's −Z (directional and spot lights). In the extension's units:
// a directional light's intensity in lux (lm/m²), a point or spot light's in candela (lm/sr), with
// the Lambert lobe albedo/π (pipeline/Backend.h). A scene with lights is lit by them and the
// environment; one without gets the default directional light.
struct PunctualLight {
    std::string name;
    LightType type = LightType::Point;
    glm::vec3 color{1.0f};   // linear, each at least 0
    float intensity = 1.0f;  // finite, at least 0
    // Point and spot: 0 = unbounded (the inverse square alone), else where the light ends (> 0):
    // the inverse square times max(min(1 − (d / range)⁴, 1), 0), as the Khronos renderer fades it.
    float range = 0.0f;
    // Spot: full intensity within innerConeAngle of the axis, none beyond outerConeAngle, between
    // them ((cos θ − cos outer) / (cos inner − cos outer))²; radians, 0 ≤ inner < outer ≤ π/2.
    float innerConeAngle = 0.0f;
    float outerConeAngle = 0.785398163f;
};

// How many punctual lights a frame draws: the first ones, in node order (a file with more is told
// so: Scene::unsupported).
inline constexpr int kMaxLights = 8;

struct Node {
    std::string name;
    int parent = -1;
    std::vector<int> children;
    // Local transform: matrix when `hasMatrix`, else T * R * S (glTF order).
    bool hasMatrix = false;
    glm::mat4 matrix{1.0f};
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
    glm::vec3 scale{1.0f};
    std::vector<int> meshes;  // indices into Scene::meshes (a glTF mesh's primitives)
    int camera = -1;
    int light = -1;  // index into Scene::lights
    // glTF's node.weights: the morph weights of the node's meshes (empty: the meshes' own).
    std::vector<float> weights;
    int skin = -1;  // index into Scene::skins: the node's skinned meshes follow its joints
};

// A glTF skin: the joint nodes and their inverse bind matrices (identity where the file has none).
// A vertex of a mesh drawn by node N with this skin is, in N's frame, Σ weightᵢ · Jᵢ · vertex with
// Jᵢ = inverse(world(N)) · world(jointᵢ) · inverseBindᵢ (glTF's skinning, as the Khronos renderer
// computes it: N's own transform then places it).
struct Skin {
    std::string name;
    std::vector<int> joints;
    std::vector<glm::mat4> inverseBindMatrices;  // one a joint
};

// One drawn mesh: a (node, mesh) pair. Instances are numbered in a stable order (node order, then
// the node's primitive order); that order is also the draw order.
struct Instance {
    int node = -1;
    int mesh = -1;
    std::uint32_t firstId = 1;  // id of the mesh's source primitive 0 in this instance
};

struct SceneCamera {
    std::string name;
    int node = -1;  // camera looks down the node's -Z, +Y up (glTF)
    bool perspective = true;
    float yfov = 0.8f;    // radians
    float aspect = 0.0f;  // 0 = take the viewport's
    float znear = 0.01f;
    float zfar = 0.0f;               // 0 = infinite (perspective only)
    float xmag = 1.0f, ymag = 1.0f;  // orthographic half extents

    // The aspect ratio (width / height) the file gives: aspectRatio, or xmag / ymag; 0 = none.
    float fileAspect() const {
        if (perspective) return aspect;
        return ymag != 0.0f ? xmag / ymag : 0.0f;
    }
};

enum class AnimPath : std::uint8_t { Translation, Rotation, Scale, Weights };
enum class Interp : std::uint8_t { Step, Linear, CubicSpline };

struct AnimChannel {
    int node = -1;
    AnimPath path = AnimPath::Translation;
    Interp interpolation = Interp::Linear;
    std::vector<float> times;       // strictly increasing, finite
    std::vector<glm::vec4> values;  // xyz (T, S) or xyzw quaternion (R); ×3 for CubicSpline (in, value, out)
    // Weights: the node's morph weights, `weightCount` a key (×3 for CubicSpline, in, value, out
    // as above); `values` is empty.
    std::vector<float> weights;
    int weightCount = 0;
};

struct Animation {
    std::string name;
    std::vector<AnimChannel> channels;
};

struct Bounds {
    glm::vec3 min{1e30f};
    glm::vec3 max{-1e30f};
    bool empty() const { return min.x > max.x; }
    void add(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    glm::vec3 center() const { return (min + max) * 0.5f; }
    float radius() const { return empty() ? 0.0f : glm::length(max - min) * 0.5f; }
};

// Compressed geometry a loader decoded, one entry a method (KHR_draco_mesh_compression: primitives;
// EXT_meshopt_compression: bufferViews): how many, the bytes read and written, and the time taken.
struct Decompression {
    std::string method;
    std::size_t items = 0;
    std::size_t compressedBytes = 0, decodedBytes = 0;
    double seconds = 0.0;
};

struct Scene {
    std::string source;  // file path or builtin name
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Node> nodes;
    std::vector<int> roots;
    std::vector<Instance> instances;
    std::vector<SceneCamera> cameras;
    std::vector<PunctualLight> lights;  // placed by Node::light
    std::vector<Animation> animations;
    std::vector<Skin> skins;
    // Features in the file that frugal does not model, by name ("skins", "morph targets",
    // "KHR_materials_clearcoat", ...). Reported by `frugal info` and as a warning on render.
    std::vector<std::string> unsupported;
    // What the loader decompressed (empty for an uncompressed file). Reported by `frugal info`.
    std::vector<Decompression> decompressed;
    // Non-fatal problems found while loading (dropped triangles, ...), one line each.
    std::vector<std::string> warnings;
    // Frames per second the scene's animation is meant to be sampled at (builtins set it).
    double fps = 30.0;
    // A world-space box that holds every instance's triangles at every time, animations included:
    // conservative, not tight, where something moves (a part that rotates counts as the ball it can
    // sweep; computeEnvelope). Set by buildInstances(); empty when nothing is drawn. Depth ranges
    // are fitted to it (pipeline/Camera.h), so a still camera keeps one projection while parts move.
    Bounds envelope;

    // Rebuilds `instances` (and their ids) from the node hierarchy, and `envelope`. Loaders call it
    // last, and so must anything that changes nodes, meshes or animations afterwards.
    void buildInstances();
    std::size_t triangleCount() const;   // over instances
    std::size_t primitiveCount() const;  // over instances: triangles, segments and points
    double duration() const;             // last key time of any animation, 0 if static
    // World matrix of every node at `time` seconds (animations sampled, hierarchy applied).
    std::vector<glm::mat4> worldTransforms(double time) const;
    // Morph weights of every node at `time` (empty for a node whose meshes have no targets): its
    // "weights" channel sampled, else the node's own, else its first morphing mesh's.
    std::vector<std::vector<float>> morphWeights(double time) const;
    // Does instance `instance` change shape (morph targets, or a skinned mesh drawn by a node with a
    // skin)? Such an instance is posed per frame (posedMesh) and drawn whole by every culling
    // method; deforms() asks it of every instance.
    bool deforms(const Instance& instance) const;
    bool deforms() const;
    // The joint matrices J of instance `instance` (deforms: skinned) under node matrices `world`;
    // empty when it is not skinned.
    std::vector<glm::mat4> jointMatrices(const Instance& instance, const std::vector<glm::mat4>& world) const;
    Bounds bounds(double time) const;
    // The envelope as defined above, computed from the meshes, nodes and animations.
    Bounds computeEnvelope() const;

    // Building a scene in memory, as the loaders build one from a file. Each checks what it is
    // given and returns the new element's index, or one line naming the value (BadInput):
    //   "mesh: index 120 (triangle 7) is past the 100 vertices"
    //   "mesh: position 17 is (nan, 0, 1), not finite"
    //   "texture: 12288 bytes for 64x64 RGBA (16384 expected)"
    // A texture: RGBA8, rows in file order (Texture). A material: its texture (-1 = none) must
    // exist, its factors be finite, emissive at least 0, metallic and roughness in [0, 1], the alpha
    // cutoff finite and at least 0. A mesh:
    // indices 3 a triangle, each below the vertex count; normals, colours and uvs empty or one a
    // vertex; every value finite; material -1 (the default) or one that exists; each morph target's
    // displacements empty or one a vertex, its weights empty (all 0) or one a target. It
    // is finished as the loaders finish theirs (triangleSource filled, missing normals computed,
    // and with `optimizeOrder` triangles reordered for the vertex cache, ids kept), so a mesh
    // added here draws exactly as the same mesh read from a glTF file.
    Result<int> addTexture(Texture texture);
    Result<int> addMaterial(Material material);
    Result<int> addMesh(Mesh mesh, bool optimizeOrder = true);
    // An instance of `mesh`: a new root node with `transform` (a finite matrix) as its local
    // matrix. Returns the node's index, which setTransform and Renderer::setTransform take.
    // Instances and ids are numbered by buildInstances(): call it once the scene is built.
    Result<int> addInstance(int mesh, const glm::mat4& transform, std::string name = {});
    // A punctual light placed by a new root node with `transform` (a finite matrix) as its local
    // matrix: at its origin, shining down its −Z. The light must be one a glTF file may hold: its
    // type one of LightType's, colour and intensity finite and at least 0, range finite and at least
    // 0, a spot's cone angles 0 ≤ inner < outer ≤ π/2. Returns the node's index (setTransform moves
    // it); the first kMaxLights lit nodes light a frame.
    Result<int> addLight(PunctualLight light, const glm::mat4& transform, std::string name = {});
    // Node `node`'s local transform becomes `transform` (a finite matrix), at every time.
    Result<bool> setTransform(int node, const glm::mat4& transform);
};

// Samples one channel at `time` (clamped to its key range). Rotations are slerped (Linear) or
// Hermite-interpolated and normalised (CubicSpline).
glm::vec4 sampleChannel(const AnimChannel& channel, double time);

glm::mat4 localMatrix(const Node& node);

// `weights` of a Weights channel at `time`, `channel.weightCount` of them, sampled as sampleChannel
// samples the other paths (step, linear, or the cubic Hermite spline).
std::vector<float> sampleWeights(const AnimChannel& channel, double time);

// `mesh` posed by morph weights `weights` (one per target; missing ones count 0): positions,
// normals (normalised; a zero sum keeps the base normal) and tangents displaced, in float, the
// targets summed in order; then, with `joints` (Scene::jointMatrices), skinned: each position
// Σ weight · J · position over the influences in order, each normal Σ weight · J⁻ᵀ · normal
// normalised, each tangent's xyz Σ weight · J · xyz. What both backends draw, so they draw the
// same vertices.
Mesh posedMesh(const Mesh& mesh, const std::vector<float>& weights, const std::vector<glm::mat4>& joints = {});

// The arrays a pose changes, as posedMesh computes them (the same floats), into `out` (its vectors
// reused from call to call): positions always; normals and tangents when `frames` (else left
// empty). What a renderer uploads each frame a mesh deforms, without copying the rest of the mesh.
struct PosedVertices {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec4> tangents;
};
void poseVertices(const Mesh& mesh, const std::vector<float>& weights, const std::vector<glm::mat4>& joints,
                  PosedVertices& out, bool frames = true);

struct LoadOptions {
    bool optimizeOrder = true;   // reorder triangles for the vertex cache (meshoptimizer)
    bool objDoubleSided = true;  // OBJ has no culling flag: drawn double-sided unless told otherwise
};

// A scene from `spec`: a .gltf/.glb (glTF 2.0) or .obj file, or a built-in procedural scene
// "builtin:NAME?key=value&..." (builtinScenes). Errors, one line naming the file: a file that does
// not exist or cannot be read, a format frugal does not read, anything the file holds that cannot be
// drawn as given ("bunny.obj: line 12: 'nan' in a v line is not finite"). Features that are not
// modelled (skins, morph targets, ...) load, are listed in Scene::unsupported and drawn without.
Result<Scene> loadScene(const std::string& spec, const LoadOptions& options = {});

// Scene time of frame `frame` (0-based) at `fps` frames per second: frame / fps.
double frameTime(int frame, double fps);

// Names and one-line descriptions of the built-in scenes, with their parameters.
std::vector<std::pair<std::string, std::string>> builtinScenes();

}  // namespace frugal
