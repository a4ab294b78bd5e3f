// The GL backend's cached state: each call is made only when it changes something (GlStateCache.h).
#include "gl/GlStateCache.h"

namespace frugal::gl {

void GlStateCache::bindDrawFbo(GLuint fbo) {
    if (drawFbo_ != fbo) gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    drawFbo_ = fbo;
}

void GlStateCache::bindReadFbo(GLuint fbo) {
    if (readFbo_ != fbo) gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    readFbo_ = fbo;
}

void GlStateCache::drawInto(CachedFramebuffer& fb, DrawSet set) {
    bindDrawFbo(fb.fbo);
    if (fb.drawSet == set) return;
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
    fb.drawSet = set;
}

void GlStateCache::readFrom(CachedFramebuffer& fb, GLenum attachment) {
    bindReadFbo(fb.fbo);
    if (fb.readBuffer != attachment) gl_.ReadBuffer(attachment);
    fb.readBuffer = attachment;
}

void GlStateCache::setEnabled(GLenum capability, int& cached, bool on) {
    if (cached == int(on)) return;
    if (on)
        gl_.Enable(capability);
    else
        gl_.Disable(capability);
    cached = int(on);
    ++changes_.toggles;
}

void GlStateCache::setScissor(bool on, const Rect& rect) {
    setEnabled(GL_SCISSOR_TEST, scissorOn_, on);
    if (on && (rect.x != scissor_.x || rect.y != scissor_.y || rect.width != scissor_.width ||
               rect.height != scissor_.height)) {
        gl_.Scissor(rect.x, rect.y, rect.width, rect.height);
        scissor_ = rect;
    }
}

void GlStateCache::setViewport(int width, int height) {
    if (viewportWidth_ == width && viewportHeight_ == height) return;
    gl_.Viewport(0, 0, width, height);
    viewportWidth_ = width;
    viewportHeight_ = height;
}

void GlStateCache::setCull(bool on) { setEnabled(GL_CULL_FACE, cullOn_, on); }

void GlStateCache::setDepthTest(bool on) { setEnabled(GL_DEPTH_TEST, depthTestOn_, on); }

void GlStateCache::setBlend(bool on) {
    if (on && !blendFuncSet_) {
        gl_.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        blendFuncSet_ = true;
    }
    setEnabled(GL_BLEND, blendOn_, on);
}

void GlStateCache::setDepthConvention(DepthFormat format) {
    if (depthFormat_ == int(format)) return;
    const bool reversed = format == DepthFormat::D32F;
    if (gl_.ClipControl) gl_.ClipControl(GL_LOWER_LEFT, reversed ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
    gl_.DepthFunc(reversed ? GL_GREATER : GL_LESS);
    depthFormat_ = int(format);
}

bool GlStateCache::rebinds(GLuint& bound, GLuint name, std::uint64_t& counter) {
    if (bound == name) return false;
    bound = name;
    ++counter;
    return true;
}

void GlStateCache::bindVao(GLuint vao) {
    if (rebinds(vao_, vao, changes_.meshes)) gl_.BindVertexArray(vao);
}

void GlStateCache::bindTexture(GLuint texture, int unit) {
    if (!rebinds(textures_[unit], texture, changes_.textures)) return;
    if (activeUnit_ != unit) {
        gl_.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
        activeUnit_ = unit;
    }
    gl_.BindTexture(GL_TEXTURE_2D, texture);
}

void GlStateCache::useProgram(GLuint program) {
    if (rebinds(program_, program, changes_.programs)) gl_.UseProgram(program);
}

void GlStateCache::forgetFramebuffer(GLuint fbo) {
    if (drawFbo_ == fbo) drawFbo_ = 0;
    if (readFbo_ == fbo) readFbo_ = 0;
}

void GlStateCache::forgetVao(GLuint vao) {
    if (vao_ == vao) vao_ = 0;
}

void GlStateCache::forgetTexture(GLuint texture) {
    for (GLuint& bound : textures_)
        if (bound == texture) bound = 0;
}

}  // namespace frugal::gl
