#include "gl/GlApi.h"

#include <cstdio>

#include "gl/GlContext.h"

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

}  // namespace frugal
