#include "gl/GlContext.h"

#include "gl/GlApi.h"

namespace frugal {

namespace {
struct CurrentContext {
    GlContext* context = nullptr;
    ReleaseContext release = nullptr;
};
thread_local CurrentContext tCurrent;
}  // namespace

void noteCurrentContext(GlContext* context, ReleaseContext release) { tCurrent = {context, release}; }

void releaseOtherContext(const GlContext* next) {
    if (tCurrent.context == nullptr || tCurrent.context == next) return;
    tCurrent.release(tCurrent.context);
    tCurrent = {};
}

void forgetCurrentContext(const GlContext* context) {
    if (tCurrent.context == context) tCurrent = {};
}

const GlContext* currentContext() { return tCurrent.context; }

void releaseCurrentContext(const GlContext* context) {
    if (tCurrent.context == nullptr || tCurrent.context != context) return;
    tCurrent.release(tCurrent.context);
    tCurrent = {};
}

const char* contextKindName(ContextKind kind) {
    switch (kind) {
        case ContextKind::EglDevice:
            return "egl-device";
        case ContextKind::EglSurfaceless:
            return "egl-surfaceless";
        case ContextKind::OsMesa:
            return "osmesa";
    }
    return "unknown";
}

std::optional<ContextKind> contextKindNamed(const std::string& name) {
    for (ContextKind kind : {ContextKind::EglDevice, ContextKind::EglSurfaceless, ContextKind::OsMesa})
        if (name == contextKindName(kind)) return kind;
    return std::nullopt;
}

Result<std::unique_ptr<GlContext>> createContext(ContextKind kind) {
    switch (kind) {
        case ContextKind::EglDevice:
            return createEglDeviceContext(/*allowSoftwareDevice=*/true);
        case ContextKind::EglSurfaceless:
            return createEglSurfacelessContext();
        case ContextKind::OsMesa:
            return createOsMesaContext();
    }
    return Error{"unknown context kind"};
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
    return Error{"osmesa: not built (GL/osmesa.h not found, or FRUGAL_WITH_OSMESA=OFF)"};
}
#endif

}  // namespace frugal
