// The OpenGL backend: render/Backend.h on a GL 3.3 core context, all GL through GlApi.
//
// Targets: one FBO each with three renderbuffers (renderbuffers, not textures: a target is only
// drawn, cleared, blitted and read, never sampled): RGBA8 colour on attachment 0, R32UI triangle ids
// on attachment 1, DEPTH_COMPONENT24 or DEPTH_COMPONENT32F depth. A new target is cleared to
// transparent black, far depth and id 0, so its contents are defined in both backends.
//
// Depth formats (frugal/Image.h): a D24 target is drawn with GL's default clip space and GL_LESS; a
// D32F target with glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE) and GL_GREATER (reversed Z). Both
// are context state, set when a draw goes to a target of the other format (cached, so a sequence in
// one format sets them once). D32F needs glClipControl (GL 4.5 or ARB_clip_control): without it
// supportsDepthFormat says no and createTarget refuses. Its read-back (GL_FLOAT) is the stored float.
//
// D24 read-back: glReadPixels(GL_DEPTH_COMPONENT, GL_UNSIGNED_INT) returns the stored 24-bit
// value D as a 32-bit normalised integer, D·(2³²−1)/(2²⁴−1) = 256·D + D·255/(2²⁴−1), which is
// 256·D plus at most 255, so >> 8 gives D back. Measured on llvmpipe (DepthReadBackIsTheStored24-
// BitValue in tests/gl/GlBackendGLTest.cpp): clear depth 1.0 reads 0xFFFFFF, 0.0 reads 0, and 0.5
// reads 0x800000: 0.5·0xFFFFFF = 8388607.5 is rounded up, not truncated to 0x7FFFFF.
//
// Vertex arithmetic (the software reference repeats it exactly, in float, with glm):
//   u_mvp = (projection * view) * model       (projection * view computed once per frame)
//   u_normalMatrix = transpose(inverse(mat3(model)))
//   gl_Position = u_mvp * vec4(position, 1)
//
// Meshes: uploadMesh refuses (kNoHandle) attribute arrays that do not match the positions, index
// counts not a multiple of 3, indices past the last vertex, and a triangleSource of the wrong
// length. What a mesh may leave out (the software backend uses the same defaults): normals → (0,0,1),
// colours → white, uvs → (0,0), triangleSource → t for triangle t. id = firstId + source, added in
// the vertex stage in 32-bit unsigned arithmetic.
//
// Programs: one variant of shaders/mesh.vert + mesh.frag per combination of what a draw uses — a
// texture, vertex colours, ids — compiled on first use (at most 8, each also in an instanced form
// for drawInstances: 16 in all). A variant leaves out what the draw does not use instead of feeding
// it white (a 1×1 white texture, a white colour varying, an unused flat id varying), because each of
// those costs llvmpipe time per frame (docs/gl/README.md). The white texel is 1.0 exactly, so
// leaving it out changes no bit. The interpolated white colour was not always 1.0: llvmpipe
// interpolates a varying as (a·(1/w))·w, which for a = 1 is p·(1/p), 1 − 2⁻²⁴ for about 15 % of
// floats p; so "no vertex colours" is now exactly white, and a few pixels changed by one step
// against the program that fed white (docs/gl/README.md).
// Uniform values are per-program state in GL, so each variant keeps its own uniform cache.
//
// Triangle ids: reading gl_PrimitiveID in the fragment stage is slower on llvmpipe than a flat
// vertex attribute (docs/gl/README.md), so a frame that writes ids draws each mesh unindexed from an
// "expanded" vertex buffer: 3 vertices per triangle, in the mesh's triangle order, each carrying the
// flat attribute triangleSource[t]. It is built on the first draw of the mesh with ids, from the
// mesh's own GL buffers (read back once, so no CPU copy of every mesh is kept for a pass that may
// never run). Ranges become glMultiDrawArrays over [3·first, 3·count). Without ids the mesh is drawn
// indexed (glMultiDrawElements) into colour attachment 0 only, and the id attachment keeps what it
// holds. Both paths run the same arithmetic on the same vertex values, so colour and depth are
// identical.
//
// Many short ranges (a culled plan: a thousand runs or more, of a few tens of triangles each) are
// gathered into one index buffer streamed for the draw (glBufferData, GL_STREAM_DRAW) and drawn with
// one glDrawElements: the same triangles in the same order, so the same pixels. llvmpipe runs each
// range of a glMultiDrawElements as a draw of its own, and one index buffer draws a culled plan's
// ranges faster (docs/gl/README.md); kGatherMinRuns and kGatherMaxAverageRun say when a draw is
// gathered. The mesh's indices are read back from its buffer once, on the first gathered draw (no
// CPU copy is kept for meshes never culled).
//
// Clears and the id attachment: llvmpipe flushes its scene when the draw-buffer set changes, so a
// clear with draw buffers {colour, ids} followed by draws with {colour} became a full pass of its
// own (docs/gl/README.md). Each target therefore records whether its ids may be non-zero (a draw
// with ids or a copy of such ids into it; a clear of the whole target makes them zero again). While
// they are known to be zero a clear leaves the id attachment alone and uses the draw-buffer set
// already bound, which is the one the next draws of a repeated frame use. The contract of
// Backend::clear (ids to 0) holds either way.
//
// GL state is cached (program, VAO, framebuffers, draw/read buffers per FBO, culling, scissor,
// viewport, texture, uniforms per program) so a call that would not change anything is not made:
// on llvmpipe each such call has a cost per draw, a program switch the largest (docs/gl/README.md;
// `frugal info --state-costs` measures the kinds on the backend that runs).
#include "gl/GlBackend.h"

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <utility>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl/GlApi.h"
#include "gl/Shaders.h"
#include "render/Handles.h"
#include "render/IndexRanges.h"

namespace frugal {

Result<BackendChoice> parseBackendChoice(const std::string& text) {
    if (text == "auto") return BackendChoice::Auto;
    if (text == "egl") return BackendChoice::Egl;
    if (text == "egl-device") return BackendChoice::EglDevice;
    if (text == "egl-surfaceless") return BackendChoice::EglSurfaceless;
    if (text == "osmesa") return BackendChoice::OsMesa;
    return Error{"unknown GL backend '" + text + "' (expected auto, egl, egl-device, egl-surfaceless or osmesa)"};
}

namespace {

// Vertex attribute locations, as in shaders/mesh.vert.
enum Attribute : GLuint { kPosition = 0, kNormal = 1, kColor = 2, kUv = 3, kId = 4 };

// Which colour attachments an FBO draws into; glDrawBuffers is per-FBO state.
enum class DrawSet : std::uint8_t { Unknown, Color, ColorAndIds, Ids };

struct GlTarget {
    int width = 0, height = 0;
    GLuint fbo = 0, color = 0, ids = 0, depth = 0;
    DepthFormat depthFormat = DepthFormat::D24;
    DrawSet drawSet = DrawSet::Unknown;
    GLenum readBuffer = GL_NONE;  // GL_NONE = not known
    // false: every id is known to be 0 (see the top of the file). True until the first clear, as
    // new renderbuffers hold undefined values.
    bool idsDirty = true;
};

// What a draw uses, as bits of a program variant's index (≤ 16 variants).
enum Variant : unsigned { kTextureBit = 1u, kColorsBit = 2u, kIdsBit = 4u, kInstancedBit = 8u, kVariantCount = 16u };

// One instance of a batched draw as the instanced variant reads it (attributes 5–13, mesh.vert):
// the same values the uniforms of a single draw would get.
struct InstanceRecord {
    float mvp[16];
    float normalMatrix[9];
    float baseColorFactor[4];
    std::uint32_t firstId;
};
static_assert(sizeof(InstanceRecord) == 30 * 4, "tightly packed: the attribute offsets below assume it");
enum InstanceAttribute : GLuint { kInstanceMvp = 5, kInstanceNormalMatrix = 9, kInstanceColor = 12, kInstanceFirstId = 13 };

// A uniform's value as last set in one program; compared bit for bit.
template <class T>
struct CachedUniform {
    T value{};
    bool valid = false;
    // True when `v` must be sent (differs from the value set, or none was); it is then recorded.
    bool update(const T& v) {
        if (valid && std::memcmp(&value, &v, sizeof(T)) == 0) return false;
        value = v;
        valid = true;
        return true;
    }
};

// One variant of the mesh program, with its uniform locations (-1 where the variant has none)
// and the values last set in it (uniforms are per-program state).
struct GlProgram {
    GLuint name = 0;
    bool failed = false;  // did not compile; not tried again
    GLint mvp = -1, normalMatrix = -1, firstId = -1, baseColorFactor = -1, toLight = -1, ambient = -1, diffuse = -1;
    CachedUniform<glm::mat4> mvpValue;
    CachedUniform<glm::mat3> normalMatrixValue;
    CachedUniform<glm::vec4> baseColorFactorValue;
    CachedUniform<glm::vec3> toLightValue;
    CachedUniform<float> ambientValue, diffuseValue;
    CachedUniform<std::uint32_t> firstIdValue;
};

// Byte offsets of the attribute sections in a mesh's vertex buffer (positions first, at 0);
// -1 = the mesh has no such attribute and the shader gets the constant current value.
struct VertexLayout {
    GLintptr normal = -1, color = -1, uv = -1, id = -1;
    GLsizeiptr size = 0;
};

struct GlMesh {
    std::uint32_t triangles = 0;
    std::uint32_t vertices = 0;
    GLuint vao = 0, vbo = 0, ibo = 0;
    VertexLayout layout;
    std::vector<std::uint32_t> triangleSource;
    GLuint idVao = 0, idVbo = 0;  // the expanded id pass, built on first use
    bool vaoInstanced = false, idVaoInstanced = false;  // the instance attributes are attached
    std::vector<std::uint32_t> indices;  // read back on the first gathered draw
};

// A draw's ranges are gathered into one streamed index buffer when there are at least this many and
// they are this short on average (triangles); otherwise glMultiDrawElements takes them as they are.
constexpr std::size_t kGatherMinRuns = 64;
constexpr std::size_t kGatherMaxAverageRun = 256;

GLint wrapMode(Wrap wrap) {
    switch (wrap) {
        case Wrap::Repeat:
            return GL_REPEAT;
        case Wrap::ClampToEdge:
            return GL_CLAMP_TO_EDGE;
        case Wrap::MirroredRepeat:
            return GL_MIRRORED_REPEAT;
    }
    return GL_REPEAT;
}

class GlBackend final : public Backend {
public:
    explicit GlBackend(std::unique_ptr<GlContext> context) : context_(std::move(context)) {}
    GlBackend(const GlBackend&) = delete;
    GlBackend& operator=(const GlBackend&) = delete;

    ~GlBackend() override {
        if (!initialised_) return;
        activate();
        targets_.forEach([this](GlTarget& t) { deleteTarget(t); });
        meshes_.forEach([this](GlMesh& m) { deleteMesh(m); });
        textures_.forEach([this](GLuint& t) { gl_.DeleteTextures(1, &t); });
        for (const GlProgram& p : programs_)
            if (p.name) gl_.DeleteProgram(p.name);
        if (streamIbo_) gl_.DeleteBuffers(1, &streamIbo_);
        if (instanceVbo_) gl_.DeleteBuffers(1, &instanceVbo_);
        // context_ goes last (member order), with every object it held already deleted.
    }

    // Deleting a bound object binds 0 in its place; the cache must say so, or a new object that
    // gets the freed name back (drivers reuse names; Mesa does for textures and buffers with
    // force_gl_names_reuse) would be taken as bound and never bound.
    void deleteMesh(GlMesh& m) {
        if (cache_.vao == m.vao || (m.idVao != 0 && cache_.vao == m.idVao)) cache_.vao = 0;
        gl_.DeleteVertexArrays(1, &m.vao);
        gl_.DeleteBuffers(1, &m.vbo);
        gl_.DeleteBuffers(1, &m.ibo);
        if (m.idVao) gl_.DeleteVertexArrays(1, &m.idVao);
        if (m.idVbo) gl_.DeleteBuffers(1, &m.idVbo);
    }

    // Loads GL, checks the version, builds the full program variant (so that a shader that does not
    // compile is reported here) and sets the fixed state. "" or the reason.
    std::string initialise();

    std::string name() const override { return contextKindName(context_->kind()); }
    std::string renderer() const override { return renderer_; }
    int maxTargetSize() const override { return maxTargetSize_; }
    int maxTextureSize() const override { return maxTextureSize_; }

    bool supportsDepthFormat(DepthFormat format) const override {
        return format == DepthFormat::D24 || gl_.ClipControl != nullptr;
    }
    TargetHandle createTarget(int width, int height, DepthFormat format) override;
    void destroyTarget(TargetHandle target) override;
    MeshHandle uploadMesh(const Mesh& mesh) override;
    TextureHandle uploadTexture(const Texture& texture) override;
    void releaseMesh(MeshHandle mesh) override;
    void releaseTexture(TextureHandle texture) override;
    void beginFrame(TargetHandle target, const FrameParams& frame) override;
    void draw(const DrawParams& params, std::span<const IndexRange> ranges) override;
    void drawInstances(const DrawParams& params, std::span<const InstanceParams> instances, IndexRange range) override;
    void clear(TargetHandle target, const Rect& rect, const glm::vec4& color, float depth) override;
    void copy(TargetHandle from, TargetHandle to, const Rect& rect, bool color, bool depth, bool ids) override;
    Buffers readBack(TargetHandle target) override;
    void finish() override {
        activate();
        gl_.Finish();
    }
    StateChanges stateChanges() const override { return changes_; }

private:
    // Makes our context current unless it is the frugal context this thread made current last
    // (two backends, e.g. EGL and OSMesa, may be used in turn on one thread).
    void activate() {
        if (currentContext() != context_.get()) {
            [[maybe_unused]] const bool ok = context_->makeCurrent();
            assert(ok && "GlBackend: could not make the context current");
        }
    }

    // A GL error here is a bug in this file (the inputs are validated), except running out of
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

    void deleteTarget(GlTarget& t) {
        if (cache_.drawFbo == t.fbo) cache_.drawFbo = 0;  // deleting a bound FBO binds 0
        if (cache_.readFbo == t.fbo) cache_.readFbo = 0;
        gl_.DeleteFramebuffers(1, &t.fbo);
        const GLuint renderbuffers[] = {t.color, t.ids, t.depth};
        gl_.DeleteRenderbuffers(3, renderbuffers);
    }

    // --- cached state -------------------------------------------------------------------------
    void bindDrawFbo(GLuint fbo) {
        if (cache_.drawFbo != fbo) gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
        cache_.drawFbo = fbo;
    }
    void bindReadFbo(GLuint fbo) {
        if (cache_.readFbo != fbo) gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
        cache_.readFbo = fbo;
    }
    // Binds `t` for drawing with the given colour attachments enabled.
    void drawInto(GlTarget& t, DrawSet set) {
        bindDrawFbo(t.fbo);
        if (t.drawSet == set) return;
        static constexpr GLenum kColor[] = {GL_COLOR_ATTACHMENT0};
        static constexpr GLenum kBoth[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        static constexpr GLenum kIds[] = {GL_NONE, GL_COLOR_ATTACHMENT1};
        switch (set) {
            case DrawSet::Color:
                gl_.DrawBuffers(1, kColor);
                break;
            case DrawSet::ColorAndIds:
                gl_.DrawBuffers(2, kBoth);
                break;
            case DrawSet::Ids:
                gl_.DrawBuffers(2, kIds);
                break;
            case DrawSet::Unknown:
                break;
        }
        t.drawSet = set;
    }
    void readFrom(GlTarget& t, GLenum attachment) {
        bindReadFbo(t.fbo);
        if (t.readBuffer != attachment) gl_.ReadBuffer(attachment);
        t.readBuffer = attachment;
    }
    // glEnable/glDisable of `capability` unless `cached` (−1 unknown, 0 off, 1 on) says it is so.
    void setEnabled(GLenum capability, int& cached, bool on) {
        if (cached == int(on)) return;
        if (on)
            gl_.Enable(capability);
        else
            gl_.Disable(capability);
        cached = int(on);
        ++changes_.toggles;
    }
    void setScissor(bool on, const Rect& rect = {}) {
        setEnabled(GL_SCISSOR_TEST, cache_.scissorOn, on);
        if (on && (rect.x != cache_.scissor.x || rect.y != cache_.scissor.y || rect.width != cache_.scissor.width ||
                   rect.height != cache_.scissor.height)) {
            gl_.Scissor(rect.x, rect.y, rect.width, rect.height);
            cache_.scissor = rect;
        }
    }
    void setViewport(int width, int height) {
        if (cache_.viewportWidth == width && cache_.viewportHeight == height) return;
        gl_.Viewport(0, 0, width, height);
        cache_.viewportWidth = width;
        cache_.viewportHeight = height;
    }
    void setCull(bool on) { setEnabled(GL_CULL_FACE, cache_.cullOn, on); }
    // DepthMode::Off is GL_DEPTH_TEST disabled, which also stops depth writes (GL 4.5 §14.9.4); the
    // depth mask stays GL_TRUE, so clears (glClearBuffer honours the mask) keep clearing depth.
    void setDepthTest(bool on) { setEnabled(GL_DEPTH_TEST, cache_.depthTestOn, on); }
    // The clip space and depth test of a target's format (the top of this file).
    void setDepthConvention(DepthFormat format) {
        if (cache_.depthFormat == int(format)) return;
        const bool reversed = format == DepthFormat::D32F;
        if (gl_.ClipControl) gl_.ClipControl(GL_LOWER_LEFT, reversed ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
        gl_.DepthFunc(reversed ? GL_GREATER : GL_LESS);
        cache_.depthFormat = int(format);
    }
    void bindVao(GLuint vao) {
        if (cache_.vao == vao) return;
        gl_.BindVertexArray(vao);
        cache_.vao = vao;
        ++changes_.meshes;
    }
    void bindTexture(GLuint texture) {
        if (cache_.texture == texture) return;
        gl_.BindTexture(GL_TEXTURE_2D, texture);
        cache_.texture = texture;
        ++changes_.textures;
    }
    void useProgram(GLuint program) {
        if (cache_.program == program) return;
        gl_.UseProgram(program);
        cache_.program = program;
        ++changes_.programs;
    }
    // The variant for `variant` (bits of Variant), compiled on first use and bound; nullptr when it
    // does not compile (a bug in the shaders: the full variant compiled in initialise()).
    GlProgram* program(unsigned variant);
    // Compiles programs_[variant] and looks up its uniforms. "" or the reason.
    std::string compileVariant(unsigned variant);

    void setVertexLayout(GLuint vao, GLuint vbo, GLuint ibo, const VertexLayout& layout);
    bool buildIdPass(GlMesh& mesh);
    // Reads `size` bytes of a buffer object back into `data` (nothing for size 0).
    void readBuffer(GLuint buffer, void* data, GLsizeiptr size);
    // Draws runs_ of `mesh` (`triangles` in all) from one streamed index buffer.
    void drawGathered(GlMesh& mesh, std::uint64_t triangles);
    // What draw and drawInstances share: the variant for `params` (| extraBits) compiled and bound,
    // the target, viewport, faces, depth test, texture and lighting set. nullptr: nothing to draw.
    GlProgram* prepareDraw(const DrawParams& params, GlTarget& target, const GlMesh& mesh, unsigned extraBits);
    // Attaches the instance buffer's attributes (divisor 1) to `vao`, once per vertex array.
    void attachInstances(GLuint vao, bool& attached);

    std::unique_ptr<GlContext> context_;
    GlApi gl_;
    bool initialised_ = false;
    std::string renderer_;
    int maxTargetSize_ = 0, maxTextureSize_ = 0;

    GlProgram programs_[kVariantCount];
    struct {
        GLuint drawFbo = 0, readFbo = 0, vao = 0, texture = 0, program = 0;
        int scissorOn = -1, cullOn = -1, depthTestOn = -1, depthFormat = -1;
        Rect scissor{-1, -1, -1, -1};
        int viewportWidth = -1, viewportHeight = -1;
    } cache_;
    StateChanges changes_;

    HandleTable<GlTarget, TargetHandle> targets_;
    HandleTable<GlMesh, MeshHandle> meshes_;
    HandleTable<GLuint, TextureHandle> textures_;

    TargetHandle frameTarget_ = kNoHandle;
    FrameParams frame_;
    glm::mat4 viewProjection_{1.0f};

    // The streamed index buffer of gathered draws, and its CPU side.
    GLuint streamIbo_ = 0;
    GLuint instanceVbo_ = 0;                    // drawInstances' per-instance records, streamed
    std::vector<InstanceRecord> instanceData_;
    std::vector<std::uint32_t> gathered_;

    // Scratch for the multi-draw argument arrays (no allocation per draw once grown).
    std::vector<IndexRange> runs_;
    std::vector<GLsizei> counts_;
    std::vector<GLint> firsts_;
    std::vector<const void*> offsets_;
};

std::string GlBackend::initialise() {
    if (!context_->makeCurrent()) return "could not make the context current";
    if (std::string missing = gl_.load(*context_); !missing.empty()) return missing;

    GLint major = 0, minor = 0;
    gl_.GetIntegerv(GL_MAJOR_VERSION, &major);
    gl_.GetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 33)
        return "OpenGL 3.3 needed, the context has " + std::to_string(major) + "." + std::to_string(minor);
    const auto text = [this](GLenum e) {
        const GLubyte* s = gl_.GetString(e);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    renderer_ = text(GL_RENDERER) + "; " + text(GL_VERSION);

    GLint maxRenderbuffer = 0, maxViewport[2] = {0, 0};
    gl_.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbuffer);
    gl_.GetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
    gl_.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTextureSize_);
    maxTargetSize_ = std::min({maxRenderbuffer, maxViewport[0], maxViewport[1]});

    // The full variant has every line of both sources: if it compiles, the others do.
    if (std::string reason = compileVariant(kTextureBit | kColorsBit | kIdsBit); !reason.empty()) return reason;

    // The fixed state (Backend.h): depth writes, no blending (the default), no dithering (Mesa may
    // dither 8-bit targets otherwise), counter-clockwise front faces. The depth test itself is per
    // draw (DepthMode, setDepthTest), its function per target format (setDepthConvention).
    setDepthTest(true);
    setDepthConvention(DepthFormat::D24);
    gl_.DepthMask(GL_TRUE);
    gl_.Disable(GL_DITHER);
    gl_.Disable(GL_BLEND);
    gl_.CullFace(GL_BACK);
    gl_.FrontFace(GL_CCW);
    gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl_.ActiveTexture(GL_TEXTURE0);
    setCull(false);
    setScissor(false);

    const GLenum error = gl_.GetError();
    if (error != GL_NO_ERROR) return glErrorName(error) + " while setting up the GL backend";
    initialised_ = true;
    return {};
}

std::string GlBackend::compileVariant(unsigned variant) {
    GlProgram& p = programs_[variant];
    std::string defines;
    if (variant & kTextureBit) defines += "#define FRUGAL_TEXTURE\n";
    if (variant & kColorsBit) defines += "#define FRUGAL_COLORS\n";
    if (variant & kIdsBit) defines += "#define FRUGAL_IDS\n";
    if (variant & kInstancedBit) defines += "#define FRUGAL_INSTANCED\n";
    if (std::string reason = compileProgram(gl_, "mesh.vert", "mesh.frag", defines, &p.name); !reason.empty()) {
        p.failed = true;
        return reason;
    }
    p.mvp = gl_.GetUniformLocation(p.name, "u_mvp");
    p.normalMatrix = gl_.GetUniformLocation(p.name, "u_normalMatrix");
    p.firstId = gl_.GetUniformLocation(p.name, "u_firstId");
    p.baseColorFactor = gl_.GetUniformLocation(p.name, "u_baseColorFactor");
    p.toLight = gl_.GetUniformLocation(p.name, "u_toLight");
    p.ambient = gl_.GetUniformLocation(p.name, "u_ambient");
    p.diffuse = gl_.GetUniformLocation(p.name, "u_diffuse");
    if (variant & kTextureBit) {
        useProgram(p.name);
        gl_.Uniform1i(gl_.GetUniformLocation(p.name, "u_baseColor"), 0);  // texture unit 0
    }
    return {};
}

GlProgram* GlBackend::program(unsigned variant) {
    GlProgram& p = programs_[variant];
    if (p.name == 0 && !p.failed) {
        if (std::string reason = compileVariant(variant); !reason.empty()) {
            std::fprintf(stderr, "frugal: %s: program variant %u: %s\n", name().c_str(), variant, reason.c_str());
            assert(false && "a mesh program variant does not compile");
        }
    }
    if (p.name == 0) return nullptr;
    useProgram(p.name);
    return &p;
}

TargetHandle GlBackend::createTarget(int width, int height, DepthFormat format) {
    // Sizes outside what GL can attach or view are refused, not clamped: the caller reports them.
    if (width <= 0 || height <= 0 || width > maxTargetSize_ || height > maxTargetSize_) return kNoHandle;
    if (!supportsDepthFormat(format)) return kNoHandle;
    activate();
    while (gl_.GetError() != GL_NO_ERROR) {
    }

    GlTarget t;
    t.width = width;
    t.height = height;
    GLuint renderbuffers[3] = {0, 0, 0};
    gl_.GenRenderbuffers(3, renderbuffers);
    t.color = renderbuffers[0];
    t.ids = renderbuffers[1];
    t.depth = renderbuffers[2];
    t.depthFormat = format;
    const GLenum formats[3] = {
        GL_RGBA8, GL_R32UI, format == DepthFormat::D32F ? GLenum(GL_DEPTH_COMPONENT32F) : GLenum(GL_DEPTH_COMPONENT24)};
    for (int i = 0; i < 3; ++i) {
        gl_.BindRenderbuffer(GL_RENDERBUFFER, renderbuffers[i]);
        gl_.RenderbufferStorage(GL_RENDERBUFFER, formats[i], width, height);
    }
    gl_.BindRenderbuffer(GL_RENDERBUFFER, 0);
    gl_.GenFramebuffers(1, &t.fbo);
    bindDrawFbo(t.fbo);
    gl_.FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t.color);
    gl_.FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER, t.ids);
    gl_.FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t.depth);
    const GLenum status = gl_.CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
    const GLenum error = gl_.GetError();  // GL_OUT_OF_MEMORY for a size the heap cannot take
    if (status != GL_FRAMEBUFFER_COMPLETE || error != GL_NO_ERROR) {
        deleteTarget(t);
        return kNoHandle;
    }
    const TargetHandle handle = targets_.add(t);
    clear(handle, Rect{0, 0, width, height}, glm::vec4(0.0f), farDepth(format));
    return handle;
}

void GlBackend::releaseMesh(MeshHandle mesh) {
    GlMesh* m = meshes_.find(mesh);
    if (m == nullptr) return;
    activate();
    deleteMesh(*m);  // GL keeps the objects alive until draws already queued have used them
    meshes_.remove(mesh);
    check("releaseMesh");
}

void GlBackend::releaseTexture(TextureHandle texture) {
    GLuint* t = textures_.find(texture);
    if (t == nullptr) return;
    activate();
    if (cache_.texture == *t) cache_.texture = 0;  // as in deleteMesh
    gl_.DeleteTextures(1, t);
    textures_.remove(texture);
    check("releaseTexture");
}

void GlBackend::destroyTarget(TargetHandle target) {
    GlTarget* t = targets_.find(target);
    if (t == nullptr) return;
    activate();
    deleteTarget(*t);
    targets_.remove(target);
    if (frameTarget_ == target) frameTarget_ = kNoHandle;
    check("destroyTarget");
}

void GlBackend::setVertexLayout(GLuint vao, GLuint vbo, GLuint ibo, const VertexLayout& layout) {
    bindVao(vao);
    gl_.BindBuffer(GL_ARRAY_BUFFER, vbo);
    if (ibo) gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);  // VAO state
    const auto offset = [](GLintptr bytes) { return reinterpret_cast<const void*>(bytes); };
    gl_.EnableVertexAttribArray(kPosition);
    gl_.VertexAttribPointer(kPosition, 3, GL_FLOAT, GL_FALSE, 0, offset(0));
    if (layout.normal >= 0) {
        gl_.EnableVertexAttribArray(kNormal);
        gl_.VertexAttribPointer(kNormal, 3, GL_FLOAT, GL_FALSE, 0, offset(layout.normal));
    }
    if (layout.color >= 0) {
        gl_.EnableVertexAttribArray(kColor);
        gl_.VertexAttribPointer(kColor, 4, GL_FLOAT, GL_FALSE, 0, offset(layout.color));
    }
    if (layout.uv >= 0) {
        gl_.EnableVertexAttribArray(kUv);
        gl_.VertexAttribPointer(kUv, 2, GL_FLOAT, GL_FALSE, 0, offset(layout.uv));
    }
    if (layout.id >= 0) {
        gl_.EnableVertexAttribArray(kId);
        gl_.VertexAttribIPointer(kId, 1, GL_UNSIGNED_INT, 0, offset(layout.id));
    }
}

MeshHandle GlBackend::uploadMesh(const Mesh& mesh) {
    // Bad data gets kNoHandle, never a GL call that reads out of bounds.
    if (!isUploadable(mesh)) return kNoHandle;
    const std::size_t vertices = mesh.positions.size();
    const std::size_t triangles = mesh.triangleCount();

    activate();
    GlMesh m;
    m.triangles = std::uint32_t(triangles);
    m.vertices = std::uint32_t(vertices);
    m.triangleSource = triangleSources(mesh);

    // One buffer, one section per attribute (positions, normals, colours, uvs).
    GLsizeiptr size = GLsizeiptr(vertices * sizeof(glm::vec3));
    const auto section = [&size](std::size_t count, std::size_t elementSize) -> GLintptr {
        if (count == 0) return -1;
        const GLintptr at = size;
        size += GLsizeiptr(count * elementSize);
        return at;
    };
    m.layout.normal = section(mesh.normals.size(), sizeof(glm::vec3));
    m.layout.color = section(mesh.colors.size(), sizeof(glm::vec4));
    m.layout.uv = section(mesh.uvs.size(), sizeof(glm::vec2));
    m.layout.size = size;
    std::vector<std::uint8_t> data(static_cast<std::size_t>(size));
    const auto put = [&data](GLintptr at, const void* source, std::size_t bytes) {
        if (at >= 0 && bytes > 0) std::memcpy(data.data() + at, source, bytes);
    };
    put(0, mesh.positions.data(), vertices * sizeof(glm::vec3));
    put(m.layout.normal, mesh.normals.data(), mesh.normals.size() * sizeof(glm::vec3));
    put(m.layout.color, mesh.colors.data(), mesh.colors.size() * sizeof(glm::vec4));
    put(m.layout.uv, mesh.uvs.data(), mesh.uvs.size() * sizeof(glm::vec2));

    gl_.GenVertexArrays(1, &m.vao);
    gl_.GenBuffers(1, &m.vbo);
    gl_.GenBuffers(1, &m.ibo);
    bindVao(m.vao);
    gl_.BindBuffer(GL_ARRAY_BUFFER, m.vbo);
    gl_.BufferData(GL_ARRAY_BUFFER, size, data.data(), GL_STATIC_DRAW);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ibo);
    gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                   mesh.indices.data(), GL_STATIC_DRAW);
    setVertexLayout(m.vao, m.vbo, m.ibo, m.layout);
    check("uploadMesh");
    return meshes_.add(std::move(m));
}

void GlBackend::readBuffer(GLuint buffer, void* data, GLsizeiptr size) {
    if (size <= 0) return;
    // Through GL_COPY_READ_BUFFER: binding GL_ELEMENT_ARRAY_BUFFER would change the bound VAO.
    gl_.BindBuffer(GL_COPY_READ_BUFFER, buffer);
    gl_.GetBufferSubData(GL_COPY_READ_BUFFER, 0, size, data);
    gl_.BindBuffer(GL_COPY_READ_BUFFER, 0);
}

void GlBackend::drawGathered(GlMesh& m, std::uint64_t triangles) {
    if (m.indices.empty()) {
        m.indices.resize(std::size_t(m.triangles) * 3);
        readBuffer(m.ibo, m.indices.data(), GLsizeiptr(m.indices.size() * sizeof(std::uint32_t)));
    }
    gathered_.resize(std::size_t(triangles) * 3);
    std::uint32_t* out = gathered_.data();
    for (const IndexRange& run : runs_) {
        const std::uint32_t* from = m.indices.data() + std::size_t(run.firstTriangle) * 3;
        out = std::copy(from, from + std::size_t(run.triangleCount) * 3, out);
    }
    if (streamIbo_ == 0) gl_.GenBuffers(1, &streamIbo_);
    // The element binding is VAO state: the stream buffer goes into the mesh's VAO for this draw and
    // the mesh's own index buffer comes back after it.
    bindVao(m.vao);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, streamIbo_);
    gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(gathered_.size() * sizeof(std::uint32_t)), gathered_.data(),
                   GL_STREAM_DRAW);
    gl_.DrawElements(GL_TRIANGLES, GLsizei(gathered_.size()), GL_UNSIGNED_INT, nullptr);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ibo);
}

bool GlBackend::buildIdPass(GlMesh& m) {
    std::vector<std::uint8_t> vertexData(static_cast<std::size_t>(m.layout.size));
    std::vector<std::uint32_t> indices(std::size_t(m.triangles) * 3);
    readBuffer(m.vbo, vertexData.data(), m.layout.size);
    readBuffer(m.ibo, indices.data(), GLsizeiptr(indices.size() * sizeof(std::uint32_t)));

    // Same sections as the indexed buffer, 3 vertices per triangle, plus the id section.
    const std::size_t n = indices.size();
    VertexLayout expanded;
    GLsizeiptr size = GLsizeiptr(n * sizeof(glm::vec3));
    const auto section = [&size, n](GLintptr source, std::size_t elementSize) -> GLintptr {
        if (source < 0) return -1;
        const GLintptr at = size;
        size += GLsizeiptr(n * elementSize);
        return at;
    };
    expanded.normal = section(m.layout.normal, sizeof(glm::vec3));
    expanded.color = section(m.layout.color, sizeof(glm::vec4));
    expanded.uv = section(m.layout.uv, sizeof(glm::vec2));
    expanded.id = section(0, sizeof(std::uint32_t));
    expanded.size = size;
    std::vector<std::uint8_t> data(static_cast<std::size_t>(size));
    const auto gather = [&](GLintptr from, GLintptr to, std::size_t elementSize) {
        if (from < 0) return;
        for (std::size_t k = 0; k < n; ++k)
            std::memcpy(data.data() + to + k * elementSize, vertexData.data() + from + indices[k] * elementSize,
                        elementSize);
    };
    gather(0, 0, sizeof(glm::vec3));
    gather(m.layout.normal, expanded.normal, sizeof(glm::vec3));
    gather(m.layout.color, expanded.color, sizeof(glm::vec4));
    gather(m.layout.uv, expanded.uv, sizeof(glm::vec2));
    for (std::size_t k = 0; k < n; ++k)
        std::memcpy(data.data() + expanded.id + k * sizeof(std::uint32_t), &m.triangleSource[k / 3],
                    sizeof(std::uint32_t));

    gl_.GenVertexArrays(1, &m.idVao);
    gl_.GenBuffers(1, &m.idVbo);
    bindVao(m.idVao);
    gl_.BindBuffer(GL_ARRAY_BUFFER, m.idVbo);
    gl_.BufferData(GL_ARRAY_BUFFER, size, data.data(), GL_STATIC_DRAW);
    setVertexLayout(m.idVao, m.idVbo, 0, expanded);
    return gl_.GetError() == GL_NO_ERROR;
}

TextureHandle GlBackend::uploadTexture(const Texture& texture) {
    if (texture.width <= 0 || texture.height <= 0 || texture.width > maxTextureSize_ ||
        texture.height > maxTextureSize_ ||
        texture.rgba.size() != std::size_t(texture.width) * std::size_t(texture.height) * 4)
        return kNoHandle;
    activate();
    GLuint name = 0;
    gl_.GenTextures(1, &name);
    bindTexture(name);
    // Rows as stored: the first row is v = 0, which is where glTF puts (0,0) (frugal/Scene.h).
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, texture.width, texture.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                   texture.rgba.data());
    // Base level only (Scene.h: no mipmaps in either backend).
    const GLint filter = texture.filter == Filter::Nearest ? GL_NEAREST : GL_LINEAR;
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrapMode(texture.wrapS));
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrapMode(texture.wrapT));
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    if (gl_.GetError() != GL_NO_ERROR) {
        gl_.DeleteTextures(1, &name);
        cache_.texture = 0;
        return kNoHandle;
    }
    return textures_.add(name);
}

void GlBackend::beginFrame(TargetHandle target, const FrameParams& frame) {
    assert(targets_.find(target) != nullptr && "beginFrame: no such target");
    if (targets_.find(target) == nullptr) return;
    assert(targets_.find(target)->depthFormat == frame.depthFormat &&
           "beginFrame: the projection is for another depth format");
    frameTarget_ = target;
    frame_ = frame;
    // The lighting goes to each program on its first draw of the frame (uniforms are per program).
    viewProjection_ = frame.projection * frame.view;
}

GlProgram* GlBackend::prepareDraw(const DrawParams& params, GlTarget& target, const GlMesh& mesh, unsigned extraBits) {
    const bool writeIds = frame_.writeIds;
    // The variant: a texture, vertex colours and ids only when the draw uses them.
    unsigned variant = (writeIds ? kIdsBit : 0u) | extraBits;
    GLuint texture = 0;
    if (params.texture != kNoHandle) {
        const GLuint* t = textures_.find(params.texture);
        assert(t != nullptr && "draw: no such texture");
        if (t) {
            texture = *t;
            variant |= kTextureBit;
        }
    }
    if (mesh.layout.color >= 0) variant |= kColorsBit;
    GlProgram* p = program(variant);
    if (p == nullptr) return nullptr;

    drawInto(target, writeIds ? DrawSet::ColorAndIds : DrawSet::Color);
    setViewport(target.width, target.height);
    setScissor(false);
    setCull(!params.doubleSided);
    setDepthTest(params.depth == DepthMode::Test);
    setDepthConvention(target.depthFormat);
    if (texture) bindTexture(texture);

    const Lighting& light = frame_.lighting;
    const auto uploaded = [this](bool sent) { changes_.uniforms += sent ? 1 : 0; return sent; };
    if (uploaded(p->toLightValue.update(light.toLight))) gl_.Uniform3fv(p->toLight, 1, glm::value_ptr(light.toLight));
    if (uploaded(p->ambientValue.update(light.ambient))) gl_.Uniform1f(p->ambient, light.ambient);
    if (uploaded(p->diffuseValue.update(light.diffuse))) gl_.Uniform1f(p->diffuse, light.diffuse);

    // Attributes the mesh lacks read the current generic value. That value is context state, and
    // GL 3.3 leaves it undefined after a draw that sourced the attribute from an array, so it is
    // set before every draw that needs it: normal +z, uv (0,0). (Colours and ids are only in the
    // variants of meshes that have them.)
    if (mesh.layout.normal < 0) gl_.VertexAttrib3f(kNormal, 0.0f, 0.0f, 1.0f);
    if ((variant & kTextureBit) && mesh.layout.uv < 0) gl_.VertexAttrib2f(kUv, 0.0f, 0.0f);
    return p;
}

void GlBackend::attachInstances(GLuint vao, bool& attached) {
    bindVao(vao);
    if (attached) return;
    gl_.BindBuffer(GL_ARRAY_BUFFER, instanceVbo_);
    constexpr GLsizei stride = sizeof(InstanceRecord);
    const auto at = [](std::size_t bytes) { return reinterpret_cast<const void*>(bytes); };
    for (GLuint column = 0; column < 4; ++column) {
        gl_.EnableVertexAttribArray(kInstanceMvp + column);
        gl_.VertexAttribPointer(kInstanceMvp + column, 4, GL_FLOAT, GL_FALSE, stride,
                                at(offsetof(InstanceRecord, mvp) + 16 * column));
        gl_.VertexAttribDivisor(kInstanceMvp + column, 1);
    }
    for (GLuint column = 0; column < 3; ++column) {
        gl_.EnableVertexAttribArray(kInstanceNormalMatrix + column);
        gl_.VertexAttribPointer(kInstanceNormalMatrix + column, 3, GL_FLOAT, GL_FALSE, stride,
                                at(offsetof(InstanceRecord, normalMatrix) + 12 * column));
        gl_.VertexAttribDivisor(kInstanceNormalMatrix + column, 1);
    }
    gl_.EnableVertexAttribArray(kInstanceColor);
    gl_.VertexAttribPointer(kInstanceColor, 4, GL_FLOAT, GL_FALSE, stride, at(offsetof(InstanceRecord, baseColorFactor)));
    gl_.VertexAttribDivisor(kInstanceColor, 1);
    gl_.EnableVertexAttribArray(kInstanceFirstId);
    gl_.VertexAttribIPointer(kInstanceFirstId, 1, GL_UNSIGNED_INT, stride, at(offsetof(InstanceRecord, firstId)));
    gl_.VertexAttribDivisor(kInstanceFirstId, 1);
    attached = true;
}

void GlBackend::drawInstances(const DrawParams& params, std::span<const InstanceParams> instances, IndexRange range) {
    GlTarget* target = targets_.find(frameTarget_);
    GlMesh* mesh = meshes_.find(params.mesh);
    assert(target != nullptr && "drawInstances: no beginFrame, or its target was destroyed");
    assert(mesh != nullptr && "drawInstances: no such mesh");
    if (target == nullptr || mesh == nullptr || instances.empty()) return;
    const std::uint64_t triangles = normalizeRanges({&range, 1}, mesh->triangles, runs_);
    if (triangles == 0) return;
    const IndexRange run = runs_[0];

    activate();
    const bool writeIds = frame_.writeIds;
    GlProgram* p = prepareDraw(params, *target, *mesh, kInstancedBit);
    if (p == nullptr) return;
    // The records: what draw() would put in its uniforms, computed the same way (glm, float).
    instanceData_.resize(instances.size());
    for (std::size_t i = 0; i < instances.size(); ++i) {
        const InstanceParams& in = instances[i];
        InstanceRecord& out = instanceData_[i];
        const glm::mat4 mvp = viewProjection_ * in.model;
        const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(in.model));
        std::memcpy(out.mvp, glm::value_ptr(mvp), sizeof out.mvp);
        std::memcpy(out.normalMatrix, glm::value_ptr(normalMatrix), sizeof out.normalMatrix);
        std::memcpy(out.baseColorFactor, glm::value_ptr(in.baseColorFactor), sizeof out.baseColorFactor);
        out.firstId = in.firstId;
    }
    if (instanceVbo_ == 0) gl_.GenBuffers(1, &instanceVbo_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, instanceVbo_);
    gl_.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(instanceData_.size() * sizeof(InstanceRecord)), instanceData_.data(),
                   GL_STREAM_DRAW);
    const GLsizei count = GLsizei(instances.size());
    if (writeIds) {
        target->idsDirty = true;
        if (mesh->idVao == 0 && !buildIdPass(*mesh)) {
            assert(false && "drawInstances: could not build the id pass (out of memory?)");
            return;
        }
        attachInstances(mesh->idVao, mesh->idVaoInstanced);
        gl_.DrawArraysInstanced(GL_TRIANGLES, GLint(run.firstTriangle) * 3, GLsizei(run.triangleCount) * 3, count);
    } else {
        attachInstances(mesh->vao, mesh->vaoInstanced);
        gl_.DrawElementsInstanced(GL_TRIANGLES, GLsizei(run.triangleCount) * 3, GL_UNSIGNED_INT,
                                  reinterpret_cast<const void*>(std::uintptr_t(run.firstTriangle) * 3 * sizeof(std::uint32_t)),
                                  count);
    }
    ++changes_.draws;
    check("drawInstances");
}

void GlBackend::draw(const DrawParams& params, std::span<const IndexRange> ranges) {
    GlTarget* target = targets_.find(frameTarget_);
    GlMesh* mesh = meshes_.find(params.mesh);
    assert(target != nullptr && "draw: no beginFrame, or its target was destroyed");
    assert(mesh != nullptr && "draw: no such mesh");
    if (target == nullptr || mesh == nullptr) return;

    const std::uint64_t triangles = normalizeRanges(ranges, mesh->triangles, runs_);
    if (triangles == 0) return;
    counts_.clear();
    firsts_.clear();
    for (const IndexRange& run : runs_) {
        firsts_.push_back(GLint(run.firstTriangle));
        counts_.push_back(GLsizei(run.triangleCount));
    }

    activate();
    const bool writeIds = frame_.writeIds;
    GlProgram* p = prepareDraw(params, *target, *mesh, 0u);
    if (p == nullptr) return;
    const auto uploaded = [this](bool sent) { changes_.uniforms += sent ? 1 : 0; return sent; };
    const glm::mat4 mvp = viewProjection_ * params.model;
    const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(params.model));
    if (uploaded(p->mvpValue.update(mvp))) gl_.UniformMatrix4fv(p->mvp, 1, GL_FALSE, glm::value_ptr(mvp));
    if (uploaded(p->normalMatrixValue.update(normalMatrix)))
        gl_.UniformMatrix3fv(p->normalMatrix, 1, GL_FALSE, glm::value_ptr(normalMatrix));
    if (uploaded(p->baseColorFactorValue.update(params.baseColorFactor)))
        gl_.Uniform4fv(p->baseColorFactor, 1, glm::value_ptr(params.baseColorFactor));
    if (writeIds && uploaded(p->firstIdValue.update(params.firstId))) gl_.Uniform1ui(p->firstId, params.firstId);
    ++changes_.draws;

    if (writeIds) {
        target->idsDirty = true;
        if (mesh->idVao == 0 && !buildIdPass(*mesh)) {
            assert(false && "draw: could not build the id pass (out of memory?)");
            return;
        }
        for (std::size_t i = 0; i < counts_.size(); ++i) {
            firsts_[i] *= 3;
            counts_[i] *= 3;
        }
        bindVao(mesh->idVao);
        gl_.MultiDrawArrays(GL_TRIANGLES, firsts_.data(), counts_.data(), GLsizei(counts_.size()));
    } else if (runs_.size() >= kGatherMinRuns &&
               triangles / runs_.size() < kGatherMaxAverageRun) {
        drawGathered(*mesh, triangles);
    } else {
        offsets_.resize(counts_.size());
        for (std::size_t i = 0; i < counts_.size(); ++i) {
            offsets_[i] = reinterpret_cast<const void*>(std::uintptr_t(firsts_[i]) * 3 * sizeof(std::uint32_t));
            counts_[i] *= 3;
        }
        bindVao(mesh->vao);
        gl_.MultiDrawElements(GL_TRIANGLES, counts_.data(), GL_UNSIGNED_INT, offsets_.data(), GLsizei(counts_.size()));
    }
    check("draw");
}

void GlBackend::clear(TargetHandle target, const Rect& rect, const glm::vec4& color, float depth) {
    GlTarget* t = targets_.find(target);
    assert(t != nullptr && "clear: no such target");
    if (t == nullptr) return;
    const Rect r = clipRect(rect, t->width, t->height);
    if (r.empty()) return;
    activate();
    // Ids known to be 0 stay untouched, and the draw-buffer set stays the one bound if it has the
    // colour at index 0 (llvmpipe flushes its scene on a switch; see the top of the file).
    const bool clearIds = t->idsDirty;
    drawInto(*t, clearIds || t->drawSet == DrawSet::ColorAndIds ? DrawSet::ColorAndIds : DrawSet::Color);
    setScissor(true, r);
    const GLfloat clampedDepth = std::clamp(depth, 0.0f, 1.0f);
    // Draw buffer indices, not attachments: 0 is colour, 1 is ids in the ColorAndIds set.
    gl_.ClearBufferfv(GL_COLOR, 0, glm::value_ptr(color));
    if (clearIds) {
        const GLuint zero[4] = {0, 0, 0, 0};
        gl_.ClearBufferuiv(GL_COLOR, 1, zero);
        if (r.x == 0 && r.y == 0 && r.width == t->width && r.height == t->height) t->idsDirty = false;
    }
    gl_.ClearBufferfv(GL_DEPTH, 0, &clampedDepth);
    check("clear");
}

void GlBackend::copy(TargetHandle from, TargetHandle to, const Rect& rect, bool color, bool depth, bool ids) {
    GlTarget* source = targets_.find(from);
    GlTarget* dest = targets_.find(to);
    assert(source != nullptr && dest != nullptr && "copy: no such target");
    if (source == nullptr || dest == nullptr || from == to) return;
    assert(source->width == dest->width && source->height == dest->height && "copy: targets differ in size");
    assert(source->depthFormat == dest->depthFormat && "copy: targets differ in depth format");
    const Rect r = clipRect(clipRect(rect, source->width, source->height), dest->width, dest->height);
    if (r.empty() || !(color || depth || ids)) return;
    activate();
    // Blits obey the scissor test; the rectangle is the blit's own.
    setScissor(false);
    const int x1 = r.x + r.width, y1 = r.y + r.height;
    // A blit writes every enabled draw buffer from the one read buffer, and a normalised colour
    // buffer cannot be blitted into an integer one: colour and ids go in separate blits, each with
    // only the matching draw buffer enabled. Depth rides along with the first blit.
    GLbitfield depthBit = depth ? GL_DEPTH_BUFFER_BIT : 0;
    if (color) {
        readFrom(*source, GL_COLOR_ATTACHMENT0);
        drawInto(*dest, DrawSet::Color);
        gl_.BlitFramebuffer(r.x, r.y, x1, y1, r.x, r.y, x1, y1, GL_COLOR_BUFFER_BIT | depthBit, GL_NEAREST);
        depthBit = 0;
    }
    if (ids && (source->idsDirty || dest->idsDirty)) {  // zeros onto zeros: nothing to copy
        dest->idsDirty = dest->idsDirty || source->idsDirty;  // copying zeros keeps them zero
        readFrom(*source, GL_COLOR_ATTACHMENT1);
        drawInto(*dest, DrawSet::Ids);
        gl_.BlitFramebuffer(r.x, r.y, x1, y1, r.x, r.y, x1, y1, GL_COLOR_BUFFER_BIT | depthBit, GL_NEAREST);
        depthBit = 0;
    }
    if (depthBit) {
        bindReadFbo(source->fbo);
        bindDrawFbo(dest->fbo);
        gl_.BlitFramebuffer(r.x, r.y, x1, y1, r.x, r.y, x1, y1, depthBit, GL_NEAREST);
    }
    check("copy");
}

Buffers GlBackend::readBack(TargetHandle target) {
    Buffers out;
    GlTarget* t = targets_.find(target);
    assert(t != nullptr && "readBack: no such target");
    if (t == nullptr) return out;
    activate();
    out.width = t->width;
    out.height = t->height;
    out.rgba.resize(out.pixelCount() * 4);
    out.ids.resize(out.pixelCount());
    out.depth.resize(out.pixelCount());
    // Rows come bottom-up (window origin bottom-left), as Buffers wants. Pack alignment is 1.
    readFrom(*t, GL_COLOR_ATTACHMENT0);
    gl_.ReadPixels(0, 0, t->width, t->height, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
    readFrom(*t, GL_COLOR_ATTACHMENT1);
    gl_.ReadPixels(0, 0, t->width, t->height, GL_RED_INTEGER, GL_UNSIGNED_INT, out.ids.data());
    out.depthFormat = t->depthFormat;
    if (t->depthFormat == DepthFormat::D32F) {
        gl_.ReadPixels(0, 0, t->width, t->height, GL_DEPTH_COMPONENT, GL_FLOAT, out.depth.data());  // the floats' bits
    } else {
        gl_.ReadPixels(0, 0, t->width, t->height, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, out.depth.data());
        // 32-bit normalised → the stored 24-bit value (see the top of this file).
        for (std::uint32_t& d : out.depth) d >>= 8;
    }
    check("readBack");
    return out;
}

}  // namespace

Result<std::unique_ptr<Backend>> makeGlBackend(std::unique_ptr<GlContext> context) {
    if (!context) return Error{"no GL context"};
    const std::string kind = contextKindName(context->kind());
    auto backend = std::make_unique<GlBackend>(std::move(context));
    if (std::string reason = backend->initialise(); !reason.empty()) return Error{kind + ": " + reason};
    return std::unique_ptr<Backend>(std::move(backend));
}

Result<std::unique_ptr<Backend>> createGlBackend(BackendChoice choice, std::vector<std::string>* log) {
    using Factory = Result<std::unique_ptr<GlContext>> (*)();
    std::vector<Factory> attempts;
    const Factory hardwareDevice = [] { return createEglDeviceContext(false); };
    const Factory anyDevice = [] { return createEglDeviceContext(true); };
    switch (choice) {
        case BackendChoice::Auto:
            attempts = {hardwareDevice, createEglSurfacelessContext, createOsMesaContext};
            break;
        case BackendChoice::Egl:
            attempts = {hardwareDevice, createEglSurfacelessContext};
            break;
        case BackendChoice::EglDevice:
            attempts = {anyDevice};
            break;
        case BackendChoice::EglSurfaceless:
            attempts = {createEglSurfacelessContext};
            break;
        case BackendChoice::OsMesa:
            attempts = {createOsMesaContext};
            break;
    }

    std::string reasons;
    for (Factory factory : attempts) {
        Result<std::unique_ptr<GlContext>> context = factory();
        std::string line;
        if (context) {
            const std::string description = (*context)->description();
            auto backend = makeGlBackend(std::move(*context));
            if (backend) {
                if (log)
                    log->push_back((*backend)->name() + ": ok (" + description + "; " + (*backend)->renderer() + ")");
                return backend;
            }
            line = backend.error();
        } else {
            line = context.error();
        }
        if (log) log->push_back(line);
        reasons += (reasons.empty() ? "" : "; ") + line;
    }
    return Error{"no usable GL context: " + reasons};
}

}  // namespace frugal
