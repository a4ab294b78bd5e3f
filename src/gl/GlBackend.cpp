// The OpenGL backend: pipeline/Backend.h on a GL 3.3 core context, all GL through GlApi.
// GlBackendImpl.h declares the class and says which file defines which part; this one holds
// construction, the choice of context, targets, clears, copies and read-back.
//
// Targets: one FBO each with three renderbuffers (renderbuffers, not textures: a target is only
// drawn, cleared, blitted and read, never sampled): RGBA8 (or RGBA32F) colour on attachment 0, R32UI triangle ids
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
// Clears and the id attachment: llvmpipe flushes its scene when the draw-buffer set changes, so a
// clear with draw buffers {colour, ids} followed by draws with {colour} became a full pass of its
// own (docs/gl/README.md). Each target therefore records whether its ids may be non-zero (a draw
// with ids or a copy of such ids into it; a clear of the whole target makes them zero again). While
// they are known to be zero a clear leaves the id attachment alone and uses the draw-buffer set
// already bound, which is the one the next draws of a repeated frame use. The contract of
// Backend::clear (ids to 0) holds either way.
#include "gl/GlBackend.h"

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <utility>

#include <glm/gtc/type_ptr.hpp>

#include "gl/GlApi.h"
#include "gl/GlBackendImpl.h"

namespace frugal {

Result<BackendChoice> parseBackendChoice(const std::string& text) {
    if (text == "auto") return BackendChoice::Auto;
    if (text == "egl") return BackendChoice::Egl;
    if (text == "egl-device") return BackendChoice::EglDevice;
    if (text == "egl-surfaceless") return BackendChoice::EglSurfaceless;
    if (text == "osmesa") return BackendChoice::OsMesa;
    return Error{"unknown GL backend '" + text + "' (expected auto, egl, egl-device, egl-surfaceless or osmesa)"};
}

}  // namespace frugal

namespace frugal::gl {

GlBackend::~GlBackend() {
    if (!initialised_) return;
    activate();
    targets_.forEach([this](GlTarget& t) { deleteTarget(t); });
    meshes_.forEach([this](GlMesh& m) { deleteMesh(m); });
    textures_.forEach([this](GLuint& t) { gl_.DeleteTextures(1, &t); });
    if (environmentTexture_) gl_.DeleteTextures(1, &environmentTexture_);
    for (const auto& [variant, p] : programs_)
        if (p.name) gl_.DeleteProgram(p.name);
    if (streamIbo_) gl_.DeleteBuffers(1, &streamIbo_);
    if (instanceVbo_) gl_.DeleteBuffers(1, &instanceVbo_);
    // context_ goes last (member order), with every object it held already deleted.
}

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
    // Renderbuffers of every format but integer ones take GL_MAX_SAMPLES; the ids' R32UI takes
    // GL_MAX_INTEGER_SAMPLES.
    GLint maxSamples = 1, maxIntegerSamples = 1;
    gl_.GetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    gl_.GetIntegerv(GL_MAX_INTEGER_SAMPLES, &maxIntegerSamples);
    maxSamples_ = std::max(1, std::min(maxSamples, maxIntegerSamples));

    // The full variant has every line of both sources: if it compiles, the others do.
    if (std::string reason = compileVariant(kTextureBit | kColorsBit | kIdsBit); !reason.empty()) return reason;

    // The fixed state (Backend.h): depth writes, no blending (the default), no dithering (Mesa may
    // dither 8-bit targets otherwise), counter-clockwise front faces. The depth test itself is per
    // draw (DepthMode, setDepthTest), its function per target format (setDepthConvention).
    state_.setDepthTest(true);
    state_.setDepthConvention(DepthFormat::D24);
    gl_.DepthMask(GL_TRUE);
    gl_.Disable(GL_DITHER);
    gl_.Disable(GL_BLEND);
    gl_.CullFace(GL_BACK);
    gl_.FrontFace(GL_CCW);
    gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl_.ActiveTexture(GL_TEXTURE0);
    state_.setCull(false);
    state_.setScissor(false);

    const GLenum error = gl_.GetError();
    if (error != GL_NO_ERROR) return glErrorName(error) + " while setting up the GL backend";
    initialised_ = true;
    return {};
}

TargetHandle GlBackend::createTarget(int width, int height, DepthFormat format, int samples, ColorFormat color) {
    // Sizes outside what GL can attach or view are refused, not clamped: the caller reports them.
    if (width <= 0 || height <= 0 || width > maxTargetSize_ || height > maxTargetSize_) return kNoHandle;
    if (!supportsDepthFormat(format) || samples < 1 || samples > maxSamples_) return kNoHandle;
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
    t.colorFormat = color;
    const GLenum formats[3] = {
        color == ColorFormat::Rgba32F ? GLenum(GL_RGBA32F) : GLenum(GL_RGBA8), GL_R32UI,
        format == DepthFormat::D32F ? GLenum(GL_DEPTH_COMPONENT32F) : GLenum(GL_DEPTH_COMPONENT24)};
    for (int i = 0; i < 3; ++i) {
        gl_.BindRenderbuffer(GL_RENDERBUFFER, renderbuffers[i]);
        if (samples > 1)  // at least `samples`, as the driver chooses (the same count for each)
            gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, formats[i], width, height);
        else
            gl_.RenderbufferStorage(GL_RENDERBUFFER, formats[i], width, height);
    }
    if (samples > 1) {
        GLint made = 0;
        gl_.GetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES, &made);
        t.samples = std::max(1, int(made));
    }
    gl_.BindRenderbuffer(GL_RENDERBUFFER, 0);
    gl_.GenFramebuffers(1, &t.fbo);
    state_.bindDrawFbo(t.fbo);
    gl_.FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t.color);
    gl_.FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER, t.ids);
    gl_.FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t.depth);
    const GLenum status = gl_.CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
    const GLenum error = gl_.GetError();  // GL_OUT_OF_MEMORY for a size the heap cannot take
    if (status != GL_FRAMEBUFFER_COMPLETE || error != GL_NO_ERROR) {
        deleteTarget(t);
        return kNoHandle;
    }
    if (t.samples > 1) {  // the single-sampled target readBack resolves into
        t.resolved = createTarget(width, height, format, 1, color);
        if (t.resolved == kNoHandle) {
            deleteTarget(t);
            return kNoHandle;
        }
    }
    const TargetHandle handle = targets_.add(t);
    clear(handle, Rect{0, 0, width, height}, glm::vec4(0.0f), farDepth(format));
    return handle;
}

void GlBackend::destroyTarget(TargetHandle target) {
    GlTarget* t = targets_.find(target);
    if (t == nullptr) return;
    if (t->resolved != kNoHandle) destroyTarget(t->resolved);
    activate();
    deleteTarget(*t);
    targets_.remove(target);
    if (frameTarget_ == target) frameTarget_ = kNoHandle;
    check("destroyTarget");
}

void GlBackend::deleteTarget(GlTarget& t) {
    state_.forgetFramebuffer(t.fbo);  // deleting a bound FBO binds 0
    gl_.DeleteFramebuffers(1, &t.fbo);
    const GLuint renderbuffers[] = {t.color, t.ids, t.depth};
    gl_.DeleteRenderbuffers(3, renderbuffers);
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
    state_.drawInto(*t, clearIds || t->drawSet == DrawSet::ColorAndIds ? DrawSet::ColorAndIds : DrawSet::Color);
    state_.setScissor(true, r);
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
    const std::optional<Rect> region = copyRegion(source, dest, from == to, rect, color || depth || ids);
    if (!region) return;
    activate();
    const bool copyIds = ids && (source->idsDirty || dest->idsDirty);  // zeros onto zeros: nothing to copy
    if (copyIds) dest->idsDirty = dest->idsDirty || source->idsDirty;  // copying zeros keeps them zero
    blit(*source, *dest, *region, color, depth, copyIds);
    check("copy");
}

void GlBackend::blit(GlTarget& source, GlTarget& dest, const Rect& r, bool color, bool depth, bool ids) {
    // Blits obey the scissor test; the rectangle is the blit's own.
    state_.setScissor(false);
    const int x1 = r.x + r.width, y1 = r.y + r.height;
    // A blit writes every enabled draw buffer from the one read buffer, and a normalised colour
    // buffer cannot be blitted into an integer one: colour and ids go in separate blits, each with
    // only the matching draw buffer enabled. Depth rides along with the first blit.
    GLbitfield depthBit = depth ? GL_DEPTH_BUFFER_BIT : 0;
    if (color) {
        state_.readFrom(source, GL_COLOR_ATTACHMENT0);
        state_.drawInto(dest, DrawSet::Color);
        gl_.BlitFramebuffer(r.x, r.y, x1, y1, r.x, r.y, x1, y1, GL_COLOR_BUFFER_BIT | depthBit, GL_NEAREST);
        depthBit = 0;
    }
    if (ids) {
        state_.readFrom(source, GL_COLOR_ATTACHMENT1);
        state_.drawInto(dest, DrawSet::Ids);
        gl_.BlitFramebuffer(r.x, r.y, x1, y1, r.x, r.y, x1, y1, GL_COLOR_BUFFER_BIT | depthBit, GL_NEAREST);
        depthBit = 0;
    }
    if (depthBit) {
        state_.bindReadFbo(source.fbo);
        state_.bindDrawFbo(dest.fbo);
        gl_.BlitFramebuffer(r.x, r.y, x1, y1, r.x, r.y, x1, y1, depthBit, GL_NEAREST);
    }
}

GlTarget& GlBackend::resolve(GlTarget& from, Planes planes) {
    GlTarget& to = *targets_.find(from.resolved);
    // glBlitFramebuffer to one sample: the colour's samples averaged, depth's and the integer ids'
    // sample 0 (llvmpipe's u_blitter).
    blit(from, to, Rect{0, 0, from.width, from.height}, true, planes.depth, planes.ids);
    check("resolve");
    return to;
}

void GlBackend::readBackInto(TargetHandle target, Buffers& out, Planes planes) {
    GlTarget* t = targets_.find(target);
    assert(t != nullptr && "readBack: no such target");
    if (t == nullptr) {
        out = Buffers{};
        return;
    }
    activate();
    if (t->samples > 1) t = &resolve(*t, planes);
    out.width = t->width;
    out.height = t->height;
    const bool linear = t->colorFormat == ColorFormat::Rgba32F;
    out.rgba.resize(out.pixelCount() * 4);
    out.linear.resize(linear ? out.pixelCount() * 4 : 0);
    out.ids.resize(planes.ids ? out.pixelCount() : 0);
    out.depth.resize(planes.depth ? out.pixelCount() : 0);
    // Rows come bottom-up (window origin bottom-left), as Buffers wants. Pack alignment is 1.
    state_.readFrom(*t, GL_COLOR_ATTACHMENT0);
    if (linear)
        gl_.ReadPixels(0, 0, t->width, t->height, GL_RGBA, GL_FLOAT, out.linear.data());
    else
        gl_.ReadPixels(0, 0, t->width, t->height, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
    if (planes.ids) {
        state_.readFrom(*t, GL_COLOR_ATTACHMENT1);
        gl_.ReadPixels(0, 0, t->width, t->height, GL_RED_INTEGER, GL_UNSIGNED_INT, out.ids.data());
    }
    out.depthFormat = t->depthFormat;
    if (!planes.depth) {
        // no depth asked for
    } else if (t->depthFormat == DepthFormat::D32F) {
        gl_.ReadPixels(0, 0, t->width, t->height, GL_DEPTH_COMPONENT, GL_FLOAT, out.depth.data());  // the floats' bits
    } else {
        gl_.ReadPixels(0, 0, t->width, t->height, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, out.depth.data());
        // 32-bit normalised → the stored 24-bit value (see the top of this file).
        for (std::uint32_t& d : out.depth) d >>= 8;
    }
    check("readBack");
    if (linear) encodeLinear(out);
}

}  // namespace frugal::gl

namespace frugal {

Result<std::unique_ptr<Backend>> makeGlBackend(std::unique_ptr<GlContext> context) {
    if (!context) return Error{"no GL context"};
    const std::string kind = contextKindName(context->kind());
    auto backend = std::make_unique<gl::GlBackend>(std::move(context));
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
            line = backend.error().message;
        } else {
            line = context.error().message;
        }
        if (log) log->push_back(line);
        reasons += (reasons.empty() ? "" : "; ") + line;
    }
    return Error{"no usable GL context: " + reasons};
}

}  // namespace frugal
