// OpenGL contexts: small RAII classes behind one interface (filament's PlatformEGL/PlatformOSMesa).
// A context owns no framebuffer of its own that frugal draws into: all rendering goes to FBOs, so
// the same code runs on every platform. EGL and OSMesa are each included in exactly one .cpp.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <frugal/Result.h>

namespace frugal {

enum class ContextKind {
    EglDevice,       // EGL_EXT_platform_device: a GPU vendor's EGL, or Mesa's software device
    EglSurfaceless,  // EGL_MESA_platform_surfaceless
    OsMesa,          // Mesa's off-screen library (removed from Mesa 25.1)
};

const char* contextKindName(ContextKind kind);  // "egl-device", "egl-surfaceless", "osmesa"
// The kind contextKindName names (a GL backend's name()), or nullopt ("software", anything else).
std::optional<ContextKind> contextKindNamed(const std::string& name);

class GlContext {
public:
    virtual ~GlContext() = default;
    virtual ContextKind kind() const = 0;
    // Entry point by name, through the platform's own get-proc-address (never a linked libGL).
    virtual void* getProcAddress(const char* name) const = 0;
    virtual bool makeCurrent() = 0;
    // Extra detail for the log, e.g. which EGL device was chosen.
    virtual std::string description() const = 0;
};

// Each returns a current GL 3.3 (or later) core context, or an error naming what is missing
// ("no EGL display: ...", "OSMesa: GALLIUM_DRIVER=foo is not a driver OSMesa has (...)").
// `allowSoftwareDevice`: the EGL device platform on Mesa offers a software device; by default
// only hardware devices are taken there, since surfaceless gives the same llvmpipe.
Result<std::unique_ptr<GlContext>> createEglDeviceContext(bool allowSoftwareDevice = false);
Result<std::unique_ptr<GlContext>> createEglSurfacelessContext();
Result<std::unique_ptr<GlContext>> createOsMesaContext();

// A context of `kind`; the EGL device platform with software devices allowed (a caller that asks
// for a kind by name wants that kind, whatever device it has).
Result<std::unique_ptr<GlContext>> createContext(ContextKind kind);

// Which kinds this build can create, in the order `auto` tries them.
std::vector<ContextKind> availableContextKinds();

}  // namespace frugal
