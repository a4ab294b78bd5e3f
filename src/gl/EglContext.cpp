// EGL contexts: the surfaceless platform (EGL_MESA_platform_surfaceless) and the device platform
// (EGL_EXT_platform_device). The only file that includes EGL.
//
// Both make a desktop-GL 3.3 core context (EGL_KHR_create_context, or EGL 1.5 where the same
// attributes are core) current without any surface (EGL_KHR_surfaceless_context); rendering goes to
// FBOs. The device path is the one a GPU vendor's EGL (NVIDIA's, through libglvnd) takes, so it is
// written by the specs even where only Mesa's software device can exercise it:
// - devices come from eglQueryDevicesEXT (EGL_EXT_device_enumeration, or EGL_EXT_device_base which
//   bundles it with EGL_EXT_device_query);
// - a device whose extension string has EGL_MESA_device_software is llvmpipe, the same renderer
//   the surfaceless platform gives, so it is skipped unless asked for;
// - device displays have no window configs, so when a config must be chosen (no
//   EGL_KHR_no_config_context) EGL_SURFACE_TYPE is 0 ("any"), not the default EGL_WINDOW_BIT.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <sys/stat.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "gl/GlApi.h"
#include "gl/GlContext.h"

namespace frugal {
namespace {

std::string eglErrorName(EGLint error) {
    switch (error) {
#define FRUGAL_EGL_ERROR(e) \
    case e:                 \
        return #e;
        FRUGAL_EGL_ERROR(EGL_SUCCESS)
        FRUGAL_EGL_ERROR(EGL_NOT_INITIALIZED)
        FRUGAL_EGL_ERROR(EGL_BAD_ACCESS)
        FRUGAL_EGL_ERROR(EGL_BAD_ALLOC)
        FRUGAL_EGL_ERROR(EGL_BAD_ATTRIBUTE)
        FRUGAL_EGL_ERROR(EGL_BAD_CONFIG)
        FRUGAL_EGL_ERROR(EGL_BAD_CONTEXT)
        FRUGAL_EGL_ERROR(EGL_BAD_CURRENT_SURFACE)
        FRUGAL_EGL_ERROR(EGL_BAD_DISPLAY)
        FRUGAL_EGL_ERROR(EGL_BAD_MATCH)
        FRUGAL_EGL_ERROR(EGL_BAD_NATIVE_PIXMAP)
        FRUGAL_EGL_ERROR(EGL_BAD_NATIVE_WINDOW)
        FRUGAL_EGL_ERROR(EGL_BAD_PARAMETER)
        FRUGAL_EGL_ERROR(EGL_BAD_SURFACE)
        FRUGAL_EGL_ERROR(EGL_CONTEXT_LOST)
        FRUGAL_EGL_ERROR(EGL_BAD_DEVICE_EXT)
#undef FRUGAL_EGL_ERROR
        default:
            break;
    }
    char text[16];
    std::snprintf(text, sizeof text, "0x%04X", unsigned(error));
    return text;
}

std::string lastEglError() { return eglErrorName(eglGetError()); }

// Whole-token match in a space-separated extension string (a prefix match would take
// "EGL_EXT_device_base" for "EGL_EXT_device_base_foo").
bool hasExtension(const char* list, const char* name) {
    if (list == nullptr) return false;
    const std::size_t length = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += length) {
        const bool startsToken = p == list || p[-1] == ' ';
        const bool endsToken = p[length] == ' ' || p[length] == '\0';
        if (startsToken && endsToken) return true;
    }
    return false;
}

// When the variables that choose Mesa's driver name something it does not have, EGL fails with a
// bare EGL_NOT_INITIALIZED; naming the ones set points at the cause: " (GALLIUM_DRIVER=x is set)".
std::string driverVariablesHint() {
    std::string set;
    int count = 0;
    for (const char* name : {"GALLIUM_DRIVER", "MESA_LOADER_DRIVER_OVERRIDE", "LIBGL_DRIVERS_PATH",
                             "__EGL_VENDOR_LIBRARY_FILENAMES", "__EGL_VENDOR_LIBRARY_DIRS"}) {
        const char* value = std::getenv(name);
        if (value == nullptr || *value == '\0') continue;
        set += std::string(count++ > 0 ? " and " : "") + name + "=" + value;
    }
    return count == 0 ? std::string() : " (" + set + (count > 1 ? " are set)" : " is set)");
}

// Mesa prints its own warnings on stderr ("libEGL warning: egl: failed to create dri2 screen",
// "MESA-LOADER: failed to open swrast ...") before it returns the failure that frugal reports in
// one line. A level the user set is kept: EGL_LOG_LEVEL=debug shows Mesa's reasons.
void quietMesaEglLog() { setenv("EGL_LOG_LEVEL", "fatal", /*overwrite=*/0); }

// A GALLIUM_DRIVER that Mesa's EGL cannot survive, checked before EGL loads it: "" or why.
// virpipe sends GL to a virgl test server on Mesa 22's fixed socket /tmp/.virgl_test; with no
// server there, eglInitialize aborts the process ("lost connection to rendering server"). The
// socket is only looked at, never connected to: a single-client server would take the probe for
// its one client. Every other unknown name fails cleanly (measured: swrast, zink, i915, iris,
// radeonsi, d3d12, nonexistent, ...: EGL_NOT_INITIALIZED).
std::string unsurvivableGalliumDriver() {
    const char* driver = std::getenv("GALLIUM_DRIVER");
    if (driver == nullptr || std::strcmp(driver, "virpipe") != 0) return {};
    constexpr const char* kVtestSocket = "/tmp/.virgl_test";
    struct stat status {};
    if (::stat(kVtestSocket, &status) == 0 && S_ISSOCK(status.st_mode)) return {};
    return std::string("GALLIUM_DRIVER=virpipe needs a virgl test server on ") + kVtestSocket +
           " and there is none (Mesa would abort); unset it or pick llvmpipe or softpipe";
}

// Why there is no EGL at all, or "": libglvnd with no vendor library to load answers an empty
// client extension list.
std::string noVendorReason(const char* clientExtensionList) {
    if (clientExtensionList != nullptr && *clientExtensionList != '\0') return {};
    return "no EGL display: no EGL vendor library answered (libglvnd reads /usr/share/glvnd/egl_vendor.d; "
           "Debian: libegl-mesa0)";
}

// frugal initialises an EGL display and never terminates it; the display lives until the process
// exits (the OS, or Mesa's own exit handler, reclaims it). Why not eglTerminate in the destructor:
// - eglGetPlatformDisplayEXT returns the same EGLDisplay for the same platform and native display,
//   so every surfaceless context in the process (and the host application's, if it has one) shares
//   one display; eglTerminate is not reference counted (EGL_KHR_display_reference, which would make
//   it so, is not in Mesa 22) and invalidates every context on the display at once;
// - a reference count of frugal's own contexts fixes that, but then each new backend after the
//   last one went re-initialises the display, which loads the DRI driver and LLVM again: several
//   times what a new backend costs with the display kept (docs/gl/README.md);
// - Mesa 22 unloads its DRI driver on the last eglTerminate, which turns the driver's own small
//   leaks into reports from an "<unknown module>" that no LSan suppression can name.
// eglInitialize on an initialised display is a no-op that succeeds (EGL 1.5 §3.2), so no
// bookkeeping is needed.
std::string initialiseDisplay(EGLDisplay display) {
    EGLint major = 0, minor = 0;
    if (eglInitialize(display, &major, &minor) != EGL_TRUE) return "eglInitialize failed: " + lastEglError();
    return {};
}

class EglContext final : public GlContext {
public:
    EglContext(ContextKind kind, EGLDisplay display) : kind_(kind), display_(display) {}
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    ~EglContext() override {
        forgetCurrentContext(this);
        if (context_ != EGL_NO_CONTEXT) {
            if (eglGetCurrentContext() == context_) {
                // Releasing applies to the thread's bound API (EGL 1.5 §3.7.3), so bind ours first.
                eglBindAPI(EGL_OPENGL_API);
                eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            }
            eglDestroyContext(display_, context_);
        }
    }

    // Everything after eglGetPlatformDisplayEXT; returns "" or the reason.
    std::string create() {
        std::string reason = initialiseDisplay(display_);
        if (!reason.empty()) return reason;

        const char* extensions = eglQueryString(display_, EGL_EXTENSIONS);
        const char* version = eglQueryString(display_, EGL_VERSION);
        const char* vendor = eglQueryString(display_, EGL_VENDOR);
        description_ = std::string(vendor ? vendor : "?") + " EGL " + (version ? version : "?");

        if (!hasExtension(extensions, "EGL_KHR_surfaceless_context"))
            return "display lacks EGL_KHR_surfaceless_context (" + description_ + ")";
        // The context-version attributes are core in EGL 1.5, else they need EGL_KHR_create_context.
        int major = 0, minor = 0;
        if (version) std::sscanf(version, "%d.%d", &major, &minor);
        if (major * 10 + minor < 15 && !hasExtension(extensions, "EGL_KHR_create_context"))
            return "display lacks EGL 1.5 and EGL_KHR_create_context (" + description_ + ")";
        if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE)
            return "eglBindAPI(EGL_OPENGL_API) failed: " + lastEglError() + " (no desktop GL)";

        EGLConfig config = EGL_NO_CONFIG_KHR;
        if (!hasExtension(extensions, "EGL_KHR_no_config_context") &&
            !hasExtension(extensions, "EGL_MESA_configless_context")) {
            // clang-format off
            const EGLint configAttribs[] = {
                EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                EGL_SURFACE_TYPE, 0,  // any: frugal draws into FBOs
                EGL_NONE};
            // clang-format on
            EGLint count = 0;
            if (eglChooseConfig(display_, configAttribs, &config, 1, &count) != EGL_TRUE || count < 1)
                return "no EGL config with EGL_OPENGL_BIT (eglChooseConfig: " + lastEglError() + ", " +
                       std::to_string(count) + " configs)";
        }

        // clang-format off
        const EGLint contextAttribs[] = {
            EGL_CONTEXT_MAJOR_VERSION_KHR, 3,
            EGL_CONTEXT_MINOR_VERSION_KHR, 3,
            EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR,
            EGL_NONE};
        // clang-format on
        context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, contextAttribs);
        if (context_ == EGL_NO_CONTEXT) return "eglCreateContext(OpenGL 3.3 core) failed: " + lastEglError();
        if (!makeCurrent()) return "eglMakeCurrent without a surface failed: " + lastEglError();
        return {};
    }

    void appendDescription(const std::string& text) { description_ += text; }

    ContextKind kind() const override { return kind_; }

    void* getProcAddress(const char* name) const override {
        // Core GL functions too: Mesa and libglvnd offer EGL_KHR_get_all_proc_addresses.
        return reinterpret_cast<void*>(eglGetProcAddress(name));
    }

    bool makeCurrent() override {
        releaseOtherContext(this);  // see gl/GlApi.h: an OSMesa context would otherwise stay bound
        // eglBindAPI is per thread; a context made on another thread must still bind as OpenGL.
        if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) return false;
        if (eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) != EGL_TRUE) return false;
        noteCurrentContext(this, &EglContext::release);
        return true;
    }

    std::string description() const override { return description_; }

private:
    static void release(GlContext* context) {
        auto* self = static_cast<EglContext*>(context);
        eglBindAPI(EGL_OPENGL_API);
        eglMakeCurrent(self->display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }

    ContextKind kind_;
    EGLDisplay display_;
    EGLContext context_ = EGL_NO_CONTEXT;
    std::string description_;
};

template <class Function>
Function loadEgl(const char* name) {
    return reinterpret_cast<Function>(eglGetProcAddress(name));
}

// Client extensions (EGL_EXT_client_extensions): NULL when that extension itself is missing.
const char* clientExtensions() {
    const char* list = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (list == nullptr) eglGetError();  // EGL_BAD_DISPLAY; not an error worth keeping
    return list;
}

}  // namespace

Result<std::unique_ptr<GlContext>> createEglSurfacelessContext() {
    const std::string who = "egl-surfaceless: ";
    if (std::string driver = unsurvivableGalliumDriver(); !driver.empty()) return Error{who + driver};
    quietMesaEglLog();
    const char* client = clientExtensions();
    if (std::string reason = noVendorReason(client); !reason.empty())
        return Error{who + reason + driverVariablesHint()};
    for (const char* needed : {"EGL_EXT_platform_base", "EGL_MESA_platform_surfaceless"})
        if (!hasExtension(client, needed)) return Error{who + "EGL client extension " + needed + " missing"};
    auto getPlatformDisplay = loadEgl<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
    if (getPlatformDisplay == nullptr) return Error{who + "eglGetPlatformDisplayEXT not found"};

    EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY)
        return Error{who + "no EGL display (eglGetPlatformDisplayEXT failed: " + lastEglError() + ")" +
                     driverVariablesHint()};
    auto context = std::make_unique<EglContext>(ContextKind::EglSurfaceless, display);
    std::string reason = context->create();
    if (!reason.empty()) {
        if (reason.rfind("eglInitialize", 0) == 0) reason = "no EGL display (" + reason + ")";
        return Error{who + reason + driverVariablesHint()};
    }
    return std::unique_ptr<GlContext>(std::move(context));
}

Result<std::unique_ptr<GlContext>> createEglDeviceContext(bool allowSoftwareDevice) {
    const std::string who = "egl-device: ";
    quietMesaEglLog();
    const char* client = clientExtensions();
    if (std::string reason = noVendorReason(client); !reason.empty())
        return Error{who + reason + driverVariablesHint()};
    const bool enumeration =
        hasExtension(client, "EGL_EXT_device_base") ||
        (hasExtension(client, "EGL_EXT_device_enumeration") && hasExtension(client, "EGL_EXT_device_query"));
    if (!enumeration) return Error{who + "EGL client extension EGL_EXT_device_enumeration missing"};
    for (const char* needed : {"EGL_EXT_platform_base", "EGL_EXT_platform_device"})
        if (!hasExtension(client, needed)) return Error{who + "EGL client extension " + needed + " missing"};
    auto queryDevices = loadEgl<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
    auto queryDeviceString = loadEgl<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
    auto getPlatformDisplay = loadEgl<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
    if (!queryDevices || !queryDeviceString || !getPlatformDisplay)
        return Error{who +
                     "eglQueryDevicesEXT, eglQueryDeviceStringEXT or "
                     "eglGetPlatformDisplayEXT not found"};

    EGLint count = 0;
    if (queryDevices(0, nullptr, &count) != EGL_TRUE)
        return Error{who + "eglQueryDevicesEXT failed: " + lastEglError()};
    std::vector<EGLDeviceEXT> devices(std::size_t(count > 0 ? count : 0));
    if (count > 0 && queryDevices(count, devices.data(), &count) != EGL_TRUE)
        return Error{who + "eglQueryDevicesEXT failed: " + lastEglError()};
    devices.resize(std::size_t(count > 0 ? count : 0));

    int skipped = 0;
    std::string failures;
    for (std::size_t i = 0; i < devices.size(); ++i) {
        const char* extensions = queryDeviceString(devices[i], EGL_EXTENSIONS);
        const bool software = hasExtension(extensions, "EGL_MESA_device_software");
        if (software && !allowSoftwareDevice) {
            ++skipped;
            continue;
        }
        std::string name = "device " + std::to_string(i);
        if (software) {
            name += " (software)";
        } else if (hasExtension(extensions, "EGL_EXT_device_drm")) {
            const char* file = queryDeviceString(devices[i], EGL_DRM_DEVICE_FILE_EXT);
            if (file) name += std::string(" (") + file + ")";
        }

        // Mesa's software device is where GALLIUM_DRIVER applies (a GPU's driver is chosen by its PCI id).
        std::string reason = software ? unsurvivableGalliumDriver() : std::string();
        if (reason.empty()) {
            EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
            if (display == EGL_NO_DISPLAY) {
                reason = "eglGetPlatformDisplayEXT failed: " + lastEglError();
            } else {
                auto context = std::make_unique<EglContext>(ContextKind::EglDevice, display);
                reason = context->create();
                if (reason.empty()) {
                    context->appendDescription(", " + name + " of " + std::to_string(devices.size()));
                    return std::unique_ptr<GlContext>(std::move(context));
                }
            }
        }
        failures += (failures.empty() ? "" : "; ") + name + ": " + reason;
    }

    const std::string skippedText =
        skipped > 0 ? std::to_string(skipped) + " software device" + (skipped > 1 ? "s" : "") + " skipped"
                    : std::string();
    if (failures.empty())
        return Error{who + (allowSoftwareDevice ? "no EGL device" : "no hardware EGL device") + " (" +
                     std::to_string(devices.size()) + " found" + (skippedText.empty() ? "" : ", " + skippedText) + ")"};
    return Error{who + "no usable EGL device (" + failures + (skippedText.empty() ? "" : "; " + skippedText) + ")" +
                 driverVariablesHint()};
}

}  // namespace frugal
