// The yardstick of `frugal-lab bench render`: the same frame as the GL backend draws through
// SceneRenderer, drawn by the fewest GL calls that give the same pixels, on a context of its own.
// One program with position and normal only (mesh.vert + mesh.frag with only the frame's shading model,
// tone mapping and environment specular term as defines), the default light and environment and the material's factors
// as uniforms, one VAO per mesh, glClear of colour and depth with the FBO's default draw buffer, glDrawElements per
// instance, culling per material. No ids, no textures, no vertex colours, no state cache beyond culling: whatever the
// backend spends beyond this is its overhead, and the bench reports frugal ÷ minimal.
//
// Vertex arithmetic is the backend's (gl/GlDraw.cpp): mvp = (projection · view) · model and
// normalMatrix = inverseTranspose(mat3(model)) in float with glm on the CPU; the shaders are the
// backend's own variant without colour, texture and id. So on the scenes it supports the colour and depth
// images equal the backend's bit for bit (tests/gl/MinimalFrameGLTest.cpp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Image.h>
#include <frugal/Result.h>
#include <frugal/Scene.h>

#include "renderer/Research.h"

namespace frugal {

class MinimalFrame {
public:
    virtual ~MinimalFrame() = default;

    // Draws the full frame: clear to `background` and far depth, then every instance of the scene,
    // whole, in instance order (SceneRenderer::renderFrame's frame). `frame.writeIds` is ignored.
    virtual void render(const FrameParams& frame, const std::vector<glm::mat4>& world, const glm::vec4& background) = 0;
    // glFinish: waits until the frame is drawn (for timing).
    virtual void finish() = 0;
    // Makes the context current (before a timed frame, so the switch is not timed).
    virtual void activate() = 0;
    // Colour and, with `depth`, the depth (ids empty), rows bottom-up as Backend::readBack gives
    // them: glReadPixels into memory, as the GL backend reads. `out`'s vectors are reused (resized,
    // never reallocated when already of the size), as the backend reuses a frame's.
    virtual void readBackInto(Buffers& out, bool depth) = 0;
    Buffers readBack(bool depth = true) {
        Buffers out;
        readBackInto(out, depth);
        return out;
    }
    // The same images through pixel buffer objects, in two steps (write-bench's read-back
    // experiment): startReadBack queues glReadPixels of the colour (and the depth) into the buffer
    // of `slot` (0 or 1) and returns without waiting for the frame; endReadBack copies the buffer
    // out (glGetBufferSubData) into `out`, waiting for what it holds. Between the two, the next
    // frame may be drawn: a slot's images are those of the frame drawn before its startReadBack.
    virtual void startReadBack(int slot, bool depth) = 0;
    virtual void endReadBack(int slot, Buffers& out, bool depth) = 0;
};

// "" when MinimalFrame can draw `scene`, else why not: "mesh 0 'x' has vertex colours" or
// "material 1 'y' has a texture" (only meshes some instance draws count).
std::string minimalFrameUnsupported(const Scene& scene);

// A context of `kind` (the EGL device platform with software devices allowed, as
// `--backend egl-device` opens it), a width × height target with depth of `format` (D32F: reversed
// Z, as the backend draws it), and the scene's meshes uploaded. `scene` must outlive the result.
// Errors, "minimal frame: <why>": the context's error, minimalFrameUnsupported's reason, a size the
// context cannot take, no glClipControl for D32F, a shader that does not compile.
Result<std::unique_ptr<MinimalFrame>> createMinimalFrame(ContextKind kind, const Scene& scene, int width, int height,
                                                         DepthFormat format = DepthFormat::D24);

}  // namespace frugal
