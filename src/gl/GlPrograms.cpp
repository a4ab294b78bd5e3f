// The GL backend's program variants (the class: GlBackendImpl.h).
//
// Programs: one variant of shaders/mesh.vert + mesh.frag per combination of what a draw uses — each
// of the material's maps, vertex colours, ids, an unlit material, its alpha mode, specular-glossiness
// — compiled on first use (each also in an instanced form for drawInstances, but for the normal
// map's): 8192 possible, a scene uses a few. A variant leaves out what the draw does not use instead
// of feeding it white (a 1×1 white texture, a white colour varying, an unused flat id varying),
// because each of those costs llvmpipe time per frame (docs/gl/README.md). The white texel is 1.0
// exactly, so leaving it out changes no bit. The interpolated white colour was not always 1.0:
// llvmpipe interpolates a varying as (a·(1/w))·w, which for a = 1 is p·(1/p), 1 − 2⁻²⁴ for about 15 % of
// floats p; so "no vertex colours" is now exactly white, and a few pixels changed by one step
// against the program that fed white (docs/gl/README.md).
// Uniform values are per-program state in GL, so each variant keeps its own uniform cache.
#include <cassert>
#include <cstdio>
#include <string>

#include "gl/GlApi.h"
#include "gl/GlBackendImpl.h"
#include "pipeline/Brdf.h"

namespace frugal {

namespace {

// A float as a GLSL literal that reads back as the same float.
std::string literal(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", double(value));
    std::string s = text;
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return "(" + s + ")";
}

// One channel of brdf::dfg's polynomial as GLSL, in its order.
std::string dfgPolynomial(const char* name, const std::array<float, 18>& c) {
    const auto k = [&](int i) { return literal(c[std::size_t(i)]); };
    return "float " + std::string(name) + "(float x, float r, float u, float f5) {\n" +
           "    float inR = " + k(0) + " + r * (" + k(1) + " + r * (" + k(2) + " + r * (" + k(3) + " + r * (" + k(4) +
           " + r * " + k(5) + "))));\n" +
           "    float inX = x * ((" + k(6) + " + r * (" + k(7) + " + r * " + k(8) + ")) + x * " + k(9) + ");\n" +
           "    float inU = u * (((" + k(10) + " + r * (" + k(11) + " + r * (" + k(12) + " + r * " + k(13) +
           "))) + x * " + k(14) + ") + u * " + k(15) + ");\n" +
           "    float inF = f5 * (" + k(16) + " + r * " + k(17) + ");\n" +
           "    return ((inR + inX) + inU) + inF;\n}\n";
}

}  // namespace

std::string meshPreamble() {
    static const std::string text =
        dfgPolynomial("dfgA", brdf::kDfgA) + dfgPolynomial("dfgB", brdf::kDfgB) +
        "vec2 dfg(float x, float r) {  // pipeline/Brdf.h\n"
        "    float alpha = r * r;\n"
        "    float u = x * inversesqrt(max(x * x + 4.0 * (alpha * alpha), 1.0e-30));\n"
        "    float y = 1.0 - x;\n"
        "    float y2 = y * y;\n"
        "    float f5 = (y2 * y2) * y;\n"
        "    return vec2(min(max(dfgA(x, r, u, f5), 0.0), 1.0), min(max(dfgB(x, r, u, f5), 0.0), 1.0));\n"
        "}\n";
    return text;
}

std::string metalMixDefine(MetalMix mix) {
    return mix == MetalMix::Dielectric ? "#define FRUGAL_DIELECTRIC\n"
           : mix == MetalMix::Metal    ? "#define FRUGAL_METAL\n"
                                       : "";
}

std::string frameDefines(ShadingModel shading, ToneMap tonemap, bool environmentSpecular) {
    std::string defines;
    if (!environmentSpecular) defines += "#define FRUGAL_NO_ENVIRONMENT_SPECULAR\n";
    if (tonemap == ToneMap::PbrNeutral) defines += "#define FRUGAL_TONEMAP_NEUTRAL\n";
    if (tonemap == ToneMap::Aces) defines += "#define FRUGAL_TONEMAP_ACES\n";
    if (shading == ShadingModel::Lambert) defines += "#define FRUGAL_LAMBERT\n";
    return defines;
}

}  // namespace frugal

namespace frugal::gl {

std::string GlBackend::compileVariant(unsigned variant) {
    GlProgram& p = programs_[variant];
    std::string defines = meshPreamble();
    if (variant & kMapBits) defines += "#define FRUGAL_UV\n";
    if (variant & kTextureBit) defines += "#define FRUGAL_TEXTURE\n";
    if (variant & kMetallicRoughnessBit) defines += "#define FRUGAL_METALLIC_ROUGHNESS_MAP\n";
    if (variant & kOcclusionBit) defines += "#define FRUGAL_OCCLUSION_MAP\n";
    if (variant & kEmissiveBit) defines += "#define FRUGAL_EMISSIVE_MAP\n";
    if (variant & kNormalMapBit) defines += "#define FRUGAL_NORMAL_MAP\n";
    if (variant & (kNormalMapBit | kClearcoatNormalMapBit)) defines += "#define FRUGAL_TANGENTS\n";
    if (variant & kColorsBit) defines += "#define FRUGAL_COLORS\n";
    if (variant & kIdsBit) defines += "#define FRUGAL_IDS\n";
    if (variant & kInstancedBit) defines += "#define FRUGAL_INSTANCED\n";
    if (variant & kUnlitBit) defines += "#define FRUGAL_UNLIT\n";
    if (variant & kBareBit) defines += "#define FRUGAL_BARE\n";
    if (variant & kAlphaMaskBit) defines += "#define FRUGAL_ALPHA_MASK\n";
    if (variant & kAlphaBlendBit) defines += "#define FRUGAL_ALPHA_BLEND\n";
    if (variant & kSpecularGlossinessBit) defines += "#define FRUGAL_SPECULAR_GLOSSINESS\n";
    if (variant & kSpecularGlossinessMapBit) defines += "#define FRUGAL_SPECULAR_GLOSSINESS_MAP\n";
    if (variant & kClearcoatBit) defines += "#define FRUGAL_CLEARCOAT\n";
    if (variant & kClearcoatMapBit) defines += "#define FRUGAL_CLEARCOAT_MAP\n";
    if (variant & kClearcoatRoughnessMapBit) defines += "#define FRUGAL_CLEARCOAT_ROUGHNESS_MAP\n";
    if (variant & kClearcoatNormalMapBit) defines += "#define FRUGAL_CLEARCOAT_NORMAL_MAP\n";
    defines += frameDefines(variant & kLambertBit ? ShadingModel::Lambert : ShadingModel::Full,
                            variant & kToneMapNeutralBit ? ToneMap::PbrNeutral
                            : variant & kToneMapAcesBit  ? ToneMap::Aces
                                                         : ToneMap::None,
                            (variant & kNoEnvironmentSpecularBit) == 0);
    if (variant & kLinearBit) defines += "#define FRUGAL_LINEAR_OUTPUT\n";
    defines += metalMixDefine(variant & kDielectricBit ? MetalMix::Dielectric
                              : variant & kMetalBit    ? MetalMix::Metal
                                                       : MetalMix::Both);
    if (variant & kLightsBit) defines += "#define FRUGAL_LIGHTS " + std::to_string(kMaxLights) + "\n";
    if (variant & kEnvironmentMapBit)
        defines += "#define FRUGAL_ENVIRONMENT_MAP " + std::to_string(EnvironmentMap::kSpecularLevels - 1) + ".0\n";
    if (std::string reason = compileProgram(gl_, "mesh.vert", "mesh.frag", defines, &p.name); !reason.empty()) {
        p.failed = true;
        return reason;
    }
    p.mvp = gl_.GetUniformLocation(p.name, "u_mvp");
    p.normalMatrix = gl_.GetUniformLocation(p.name, "u_normalMatrix");
    p.firstId = gl_.GetUniformLocation(p.name, "u_firstId");
    p.model = gl_.GetUniformLocation(p.name, "u_model");
    p.baseColorFactor = gl_.GetUniformLocation(p.name, "u_baseColorFactor");
    p.metallicRoughness = gl_.GetUniformLocation(p.name, "u_metallicRoughness");
    p.eye = gl_.GetUniformLocation(p.name, "u_eye");
    p.lights = gl_.GetUniformLocation(p.name, "u_lights");
    p.toLight = gl_.GetUniformLocation(p.name, "u_toLight");
    p.light = gl_.GetUniformLocation(p.name, "u_light");
    p.environment = gl_.GetUniformLocation(p.name, "u_environment");
    p.uvTransform = gl_.GetUniformLocation(p.name, "u_uvTransform");
    p.emissive = gl_.GetUniformLocation(p.name, "u_emissive");
    p.occlusionStrength = gl_.GetUniformLocation(p.name, "u_occlusionStrength");
    p.normalScale = gl_.GetUniformLocation(p.name, "u_normalScale");
    p.alphaCutoff = gl_.GetUniformLocation(p.name, "u_alphaCutoff");
    p.specularGlossiness = gl_.GetUniformLocation(p.name, "u_specularGlossiness");
    p.clearcoat = gl_.GetUniformLocation(p.name, "u_clearcoat");
    p.environmentSh = gl_.GetUniformLocation(p.name, "u_environmentSh");
    // Each map on its own texture unit, in DrawParams' order (absent samplers: location -1, ignored).
    state_.useProgram(p.name);
    const char* samplers[kTextureUnits] = {
        "u_baseColor",         "u_metallicRoughnessMap",  "u_occlusionMap", "u_emissiveMap",
        "u_normalMap",         "u_specularGlossinessMap", "u_clearcoatMap", "u_clearcoatRoughnessMap",
        "u_clearcoatNormalMap"};
    for (int unit = 0; unit < kTextureUnits; ++unit)
        gl_.Uniform1i(gl_.GetUniformLocation(p.name, samplers[unit]), unit);
    gl_.Uniform1i(gl_.GetUniformLocation(p.name, "u_environmentMap"), kEnvironmentUnit);
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
