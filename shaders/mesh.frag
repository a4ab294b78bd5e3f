// Mesh fragment stage: the shading model of pipeline/Backend.h (`Lighting`), written the same way in
// the software backend, in linear values:
//   base = factor * vertex colour * texture(uv);  rgb = base.rgb * (ambient + diffuse * max(0, n.l))
// with n the normalised interpolated normal, negated on back faces (seen only when double-sided).
// Factors and vertex colours are linear; an sRGB texture is decoded by its sampler (GL_SRGB8_ALPHA8).
// The colour written is encoded for display as the Khronos glTF Sample Renderer encodes it,
// rgb^(1/2.2) (its linearTosRGB), so that an 8-bit image looks as viewers show the file.
//
// Variants (see mesh.vert): without FRUGAL_COLORS the vertex colour is exactly white and without
// FRUGAL_TEXTURE the texel is, so their factors are left out; without FRUGAL_IDS there is no id
// output. Sampling a 1×1 white texture instead cost +0.64 ms per bunny frame on llvmpipe.
#version 330 core

in vec3 v_normal;

#ifdef FRUGAL_INSTANCED
flat in vec4 v_baseColorFactor;  // per instance (mesh.vert)
#define BASE_COLOR_FACTOR v_baseColorFactor
#else
uniform vec4 u_baseColorFactor;
#define BASE_COLOR_FACTOR u_baseColorFactor
#endif
uniform vec3 u_toLight;  // world space, unit
uniform float u_ambient;
uniform float u_diffuse;

layout(location = 0) out vec4 o_color;

#ifdef FRUGAL_COLORS
in vec4 v_color;
#endif
#ifdef FRUGAL_TEXTURE
in vec2 v_uv;
uniform sampler2D u_baseColor;  // texture unit 0
#endif
#ifdef FRUGAL_IDS
flat in uint v_id;
layout(location = 1) out uint o_id;
#endif

void main() {
    vec4 base = BASE_COLOR_FACTOR;
#ifdef FRUGAL_COLORS
    base = base * v_color;
#endif
#ifdef FRUGAL_TEXTURE
    base = base * texture(u_baseColor, v_uv);
#endif
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;
    float lambert = max(0.0, dot(n, u_toLight));
    vec3 linear = base.rgb * (u_ambient + u_diffuse * lambert);
    o_color = vec4(pow(linear, vec3(1.0 / 2.2)), base.a);
#ifdef FRUGAL_IDS
    o_id = v_id;
#endif
}
