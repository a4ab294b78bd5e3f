// The GL backend's class and the records it keeps (internal to src/gl/; users go through
// gl/GlBackend.h and pipeline/Backend.h). Its members are defined by concern, each file opening with
// the contracts of its part:
//   GlBackend.cpp     construction, the choice of context, targets, clear, copy, read-back
//   GlStateCache.h    the cached GL state (GlStateCache.cpp)
//   GlResources.cpp   mesh and texture upload and release
//   GlPrograms.cpp    the program variants
//   GlDraw.cpp        beginFrame, draw, drawInstances, the id pass's expanded vertex buffers, and
//                     many short ranges gathered into one index buffer
#pragma once

#include <array>
#include <cassert>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "gl/GlApi.h"
#include "gl/GlContext.h"
#include "gl/GlStateCache.h"
#include "pipeline/Backend.h"
#include "pipeline/Handles.h"

namespace frugal::gl {

// Vertex attribute locations, as in shaders/mesh.vert.
// The tangent shares location 5 with the instanced forms' first attribute: a mesh with tangents is
// never drawn instanced (drawInstances draws it once an instance).
enum Attribute : GLuint { kPosition = 0, kNormal = 1, kColor = 2, kUv = 3, kId = 4, kTangent = 5 };

// One FBO with its renderbuffers (the top of GlBackend.cpp).
struct GlTarget : CachedFramebuffer {
    int width = 0, height = 0;
    int samples = 1;  // as GL made the renderbuffers
    GLuint color = 0, ids = 0, depth = 0;
    DepthFormat depthFormat = DepthFormat::D24;
    ColorFormat colorFormat = ColorFormat::Rgba8;  // Rgba32F: GL_RGBA32F, drawn by the linear variants
    // A multisampled target's single-sampled twin, which readBack resolves into.
    TargetHandle resolved = kNoHandle;
    // false: every id is known to be 0 (the top of GlBackend.cpp). True until the first clear, as
    // new renderbuffers hold undefined values.
    bool idsDirty = true;
};

// What a draw uses, as bits of a program variant's index (GlPrograms.cpp).
enum Variant : unsigned {
    kTextureBit = 1u,  // the base colour texture
    kColorsBit = 2u,
    kIdsBit = 4u,
    kInstancedBit = 8u,
    kUnlitBit = 16u,
    kMetallicRoughnessBit = 32u,  // the other maps (Material)
    kOcclusionBit = 64u,
    kEmissiveBit = 128u,
    kNormalMapBit = 256u,
    kAlphaMaskBit = 512u,               // AlphaMode::Mask: discard below the cutoff
    kAlphaBlendBit = 1024u,             // AlphaMode::Blend: alpha written as it is (else 1)
    kSpecularGlossinessBit = 2048u,     // KHR_materials_pbrSpecularGlossiness
    kSpecularGlossinessMapBit = 4096u,  // its map
    kClearcoatBit = 8192u,              // KHR_materials_clearcoat
    kClearcoatMapBit = 16384u,          // its maps
    kClearcoatRoughnessMapBit = 32768u,
    kClearcoatNormalMapBit = 65536u,
    kToneMapNeutralBit = 131072u,  // FrameParams::tonemap
    kToneMapAcesBit = 262144u,
    kLightsBit = 524288u,    // the scene's punctual lights (Lighting::lights) instead of the directional light
    kLambertBit = 1048576u,  // FrameParams::shading Lambert: the diffuse term alone
    kNoEnvironmentSpecularBit = 2097152u,  // Lighting::environmentSpecular false
    kEnvironmentMapBit = 4194304u,         // Lighting::map: the environment from its map
    kLinearBit = 8388608u,                 // a Rgba32F target: the linear colour, unencoded
    kDielectricBit = 16777216u,            // metallic exactly 0, no map: the metal terms left out
    kMetalBit = 33554432u,                 // metallic exactly 1, no map: the dielectric terms left out
    kBareBit = 67108864u,  // segments or points without normals: unlit, base colour + emission (Mesh::topology)
    kVariantCount = 134217728u
};
constexpr unsigned kMapBits = kTextureBit | kMetallicRoughnessBit | kOcclusionBit | kEmissiveBit | kNormalMapBit |
                              kSpecularGlossinessMapBit | kClearcoatMapBit | kClearcoatRoughnessMapBit |
                              kClearcoatNormalMapBit;
constexpr unsigned kClearcoatBits =
    kClearcoatBit | kClearcoatMapBit | kClearcoatRoughnessMapBit | kClearcoatNormalMapBit;

// One instance of a batched draw as the instanced variant reads it (attributes 5–15, mesh.vert):
// the same values the uniforms of a single draw would get. The model matrix goes as its first three
// rows (a glTF transform is affine), so that the 16 attributes GL guarantees are enough.
struct InstanceRecord {
    float mvp[16];
    float normalMatrix[9];
    float modelRows[12];
    std::uint32_t firstId;
};
static_assert(sizeof(InstanceRecord) == 38 * 4, "tightly packed: the attribute offsets (attachInstances) assume it");
enum InstanceAttribute : GLuint {
    kInstanceMvp = 5,
    kInstanceNormalMatrix = 9,
    kInstanceModelRows = 12,
    kInstanceFirstId = 15
};

// One variant of the mesh program, with its uniform locations (-1 where the variant has none)
// and the values last set in it (uniforms are per-program state).
struct GlProgram {
    GLuint name = 0;
    bool failed = false;  // did not compile; not tried again
    GLint mvp = -1, normalMatrix = -1, model = -1, firstId = -1, baseColorFactor = -1, metallicRoughness = -1;
    GLint eye = -1, toLight = -1, light = -1, environment = -1, uvTransform = -1, emissive = -1;
    GLint occlusionStrength = -1, normalScale = -1, alphaCutoff = -1, specularGlossiness = -1, clearcoat = -1;
    GLint lights = -1;  // vec4 u_lights[4 · kMaxLights + 1] (mesh.frag)
    GLint environmentSh = -1;  // vec3 u_environmentSh[9] (EnvironmentMap::sh)
    CachedUniform<glm::mat4> mvpValue, modelValue;
    CachedUniform<glm::mat3> normalMatrixValue, uvTransformValue;
    CachedUniform<glm::vec4> baseColorFactorValue, specularGlossinessValue;
    CachedUniform<glm::vec2> metallicRoughnessValue;
    CachedUniform<glm::vec3> clearcoatValue;  // factor, roughness, normal scale
    CachedUniform<glm::vec3> eyeValue, toLightValue, emissiveValue;
    CachedUniform<float> lightValue, environmentValue, occlusionStrengthValue, normalScaleValue, alphaCutoffValue;
    CachedUniform<std::uint32_t> firstIdValue;
    CachedUniform<std::array<glm::vec4, 4 * kMaxLights + 1>> lightsValue;
    CachedUniform<std::array<glm::vec3, 9>> environmentShValue;
};

// Byte offsets of the attribute sections in a mesh's vertex buffer (positions first, at 0);
// -1 = the mesh has no such attribute and the shader gets the constant current value.
struct VertexLayout {
    GLintptr normal = -1, color = -1, uv = -1, id = -1, tangent = -1;
    GLsizeiptr size = 0;
};

struct GlMesh {
    std::uint32_t triangles = 0;  // primitives: triangles, segments or points (Mesh::topology)
    GLenum mode = GL_TRIANGLES;   // GL_TRIANGLES, GL_LINES or GL_POINTS
    std::uint32_t corners = 3;    // vertices a primitive
    std::uint32_t vertices = 0;
    GLuint vao = 0, vbo = 0, ibo = 0;
    VertexLayout layout;
    std::vector<std::uint32_t> triangleSource;
    GLuint idVao = 0, idVbo = 0;  // the expanded id pass, built on first use
    VertexLayout idLayout;        // its sections
    bool vaoInstanced = false, idVaoInstanced = false;  // the instance attributes are attached
    std::vector<std::uint32_t> indices;  // read back on the first gathered draw
};

class GlBackend final : public Backend {
public:
    explicit GlBackend(std::unique_ptr<GlContext> context) : context_(std::move(context)) {}
    GlBackend(const GlBackend&) = delete;
    GlBackend& operator=(const GlBackend&) = delete;
    ~GlBackend() override;

    // Loads GL, checks the version, builds the full program variant (so that a shader that does not
    // compile is reported here) and sets the fixed state. "" or the reason.
    std::string initialise();

    std::string name() const override { return contextKindName(context_->kind()); }
    std::string renderer() const override { return renderer_; }
    int maxTargetSize() const override { return maxTargetSize_; }
    int maxSamples() const override { return maxSamples_; }
    int maxTextureSize() const override { return maxTextureSize_; }

    bool supportsDepthFormat(DepthFormat format) const override {
        return format == DepthFormat::D24 || gl_.ClipControl != nullptr;
    }
    TargetHandle createTarget(int width, int height, DepthFormat format, int samples, ColorFormat color) override;
    void destroyTarget(TargetHandle target) override;
    MeshHandle uploadMesh(const Mesh& mesh) override;
    TextureHandle uploadTexture(const Texture& texture) override;
    void releaseMesh(MeshHandle mesh) override;
    bool updateVertices(MeshHandle mesh, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                        std::span<const glm::vec4> tangents) override;
    void releaseTexture(TextureHandle texture) override;
    void beginFrame(TargetHandle target, const FrameParams& frame) override;
    void draw(const DrawParams& params, std::span<const IndexRange> ranges) override;
    void drawInstances(const DrawParams& params, std::span<const InstanceParams> instances, IndexRange range) override;
    void clear(TargetHandle target, const Rect& rect, const glm::vec4& color, float depth) override;
    void copy(TargetHandle from, TargetHandle to, const Rect& rect, bool color, bool depth, bool ids) override;
    void readBackInto(TargetHandle target, Buffers& out, Planes planes) override;
    void finish() override {
        activate();
        gl_.Finish();
    }
    StateChanges stateChanges() const override { return state_.changes(); }
    RangeGathering rangeGathering() const override;
    void releaseThread() override { releaseCurrentContext(context_.get()); }

private:
    // Makes our context current unless it is the frugal context this thread made current last
    // (two backends, e.g. EGL and OSMesa, may be used in turn on one thread).
    void activate() {
        if (currentContext() != context_.get()) {
            [[maybe_unused]] const bool ok = context_->makeCurrent();
            assert(ok && "GlBackend: could not make the context current");
        }
    }

    // A GL error here is a bug in the backend (the inputs are validated), except running out of
    // memory; debug builds say where and stop.
    void check([[maybe_unused]] const char* where) {
#ifndef NDEBUG
        for (int i = 0; i < 8; ++i) {
            const GLenum error = gl_.GetError();
            if (error == GL_NO_ERROR) return;
            std::fprintf(stderr, "frugal: %s: %s after %s\n", name().c_str(), glErrorName(error).c_str(), where);
            assert(error == GL_OUT_OF_MEMORY && "GL error in GlBackend");
        }
#endif
    }

    // --- targets (GlBackend.cpp) --------------------------------------------------------------
    void deleteTarget(GlTarget& t);
    // Blits the planes asked for of rectangle `r` from `source` into the same place of `dest`: what
    // copy() and resolve() do.
    void blit(GlTarget& source, GlTarget& dest, const Rect& r, bool color, bool depth, bool ids);
    // Resolves multisampled `from` into its single-sampled twin, which it returns: colour averaged,
    // depth and ids of sample 0 (Backend::createTarget).
    GlTarget& resolve(GlTarget& from, Planes planes);

    // --- meshes and textures (GlResources.cpp) ------------------------------------------------
    void deleteMesh(GlMesh& m);
    // Binds `vao` and points its attributes at the sections of `vbo` (and its indices at `ibo`,
    // unless 0).
    void setVertexLayout(GLuint vao, GLuint vbo, GLuint ibo, const VertexLayout& layout);

    // --- program variants (GlPrograms.cpp) ----------------------------------------------------
    // The variant for `variant` (bits of Variant), compiled on first use and bound; nullptr when it
    // does not compile (a bug in the shaders: the full variant compiled in initialise()).
    GlProgram* program(unsigned variant);
    // Compiles programs_[variant] and looks up its uniforms. "" or the reason.
    std::string compileVariant(unsigned variant);

    // --- drawing (GlDraw.cpp) -----------------------------------------------------------------
    // The map's specular levels into environmentTexture_ (made on first use), bound to kEnvironmentUnit.
    void uploadEnvironment(const EnvironmentMap& map);
    // What draw and drawInstances share: the variant for `params` (| extraBits) compiled and bound,
    // the target, viewport, faces, depth test, texture and lighting set. nullptr: nothing to draw.
    GlProgram* prepareDraw(const DrawParams& params, GlTarget& target, const GlMesh& mesh, unsigned extraBits);
    // Builds the expanded vertex buffer and vertex array of the id pass. False on a GL error.
    bool buildIdPass(GlMesh& mesh);
    // Reads `size` bytes of a buffer object back into `data` (nothing for size 0).
    void readBuffer(GLuint buffer, void* data, GLsizeiptr size);
    // Draws runs_ of `mesh` (`triangles` in all) from one streamed index buffer.
    void drawGathered(GlMesh& mesh, std::uint64_t triangles);
    // Attaches the instance buffer's attributes (divisor 1) to `vao`, once per vertex array.
    void attachInstances(GLuint vao, bool& attached);

    std::unique_ptr<GlContext> context_;
    GlApi gl_;
    GlStateCache state_{gl_};
    bool initialised_ = false;
    std::string renderer_;
    int maxTargetSize_ = 0, maxTextureSize_ = 0, maxSamples_ = 1;

    std::unordered_map<unsigned, GlProgram> programs_;  // by variant (at most kVariantCount), made on first use

    HandleTable<GlTarget, TargetHandle> targets_;
    HandleTable<GlMesh, MeshHandle> meshes_;
    HandleTable<GLuint, TextureHandle> textures_;

    TargetHandle frameTarget_ = kNoHandle;
    FrameParams frame_;
    glm::mat4 viewProjection_{1.0f};
    glm::vec3 eye_{0.0f};  // eyePosition(frame_.view)
    // frame_.lighting.lights as mesh.frag's u_lights reads them: four vec4 a light (position, type;
    // direction, range; intensity, outer cosine; inner cosine), then the count. Set by beginFrame.
    std::array<glm::vec4, 4 * kMaxLights + 1> lights_{};
    // The environment map uploaded last (Lighting::map) and its texture: the specular levels as the
    // mip levels of one RGBA32F texture, uploaded again only when a frame brings another map.
    std::shared_ptr<const EnvironmentMap> environment_;
    GLuint environmentTexture_ = 0;

    // The streamed index buffer of gathered draws, and its CPU side.
    GLuint streamIbo_ = 0;
    std::vector<std::uint32_t> gathered_;
    // drawInstances' per-instance records, streamed, and their CPU side.
    GLuint instanceVbo_ = 0;
    std::vector<InstanceRecord> instanceData_;

    // Scratch for the multi-draw argument arrays (no allocation per draw once grown).
    std::vector<IndexRange> runs_;
    std::vector<GLsizei> counts_;
    std::vector<GLint> firsts_;
    std::vector<const void*> offsets_;
};

}  // namespace frugal::gl
