#include "gl/GlContext.h"

#include "gl/GlApi.h"

namespace frugal {

namespace {
thread_local const GlContext* tCurrentContext = nullptr;
}  // namespace

void noteCurrentContext(const GlContext* context) { tCurrentContext = context; }
void forgetCurrentContext(const GlContext* context) {
    if (tCurrentContext == context) tCurrentContext = nullptr;
}
const GlContext* currentContext() { return tCurrentContext; }

const char* contextKindName(ContextKind kind) {
    switch (kind) {
        case ContextKind::EglDevice: return "egl-device";
        case ContextKind::EglSurfaceless: return "egl-surfaceless";
        case ContextKind::OsMesa: return "osmesa";
    }
    return "unknown";
}

std::vector<ContextKind> availableContextKinds() {
    std::vector<ContextKind> kinds;
#if FRUGAL_HAVE_EGL
    kinds.push_back(ContextKind::EglDevice);
    kinds.push_back(ContextKind::EglSurfaceless);
#endif
#if FRUGAL_HAVE_OSMESA
    kinds.push_back(ContextKind::OsMesa);
#endif
    return kinds;
}

// A build without one of the platforms still links: the factory says it was left out.
#if !FRUGAL_HAVE_EGL
Result<std::unique_ptr<GlContext>> createEglDeviceContext(bool) {
    return Error{"egl-device: not built (FRUGAL_WITH_EGL=OFF)"};
}
Result<std::unique_ptr<GlContext>> createEglSurfacelessContext() {
    return Error{"egl-surfaceless: not built (FRUGAL_WITH_EGL=OFF)"};
}
#endif
#if !FRUGAL_HAVE_OSMESA
Result<std::unique_ptr<GlContext>> createOsMesaContext() {
    return Error{"osmesa: not built (GL/osmesa.h or libOSMesa not found, or FRUGAL_WITH_OSMESA=OFF)"};
}
#endif

}  // namespace frugal
