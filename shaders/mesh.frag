// Mesh fragment stage: the shading model of render/Backend.h (`Lighting`), written the same way in
// the software backend:
//   base = factor * vertex colour * texture(uv);  rgb = base.rgb * (ambient + diffuse * max(0, n.l))
// with n the normalised interpolated normal, negated on back faces (seen only when double-sided).
#version 330 core

in vec3 v_normal;
in vec4 v_color;
in vec2 v_uv;
flat in uint v_id;

uniform vec4 u_baseColorFactor;
uniform sampler2D u_baseColor;  // a 1x1 white texture when the material has none
uniform vec3 u_toLight;         // world space, unit
uniform float u_ambient;
uniform float u_diffuse;

layout(location = 0) out vec4 o_color;
layout(location = 1) out uint o_id;  // dropped (no draw buffer) when ids are not written

void main() {
    vec4 base = u_baseColorFactor * v_color * texture(u_baseColor, v_uv);
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;
    float lambert = max(0.0, dot(n, u_toLight));
    o_color = vec4(base.rgb * (u_ambient + u_diffuse * lambert), base.a);
    o_id = v_id;
}
