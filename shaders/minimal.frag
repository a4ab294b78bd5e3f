// The bench's minimal frame (gl/MinimalFrame.h): the shading model of render/Backend.h with white
// vertex colour and no texture, written as in mesh.frag so that the pixels are the same.
#version 330 core

in vec3 v_normal;

uniform vec4 u_baseColorFactor;
uniform vec3 u_toLight;
uniform float u_ambient;
uniform float u_diffuse;

out vec4 o_color;

void main() {
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;
    float lambert = max(0.0, dot(n, u_toLight));
    o_color = vec4(u_baseColorFactor.rgb * (u_ambient + u_diffuse * lambert), u_baseColorFactor.a);
}
