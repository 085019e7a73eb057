#version 430 core
// The per-pixel pass (docs/design/GPU_DESIGN.md "Per-pixel pass"): each pixel of a part
// shaded per pixel takes the whole sum at the point it sees, as the vertex
// pass takes it at a vertex (point_sum.glsl): every light's square in the
// pixel's own frame, the BRDF averages at its own view, sphere lights from
// its own position, and the other parts' occluder factor at the point, from
// the part's candidate occluders with the CPU's per-vertex tests. Two kinds
// of parts come here:
//  * one flat rectangle (a ground, a floor, a wall; RenderOptions::
//    pixel_shadows), whose vertices are often coarser than the shadows on
//    it. It cannot shadow itself: no SVDF is read.
//  * a glossy part (RenderOptions::pixel_highlights), whose highlights are
//    narrower than its triangles. Its self-visibility is the blend of the
//    triangle's corners' SVDFs, each in its corner's frame (u_corners).
// The CPU forms the same pixels from the vertices' kept terms
// (src/render/pixel_shading.cpp).
in vec3 v_position;
in vec3 v_local;
in vec3 v_normal;
in vec3 v_tangent;
in vec2 v_texcoord;
uniform int u_part;
uniform bool u_corners;     // the corners' SVDF blend (glossy parts)
uniform int u_first_index;  // the part's first entry of u_indices
// The samplers u_indices, u_base_color and u_emissive_texture: the host's (src/gl/gpu_interface.h kShadingSamplers).
uniform float u_exposure;
uniform bool u_linear;    // linear radiance (images read back); else exposure and sRGB (the screen)
uniform bool u_textured;  // the diffuse sum times the base colour texture, plus the specular sum
uniform vec3 u_emissive;   // the part's emission, added at the pixel's texture coordinates (src/core/emission.h)
uniform bool u_emissive_textured;  // times u_emissive_texture
uniform bool u_depth_only;  // the depth pre-pass: each pixel is then shaded once, by its nearest part
uniform vec2 u_pbr_factors;  // a material varying per point: its (roughness, metallic) factors (u_metallic_roughness)
layout(location = 0) out vec4 o_color;

// The triangle's corners for self_visibility (g_self_corners = 3).
void set_corners() {
    int first_vertex = int(part_texel(u_part, kSlotVertices).x);
    vec4 svdf = part_texel(u_part, kSlotSvdf);
    mat4 transform = part_transform(u_part);
    mat3 normal_matrix = part_normal_matrix(u_part);
    bool self = u_self_visibility && svdf.z > 0.0;
    vec3 corner_position[3];
    bool corner_enclosed[3];
    for (int c = 0; c < 3; ++c) {
        int local = int(uint_fetch(u_indices, u_first_index + 3 * gl_PrimitiveID + c));
        int vertex = first_vertex + local;
        corner_position[c] = fetch(u_positions, vertex).xyz;
        vec4 normal = fetch(u_normals, vertex);
        vec4 tangent = fetch(u_tangents, vertex);
        g_corner_frame[c] = frame_from_normal_tangent(normalize(normal_matrix * normal.xyz), mat3(transform) * tangent.xyz);
        corner_enclosed[c] = self && mod(tangent.w, 2.0) > 0.5;  // as the CPU: only with the SVDF on; w = e + 2(s + 1)
        g_corner_cluster[c] = self && normal.w >= 0.0 ? int(normal.w) : -1;
        if (g_corner_cluster[c] >= 0) load_svdf_coefficients(svdf, local, c);
    }
    // Barycentric weights of the pixel's point, in the part's space.
    vec3 e0 = corner_position[1] - corner_position[0], e1 = corner_position[2] - corner_position[0];
    vec3 q = v_local - corner_position[0];
    float d00 = dot(e0, e0), d01 = dot(e0, e1), d11 = dot(e1, e1), d20 = dot(q, e0), d21 = dot(q, e1);
    float denominator = d00 * d11 - d01 * d01;
    float u = denominator > 0.0 ? clamp((d11 * d20 - d01 * d21) / denominator, 0.0, 1.0) : 1.0 / 3.0;
    float v = denominator > 0.0 ? clamp((d00 * d21 - d01 * d20) / denominator, 0.0, 1.0) : 1.0 / 3.0;
    float sum = u + v;
    if (sum > 1.0) u /= sum, v /= sum;
    g_corner_weight[0] = 1.0 - u - v;
    g_corner_weight[1] = u;
    g_corner_weight[2] = v;
    // An enclosed corner (the tangent's w, Svdf::enclosed_vertices) gives its
    // share to the others: its SVDF is the inside's, the pixel's point is outside.
    float open = 0.0;
    for (int c = 0; c < 3; ++c) open += corner_enclosed[c] ? 0.0 : g_corner_weight[c];
    if (open > 0.0)
        for (int c = 0; c < 3; ++c) g_corner_weight[c] = corner_enclosed[c] ? 0.0 : g_corner_weight[c] / open;
    g_self_corners = 3;
}

void main() {
    if (u_depth_only) {
        o_color = vec4(0.0);
        return;
    }
    // The side the camera sees, as the CPU's hit point (PosedScene::hit_point):
    // the shading normal turned to the side of the triangle's face that
    // faces the camera (a back face seen through a hole). Near a coarse
    // ball's rim the shading normal itself may face away: the view is then
    // below its horizon and the pixel black, as the CPU's and the truth's.
    vec3 face = cross(dFdx(v_position), dFdy(v_position));
    if (dot(face, u_camera - v_position) < 0.0) face = -face;
    vec3 n = normalize(v_normal);
    if (dot(n, face) < 0.0) n = -n;
    g_self_corners = 0;
    if (u_corners) set_corners();
    LocalFrame frame = frame_from_normal_tangent(n, v_tangent);
    vec3 p = v_position;
    // A material varying per point: the texture at the pixel (pbr_point, src/brdf/pbr_basis.h).
    if (part_texel(u_part, kSlotPbr).w > 0.5)
        g_pbr_point = clamp(u_pbr_factors * texture(u_metallic_roughness, v_texcoord).gb, 0.0, 1.0);
    uint live[LIGHT_WORDS];
    light_shares(u_part, p, frame, live);
    // The part's candidate occluders (pack_block_candidates), each with the
    // lights the part-level tests left it, 32 at a time: first those with a
    // lit light whose reach holds the point (the vertex pass's block test
    // for a block of one point; beyond it the factor is 1), then the lookups
    // for those alone, so that a loop's turns are the candidates some pixel
    // needs (a software rasterizer runs the most turns of its lanes).
    uint header = uint(u_part_count + 1), stride = uint(kCandidateHeader + LIGHT_WORDS);
    uint first = candidates[u_part], last = candidates[u_part + 1];
    for (uint chunk = first; chunk < last; chunk += 32u) {
        uint kept = 0u;
        for (uint j = 0u; j < min(last - chunk, 32u); ++j) {
            uint entry = header + (chunk + j) * stride;
            bool any = false;
            for (int w = 0; w < LIGHT_WORDS; ++w) any = any || (candidates[entry + uint(kCandidateHeader + w)] & live[w]) != 0u;
            vec4 reach = part_culling[int(candidates[entry]) * kCullingStride + kCullingReach];
            if (any && !(u_culling && beyond_reach(vec4(p, 0.0), reach))) kept |= 1u << j;
        }
        for (; kept != 0u; kept &= kept - 1u) {
            uint entry = header + (chunk + uint(findLSB(kept))) * stride;
            int o = int(candidates[entry]);
            OccluderAtVertex at = occluder_at_vertex(o, p);
            for (int w = 0; w < LIGHT_WORDS; ++w)
                shadow_by_occluder(o, at, p, frame, w, candidates[entry + uint(kCandidateHeader + w)] & live[w], live);
        }
    }
    vec3 specular;
    vec3 diffuse = point_sum(specular);
    vec3 color = u_textured ? diffuse * texture(u_base_color, v_texcoord).rgb + specular : diffuse;
    color += u_emissive_textured ? u_emissive * texture(u_emissive_texture, v_texcoord).rgb : u_emissive;
    o_color = u_linear ? vec4(color, 1.0) : vec4(srgb(color * u_exposure), 1.0);
}
