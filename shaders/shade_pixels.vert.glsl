#version 330 core
// The per-pixel pass (RenderOptions::pixel_shadows and pixel_highlights,
// docs/design/GPU_DESIGN.md "Per-pixel pass"): a part shaded per pixel drawn from the camera, its world
// position, normal and tangent interpolated for shade_pixels.frag.glsl.
// Normals and tangents come from the vertex rectangle (gl_VertexID counts
// the draw's base vertex, so it is the vertex's texel), the pose from the
// part's record, as in the vertex pass.
layout(location = 0) in vec3 a_position;  // part space
layout(location = 3) in vec2 a_texcoord;  // textured parts: glTF texture coordinates
uniform int u_part;
uniform mat4 u_view_projection;
// The depth pre-pass and the shading pass draw the same depths (GL_EQUAL-safe).
invariant gl_Position;
out vec3 v_position;
out vec3 v_local;  // part space: the barycentrics of the triangle's corners (glossy parts)
out vec3 v_normal;
out vec3 v_tangent;
out vec2 v_texcoord;
void main() {
    mat4 transform = part_transform(u_part);
    mat3 normal_matrix = part_normal_matrix(u_part);
    v_position = (transform * vec4(a_position, 1.0)).xyz;
    v_local = a_position;
    v_normal = normal_matrix * fetch(u_normals, gl_VertexID).xyz;
    v_tangent = mat3(transform) * fetch(u_tangents, gl_VertexID).xyz;
    v_texcoord = a_texcoord;
    gl_Position = u_view_projection * vec4(v_position, 1.0);
}
