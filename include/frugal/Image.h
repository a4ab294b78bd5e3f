// Images a frame is read back as: colour (RGBA8, and with Settings::linear the linear colour as
// float32 too), depth (24-bit or 32-bit float, DepthFormat) and
// triangle ids (32-bit, 0 = background; frugal/Scene.h says how ids are formed).
//
// Rows: row 0 is the bottom row (GL's window origin, bottom-left), as the backends read them back;
// the file writers (frugal/Files.h) put the top row first, and a caller that wants it first reads
// rows from the last. Both backends store the same values, so images compare exactly.
#pragma once

#include <bit>
#include <cstdint>
#include <optional>
#include <vector>

namespace frugal {

inline constexpr std::uint32_t kDepthMax = 0xFFFFFFu;

// The depth buffer's format, and with it the depth convention of the projection that draws into it.
//   D24:  24-bit unsigned normalised; GL's default clip space (clip z in [-w, w]), window z 0 at the
//         near plane and 1 at the far one, test GL_LESS, cleared to 1. A value is window z × 16777215.
//         Its steps are even in window z, which crowds them at the near plane: at distance d between
//         planes n and f it separates depths about d²·(f − n)/(f·n·2²⁴) apart.
//   D32F: 32-bit float with reversed Z: glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE) (clip z in
//         [0, w]), window z 1 at the near plane and 0 at the far one, test GL_GREATER, cleared to 0.
//         Window z falls about as n/d, and a float's steps shrink with its value, so the two cancel:
//         it separates depths about 2⁻²³·d apart at any distance and any near/far ratio.
enum class DepthFormat : std::uint8_t { D24, D32F };

// How linear colour becomes the colour image's values, before the display encoding rgb^(1/2.2) and
// the clamp to [0, 1]: as it is (None, the default), or through a tone-mapping operator as the
// Khronos glTF Sample Renderer applies them (its tonemapping.glsl): PbrNeutral, the Khronos PBR
// Neutral operator (colours below 0.76 keep their hue and value, brighter ones are compressed
// toward white), Aces, Stephen Hill's fit of the ACES filmic curve (its toneMapACES_Hill).
enum class ToneMap : std::uint8_t { None, PbrNeutral, Aces };

// How lit materials are shaded: Full, glTF's metallic-roughness model with every map and extension
// a material uses (the default); Lambert, the fast approximation: base colour (factor, vertex
// colours, texture) times the diffuse light alone (the environment's radiance plus each light's
// E·(n·l)/π) plus the emission, without specular terms and without the metallic-roughness,
// occlusion, normal, specular-glossiness and clear-coat maps. Unlit materials are unlit in both.
enum class ShadingModel : std::uint8_t { Full, Lambert };

inline const char* depthFormatName(DepthFormat format) { return format == DepthFormat::D32F ? "d32f" : "d24"; }
// Window z of the far plane: what a target of `format` is cleared to.
inline float farDepth(DepthFormat format) { return format == DepthFormat::D32F ? 0.0f : 1.0f; }

// Window z in [0, 1] of a stored depth value (D24: exactly value / 16777215, rounded to float;
// D32F: the float whose bits `value` holds, 1 near, 0 far). Both operands of the D24 quotient are
// floats exactly, so the float division is the correctly rounded quotient (the same bits as
// dividing in double and rounding, for every 24-bit value: tested), and vectorises.
inline float windowDepth(DepthFormat format, std::uint32_t value) {
    return format == DepthFormat::D32F ? std::bit_cast<float>(value) : float(value) / float(kDepthMax);
}

struct ColorImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;  // 4 bytes a pixel, R first; rows bottom-up
};

// A frame's colour in linear light (Settings::linear): what the shading computes after tone mapping
// and before the display encoding, unclamped (a bright highlight keeps its value above 1), drawn into
// a float target (RGBA32F), blended and multisample-resolved there in linear light. Alpha is 1 where
// an opaque surface is, a blended surface's alpha over what is below, the background's as cleared.
struct LinearImage {
    int width = 0, height = 0;
    std::vector<float> rgba;  // 4 floats a pixel, R first; rows bottom-up
};

// A render target's colour format: Rgba8 holds the display encoding (8 bits a channel), Rgba32F the
// linear colour (LinearImage).
enum class ColorFormat : std::uint8_t { Rgba8, Rgba32F };

// The display encoding of linear value x as an 8-bit level: x^(1/2.2) (the power in double, rounded
// to float) clamped to [0, 1] and rounded to the nearest of 255 steps; NaN and x ≤ 0 give 0. What
// the software reference writes into an 8-bit target, and how the colour image of a linear frame is
// made from its LinearImage, the same for every backend.
std::uint8_t displayLevel(float x);
// Alpha's level: clamp(a, 0, 1) · 255 rounded to nearest (NaN gives 0).
std::uint8_t alphaLevel(float a);

struct DepthImage {
    int width = 0, height = 0;
    // D24: the 24-bit values. D32F: the floats' bits; window z is never negative, so these order as
    // the floats do and their difference counts the floats between two values (ULPs). Rows bottom-up.
    std::vector<std::uint32_t> values;
    DepthFormat format = DepthFormat::D24;
    // The planes the frame was drawn with (zfar 0 = infinite) and its projection: a depth PNG
    // carries them (frugal/Files.h).
    float znear = 0.0f, zfar = 0.0f;
    bool perspective = true;

    float windowDepth(std::size_t i) const { return frugal::windowDepth(format, values[i]); }
};

struct IdImage {
    int width = 0, height = 0;
    std::vector<std::uint32_t> ids;  // rows bottom-up; 0 = background
};

}  // namespace frugal
