// The GL backend's cached state (internal to src/gl/).
//
// GL state is cached (program, VAO, framebuffers, draw/read buffers per FBO, culling, scissor,
// viewport, texture, uniforms per program) so a call that would not change anything is not made:
// on llvmpipe each such call has a cost per draw, a program switch the largest (docs/gl/README.md;
// `frugal info --state-costs` measures the kinds on the backend that runs).
//
// The calls the cache lets through are the state changes the backend reports (frugal/Stats.h),
// by kind; the backend counts its draws here too.
#pragma once

#include <cstdint>
#include <cstring>
#include <type_traits>

#include <frugal/Image.h>
#include <frugal/Stats.h>

#include "gl/GlApi.h"
#include "pipeline/Buffers.h"

namespace frugal::gl {

// Which colour attachments an FBO draws into; glDrawBuffers is per-FBO state.
enum class DrawSet : std::uint8_t { Unknown, Color, ColorAndIds, Ids };

// A framebuffer object with the per-FBO state cached for it (glDrawBuffers and glReadBuffer are
// per-FBO state, not context state). Each target is one (GlTarget).
struct CachedFramebuffer {
    GLuint fbo = 0;
    DrawSet drawSet = DrawSet::Unknown;
    GLenum readBuffer = GL_NONE;  // GL_NONE = not known
};

// A uniform's value as last set in one program; compared bit for bit. Uniform values are
// per-program state in GL, so each program variant keeps its own (GlProgram).
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

// The context state as last set through it. It starts unknown (nothing assumed of a new context)
// except for the bindings, which start at GL's 0.
// The texture units of a material's maps (GlPrograms.cpp, DrawParams' order), then the environment
// map's (Lighting::map).
constexpr int kTextureUnits = 9;
constexpr int kEnvironmentUnit = kTextureUnits;

class GlStateCache {
public:
    explicit GlStateCache(const GlApi& gl) : gl_(gl) {}
    GlStateCache(const GlStateCache&) = delete;
    GlStateCache& operator=(const GlStateCache&) = delete;

    void bindDrawFbo(GLuint fbo);
    void bindReadFbo(GLuint fbo);
    // Binds `fb` for drawing with the given colour attachments enabled.
    void drawInto(CachedFramebuffer& fb, DrawSet set);
    // Binds `fb` for reading from `attachment`.
    void readFrom(CachedFramebuffer& fb, GLenum attachment);
    void setScissor(bool on, const Rect& rect = {});
    void setViewport(int width, int height);
    void setCull(bool on);
    // DepthMode::Off is GL_DEPTH_TEST disabled, which also stops depth writes (GL 4.5 §14.9.4); the
    // depth mask stays GL_TRUE, so clears (glClearBuffer honours the mask) keep clearing depth.
    void setDepthTest(bool on);
    // Blending for AlphaMode::Blend draws (pipeline/Backend.h): the Khronos renderer's function,
    // set with the first enable. The id attachment is integer, which GL never blends.
    void setBlend(bool on);
    // The clip space and depth test of a target's format (the top of GlBackend.cpp).
    void setDepthConvention(DepthFormat format);
    void bindVao(GLuint vao);
    // Binds `texture` to texture unit `unit` (≤ kEnvironmentUnit); when it binds, that unit becomes the
    // active one (what a glTexParameter after binding a new name needs).
    void bindTexture(GLuint texture, int unit = 0);
    void useProgram(GLuint program);
    // True when `value` must be sent to its uniform in the bound program (CachedUniform::update);
    // counted as an upload.
    template <class T>
    bool uniformChanged(CachedUniform<T>& cached, const std::type_identity_t<T>& value) {
        const bool sent = cached.update(value);
        changes_.uniforms += sent ? 1 : 0;
        return sent;
    }

    // Deleting a bound object binds 0 in its place; the cache must say so, or a new object that
    // gets the freed name back (drivers reuse names; Mesa does for textures and buffers with
    // force_gl_names_reuse) would be taken as bound and never bound. Call these on deleting one.
    void forgetFramebuffer(GLuint fbo);
    void forgetVao(GLuint vao);
    void forgetTexture(GLuint texture);

    void countDraw() { ++changes_.draws; }
    const StateChanges& changes() const { return changes_; }

private:
    // glEnable/glDisable of `capability` unless `cached` (−1 unknown, 0 off, 1 on) says it is so.
    void setEnabled(GLenum capability, int& cached, bool on);
    // True when `name` is not the one `bound` holds: it is then recorded there and counted in
    // `counter` (a kind of StateChanges), and the caller makes the GL call.
    static bool rebinds(GLuint& bound, GLuint name, std::uint64_t& counter);

    const GlApi& gl_;
    GLuint drawFbo_ = 0, readFbo_ = 0, vao_ = 0, program_ = 0;
    GLuint textures_[kEnvironmentUnit + 1] = {};
    int activeUnit_ = 0;  // GL's initial GL_TEXTURE0
    int scissorOn_ = -1, cullOn_ = -1, depthTestOn_ = -1, depthFormat_ = -1, blendOn_ = -1;
    bool blendFuncSet_ = false;
    Rect scissor_{-1, -1, -1, -1};
    int viewportWidth_ = -1, viewportHeight_ = -1;
    StateChanges changes_;
};

}  // namespace frugal::gl
