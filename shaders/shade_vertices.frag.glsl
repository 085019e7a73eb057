#version 330 core
// The vertex pass (RSL paper §5.2, Figure 8): one fragment per vertex of the
// vertex rectangle computes that vertex's sum (shade_point.glsl, prepended
// by the host with the shading core) and writes it to the render targets
// that become the vertex-colour buffer (src/gl/gl_renderer.h).

uniform int u_vertex_count;

layout(location = 0) out vec4 o_color;
// Textured parts (kSlotSpecular.w = 1): o_color is the diffuse sum at unit
// texture, o_specular the specular table's sum under the same visibility.
layout(location = 1) out vec4 o_specular;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    int vertex = texel.y * kArrayWidth + texel.x;
    if (vertex >= u_vertex_count) {
        o_color = vec4(0.0);
        o_specular = vec4(0.0);
        return;
    }
    vec4 position = texelFetch(u_positions, texel, 0);
    vec4 normal = texelFetch(u_normals, texel, 0);
    vec3 tangent = texelFetch(u_tangents, texel, 0).xyz;
    int part = int(position.w);
    mat4 transform = part_transform(part);
    mat3 normal_matrix = part_normal_matrix(part);
    vec4 svdf = part_texel(part, kSlotSvdf);
    int local_vertex = vertex - int(part_texel(part, kSlotVertices).x);

    vec3 p = (transform * vec4(position.xyz, 1.0)).xyz;
    LocalFrame frame = frame_from_normal_tangent(normalize(normal_matrix * normal.xyz), mat3(transform) * tangent);
    bool self = u_self_visibility && svdf.z > 0.0 && normal.w >= 0.0;
    g_self_corners = self ? 1 : 0;
    if (self) {
        g_corner_cluster[0] = int(normal.w);
        load_svdf_coefficients(svdf, local_vertex, 0);
    }
    PointShade shaded = shade_point(part, p, frame);
    o_color = vec4(shaded.color, 1.0);
    o_specular = vec4(shaded.specular, 1.0);
}
