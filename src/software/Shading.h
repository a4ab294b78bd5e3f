// Shading in the software backend: the fragment stage of shaders/mesh.frag as llvmpipe executes it,
// texture sampling as llvmpipe's samplers do it, and the float → unorm8 / 24-bit conversions of
// Mesa's clears. The per-pixel kernels live in Kernels.inl; this header holds their parameters and
// the scalar rules.
//
// Varyings (lp_state_setup.c, lp_bld_interp.c). Every varying of mesh.vert is perspective-correct:
// setup multiplies each vertex value by that vertex's 1/w and builds a plane from the products with
// the arithmetic of Rasterizer.h (4.); per pixel, a = fma(dady, py, fma(dadx, px, a0)) and
// w = 1 / fma(dwdy, py, fma(dwdx, px, w0)) from the plane of the vertices' 1/w, and the value is a · w
// (a division, then a product: lp_build_rcp is a true division on x86).
//
// Fragment arithmetic, in float, in the order NIR gives llvmpipe (no fused operations, as found for
// the vertex stage): base = (factor · colour) · texel, where a mesh without colours uses factor alone
// and a draw without texture uses texel 1 (the GL backend's shader variants have no colour varying
// and sample nothing then: an interpolated constant 1 is p · (1/p), which is 1 − 2⁻²⁴ for about 15 %
// of floats, so interpolating white would darken rare pixels by a step); normalize(v) =
// v · (1 / sqrt(dot(v, v))) with dot(a, b) = (a.z·b.z + a.y·b.y) + a.x·b.x; n = −n on back faces; then
// the BRDF of pipeline/Backend.h in mesh.frag's order of operations (Kernels.inl, `Light`); a = 1, or
// base.a for a blended draw; a masked draw discards where base.a < cutoff (an ordered compare: NaN
// passes).
// Specular-glossiness: f0 = specular · the map's rgb per channel where the BRDF has 0.04, r = 1 −
// glossiness · its alpha, no metal terms (rgb = dielectric + emission).
// Clear coat (mesh.frag's FRUGAL_CLEARCOAT): the coat normal nc = (t · m.x + b · m.y) + n · m.z,
// m the coat map's normalised vector as below, else n (before the base normal map);
// k = coat · (0.04 + 0.96 · (1 − sat(nc · v))⁵); env = mix(dielectric, metal, metallic) · (1 − k)
// + L · k, then · occlusion; with lit the light's mix, rgb = (env + (lit · (1 − k) + E · (ncl ·
// ggx) · k)) + emission · (1 − k), mesh.frag's ggx() at the coat's dots and alpha² = rc⁴.
// Punctual lights (mesh.frag's FRUGAL_LIGHTS, DrawShading::lights): in place of the directional
// light, each light's l and E per pixel as pipeline/Backend.h writes them (FrameLight), its lobe the
// directional light's with E per channel, summed in light order into the dielectric and metal terms
// and the clear coat's (Kernels.inl, Light::shade; each light's l and E from Light::lightAt). A
// frame without them draws the directional light as the one FrameLight it has: the same operations,
// E equal in every channel.
// The maps, each sampled as below at the one uv: metallic · blue, roughness · green; the environment's
// dielectric and metal terms each · (1 + strength · (red − 1)); emission · rgb; the normal map's
// m = normalize(((rgb · 2 − 1) · (scale, scale, 1)), n = normalize((t · m.x + b · m.y) + n · m.z)
// with t and b the normalised tangent and bitangent varyings, negated with n on back faces (the
// vertex stage: tangent = ((c0 · x + c1 · y) + c2 · z) of the model matrix, bitangent =
// cross(normal, tangent) · w, each component a·b − c·d).
// NIR may still reassociate or fold a few of them (divisions by constants, mix): measured against
// llvmpipe, colour is equal on all but a few pixels in 100,000 (by one step; the regression matrix,
// tests/software/RegressionMatrixGLTest.cpp, holds it to one step on at most 0.1 %).
//
// Colour output (lp_bld_conv.c, the AVX 8×32 float → 8-bit path): clamp to [0, 1], multiply by
// 255.0f (rounded to float), round to nearest even. Mesa's float_to_ubyte (u_math.h), used for
// clears, computes bits(f·(255/256) + 32768) instead; the two agree on every float in [0, 1] (checked
// exhaustively), so one rule serves both. That is why clearing 0.3 gives 76: 0.3f·255 rounds to
// exactly 76.5 in float, and 76.5 rounds to the even 76.
//
// Depth clears: a clear of the whole target goes to pipe->clear, util_pack_z: lrint(double(z) ·
// 0xFFFFFF) (0.5 → 0x800000). A clear of part of the target is drawn by the state tracker as a quad
// (st_cb_clear.c clear_with_quad) at z' = z·2 − 1, which the pipeline maps back with
// fma(z', 0.5, 0.5) and stores like any fragment (Rasterizer.h, 5.). The two differ in the last bit
// for some values, so both are reproduced. D32F stores the float itself: a whole clear the (clamped)
// value, a partial one the quad's window z (the quad ignores glClipControl: st_cb_clear.c gives the
// clear its own rasterizer state).
//
// Texture sampling. Texels are RGBA8; a texel is decoded as float(x) · float(1/255).
// - Level of detail (lp_bld_sample.c, with llvmpipe's defaults: no "brilinear", no "rho
//   approximation", one level of detail per 2×2 quad), computed only where a texture has mipmaps
//   or minifies with another filter than it magnifies with. In the quad of pixels (x & ~1, y & ~1)
//   + {0, 1}², the coordinates' differences, top right − top left (x) and bottom left − top left (y),
//   each × the base level's width (s) or height (t); ρ² = max(sx² + tx², sy² + ty²), each square
//   and sum rounded; minified where ρ² > 1 (lod > 0). Mipmaps nearest: level (e + 1) >> 1, e the
//   exponent of ρ² (⌊log2 ρ²⌋). Mipmaps linear: lod = 0.5 · ((e − 1) + m), m the mantissa of ρ² in
//   [1, 2) (gallivm's piece-wise linear log2, exact at powers of two), level ⌊lod⌋ and the next,
//   blended by lod − ⌊lod⌋; at or below level 0, level 0 alone, at or past the last level, the last.
//   The blend: AoS, the 8-bit lerp below with weight ⌊frac · 256⌋; SoA, fma(w, v1 − v0, v0).
//   Coordinates are scaled by each level's own size. Where a vector of pixels mixes minified and
//   magnified quads under different filters, llvmpipe's AoS path picks one filter for all of them (its
//   first quad's); here each pixel takes its own: they differ there, rarely.
// - Wrap modes repeat and clamp-to-edge on both axes take llvmpipe's AoS 8-bit path
//   (lp_bld_sample_aos.c). Linear: s·(size·256) rounded to an integer, minus 128; the low 8 bits are
//   the weight, the rest the texel; the two texels of a row are blended per 8-bit channel as
//   v0 + ((w·(v1 − v0) + 128) >> 8), first along x in both rows, then along y (lp_build_lerp_2d).
//   The +128 is measured (a 2×1 texture blended across 64 pixels for eight pairs of texel values):
//   the lp_build_lerp of current Mesa truncates, 22.3 rounds.
//   Repeat on a power-of-two size masks the texel index; other sizes wrap through fract(s) first.
//   Nearest: ⌊s·size⌋, masked (power of two), fract·size truncated (other sizes), or clamped.
// - Any mirrored-repeat axis sends both axes through the SoA float path (lp_bld_sample_soa.c):
//   coordinates and weights in float, the blend as fma(w, v1 − v0, v0) on decoded texels.
// - An sRGB texture (Texture::srgb, GL_SRGB8_ALPHA8) takes the SoA float path too, its colour
//   channels decoded to linear before filtering, not by the exact curve but by gallivm's polynomial
//   (lp_build_srgb_to_linear), which llvmpipe evaluates as:  x ≤ 15: x · (1 / (12.6 · 255));  else
//   odd · x + even with even = c2 · x² + c0, odd = c3 · x² + c1, each a multiply-add (fused where
//   the CPU has FMA, as the JIT fuses), c = (0.0023, 0.0030 / 255, 0.6935 / 255², 0.3012 / 255³).
//   Alpha is decoded as above. Measured: all 256 values equal llvmpipe's (read back as float from
//   an RGBA32F target), and a 2×1 texture magnified across 256 pixels equals it at every pixel.
//
// Output encoding (shaders/mesh.frag): rgb^(1/2.2) before the conversion to unorm8, as the Khronos
// glTF Sample Renderer encodes for display. Here the power is computed in double and rounded to
// float; llvmpipe's pow (exp2 of y · log2 x, from polynomials) is within 7 ULP of it, which changed
// 1 of 65,536 8-bit values measured, by one step. encodeColor() gives the byte directly from a
// table of the thresholds between bytes.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Image.h>
#include <frugal/Scene.h>

#include "pipeline/Backend.h"
#include "pipeline/ColorEncoding.h"

namespace frugal::sw {

// A texel channel's byte as llvmpipe decodes it: unorm (x · 1/255), or sRGB's colour channels (the
// polynomial above, fused or not as the host's JIT fuses).
using DecodeTable = std::array<float, 256>;

inline const DecodeTable& unormDecode() {
    static const DecodeTable table = [] {
        DecodeTable t{};
        for (int i = 0; i < 256; ++i) t[std::size_t(i)] = float(i) * float(1.0 / 255.0);
        return t;
    }();
    return table;
}

inline const DecodeTable& srgbDecode(bool fused) {
    static const auto make = [](bool fma) {
        // The coefficients as gallivm writes them: float literals, divided in double, stored as float.
        const float c0 = 0.0023f;
        const float c1 = float(double(0.0030f) / double(255.0f));
        const float c2 = float(double(0.6935f) / (double(255.0f) * double(255.0f)));
        const float c3 = float(double(0.3012f) / (double(255.0f) * double(255.0f) * double(255.0f)));
        const float linear = float(1.0 / (12.6 * 255.0));
        const auto mad = [fma](float a, float b, float c) { return fma ? std::fma(a, b, c) : a * b + c; };
        DecodeTable t{};
        for (int i = 0; i < 256; ++i) {
            const float x = float(i);
            if (x <= 15.0f) {
                t[std::size_t(i)] = x * linear;
                continue;
            }
            const float x2 = x * x;
            const float even = mad(c2, x2, c0), odd = mad(c3, x2, c1);
            t[std::size_t(i)] = mad(odd, x, even);
        }
        return t;
    };
    static const DecodeTable fusedTable = make(true), unfusedTable = make(false);
    return fused ? fusedTable : unfusedTable;
}

struct SoftwareTexture {
    struct Level {
        int width = 0, height = 0;
        std::vector<std::uint32_t> texels;  // RGBA8, little-endian (R in the low byte), row 0 = v 0
    };
    // The base level, then its mipmaps when it has them (pipeline/Mipmaps.h).
    std::vector<Level> levels;
    Filter filter = Filter::Linear, minFilter = Filter::Linear;  // magnified; minified, in a level
    MipFilter mipmaps = MipFilter::None;
    // Whether sampling needs the level of detail (the footprint of a pixel's quad, above).
    bool lod() const { return mipmaps != MipFilter::None || minFilter != filter; }
    Wrap wrapS = Wrap::Repeat, wrapT = Wrap::Repeat;
    bool aos = true;  // both axes repeat or clamp-to-edge, not sRGB: llvmpipe's AoS 8-bit path
    const DecodeTable* rgb = &unormDecode();  // how R, G and B are decoded (alpha: unormDecode)
};

// What the shading of one draw needs besides the pixels.
struct DrawShading {
    glm::vec4 factor{1.0f};
    const SoftwareTexture* texture = nullptr;  // the base colour's; nullptr: texel 1.0 exactly
    // The other maps (DrawParams), nullptr = none: the values they scale are used as they are.
    const SoftwareTexture *metallicRoughness = nullptr, *occlusion = nullptr, *emissive = nullptr;
    float occlusionStrength = 1.0f;
    const SoftwareTexture* normalMap = nullptr;  // read in the tangent basis (varyings 12–17)
    float normalScale = 1.0f;
    // KHR_materials_pbrSpecularGlossiness (DrawParams): metallic, roughness and their map unread.
    bool specularGlossiness = false;
    glm::vec3 specular{1.0f};
    float glossiness = 1.0f;
    const SoftwareTexture* specularGlossinessMap = nullptr;
    // KHR_materials_clearcoat (DrawParams): no coat at clearcoat 0.
    float clearcoat = 0.0f, clearcoatRoughness = 0.0f, clearcoatNormalScale = 1.0f;
    const SoftwareTexture *clearcoatMap = nullptr, *clearcoatRoughnessMap = nullptr, *clearcoatNormalMap = nullptr;
    bool colors = true;  // false: the mesh has none, colour 1.0 exactly (not interpolated: no varying)
    float metallic = 1.0f, roughness = 1.0f;
    bool unlit = false;   // rgb = base.rgb
    bool bare = false;    // with unlit: rgb = emission (× the emissive map) + base.rgb (Backend.h)
    bool lambert = false;  // FrameParams::shading Lambert: rgb = base.rgb · (L + Σ E·n·l/π) + emission
    glm::vec3 emission{0.0f};
    // Every texture slot above, nullptr where the draw has none.
    std::array<const SoftwareTexture*, 9> maps() const {
        return {texture,      metallicRoughness,     occlusion,         emissive, normalMap, specularGlossinessMap,
                clearcoatMap, clearcoatRoughnessMap, clearcoatNormalMap};
    }
    bool mapped() const {  // reads uvs
        const auto all = maps();
        return std::any_of(all.begin(), all.end(), [](const SoftwareTexture* t) { return t != nullptr; });
    }
    bool tangentSpace() const { return normalMap || clearcoatNormalMap; }  // reads varyings 12–17
    bool lod() const {  // a texture needs each quad's level of detail
        const auto all = maps();
        return std::any_of(all.begin(), all.end(), [](const SoftwareTexture* t) { return t != nullptr && t->lod(); });
    }
    glm::vec3 eye{0.0f};  // world space
    float environment = 0.0f;            // Lighting
    bool environmentSpecular = true;     // Lighting
    const EnvironmentMap* environmentMap = nullptr;  // Lighting::map
    std::span<const FrameLight> lights;  // Lighting::lights, or its directional light as the only one
    bool writeIds = true;  // read by the rasterizer, which writes ids at the depth test (Kernels.h)
    bool depthTest = true;  // DepthMode::Test; false: no depth read or write (Kernels.h)
    ToneMap tonemap = ToneMap::None;          // FrameParams::tonemap
    AlphaMode alphaMode = AlphaMode::Opaque;  // Mask, Blend: drawn at once, not deferred (Pipeline.cpp)
    float alphaCutoff = 0.5f;
};

// The blend of AlphaMode::Blend on RGBA8 (pipeline/Backend.h: src·a + dst·(1 − a) for rgb, src.a +
// dst.a·(1 − a) for alpha), as llvmpipe blends 8-bit targets: the fragment converted to bytes first
// (as it is stored), then each product of bytes x·y/255 rounded as x·y + (x·y >> 8) + 128, >> 8, with
// 1 − a as 255 − a, and the two terms added, saturating.
inline std::uint32_t blendOver(std::uint32_t src, std::uint32_t dst) {
    const std::uint32_t a = src >> 24, inverse = 255u - a;
    const auto product = [](std::uint32_t x, std::uint32_t y) {
        const std::uint32_t p = x * y;
        return (p + (p >> 8) + 128u) >> 8;
    };
    std::uint32_t out = 0;
    for (int c = 0; c < 4; ++c) {
        const std::uint32_t s = (src >> (8 * c)) & 255u, d = (dst >> (8 * c)) & 255u;
        const std::uint32_t sum = (c < 3 ? product(s, a) : s) + product(d, inverse);
        out |= std::min(sum, 255u) << (8 * c);
    }
    return out;
}

// The same blend on a float (linear) target, as llvmpipe blends float colour: rgb = dst + a·(src − dst)
// (its lerp for this pair of factors), alpha = a + dst.a·(1 − a); `dst` is updated in place.
inline void blendLinear(const float src[4], float dst[4]) {
    const float a = src[3];
    for (int c = 0; c < 3; ++c) dst[c] = dst[c] + a * (src[c] - dst[c]);
    dst[3] = a + dst[3] * (1.0f - a);
}

// float → unorm8 as llvmpipe converts colour (see above).
inline std::uint8_t floatToUnorm8(float f) {
    if (!(f > 0.0f)) return 0;  // also NaN, as float_to_ubyte
    if (f >= 1.0f) return 255;
    return std::uint8_t(std::nearbyint(f * 255.0f));
}

// A multisampled pixel's colour resolved (Rasterizer.h, 6.), as u_blitter's resolve shader computes
// it: each channel's texels (x · 1/255) summed in float from sample 0, times 1/count, converted as
// above. `sample` points at sample 0; the others follow `sampleStride` values apart.
inline std::uint32_t resolveColor(const std::uint32_t* sample, int count, std::size_t sampleStride) {
    const DecodeTable& decode = unormDecode();
    const float scale = 1.0f / float(count);
    std::uint32_t out = 0;
    for (int c = 0; c < 4; ++c) {
        float sum = 0.0f;
        for (int k = 0; k < count; ++k) sum = sum + decode[(sample[std::size_t(k) * sampleStride] >> (8 * c)) & 255u];
        out |= std::uint32_t(floatToUnorm8(sum * scale)) << (8 * c);
    }
    return out;
}

// A multisampled linear pixel's colour resolved: each channel's samples summed in float from sample
// 0, times 1/count, into out[4]. `sample` points at sample 0's four floats; the others follow
// `sampleStride` pixels apart.
inline void resolveLinear(const float* sample, int count, std::size_t sampleStride, float out[4]) {
    const float scale = 1.0f / float(count);
    for (int c = 0; c < 4; ++c) {
        float sum = 0.0f;
        for (int k = 0; k < count; ++k) sum = sum + sample[std::size_t(k) * sampleStride * 4 + std::size_t(c)];
        out[c] = sum * scale;
    }
}

// The value a fragment of depth `z` stores (Rasterizer.h, 5.), as the kernels' raster() computes it
// lane by lane: D24 clamped as MAXPS then MINPS clamp (a NaN gives 0) and rounded to nearest even as
// CVTPS2DQ rounds z · 16777215; D32F clamped as lp_build_depth_clamp does, min(z, 1) then max(·, 0)
// (a NaN gives 1, −0 gives 0), its bits, which order as the floats do.
inline std::uint32_t storedDepth(float z, DepthFormat format) {
    if (format == DepthFormat::D32F) {
        z = z < 1.0f ? z : 1.0f;
        return std::bit_cast<std::uint32_t>(z > 0.0f ? z : 0.0f);
    }
    z = z > 0.0f ? z : 0.0f;
    z = z < 1.0f ? z : 1.0f;
    return std::uint32_t(std::nearbyint(z * 16777215.0f));
}

// A multisampled D24 target's depth (sample 0) after the resolve blit, which fetches it as a float,
// float(d) · (1/16777215) as gallivm converts 24-bit unorm, and writes that as a fragment's depth,
// round_even(z · 16777215) (Rasterizer.h, 5.): not every value survives the round trip. D32F's
// float is copied as it is.
inline std::uint32_t resolveDepth24(std::uint32_t d) {
    const float z = std::fmin(float(d) * float(1.0 / 16777215.0), 1.0f);
    return std::uint32_t(std::nearbyint(z * 16777215.0f));
}

inline std::uint32_t packColor(const glm::vec4& c) {
    return std::uint32_t(floatToUnorm8(c.r)) | std::uint32_t(floatToUnorm8(c.g)) << 8 |
           std::uint32_t(floatToUnorm8(c.b)) << 16 | std::uint32_t(floatToUnorm8(c.a)) << 24;
}

// Depth value of glClear over the whole target (util_pack_z): D24's 24-bit value, or D32F's float
// as it is (its bits). The GL backend clamps to [0, 1] first (std::clamp: −0 stays −0).
inline std::uint32_t clearDepthWhole(float z, DepthFormat format) {
    if (format == DepthFormat::D32F) return std::bit_cast<std::uint32_t>(std::clamp(z, 0.0f, 1.0f));
    const double d = std::fmin(std::fmax(double(z), 0.0), 1.0);
    if (d == 1.0) return 0xFFFFFFu;
    return std::uint32_t(std::lrint(d * double(0xFFFFFF)));
}

// Depth value of glClear over part of the target: a quad through the pipeline at NDC z·2 − 1, with
// the clear's own rasterizer state (GL's clip space whatever glClipControl says: st_cb_clear.c).
// `fused`: the host's viewport transform fuses (Rasterizer.h, 1.). The fragment's clamp to [0, 1]:
// D24 in the unorm conversion; D32F as lp_build_depth_clamp does it, min(z, 1) then max(·, 0).
inline std::uint32_t clearDepthQuad(float z, bool fused, DepthFormat format) {
    z = std::fmin(std::fmax(z, 0.0f), 1.0f);
    const float ndc = z * 2.0f - 1.0f;
    return storedDepth(fused ? std::fma(ndc, 0.5f, 0.5f) : ndc * 0.5f + 0.5f, format);
}

// The environment map's specular levels at (u, v) and level `lod`, as llvmpipe filters the GL
// backend's RGBA32F texture (GL_LINEAR_MIPMAP_LINEAR, u repeated, v clamped to the edge): lod
// clamped to the levels, the two levels around it each bilinear at x = u·width − 0.5 (and y), then
// mixed by lod's fraction; every mix a + w·(b − a), in float.
inline glm::vec3 sampleEnvironment(const EnvironmentMap& map, glm::vec2 uv, float lod) {
    const auto lerp = [](glm::vec3 a, glm::vec3 b, float w) { return a + (b - a) * w; };
    const auto bilinear = [&](int level) {
        const EnvironmentMap::Level& l = map.specular[std::size_t(level)];
        const float x = uv.x * float(l.width) - 0.5f, y = uv.y * float(l.height) - 0.5f;
        const float fx = std::floor(x), fy = std::floor(y);
        const float wx = x - fx, wy = y - fy;
        const auto texel = [&l](int i, int j) {
            i = ((i % l.width) + l.width) % l.width;
            j = std::clamp(j, 0, l.height - 1);
            const float* t = &l.rgba[(std::size_t(j) * std::size_t(l.width) + std::size_t(i)) * 4];
            return glm::vec3(t[0], t[1], t[2]);
        };
        const int x0 = int(fx), y0 = int(fy);
        return lerp(lerp(texel(x0, y0), texel(x0 + 1, y0), wx), lerp(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), wx), wy);
    };
    const float last = float(EnvironmentMap::kSpecularLevels - 1);
    lod = std::clamp(lod, 0.0f, last);
    const float floorLod = std::floor(lod);
    const int level = int(floorLod);
    const glm::vec3 lower = bilinear(level);
    if (level + 1 > int(last)) return lower;
    return lerp(lower, bilinear(level + 1), lod - floorLod);
}

}  // namespace frugal::sw
