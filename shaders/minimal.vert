// The bench's minimal frame (gl/MinimalFrame.h): position and normal, nothing else. The same
// arithmetic as mesh.vert; u_mvp and u_normalMatrix are computed on the CPU as GlBackend does.
#version 330 core

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_mvp;
uniform mat3 u_normalMatrix;

out vec3 v_normal;

void main() {
    gl_Position = u_mvp * vec4(a_position, 1.0);
    v_normal = u_normalMatrix * a_normal;
}
