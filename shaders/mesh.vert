// Mesh vertex stage. The arithmetic is kept to exactly what the software reference repeats in
// float: u_mvp = (projection * view) * model and u_normalMatrix = transpose(inverse(mat3(model)))
// are computed on the CPU with glm (GlBackend.cpp); this shader only applies them. The world
// position (for the view direction) is the model matrix's affine part applied column by column,
// ((c0·x + c1·y) + c2·z) + c3, written out so that the batched form, which gets the matrix as
// three rows, computes the same bits.
//
// Variants: GlBackend.cpp puts `#define`s after the #version line, one per input a draw uses:
// FRUGAL_UV (uvs: the material has a map), FRUGAL_TANGENTS (a normal map's tangent basis, the
// surface's or the clear coat's, in world space: the tangent by the model matrix, the bitangent
// cross(normal, tangent) · w), FRUGAL_COLORS
// (vertex colours), FRUGAL_IDS (the id pass), FRUGAL_INSTANCED (a batched draw: the per-draw
// uniforms u_mvp, u_normalMatrix, u_model and u_firstId come per instance from attributes 5–15
// instead, the same values the CPU computes). A varying that is not needed is not there at all:
// each costs llvmpipe setup and interpolation work per triangle and per pixel (measured on the
// bunny frame, 800×600: the colour varying +0.49 ms, the flat id +0.24).
#version 330 core

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

#ifdef FRUGAL_INSTANCED
layout(location = 5) in mat4 i_mvp;           // locations 5–8
layout(location = 9) in mat3 i_normalMatrix;  // locations 9–11
layout(location = 12) in vec4 i_modelRow0;     // the model matrix's first three rows
layout(location = 13) in vec4 i_modelRow1;
layout(location = 14) in vec4 i_modelRow2;
#define MVP i_mvp
#define NORMAL_MATRIX i_normalMatrix
#define MODEL_COLUMN(k) vec3(i_modelRow0[k], i_modelRow1[k], i_modelRow2[k])
#else
uniform mat4 u_mvp;
uniform mat3 u_normalMatrix;
uniform mat4 u_model;
#define MVP u_mvp
#define NORMAL_MATRIX u_normalMatrix
#define MODEL_COLUMN(k) u_model[k].xyz
#endif

out vec3 v_normal;    // world space, not normalised
out vec3 v_position;  // world space

#ifdef FRUGAL_COLORS
layout(location = 2) in vec4 a_color;
out vec4 v_color;
#endif
#ifdef FRUGAL_UV
layout(location = 3) in vec2 a_uv;  // constant (0,0) when the mesh has no uvs
uniform mat3 u_uvTransform;         // KHR_texture_transform, identity without
out vec2 v_uv;
#endif
#ifdef FRUGAL_TANGENTS
layout(location = 5) in vec4 a_tangent;  // never instanced: location 5 is free
out vec3 v_tangent;                      // world space, not normalised
out vec3 v_bitangent;
#endif
#ifdef FRUGAL_IDS
layout(location = 4) in uint a_id;  // triangle source index, from the unindexed id pass
#ifdef FRUGAL_INSTANCED
layout(location = 15) in uint i_firstId;
#define FIRST_ID i_firstId
#else
uniform uint u_firstId;             // a vertex-stage uniform: cheaper to change than a fragment one
#define FIRST_ID u_firstId
#endif
flat out uint v_id;
#endif

void main() {
    gl_Position = MVP * vec4(a_position, 1.0);
    v_normal = NORMAL_MATRIX * a_normal;
    v_position = ((MODEL_COLUMN(0) * a_position.x + MODEL_COLUMN(1) * a_position.y) +
                  MODEL_COLUMN(2) * a_position.z) + MODEL_COLUMN(3);
#ifdef FRUGAL_TANGENTS
    v_tangent = (MODEL_COLUMN(0) * a_tangent.x + MODEL_COLUMN(1) * a_tangent.y) + MODEL_COLUMN(2) * a_tangent.z;
    v_bitangent = cross(v_normal, v_tangent) * a_tangent.w;
#endif
#ifdef FRUGAL_COLORS
    v_color = a_color;
#endif
#ifdef FRUGAL_UV
    v_uv = (u_uvTransform * vec3(a_uv, 1.0)).xy;
#endif
#ifdef FRUGAL_IDS
    v_id = FIRST_ID + a_id;
#endif
}
