#include "gl/GlApi.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "gl/GlContext.h"
#include "gl/Shaders.h"

namespace frugal {

std::string GlApi::load(const GlContext& context) {
    // A function pointer and void* may differ in representation by the letter of C++, but POSIX
    // (dlsym) and both get-proc-address APIs require the round trip to work.
#define FRUGAL_GL_LOAD(type, name)                                     \
    name = reinterpret_cast<type>(context.getProcAddress("gl" #name)); \
    if (name == nullptr)                                               \
        return std::string("GL entry point gl" #name " not found (") + contextKindName(context.kind()) + ")";
    FRUGAL_GL_FUNCTIONS(FRUGAL_GL_LOAD)
#undef FRUGAL_GL_LOAD
    GLint major = 0, minor = 0, extensions = 0;
    GetIntegerv(GL_MAJOR_VERSION, &major);
    GetIntegerv(GL_MINOR_VERSION, &minor);
    bool clipControl = major * 10 + minor >= 45;
    GetIntegerv(GL_NUM_EXTENSIONS, &extensions);
    for (GLint i = 0; i < extensions && !clipControl; ++i) {
        const GLubyte* name = GetStringi(GL_EXTENSIONS, GLuint(i));
        clipControl = name != nullptr && std::strcmp(reinterpret_cast<const char*>(name), "GL_ARB_clip_control") == 0;
    }
    if (clipControl) ClipControl = reinterpret_cast<PFNGLCLIPCONTROLPROC>(context.getProcAddress("glClipControl"));
    return {};
}

std::string glErrorName(GLenum error) {
    switch (error) {
        case GL_NO_ERROR:
            return "GL_NO_ERROR";
        case GL_INVALID_ENUM:
            return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE:
            return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION:
            return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION:
            return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY:
            return "GL_OUT_OF_MEMORY";
        default:
            break;
    }
    char text[16];
    std::snprintf(text, sizeof text, "0x%04X", unsigned(error));
    return text;
}

namespace {

// An info log on one line: newlines become "; ", trailing blanks and NULs go.
std::string oneLine(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ' || text.back() == '\0')) text.pop_back();
    std::string out;
    for (char c : text) {
        if (c == '\n')
            out += "; ";
        else if (c != '\r')
            out += c;
    }
    return out;
}

}  // namespace

std::string compileProgram(const GlApi& gl, const char* vertex, const char* fragment, const std::string& defines,
                           GLuint* program) {
    *program = 0;
    const char* names[] = {vertex, fragment};
    const GLenum stages[] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER};
    GLuint shaders[2] = {0, 0};
    std::string reason;
    for (int i = 0; i < 2 && reason.empty(); ++i) {
        const char* source = shaders::find(names[i]);
        if (source == nullptr) {
            reason = std::string("shader ") + names[i] + " is not embedded";
            break;
        }
        // #version must come first (comments aside): the defines go right after its line, the
        // first that starts with it.
        const char* version = std::strncmp(source, "#version", 8) == 0 ? source : std::strstr(source, "\n#version");
        const char* rest = version ? std::strchr(version + 1, '\n') : nullptr;
        if (rest == nullptr) {
            reason = std::string(names[i]) + ": no #version line";
            break;
        }
        ++rest;
        const char* parts[] = {source, defines.c_str(), rest};
        const GLint lengths[] = {GLint(rest - source), GLint(defines.size()), -1};
        shaders[i] = gl.CreateShader(stages[i]);
        gl.ShaderSource(shaders[i], 3, parts, lengths);
        gl.CompileShader(shaders[i]);
        GLint ok = GL_FALSE, length = 0;
        gl.GetShaderiv(shaders[i], GL_COMPILE_STATUS, &ok);
        if (ok != GL_TRUE) {
            gl.GetShaderiv(shaders[i], GL_INFO_LOG_LENGTH, &length);
            std::string log(std::size_t(std::max(length, 1)), '\0');
            gl.GetShaderInfoLog(shaders[i], GLsizei(log.size()), nullptr, log.data());
            reason = std::string(names[i]) + ": compile failed: " + oneLine(log);
        }
    }
    if (reason.empty()) {
        *program = gl.CreateProgram();
        gl.AttachShader(*program, shaders[0]);
        gl.AttachShader(*program, shaders[1]);
        gl.LinkProgram(*program);
        GLint ok = GL_FALSE, length = 0;
        gl.GetProgramiv(*program, GL_LINK_STATUS, &ok);
        if (ok != GL_TRUE) {
            gl.GetProgramiv(*program, GL_INFO_LOG_LENGTH, &length);
            std::string log(std::size_t(std::max(length, 1)), '\0');
            gl.GetProgramInfoLog(*program, GLsizei(log.size()), nullptr, log.data());
            reason = std::string(vertex) + " + " + fragment + ": link failed: " + oneLine(log);
            gl.DeleteProgram(*program);
            *program = 0;
        }
    }
    for (GLuint shader : shaders)
        if (shader) gl.DeleteShader(shader);  // flagged; freed with the program
    return reason;
}

}  // namespace frugal
