// The backend interface: what to draw, independent of how an API draws it (bgfx RendererContextI,
// filament backend). Implemented by the GL backend (src/gl/) and the software reference
// (src/software/). Plans made by cull/ and reuse/ are executed through this interface only.
//
// Render target: colour RGBA8 (or RGBA32F for linear colour: createTarget) + depth (24-bit, or
// 32-bit float with reversed Z: DepthFormat, frugal/Image.h) + triangle id R32UI, same formats in
// every backend. Depth test "nearer passes" (GL_LESS for D24, GL_GREATER for D32F; or none:
// DepthMode), depth range [0,1], colour blended only by draws of AlphaMode::Blend (DrawParams; the
// blend the Khronos renderer sets: GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA for rgb, GL_ONE,
// GL_ONE_MINUS_SRC_ALPHA for alpha; ids are never blended). Draws are executed in call order, and
// within a draw call the ranges in the order given, the triangles of a range in index-buffer order:
// that is the documented order in which depth ties resolve (the first triangle drawn keeps the
// pixel).
#pragma once

#include <cassert>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Image.h>
#include <frugal/Scene.h>
#include <frugal/Stats.h>

#include "pipeline/Buffers.h"
#include "pipeline/Environment.h"

namespace frugal {

// A backend object's handle: its slot + 1, 0 for none (pipeline/Handles.h). Each kind of object has a
// type of its own, so a mesh's handle does not compile where a target's is expected.
template <class Kind>
struct Handle {
    std::uint32_t id = 0;
    constexpr Handle() = default;
    constexpr explicit Handle(std::uint32_t value) : id(value) {}
    friend constexpr bool operator==(Handle, Handle) = default;
};
using TargetHandle = Handle<struct TargetKind>;
using MeshHandle = Handle<struct MeshKind>;
using TextureHandle = Handle<struct TextureKind>;

// No handle: what a failed create or upload gives, of whichever kind (`target == kNoHandle`).
struct NoHandle {
    template <class Kind>
    constexpr operator Handle<Kind>() const {  // NOLINT: implicit by design
        return Handle<Kind>{};
    }
};
inline constexpr NoHandle kNoHandle{};
template <class Kind>
constexpr bool operator==(Handle<Kind> handle, NoHandle) {
    return handle.id == 0;
}

// A run of triangles of one mesh, in units of triangles of its (reordered) index buffer; of a mesh
// of segments or points (Mesh::topology), a run of those: "triangle" below means a primitive.
struct IndexRange {
    std::uint32_t firstTriangle = 0;
    std::uint32_t triangleCount = 0;
    bool operator==(const IndexRange&) const = default;
};

// The shading model, written once here and twice in code (shaders/mesh.frag and the software
// backend): glTF 2.0's metallic-roughness BRDF as the Khronos glTF Sample Renderer computes it, lit
// by one directional light and a uniform environment, in linear values.
//   base = material factor × vertex colour × texture(uv) (a mesh without colours and a draw without
//   texture leave their factor out: exactly 1, never interpolated); factors and vertex colours are
//   linear, an sRGB texture (Texture::srgb) is decoded to linear before it is filtered.
//   n = the interpolated world-space normal, normalised, negated on back faces (seen only when
//   double-sided); v = normalize(eye − p), p the interpolated world position; r = roughness,
//   alpha = r², m = metallic; c5(x) = (1 − x)⁵.
//   Environment (image-based light of a uniform radiance L, `environment`): with (A, B) the
//   split-sum GGX table at (n·v, r) (pipeline/Brdf.h: a fit to the Khronos renderer's table) and
//   its Fresnel  F(f0) = Fss + Fss·Ems·Favg / (1 − Favg·Ems),  with
//   Fss = (f0 + (max(1 − r, f0) − f0)·c5(n·v))·A + B,  Ems = 1 − (A + B),  Favg = f0 + (1 − f0)/21:
//     dielectric = L·base.rgb·(1 − F(0.04)) + L·F(0.04);   metal = L·F(base.rgb)
//   Light (direction l = toLight, intensity E = `light`, in the specification's units, where the
//   Lambert lobe is albedo/π), h = normalize(l + v), the dots clamped to [0, 1]:
//     D = alpha² / (π·f²), f = (n·h)²(alpha² − 1) + 1;
//     V = 0.5 / (n·l·√((n·v)²(1 − alpha²) + alpha²) + n·v·√((n·l)²(1 − alpha²) + alpha²))
//       (0 where the sum is 0);  S = E·n·l·V·D
//     dielectric = E·n·l·base.rgb/π·(1 − Fl(0.04)) + S·Fl(0.04);  metal = S·Fl(base.rgb),
//     Fl(f0) = f0 + (1 − f0)·c5(v·h)
//   Specular-glossiness (DrawParams::specularGlossiness): m = 0 (the metal terms are not computed),
//   the dielectric's 0.04 becomes f0 = specular × the map's rgb, per channel, in F and Fl above,
//   and r = 1 − glossiness × the map's alpha.
//   rgb = mix(dielectric, metal, m) of both, summed, + the material's emissive. An unlit material
//   (DrawParams::unlit, KHR_materials_unlit) has rgb = base.rgb. Alpha (DrawParams::alphaMode): a = 1
//   for Opaque; Mask discards the fragment (no colour, depth or id) where base.a < alphaCutoff and
//   writes a = 1 elsewhere; Blend writes a = base.a, blended as above.
// Tone mapping (FrameParams::tonemap), when asked for, maps rgb first, as the Khronos renderer's
// tonemapping.glsl does (mix written out as above, each matrix product summed from its first column):
//   PbrNeutral: x = min(r, min(g, b)); rgb −= x < 0.08 ? x − (6.25·x)·x : 0.04; p = max(r, max(g, b));
//     unless p < 0.76: q = 1 − d²/((p + d) − 0.76) with d = 1 − 0.76, rgb ·= q/p, then
//     rgb = mix(rgb, q, 1 − 1/(0.15·(p − q) + 1)).
//   Aces: c = I·rgb; c = (c·(c + 0.0245786) − 0.000090537) / (c·(0.983729·c + 0.432951) + 0.238081);
//     rgb = clamp(O·c, 0, 1), I and O the Khronos renderer's ACESInputMat and ACESOutputMat.
// The colour written is rgb^(1/2.2), the display encoding of the Khronos glTF Sample Renderer, and a
// unencoded; the 8-bit target clamps to [0,1] and rounds to nearest (a blended draw mixes these
// encoded bytes, as the Khronos renderer's canvas does). A float target (ColorFormat::Rgba32F)
// is written rgb itself, unclamped, and a blended draw's alpha clamped to [0, 1]; it blends in
// linear light. The clear colour (the background) is written as given, not encoded. With the default light a white rough dielectric
// facing the light and the viewer is about 1.0 of diffuse light (0.3 + 0.7) less the 4 % the
// surface reflects, plus that reflection.
// A scene's punctual light where a frame sees it (Scene::lights, placed by its node at the frame's
// time). Its term is the directional light's above with l and E per pixel, in mesh.frag's operations:
// a directional light's l = −direction and E = intensity; a point or spot light's pointToLight =
// position − p, l = normalize(pointToLight), d2 = dot(pointToLight, pointToLight), E = intensity ·
// (1/d2, or max(min(1 − q·q, 1), 0)/d2 with q = d2 / range² when it has a range); a spot light's E
// also × ((c − outerCos) / (innerCos − outerCos))² where c = dot(direction, −l) is between the
// cosines, × 0 at or beyond outerCos. The clear coat's lobe is summed over the lights the same way.
struct FrameLight {
    LightType type = LightType::Directional;
    glm::vec3 position{0.0f};                // world space (point, spot)
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // where it shines, world space, unit (directional, spot)
    glm::vec3 intensity{1.0f};               // colour × intensity
    float range = 0.0f;                      // 0 = unbounded
    float outerCos = 0.0f, innerCos = 1.0f;  // spot: the cones' cosines
    bool operator==(const FrameLight&) const = default;
};

struct Lighting {
    glm::vec3 toLight = glm::normalize(glm::vec3(0.35f, 0.8f, 0.5f));  // world space, unit
    float light = 0.7f * 3.14159265f;  // the directional light's intensity (white): E above
    float environment = 0.3f;          // the uniform environment's radiance (white): L above
    // false: the environment's specular term is left out: dielectric = L·base.rgb, metal = 0, and a
    // clear coat adds no L·k (its light's terms stay). Lambert and unlit shading have none anyway.
    bool environmentSpecular = true;
    // An environment map (Environment.h) lighting instead of the uniform environment: the diffuse
    // light L·base.rgb above becomes E(n)/π·base.rgb from its coefficients, and the specular L its
    // prefiltered level at the reflected view direction and roughness · 4 (a clear coat's, at the
    // coat's normal and roughness). Compared by identity: one loaded map, one frame's lighting.
    std::shared_ptr<const EnvironmentMap> map;
    // The scene's punctual lights, at most kMaxLights: when there are any, they light the frame
    // instead of the directional light above (the environment stays).
    std::vector<FrameLight> lights;
    bool operator==(const Lighting&) const = default;
};

// Where the camera of `view` (a rigid world-to-eye transform) is, in world space: the same float
// arithmetic in every backend, so that v above is the same.
inline glm::vec3 eyePosition(const glm::mat4& view) { return glm::vec3(glm::inverse(view)[3]); }

struct FrameParams {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    // The projection's depth convention (frugal/Image.h); the target drawn into must have this format.
    DepthFormat depthFormat = DepthFormat::D24;
    Lighting lighting;
    ToneMap tonemap = ToneMap::None;  // applied to rgb before its encoding (frugal/Image.h, below)
    ShadingModel shading = ShadingModel::Full;  // frugal/Image.h; Lambert: rgb = base.rgb·(L + Σ E·n·l/π) + emission
    bool writeIds = true;  // false: the id attachment is left as cleared (faster on llvmpipe)
    // Scene time of the frame: SceneRenderer poses morphing meshes at it (Scene::morphWeights).
    double time = 0.0;
};

// Which side of rgb = mix(dielectric, metal, m) a material needs: with a metallic factor of exactly
// 0 or 1 and nothing to vary it (no metallic-roughness map; not specular-glossiness, which has no
// metal side) one side's weight is 0, so the other alone is that sum (Dielectric, Metal) and the
// first side's terms are not computed: the same pixels for less work (mesh.frag's metalMix).
enum class MetalMix : std::uint8_t { Both, Dielectric, Metal };
inline MetalMix metalMixOf(float metallic, bool metallicRoughnessMap, bool specularGlossiness) {
    if (metallicRoughnessMap || specularGlossiness) return MetalMix::Both;
    return metallic == 0.0f ? MetalMix::Dielectric : metallic == 1.0f ? MetalMix::Metal : MetalMix::Both;
}

// How a draw uses the depth buffer.
//   Test: the z-buffer: a fragment passes when it is nearer than the stored depth (less for D24,
//         greater for D32F), and writes it.
//   Off:  no depth read and no depth write: every covered pixel takes the fragment, in draw order
//         (the painter's method; hidden-surface modes of paper 003, src/hsr/).
enum class DepthMode : std::uint8_t { Test, Off };

// Everything a draw needs besides the mesh's buffers.
struct DrawParams {
    MeshHandle mesh = kNoHandle;
    glm::mat4 model{1.0f};
    glm::vec4 baseColorFactor{1.0f};
    float metallic = 1.0f, roughness = 1.0f;  // the material's factors, each in [0, 1]
    bool unlit = false;                       // rgb = base.rgb (KHR_materials_unlit)
    glm::vec3 emissive{0.0f};                 // added to the lit rgb
    TextureHandle texture = kNoHandle;  // the base colour texture; kNoHandle = white
    // The other maps (Material), kNoHandle = none: metallic-roughness (blue × metallic, green ×
    // roughness), occlusion (red, at occlusionStrength) and emissive (rgb × emissive).
    TextureHandle metallicRoughnessTexture = kNoHandle, occlusionTexture = kNoHandle, emissiveTexture = kNoHandle;
    float occlusionStrength = 1.0f;
    // Tangent-space normals in the basis of the mesh's tangents (drawn without when it has none).
    TextureHandle normalTexture = kNoHandle;
    float normalScale = 1.0f;
    glm::mat3 uvTransform{1.0f};  // every texture is sampled at uvTransform · (u, v, 1), per vertex
    bool doubleSided = false;           // false: cull back faces (counter-clockwise is front)
    AlphaMode alphaMode = AlphaMode::Opaque;  // see the shading model above
    float alphaCutoff = 0.5f;                 // Mask's
    // KHR_materials_pbrSpecularGlossiness (Material): metallic, roughness and their map unread.
    bool specularGlossiness = false;
    glm::vec3 specular{1.0f};
    float glossiness = 1.0f;
    TextureHandle specularGlossinessTexture = kNoHandle;  // rgb × specular, alpha × glossiness
    // KHR_materials_clearcoat (Material): no coat at clearcoat 0.
    float clearcoat = 0.0f, clearcoatRoughness = 0.0f;
    TextureHandle clearcoatTexture = kNoHandle;           // red × clearcoat
    TextureHandle clearcoatRoughnessTexture = kNoHandle;  // green × clearcoatRoughness
    TextureHandle clearcoatNormalTexture = kNoHandle;     // read as normalTexture is, at clearcoatNormalScale
    float clearcoatNormalScale = 1.0f;
    std::uint32_t firstId = 1;          // id = firstId + mesh.triangleSource[t]
    DepthMode depth = DepthMode::Test;
};

// What differs between the instances of one batched draw (Backend::drawInstances); the material
// is the draw's.
struct InstanceParams {
    glm::mat4 model{1.0f};
    std::uint32_t firstId = 1;
};

// The contract uploadMesh checks in every backend (a mesh that breaks it gets kNoHandle): attribute
// arrays (tangents too) match the positions or are empty, indices come in threes (twos for segments,
// ones for points) and stay below the vertex count, triangleSource has one entry per primitive or is
// empty (then primitive t has source t). A mesh of segments or points without normals is drawn
// unlit: rgb = base.rgb + the emission (Mesh::topology).
bool isUploadable(const Mesh& mesh);

// How a backend draws one draw() of several index ranges: each range as a draw of its own, or, from
// `minRuns` ranges on whose average is below `maxAverageRun` triangles, all as one draw (0: never).
// What the occlusion pass counts when it weighs the draws it saves.
struct RangeGathering {
    std::uint64_t minRuns = 0, maxAverageRun = 0;
    std::uint64_t drawsOf(std::uint64_t runs, std::uint64_t triangles) const {
        return minRuns > 0 && runs >= minRuns && triangles / runs < maxAverageRun ? 1 : runs;
    }
    bool operator==(const RangeGathering&) const = default;
};

class Backend {
public:
    virtual ~Backend() = default;

    virtual std::string name() const = 0;      // "egl-surfaceless", "osmesa", "software", ...
    virtual std::string renderer() const = 0;  // GL_RENDERER / GL_VERSION, or a description

    // Whether it rasterizes by llvmpipe's rules (raster/Rasterizer.h): llvmpipe itself, or the
    // software backend. Plans that depend on which pixels a triangle covers (occlusion culling's
    // per-triangle tests) are exact only then.
    bool followsLlvmpipeRules() const {
        return name() == "software" || renderer().find("llvmpipe") != std::string::npos;
    }

    // How draw() draws many ranges (the GL backend gathers many short ones into one draw).
    virtual RangeGathering rangeGathering() const { return {}; }

    // Largest width or height createTarget accepts (GL_MAX_RENDERBUFFER_SIZE and GL_MAX_VIEWPORT_DIMS).
    virtual int maxTargetSize() const = 0;
    // Largest width or height uploadTexture accepts (GL_MAX_TEXTURE_SIZE).
    virtual int maxTextureSize() const = 0;
    // Whether createTarget can make targets of `format` (D32F needs glClipControl: GL 4.5 or
    // ARB_clip_control).
    virtual bool supportsDepthFormat(DepthFormat format) const = 0;
    // Most samples a target may have (GL_MAX_SAMPLES; the software backend's llvmpipe's 4).
    virtual int maxSamples() const = 0;
    // A target cleared to transparent black, the far depth of `format` and id 0. kNoHandle when width
    // or height is < 1 or > maxTargetSize(), the format is not supported, `samples` is < 1 or >
    // maxSamples(), or the allocation fails. With `samples` > 1 it is multisampled with at least that
    // many samples, as GL chooses (llvmpipe, and the software backend after it, has 4): colour,
    // depth and ids are kept per sample, copy() copies every sample, and readBack resolves: the
    // samples' mean colour, sample 0's depth and id (raster/Rasterizer.h, 6.).
    // `color` Rgba32F makes a float colour plane (frugal/Image.h, LinearImage): draws write the
    // linear colour there (after tone mapping, unencoded, unclamped), blend in float, and readBack
    // fills Buffers::linear and, from it, Buffers::rgba (encodeLinear).
    virtual TargetHandle createTarget(int width, int height, DepthFormat format = DepthFormat::D24, int samples = 1,
                                      ColorFormat color = ColorFormat::Rgba8) = 0;
    virtual void destroyTarget(TargetHandle target) = 0;

    virtual MeshHandle uploadMesh(const Mesh& mesh) = 0;
    virtual TextureHandle uploadTexture(const Texture& texture) = 0;
    // Frees what an upload made; draws already submitted with it are executed first. A handle that
    // is not (or no longer) a mesh / texture is ignored.
    virtual void releaseMesh(MeshHandle mesh) = 0;
    // New positions, normals and tangents for an uploaded mesh (a deforming mesh's pose, PosedVertices):
    // each array as long as the mesh's (normals and tangents only where the mesh has them; empty keeps
    // them), in place, so that later draws use them and draws already submitted keep the old ones.
    // False (nothing changed) for a handle that is no mesh or arrays of another length.
    virtual bool updateVertices(MeshHandle mesh, std::span<const glm::vec3> positions,
                                std::span<const glm::vec3> normals, std::span<const glm::vec4> tangents) = 0;
    virtual void releaseTexture(TextureHandle texture) = 0;

    // Starts drawing into `target` with the given camera and light; following draws use them.
    // frame.depthFormat must be the target's format.
    virtual void beginFrame(TargetHandle target, const FrameParams& frame) = 0;
    virtual void draw(const DrawParams& params, std::span<const IndexRange> ranges) = 0;
    // The same mesh, material, faces and depth mode (`params`) drawn once per instance, in instance
    // order, each with its own model matrix and first id (params' are not read): the same pixels
    // as one draw(params with the instance's values, {range}) per instance. The GL
    // backend issues one instanced draw; this default (the software backend's) calls draw().
    virtual void drawInstances(const DrawParams& params, std::span<const InstanceParams> instances, IndexRange range);

    // Clears a rectangle of the target: colour to `color`, depth to `depth` (window z, clamped to
    // [0, 1]), ids to 0. farDepth(format) is the far plane.
    virtual void clear(TargetHandle target, const Rect& rect, const glm::vec4& color, float depth) = 0;
    // Copies a rectangle (same position) from one target to another of the same size and depth format.
    virtual void copy(TargetHandle from, TargetHandle to, const Rect& rect, bool color,
                      bool depth, bool ids) = 0;
    // Which planes readBackInto reads besides the colour; one left out stays empty in Buffers.
    struct Planes {
        bool depth = true, ids = true;
    };
    // Reads the whole target back into `out`, in the memory its vectors already hold when they are
    // large enough (a frame loop that passes the same Buffers allocates, and faults in, nothing);
    // the colour always, depth and ids as `planes` says. Waits for the rendering to finish.
    virtual void readBackInto(TargetHandle target, Buffers& out, Planes planes) = 0;
    // Every plane into new buffers.
    Buffers readBack(TargetHandle target) {
        Buffers out;
        readBackInto(target, out, {});
        return out;
    }
    // Waits until all submitted work is done (for timing).
    virtual void finish() = 0;
    // Counted since the backend was made (StateChanges above).
    virtual StateChanges stateChanges() const = 0;
    // Lets another thread use the backend next: a GL backend releases its context from the calling
    // thread (a context is current on one thread at a time; the next call on any thread makes it
    // current there). Nothing for a backend without a context.
    virtual void releaseThread() {}
};

// "egl-surfaceless (llvmpipe (...); 4.5 (Core Profile) Mesa 22.3.6)": which backend runs, as
// progress lines name it.
inline std::string describe(const Backend& backend) { return backend.name() + " (" + backend.renderer() + ")"; }

// copy()'s contract as every backend checks it, on its own target records (width, height,
// depthFormat, samples, colorFormat): both targets exist (asserted), they are two, of one size, depth
// format, sample count and colour format (asserted); the region is `rect` clipped to them. Nothing
// when there is nothing to copy.
template <class Target>
std::optional<Rect> copyRegion(const Target* source, const Target* dest, bool sameTarget, const Rect& rect,
                               bool anyPlane) {
    assert(source != nullptr && dest != nullptr && "copy: no such target");
    if (source == nullptr || dest == nullptr || sameTarget) return std::nullopt;
    assert(source->width == dest->width && source->height == dest->height && "copy: targets differ in size");
    assert(source->depthFormat == dest->depthFormat && "copy: targets differ in depth format");
    assert(source->samples == dest->samples && "copy: targets differ in samples");
    assert(source->colorFormat == dest->colorFormat && "copy: targets differ in colour format");
    if (source->colorFormat != dest->colorFormat) return std::nullopt;
    const Rect r = clipRect(clipRect(rect, source->width, source->height), dest->width, dest->height);
    if (r.empty() || !anyPlane) return std::nullopt;
    return r;
}

}  // namespace frugal
