// The OSMesa context: Mesa's off-screen library (gallium frontend, llvmpipe or softpipe), the
// fallback when EGL is not there. The only file that includes OSMesa. Mesa 25.1 removed OSMesa, so
// libOSMesa is loaded when a context is first asked for (dlopen), not linked: a program or Python
// module built with OSMesa still starts, and renders with EGL, where Mesa has none.
//
// Include order matters here: <GL/glcorearb.h> (through gl/GlApi.h) must come before <GL/osmesa.h>,
// whose <GL/gl.h> defines GL_VERSION_1_1 and would make glcorearb.h skip the 1.1 typedefs.
// clang-format off
#include "gl/GlApi.h"
#include "gl/GlContext.h"

#include <GL/osmesa.h>
// clang-format on

#include <dlfcn.h>

#include <array>
#include <cstdlib>
#include <cstring>
#include <string>

namespace frugal {
namespace {

// The entry points frugal calls, from the library loaded once and kept (contexts and the GL
// functions OSMesaGetProcAddress hands out live in it).
struct OsMesaApi {
    decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
    decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
    decltype(&OSMesaGetCurrentContext) getCurrentContext = nullptr;
    decltype(&OSMesaDestroyContext) destroyContext = nullptr;
    decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
};

Result<OsMesaApi> loadOsMesa() {
    constexpr const char* kLibrary = "libOSMesa.so.8";  // Mesa's soname since 2012 (Debian: libosmesa6)
    // RTLD_GLOBAL, as linking would: Mesa's shared glapi resolves through the global scope.
    void* library = dlopen(kLibrary, RTLD_NOW | RTLD_GLOBAL);
    if (library == nullptr) {
        const char* why = dlerror();
        return Error{std::string("osmesa: cannot load ") + kLibrary + " (" + (why ? why : "no reason given") +
                         "): Mesa 25.1 and later have no OSMesa; Debian 12: apt-get install libosmesa6",
                     ErrorKind::BackendUnavailable};
    }
    OsMesaApi api;
    const auto load = [library]<class F>(F& to, const char* name) {
        to = reinterpret_cast<F>(dlsym(library, name));
        return to != nullptr;
    };
    for (const bool found : {load(api.createContextAttribs, "OSMesaCreateContextAttribs"),
                             load(api.makeCurrent, "OSMesaMakeCurrent"),
                             load(api.getCurrentContext, "OSMesaGetCurrentContext"),
                             load(api.destroyContext, "OSMesaDestroyContext"),
                             load(api.getProcAddress, "OSMesaGetProcAddress")})
        if (!found)
            return Error{std::string("osmesa: ") + kLibrary + " lacks an entry point frugal calls (OSMesa 11.2 or later has them all)",
                         ErrorKind::BackendUnavailable};
    return api;
}

// Loaded on first use, once per process; a context exists only after it loaded.
const Result<OsMesaApi>& osMesa() {
    static const Result<OsMesaApi> api = loadOsMesa();
    return api;
}

class OsMesaContext final : public GlContext {
public:
    explicit OsMesaContext(OSMesaContext context) : context_(context) {}
    OsMesaContext(const OsMesaContext&) = delete;
    OsMesaContext& operator=(const OsMesaContext&) = delete;

    ~OsMesaContext() override {
        forgetCurrentContext(this);
        // Unbind first so the thread is not left with a dangling current context; OSMesa accepts
        // a null context for that.
        const OsMesaApi& api = *osMesa();
        if (api.getCurrentContext() == context_) api.makeCurrent(nullptr, nullptr, 0, 0, 0);
        api.destroyContext(context_);
    }

    ContextKind kind() const override { return ContextKind::OsMesa; }

    void* getProcAddress(const char* name) const override {
        return reinterpret_cast<void*>(osMesa()->getProcAddress(name));
    }

    bool makeCurrent() override {
        // OSMesa needs a colour buffer to be current; frugal draws into FBOs only, so a 1×1 RGBA
        // buffer owned here is enough (it is the window-system framebuffer nobody uses).
        releaseOtherContext(this);  // see gl/GlApi.h: unbinds an EGL context first
        if (osMesa()->makeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1) != GL_TRUE) return false;
        noteCurrentContext(this, [](GlContext*) { osMesa()->makeCurrent(nullptr, nullptr, 0, 0, 0); });
        return true;
    }

    std::string description() const override { return "OSMesa, 1x1 RGBA buffer"; }

private:
    OSMesaContext context_;
    std::array<unsigned char, 4> buffer_{};
};

}  // namespace

Result<std::unique_ptr<GlContext>> createOsMesaContext() {
    // Mesa's gallium OSMesa (22.x, sw_screen_create) takes the screen named by GALLIUM_DRIVER and,
    // when it is set and not empty, does not fall back: any other name gives a null screen that
    // OSMesaCreateContextAttribs dereferences. Measured on Mesa 22.3.6: llvmpipe and softpipe work;
    // swrast, zink, kms_swrast, virpipe, i915, iris, crocus, radeonsi, r300, r600, nouveau, svga,
    // d3d12, lavapipe, "nonexistent", "LLVMPIPE" and "llvmpipe " segfault. So check first.
    if (const char* driver = std::getenv("GALLIUM_DRIVER"); driver != nullptr && *driver != '\0') {
        if (std::strcmp(driver, "llvmpipe") != 0 && std::strcmp(driver, "softpipe") != 0)
            return Error{std::string("osmesa: GALLIUM_DRIVER=") + driver +
                         " is not a driver OSMesa has (llvmpipe, softpipe); unset it or pick one"};
    }

    // No depth/stencil/accum for the 1×1 window buffer: all rendering goes to FBOs.
    // clang-format off
    const int attribs[] = {
        OSMESA_FORMAT, OSMESA_RGBA,
        OSMESA_DEPTH_BITS, 0,
        OSMESA_STENCIL_BITS, 0,
        OSMESA_ACCUM_BITS, 0,
        OSMESA_PROFILE, OSMESA_CORE_PROFILE,
        OSMESA_CONTEXT_MAJOR_VERSION, 3,
        OSMESA_CONTEXT_MINOR_VERSION, 3,
        0};
    // clang-format on
    const Result<OsMesaApi>& api = osMesa();
    if (!api) return api.error();
    OSMesaContext raw = api->createContextAttribs(attribs, nullptr);
    if (raw == nullptr) return Error{"osmesa: OSMesaCreateContextAttribs(OpenGL 3.3 core) failed"};
    auto context = std::make_unique<OsMesaContext>(raw);
    if (!context->makeCurrent()) return Error{"osmesa: OSMesaMakeCurrent on a 1x1 RGBA buffer failed"};
    return std::unique_ptr<GlContext>(std::move(context));
}

}  // namespace frugal
