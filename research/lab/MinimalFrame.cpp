// The bench's minimal frame (gl/MinimalFrame.h). Kept deliberately plain: every call here is one
// the frame needs, so the bench's ratio frugal ÷ minimal is the backend's overhead on that frame.
#include "lab/MinimalFrame.h"

#include <cassert>
#include <cstdint>
#include <cstring>
#include <utility>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "renderer/Research.h"

namespace frugal {

namespace {

class Minimal final : public MinimalFrame {
public:
    Minimal(std::unique_ptr<GlContext> context, const Scene& scene) : context_(std::move(context)), scene_(&scene) {}
    Minimal(const Minimal&) = delete;
    Minimal& operator=(const Minimal&) = delete;

    ~Minimal() override {
        if (!loaded_) return;
        activate();
        for (const MeshObjects& m : meshes_) {
            gl_.DeleteVertexArrays(1, &m.vao);
            gl_.DeleteBuffers(1, &m.vbo);
            gl_.DeleteBuffers(1, &m.ibo);
        }
        for (const Program& p : programs_) gl_.DeleteProgram(p.name);
        gl_.DeleteFramebuffers(1, &fbo_);
        gl_.DeleteRenderbuffers(2, renderbuffers_);
        gl_.DeleteBuffers(2, packBuffers_);  // names of 0 are ignored
    }

    // "" or why the frame cannot be drawn.
    std::string initialise(int width, int height, DepthFormat format);

    void render(const FrameParams& frame, const std::vector<glm::mat4>& world, const glm::vec4& background) override;
    void finish() override {
        activate();
        gl_.Finish();
    }
    void activate() override {
        if (currentContext() != context_.get()) {
            [[maybe_unused]] const bool ok = context_->makeCurrent();
            assert(ok && "MinimalFrame: could not make the context current");
        }
    }
    void readBackInto(Buffers& out, bool depth) override;
    void startReadBack(int slot, bool depth) override;
    void endReadBack(int slot, Buffers& out, bool depth) override;

private:
    std::size_t pixels() const { return std::size_t(width_) * std::size_t(height_); }
    // Sizes `out` for the frame, the depth only when asked for.
    void sizeBuffers(Buffers& out, bool depth) const;

    struct MeshObjects {
        GLuint vao = 0, vbo = 0, ibo = 0;
        GLsizei indices = 0;
        bool normals = false;
    };

    std::unique_ptr<GlContext> context_;
    const Scene* scene_;
    GlApi gl_;
    bool loaded_ = false;
    int width_ = 0, height_ = 0;
    DepthFormat format_ = DepthFormat::D24;
    // The mesh program for each shading model, tone mapping, environment specular term and side of
    // the metal mix (FrameParams::shading, tonemap, Lighting::environmentSpecular, MetalMix), uniforms
    // by location; made by initialise for the sides the scene's materials need.
    struct Program {
        GLuint name = 0;
        GLint mvp = -1, normalMatrix = -1, model = -1, factor = -1, metallicRoughness = -1, emissive = -1;
        GLint eye = -1, toLight = -1, light = -1, environment = -1;
    };
    static constexpr int kToneMaps = 3;
    // Lambert has no environment specular term to leave out: one program serves it either way (the
    // backend's variants are the same), and the slots of Lambert without the term stay empty.
    // Lambert has no metal mix either.
    static int programIndex(ShadingModel shading, ToneMap tonemap, bool environmentSpecular, MetalMix mix) {
        const bool lambert = shading == ShadingModel::Lambert;
        return ((int(shading) * kToneMaps + int(tonemap)) * 2 + int(environmentSpecular || lambert)) * 3 +
               (lambert ? 0 : int(mix));
    }
    // The side of the metal mix a material's program has (as the backend's variant: no maps here).
    static MetalMix mixOf(const Material& material) { return metalMixOf(material.metallicFactor, false, false); }
    // Compiles the program of one slot unless it is made: "" or why it did not compile.
    std::string compile(ShadingModel shading, ToneMap tonemap, bool environmentSpecular, MetalMix mix);
    Program programs_[2 * kToneMaps * 2 * 3];
    GLuint fbo_ = 0;
    GLuint renderbuffers_[2] = {0, 0};  // colour, depth
    GLuint packBuffers_[2] = {0, 0};    // read-back slots: colour then depth, 8 bytes a pixel; made when first used
    std::vector<MeshObjects> meshes_;   // one per scene mesh
    int cullOn_ = -1;
};

std::string Minimal::initialise(int width, int height, DepthFormat format) {
    if (!context_->makeCurrent()) return "could not make the context current";
    if (std::string missing = gl_.load(*context_); !missing.empty()) return missing;
    loaded_ = true;

    GLint maxRenderbuffer = 0, maxViewport[2] = {0, 0};
    gl_.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbuffer);
    gl_.GetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
    if (width < 1 || height < 1 || width > maxRenderbuffer || height > maxRenderbuffer || width > maxViewport[0] ||
        height > maxViewport[1])
        return "a " + std::to_string(width) + "x" + std::to_string(height) + " target is beyond this context";
    width_ = width;
    height_ = height;
    format_ = format;
    if (format == DepthFormat::D32F && gl_.ClipControl == nullptr)
        return "no glClipControl for d32f (GL 4.5 or ARB_clip_control)";

    // Colour and depth only, the FBO's default draw buffer (colour attachment 0).
    gl_.GenRenderbuffers(2, renderbuffers_);
    gl_.BindRenderbuffer(GL_RENDERBUFFER, renderbuffers_[0]);
    gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    gl_.BindRenderbuffer(GL_RENDERBUFFER, renderbuffers_[1]);
    gl_.RenderbufferStorage(GL_RENDERBUFFER, format == DepthFormat::D32F ? GL_DEPTH_COMPONENT32F : GL_DEPTH_COMPONENT24,
                            width, height);
    gl_.GenFramebuffers(1, &fbo_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffers_[0]);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, renderbuffers_[1]);
    if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) return "incomplete framebuffer";
    gl_.Viewport(0, 0, width, height);

    // The backend's fixed state (GlBackend::initialise), where it differs from GL's defaults.
    gl_.Enable(GL_DEPTH_TEST);
    gl_.Disable(GL_DITHER);
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
    if (format == DepthFormat::D32F) {
        gl_.ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        gl_.DepthFunc(GL_GREATER);
        gl_.ClearDepth(0.0);
    } else {
        gl_.DepthFunc(GL_LESS);
        gl_.ClearDepth(1.0);
    }

    meshes_.resize(scene_->meshes.size());
    for (std::size_t i = 0; i < scene_->meshes.size(); ++i) {
        const Mesh& mesh = scene_->meshes[i];
        if (!isUploadable(mesh))
            return "mesh " + std::to_string(i) + quotedName(mesh.name) + " breaks the upload contract";
        MeshObjects& m = meshes_[i];
        m.indices = GLsizei(mesh.indices.size());
        m.normals = !mesh.normals.empty();
        const GLsizeiptr positions = GLsizeiptr(mesh.positions.size() * sizeof(glm::vec3));
        const GLsizeiptr normals = GLsizeiptr(mesh.normals.size() * sizeof(glm::vec3));
        gl_.GenVertexArrays(1, &m.vao);
        gl_.GenBuffers(1, &m.vbo);
        gl_.GenBuffers(1, &m.ibo);
        gl_.BindVertexArray(m.vao);
        gl_.BindBuffer(GL_ARRAY_BUFFER, m.vbo);
        std::vector<std::uint8_t> data(static_cast<std::size_t>(positions + normals));
        if (positions > 0) std::memcpy(data.data(), mesh.positions.data(), std::size_t(positions));
        if (normals > 0) std::memcpy(data.data() + positions, mesh.normals.data(), std::size_t(normals));
        gl_.BufferData(GL_ARRAY_BUFFER, positions + normals, data.data(), GL_STATIC_DRAW);
        gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ibo);
        gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                       mesh.indices.data(), GL_STATIC_DRAW);
        gl_.EnableVertexAttribArray(0);
        gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
        if (m.normals) {
            gl_.EnableVertexAttribArray(1);
            gl_.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, reinterpret_cast<const void*>(positions));
        }
    }
    // Every frame's programs for the sides of the metal mix the drawn materials need.
    bool needed[3] = {false, false, false};
    for (const Instance& instance : scene_->instances) {
        const Mesh& mesh = scene_->meshes[std::size_t(instance.mesh)];
        needed[int(mixOf(mesh.material >= 0 ? scene_->materials[std::size_t(mesh.material)] : Material{}))] = true;
    }
    for (const ShadingModel shading : {ShadingModel::Full, ShadingModel::Lambert})
        for (const ToneMap tonemap : {ToneMap::None, ToneMap::PbrNeutral, ToneMap::Aces})
            for (const bool environmentSpecular : {false, true})
                for (const MetalMix mix : {MetalMix::Both, MetalMix::Dielectric, MetalMix::Metal})
                    if (needed[int(mix)])
                        if (std::string reason = compile(shading, tonemap, environmentSpecular, mix); !reason.empty())
                            return reason;
    const GLenum error = gl_.GetError();
    if (error != GL_NO_ERROR) return glErrorName(error) + " while setting up the minimal frame";
    return {};
}

void Minimal::render(const FrameParams& frame, const std::vector<glm::mat4>& world, const glm::vec4& background) {
    static const Material kDefault{};
    activate();
    gl_.ClearColor(background.r, background.g, background.b, background.a);
    gl_.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const glm::vec3 eye = eyePosition(frame.view);
    const glm::mat4 viewProjection = frame.projection * frame.view;
    const Program* current = nullptr;
    for (const Instance& instance : scene_->instances) {
        const MeshObjects& m = meshes_[std::size_t(instance.mesh)];
        if (m.indices == 0) continue;
        const Mesh& mesh = scene_->meshes[std::size_t(instance.mesh)];
        const Material& material = mesh.material >= 0 ? scene_->materials[std::size_t(mesh.material)] : kDefault;
        // The program of the material's side of the metal mix; the frame's uniforms set when it is
        // first used in the frame.
        const Program& p =
            programs_[programIndex(frame.shading, frame.tonemap, frame.lighting.environmentSpecular, mixOf(material))];
        if (&p != current) {
            gl_.UseProgram(p.name);
            gl_.Uniform3fv(p.eye, 1, glm::value_ptr(eye));
            gl_.Uniform3fv(p.toLight, 1, glm::value_ptr(frame.lighting.toLight));
            gl_.Uniform1f(p.light, frame.lighting.light);
            gl_.Uniform1f(p.environment, frame.lighting.environment);
            current = &p;
        }
        const glm::mat4& model = world[std::size_t(instance.node)];
        const glm::mat4 mvp = viewProjection * model;
        const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(model));
        gl_.UniformMatrix4fv(p.mvp, 1, GL_FALSE, glm::value_ptr(mvp));
        gl_.UniformMatrix3fv(p.normalMatrix, 1, GL_FALSE, glm::value_ptr(normalMatrix));
        gl_.UniformMatrix4fv(p.model, 1, GL_FALSE, glm::value_ptr(model));
        gl_.Uniform4fv(p.factor, 1, glm::value_ptr(material.baseColorFactor));
        gl_.Uniform2f(p.metallicRoughness, material.metallicFactor, material.roughnessFactor);
        gl_.Uniform3fv(p.emissive, 1, glm::value_ptr(material.emissiveFactor));
        if (cullOn_ != int(!material.doubleSided)) {
            if (material.doubleSided)
                gl_.Disable(GL_CULL_FACE);
            else
                gl_.Enable(GL_CULL_FACE);
            cullOn_ = int(!material.doubleSided);
        }
        // A mesh without normals reads the constant (0,0,1), as in the backend; GL 3.3 leaves the
        // constant undefined after a draw that sourced the attribute from an array.
        if (!m.normals) gl_.VertexAttrib3f(1, 0.0f, 0.0f, 1.0f);
        gl_.BindVertexArray(m.vao);
        gl_.DrawElements(GL_TRIANGLES, m.indices, GL_UNSIGNED_INT, nullptr);
    }
}

std::string Minimal::compile(ShadingModel shading, ToneMap tonemap, bool environmentSpecular, MetalMix mix) {
    Program& p = programs_[programIndex(shading, tonemap, environmentSpecular, mix)];
    if (p.name != 0) return {};  // Lambert's, made already for another slot of the same program
    // mesh.vert + mesh.frag with only the frame's defines and the mix's: the variant with no
    // texture, colours or ids, which is the backend's own program for such a frame, so the
    // arithmetic is the same by construction.
    const bool lambert = shading == ShadingModel::Lambert;
    const std::string defines = meshPreamble() + frameDefines(shading, tonemap, environmentSpecular || lambert) +
                                (lambert ? std::string() : metalMixDefine(mix));
    if (std::string reason = compileProgram(gl_, "mesh.vert", "mesh.frag", defines, &p.name); !reason.empty())
        return reason;
    p.mvp = gl_.GetUniformLocation(p.name, "u_mvp");
    p.normalMatrix = gl_.GetUniformLocation(p.name, "u_normalMatrix");
    p.model = gl_.GetUniformLocation(p.name, "u_model");
    p.factor = gl_.GetUniformLocation(p.name, "u_baseColorFactor");
    p.metallicRoughness = gl_.GetUniformLocation(p.name, "u_metallicRoughness");
    p.emissive = gl_.GetUniformLocation(p.name, "u_emissive");
    p.eye = gl_.GetUniformLocation(p.name, "u_eye");
    p.toLight = gl_.GetUniformLocation(p.name, "u_toLight");
    p.light = gl_.GetUniformLocation(p.name, "u_light");
    p.environment = gl_.GetUniformLocation(p.name, "u_environment");
    return {};
}

void Minimal::sizeBuffers(Buffers& out, bool depth) const {
    out.width = width_;
    out.height = height_;
    out.rgba.resize(pixels() * 4);
    out.depth.resize(depth ? pixels() : 0);
    out.ids.clear();
    out.depthFormat = format_;
}

// The depth as glReadPixels gives it → the stored value (GlBackend.cpp): D32F's float bits as they
// are, D24's 32-bit normalised value shifted to the stored 24 bits.
void toStoredDepth(std::vector<std::uint32_t>& depth, DepthFormat format) {
    if (format == DepthFormat::D24)
        for (std::uint32_t& d : depth) d >>= 8;
}

void Minimal::readBackInto(Buffers& out, bool depth) {
    activate();
    sizeBuffers(out, depth);
    gl_.ReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
    if (depth) {
        const GLenum type = format_ == DepthFormat::D32F ? GL_FLOAT : GL_UNSIGNED_INT;
        gl_.ReadPixels(0, 0, width_, height_, GL_DEPTH_COMPONENT, type, out.depth.data());
        toStoredDepth(out.depth, format_);
    }
}

void Minimal::startReadBack(int slot, bool depth) {
    assert(slot == 0 || slot == 1);
    activate();
    if (packBuffers_[slot] == 0) {
        gl_.GenBuffers(1, &packBuffers_[slot]);
        gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, packBuffers_[slot]);
        gl_.BufferData(GL_PIXEL_PACK_BUFFER, GLsizeiptr(pixels() * 8), nullptr, GL_STREAM_READ);
    }
    gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, packBuffers_[slot]);
    // With a pack buffer bound, the last argument is an offset into it.
    gl_.ReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    if (depth) {
        const GLenum type = format_ == DepthFormat::D32F ? GL_FLOAT : GL_UNSIGNED_INT;
        gl_.ReadPixels(0, 0, width_, height_, GL_DEPTH_COMPONENT, type, reinterpret_cast<void*>(pixels() * 4));
    }
    gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    gl_.Flush();  // the read starts now, not when the next frame flushes
}

void Minimal::endReadBack(int slot, Buffers& out, bool depth) {
    assert((slot == 0 || slot == 1) && packBuffers_[slot] != 0);
    activate();
    sizeBuffers(out, depth);
    gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, packBuffers_[slot]);
    gl_.GetBufferSubData(GL_PIXEL_PACK_BUFFER, 0, GLsizeiptr(pixels() * 4), out.rgba.data());
    if (depth) {
        gl_.GetBufferSubData(GL_PIXEL_PACK_BUFFER, GLintptr(pixels() * 4), GLsizeiptr(pixels() * 4), out.depth.data());
        toStoredDepth(out.depth, format_);
    }
    gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

}  // namespace

std::string minimalFrameUnsupported(const Scene& scene) {
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[std::size_t(instance.mesh)];
        if (!mesh.colors.empty())
            return "mesh " + std::to_string(instance.mesh) + quotedName(mesh.name) +
                   " has vertex colours, which the minimal frame does not draw";
        if (mesh.material < 0) continue;
        const Material& material = scene.materials[std::size_t(mesh.material)];
        if (material.hasTextures())
            return "material " + std::to_string(mesh.material) + quotedName(material.name) +
                   " has a texture, which the minimal frame does not draw";
        if (material.specularGlossiness || material.alphaMode != AlphaMode::Opaque || material.clearcoat() ||
            material.unlit)
            return "material " + std::to_string(mesh.material) + quotedName(material.name) +
                   " is specular-glossiness, clear-coated, unlit or not opaque, which the minimal frame does not draw";
    }
    if (!scene.lights.empty())
        return "the scene has " + std::to_string(scene.lights.size()) +
               (scene.lights.size() == 1 ? " light" : " lights") + ", which the minimal frame does not draw";
    return {};
}

Result<std::unique_ptr<MinimalFrame>> createMinimalFrame(ContextKind kind, const Scene& scene, int width, int height,
                                                         DepthFormat format) {
    const std::string name = "minimal frame: ";
    if (std::string reason = minimalFrameUnsupported(scene); !reason.empty()) return Error{name + reason};
    Result<std::unique_ptr<GlContext>> context = createContext(kind);
    if (!context) return Error{name + context.error().message};
    auto frame = std::make_unique<Minimal>(std::move(*context), scene);
    if (std::string reason = frame->initialise(width, height, format); !reason.empty()) return Error{name + reason};
    return std::unique_ptr<MinimalFrame>(std::move(frame));
}

}  // namespace frugal
