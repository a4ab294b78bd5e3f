// The GL backend's program variants (the class: GlBackendImpl.h).
//
// Programs: one variant of shaders/mesh.vert + mesh.frag per combination of what a draw uses — a
// texture, vertex colours, ids — compiled on first use (at most 8, each also in an instanced form
// for drawInstances: 16 in all). A variant leaves out what the draw does not use instead of feeding
// it white (a 1×1 white texture, a white colour varying, an unused flat id varying), because each of
// those costs llvmpipe time per frame (docs/gl/README.md). The white texel is 1.0 exactly, so
// leaving it out changes no bit. The interpolated white colour was not always 1.0: llvmpipe
// interpolates a varying as (a·(1/w))·w, which for a = 1 is p·(1/p), 1 − 2⁻²⁴ for about 15 % of
// floats p; so "no vertex colours" is now exactly white, and a few pixels changed by one step
// against the program that fed white (docs/gl/README.md).
// Uniform values are per-program state in GL, so each variant keeps its own uniform cache.
#include <cassert>
#include <cstdio>
#include <string>

#include "gl/GlApi.h"
#include "gl/GlBackendImpl.h"

namespace frugal::gl {

std::string GlBackend::compileVariant(unsigned variant) {
    GlProgram& p = programs_[variant];
    std::string defines;
    if (variant & kTextureBit) defines += "#define FRUGAL_TEXTURE\n";
    if (variant & kColorsBit) defines += "#define FRUGAL_COLORS\n";
    if (variant & kIdsBit) defines += "#define FRUGAL_IDS\n";
    if (variant & kInstancedBit) defines += "#define FRUGAL_INSTANCED\n";
    if (std::string reason = compileProgram(gl_, "mesh.vert", "mesh.frag", defines, &p.name); !reason.empty()) {
        p.failed = true;
        return reason;
    }
    p.mvp = gl_.GetUniformLocation(p.name, "u_mvp");
    p.normalMatrix = gl_.GetUniformLocation(p.name, "u_normalMatrix");
    p.firstId = gl_.GetUniformLocation(p.name, "u_firstId");
    p.baseColorFactor = gl_.GetUniformLocation(p.name, "u_baseColorFactor");
    p.toLight = gl_.GetUniformLocation(p.name, "u_toLight");
    p.ambient = gl_.GetUniformLocation(p.name, "u_ambient");
    p.diffuse = gl_.GetUniformLocation(p.name, "u_diffuse");
    if (variant & kTextureBit) {
        state_.useProgram(p.name);
        gl_.Uniform1i(gl_.GetUniformLocation(p.name, "u_baseColor"), 0);  // texture unit 0
    }
    return {};
}

GlProgram* GlBackend::program(unsigned variant) {
    GlProgram& p = programs_[variant];
    if (p.name == 0 && !p.failed) {
        if (std::string reason = compileVariant(variant); !reason.empty()) {
            std::fprintf(stderr, "frugal: %s: program variant %u: %s\n", name().c_str(), variant, reason.c_str());
            assert(false && "a mesh program variant does not compile");
        }
    }
    if (p.name == 0) return nullptr;
    state_.useProgram(p.name);
    return &p;
}

}  // namespace frugal::gl
