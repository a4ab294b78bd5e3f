// Mesh vertex stage. The arithmetic is kept to exactly what the software reference repeats in
// float: u_mvp = (projection * view) * model and u_normalMatrix = transpose(inverse(mat3(model)))
// are computed on the CPU with glm (GlBackend.cpp); this shader only applies them.
#version 330 core

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_color;  // constant white when the mesh has no colours
layout(location = 3) in vec2 a_uv;
layout(location = 4) in uint a_id;     // triangle source index, only in the unindexed id pass

uniform mat4 u_mvp;
uniform mat3 u_normalMatrix;
uniform uint u_firstId;  // a vertex-stage uniform: cheaper to change than a fragment one

out vec3 v_normal;  // world space, not normalised
out vec4 v_color;
out vec2 v_uv;
flat out uint v_id;

void main() {
    gl_Position = u_mvp * vec4(a_position, 1.0);
    v_normal = u_normalMatrix * a_normal;
    v_color = a_color;
    v_uv = a_uv;
    v_id = u_firstId + a_id;
}
