// The GL entry points frugal uses, loaded by name through the current context's own
// get-proc-address (eglGetProcAddress / OSMesaGetProcAddress). frugal never links libGL or
// libOpenGL and never calls a gl* symbol directly: measured with Mesa 22 and libglvnd, with
// libOpenGL linked before libOSMesa such calls are silent no-ops in an OSMesa context; and a GPU
// vendor's EGL hands out its own entry points. Internal to src/gl/: the only header that includes
// <GL/glcorearb.h>.
//
// Each backend (and the bench's minimal frame, MinimalFrame.cpp) owns one GlApi for its context.
// Pointers from one context are not used with another: Mesa returns context-independent dispatch
// stubs, but EGL does not promise that across vendors.
#pragma once

#include <string>

#include <GL/glcorearb.h>

#include <frugal/Image.h>

#include "pipeline/Backend.h"

namespace frugal {

class GlContext;

// X(type, name): the pointer of type `type` is loaded from "gl" #name and called as gl.name(...).
// Keep the list to what the backend and MinimalFrame call; every entry must exist in GL 3.3 core.
#define FRUGAL_GL_FUNCTIONS(X)                                                 \
    X(PFNGLGETERRORPROC, GetError)                                             \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                                       \
    X(PFNGLGETSTRINGPROC, GetString)                                           \
    X(PFNGLGETSTRINGIPROC, GetStringi)                                         \
    X(PFNGLENABLEPROC, Enable)                                                 \
    X(PFNGLDISABLEPROC, Disable)                                               \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                                           \
    X(PFNGLDEPTHMASKPROC, DepthMask)                                           \
    X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                           \
    X(PFNGLCULLFACEPROC, CullFace)                                             \
    X(PFNGLFRONTFACEPROC, FrontFace)                                           \
    X(PFNGLVIEWPORTPROC, Viewport)                                             \
    X(PFNGLSCISSORPROC, Scissor)                                               \
    X(PFNGLFINISHPROC, Finish)                                                 \
    X(PFNGLFLUSHPROC, Flush)                                                   \
    X(PFNGLCLEARPROC, Clear)                                                   \
    X(PFNGLCLEARCOLORPROC, ClearColor)                                         \
    X(PFNGLCLEARDEPTHPROC, ClearDepth)                                         \
    X(PFNGLDRAWELEMENTSPROC, DrawElements)                                     \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                                       \
    X(PFNGLREADPIXELSPROC, ReadPixels)                                         \
    X(PFNGLREADBUFFERPROC, ReadBuffer)                                         \
    X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                                       \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                               \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                         \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                               \
    X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)               \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                 \
    X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                             \
    X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                       \
    X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                             \
    X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                       \
    X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, RenderbufferStorageMultisample) \
    X(PFNGLGETRENDERBUFFERPARAMETERIVPROC, GetRenderbufferParameteriv)         \
    X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                               \
    X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv)                                   \
    X(PFNGLCLEARBUFFERUIVPROC, ClearBufferuiv)                                 \
    X(PFNGLGENBUFFERSPROC, GenBuffers)                                         \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                   \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                                         \
    X(PFNGLBUFFERDATAPROC, BufferData)                                         \
    X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                                   \
    X(PFNGLGETBUFFERSUBDATAPROC, GetBufferSubData)                             \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                               \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                         \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                               \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)               \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                       \
    X(PFNGLVERTEXATTRIBIPOINTERPROC, VertexAttribIPointer)                     \
    X(PFNGLVERTEXATTRIB2FPROC, VertexAttrib2f)                                 \
    X(PFNGLVERTEXATTRIB3FPROC, VertexAttrib3f)                                 \
    X(PFNGLVERTEXATTRIB4FPROC, VertexAttrib4f)                                 \
    X(PFNGLVERTEXATTRIBI4UIPROC, VertexAttribI4ui)                             \
    X(PFNGLMULTIDRAWELEMENTSPROC, MultiDrawElements)                           \
    X(PFNGLMULTIDRAWARRAYSPROC, MultiDrawArrays)                               \
    X(PFNGLDRAWELEMENTSINSTANCEDPROC, DrawElementsInstanced)                   \
    X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)                       \
    X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor)                       \
    X(PFNGLGENTEXTURESPROC, GenTextures)                                       \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                 \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                                       \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                   \
    X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                         \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                   \
    X(PFNGLCREATESHADERPROC, CreateShader)                                     \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                                     \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                                   \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                                       \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                             \
    X(PFNGLDELETESHADERPROC, DeleteShader)                                     \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                   \
    X(PFNGLATTACHSHADERPROC, AttachShader)                                     \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                                       \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                     \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                           \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                   \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                                         \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                         \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                                           \
    X(PFNGLUNIFORM1UIPROC, Uniform1ui)                                         \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                                           \
    X(PFNGLUNIFORM2FPROC, Uniform2f)                                           \
    X(PFNGLUNIFORM2FVPROC, Uniform2fv)                                         \
    X(PFNGLUNIFORM3FVPROC, Uniform3fv)                                         \
    X(PFNGLUNIFORM4FVPROC, Uniform4fv)                                         \
    X(PFNGLUNIFORMMATRIX3FVPROC, UniformMatrix3fv)                             \
    X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)

struct GlApi {
#define FRUGAL_GL_MEMBER(type, name) type name = nullptr;
    FRUGAL_GL_FUNCTIONS(FRUGAL_GL_MEMBER)
#undef FRUGAL_GL_MEMBER
    // GL 4.5 or ARB_clip_control, for D32F targets: loaded when the context has it (load() checks the
    // version and the extension list, as get-proc-address may answer for any name), else nullptr.
    PFNGLCLIPCONTROLPROC ClipControl = nullptr;

    // Loads every entry point through `context` (which must be current: some implementations only
    // answer for the current API). Returns "" on success, else one line naming the first missing
    // entry point: "GL entry point glBlitFramebuffer not found (egl-surfaceless)".
    std::string load(const GlContext& context);
};

// "GL_INVALID_OPERATION" etc., or "0x…" for a code this list does not know.
std::string glErrorName(GLenum error);

// Compiles and links the embedded shaders/<vertex> + shaders/<fragment> (gl/Shaders.h) in the
// current context, with `defines` (whole lines, "#define FRUGAL_IDS\n") put right after each
// source's #version line. Returns "" and sets *program, or the reason on one line
// ("mesh.frag: compile failed: <log>") and sets *program to 0.
std::string compileProgram(const GlApi& gl, const char* vertex, const char* fragment, const std::string& defines,
                           GLuint* program);

// The text every variant of the mesh program (mesh.vert, mesh.frag) needs before its own: dfg(), the
// split-sum table's fit, written from pipeline/Brdf.h. Pass it to compileProgram with the defines.
std::string meshPreamble();

// The defines of the frame-wide settings every mesh program variant follows: FRUGAL_LAMBERT for
// the Lambert model, FRUGAL_TONEMAP_NEUTRAL or FRUGAL_TONEMAP_ACES, FRUGAL_NO_ENVIRONMENT_SPECULAR
// (FrameParams::shading, tonemap, Lighting::environmentSpecular).
std::string frameDefines(ShadingModel shading, ToneMap tonemap, bool environmentSpecular);
// FRUGAL_DIELECTRIC or FRUGAL_METAL for a material that needs one side of the metal mix alone
// (pipeline/Backend.h, MetalMix); nothing for Both.
std::string metalMixDefine(MetalMix mix);

// The frugal context this thread made current last (GlContext.cpp), kept so that contexts of
// different platforms can take turns on one thread. Measured on Mesa 22 + libglvnd: after
// OSMesaMakeCurrent, eglMakeCurrent of the EGL context that EGL still believes current is a no-op,
// and every GL call then lands in the OSMesa context (Mesa's shared glapi holds one current
// dispatch for both). So every makeCurrent() first calls releaseOtherContext(this), which unbinds
// the previously recorded context through its own platform, then binds and records itself with
// noteCurrentContext. Destructors call forgetCurrentContext. A backend skips makeCurrent when
// currentContext() is already its own. Contexts the host application makes current are not seen.
using ReleaseContext = void (*)(GlContext* context);
void noteCurrentContext(GlContext* context, ReleaseContext release);
void releaseOtherContext(const GlContext* next);
void forgetCurrentContext(const GlContext* context);  // clears the record if it is `context`
const GlContext* currentContext();
// Releases `context` from the calling thread if it is the one current here (through its platform),
// so that another thread can make it current.
void releaseCurrentContext(const GlContext* context);

}  // namespace frugal
