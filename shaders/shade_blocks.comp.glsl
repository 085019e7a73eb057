#version 430 core
// The vertex pass (docs/design/GPU_DESIGN.md "The vertex pass"): one
// workgroup shades one of the CPU renderer's vertex blocks (up to kShadeBlock
// spatially ordered vertices of one part, src/render/vertex_blocks.h), one
// invocation per vertex, with the CPU's own culling (src/render/shade_block.cpp):
//
//  1. the block's bounding sphere, from its vertices' world positions;
//  2. per candidate occluder of the part (the frame's part-level lists,
//     pack_block_candidates), its light bits for this block: the part-level
//     bits less the lights the block-level tests cull (beyond the field's
//     reach, the part's bounding cone seen from the whole block, the
//     light's cone against the part's sphere), in workgroup memory, those
//     left with no light dropped;
//  3. per vertex, the sum with the CPU's per-vertex tests (point_sum.glsl:
//     light_shares, then per kept candidate occluder_at_vertex and
//     shadow_by_occluder, then point_sum), into the vertex-colour buffer
//     the display pass draws.
//
// The host prepends SVDF_STRIDE, OVDF_STRIDE, MAX_STRIDE, SHADE_BLOCK, LIGHT_WORDS (32 lights a word), LAYERED
// (some part has a specular table), RECORD_BLOCK_LIGHTS (tests only), RAY_TRACED (the
// ray-traced baseline, RenderOptions::gpu_rays), SHADOW_MAPPED (the shadow-map baseline
// may be on), LOCAL_LIGHTS (the frame has sphere lights), MAX_SLICES (BRDF slices per average),
// the layout constants, the shading core, shading_data.glsl, visibility_fields.glsl,
// shadow_map_filter.glsl, with RAY_TRACED bvh_traverse.glsl and ray_visibility.glsl, then point_sum.glsl.

layout(local_size_x = SHADE_BLOCK) in;  // kShadeBlock: a layout takes a literal
// A software rasterizer (llvmpipe) runs both sides of every branch, uniform
// or not: what a pass cannot need is left out at compile time (the defines).

// Per block: (part, first entry of block_vertices, vertex count, 0).
layout(std430, binding = BLOCKS_BINDING) readonly buffer Blocks { ivec4 blocks[]; };
// Per block entry: the vertex's index in the vertex rectangle.
layout(std430, binding = BLOCK_VERTICES_BINDING) readonly buffer BlockVertices { int block_vertices[]; };
// kCounter* (atomic sums over the frame).
layout(std430, binding = COUNTERS_BINDING) buffer Counters { uint counters[]; };
// Per vertex its colour; with LAYERED the specular layer from u_layer_offset.
layout(std430, binding = COLORS_BINDING) writeonly buffer Colors { vec4 colors[]; };

#if RECORD_BLOCK_LIGHTS
// GlRenderer::block_candidate_lights: per block, from its offset, each
// candidate's light words after the block-level tests.
layout(std430, binding = RECORDED_BINDING) writeonly buffer Recorded { uint recorded[]; };
layout(std430, binding = RECORD_OFFSETS_BINDING) readonly buffer RecordOffsets { uint record_offsets[]; };
#endif

uniform int u_block_count;
uniform int u_layer_offset;

shared vec3 s_point[kShadeBlock];
shared vec4 s_sphere;
shared int s_occluder[kShadeBlock];
shared uint s_lights[kShadeBlock * LIGHT_WORDS];
shared int s_kept;  // the chunk's candidates with a light left after the block-level tests

// Step 1: the block sphere (the shading core's point_box, as shade_block).
void block_sphere(int n) {
    PointBox box = point_box(s_point[0]);
    for (int k = 1; k < n; ++k) box = point_box_add(box, s_point[k]);
    vec3 center = point_box_center(box);
    float r2 = 0.0;
    for (int k = 0; k < n; ++k) r2 = farther_squared(r2, center, s_point[k]);
    s_sphere = vec4(center, bounding_radius(r2));
}

// Step 2 for candidate entry `entry` (into candidates[]): its occluder and
// this block's light bits into slot `slot`; returns the (light, occluder)
// pairs the block-level tests culled.
uint block_candidate(uint entry, int slot) {
    int o = int(candidates[entry]);
    float growth = uintBitsToFloat(candidates[entry + 1u]);
    s_occluder[slot] = o;
    vec4 bounds = part_culling[o * kCullingStride + kCullingBounds];
    vec4 reach = part_culling[o * kCullingStride + kCullingReach];
    vec4 field = part_culling[o * kCullingStride + kCullingField];
    vec4 flags = part_culling[o * kCullingStride + kCullingFlags];
    bool outside = u_culling && beyond_reach(s_sphere, reach);
    // The part's bounding cone as the whole block sees it (prepare_occluder).
    vec3 pole = vec3(0.0);
    BlockSpread spread;
    spread.cosine = 1.0;
    spread.sine = 0.0;
    float cone = -1.0;
    if (u_culling && !outside && flags.y > 0.5) {
        vec3 to_part = field.xyz - s_sphere.xyz;
        float d = length(to_part);
        if (d - s_sphere.w > field.w) {
            pole = to_part / d;
            spread = block_spread(s_sphere.w, d);
            cone = ovdf_zoom(d - s_sphere.w, field.w).cone;
        }
    }
    vec4 grown = vec4(s_sphere.xyz, s_sphere.w + max(growth, 0.0));
    uint culled = 0u;
    for (int w = 0; w < LIGHT_WORDS; ++w) {
        uint part_bits = candidates[entry + uint(kCandidateHeader + w)];
        uint bits = outside ? 0u : part_bits;
        if (u_culling && !outside)
            for (uint left = part_bits; left != 0u; left &= left - 1u) {
                int l = w * 32 + findLSB(left);
                if (l >= u_environment_lights) continue;  // a local light: the reach test alone
                vec4 square = fetch(u_lights, kLightTexels * l);
                bool keep = !(flags.x > 0.5 && block_unshadowed(pole, spread, cone, square.xyz, square.w)) &&
                            (growth < 0.0 ||
                             may_shadow_direction(grown, bounds, square.xyz, square_cone_half_angle(square.w)));
                if (!keep) bits &= ~(1u << uint(findLSB(left)));
            }
        culled += uint(bitCount(part_bits) - bitCount(bits));
        s_lights[slot * LIGHT_WORDS + w] = bits;
    }
    return culled;
}

void main() {
    int block = int(gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x);
    if (block >= u_block_count) return;  // the whole workgroup: no barrier is skipped by part of it
    ivec4 record = blocks[block];
    int part = record.x, n = record.z, k = int(gl_LocalInvocationID.x);
    bool in_block = k < n;

    vec3 p = vec3(0.0);
    LocalFrame frame;
    int vertex = 0;
    int seam_partner = -1;
    if (in_block) {
        vertex = block_vertices[record.y + k];
        ivec2 texel = ivec2(vertex & (kArrayWidth - 1), vertex >> kArrayShift);
        vec4 position = texelFetch(u_positions, texel, 0);
        vec4 normal = texelFetch(u_normals, texel, 0);
        vec4 tangent_texel = texelFetch(u_tangents, texel, 0);
        g_pbr_point = texelFetch(u_pbr_points, texel, 0).xy;  // (roughness, metallic) where the material varies
        vec3 tangent = tangent_texel.xyz;
        // The seam partner (w = enclosed + 2(partner + 1), gpu_layout.cpp): its OVDF is left out.
        seam_partner = int(tangent_texel.w * 0.5) - 1;
        mat4 transform = part_transform(part);
        p = (transform * vec4(position.xyz, 1.0)).xyz;
        frame = frame_from_normal_tangent(normalize(part_normal_matrix(part) * normal.xyz), mat3(transform) * tangent);
#if RAY_TRACED
        g_local_vertex = vertex - int(part_texel(part, kSlotVertices).x);
        g_ray_origin = ray_origin(part, vertex, p, mat3(transform), frame.z);
#endif
        vec4 svdf = part_texel(part, kSlotSvdf);
        bool self = u_self_visibility && svdf.z > 0.0 && normal.w >= 0.0;
        g_self_corners = self ? 1 : 0;
        if (self) {
            g_corner_cluster[0] = int(normal.w);
            load_svdf_coefficients(svdf, vertex - int(part_texel(part, kSlotVertices).x), 0);
        }
        s_point[k] = p;
    }
    barrier();
    if (k == 0 && u_culling) block_sphere(n);

    uint live[LIGHT_WORDS];
    if (in_block) light_shares(part, p, frame, live);

    uint lookups = 0u, culled = 0u, tested = 0u;
    uint first = candidates[part], last = candidates[part + 1];
    uint header = uint(u_part_count + 1);  // the offsets
    for (uint chunk = first; chunk < last; chunk += uint(kShadeBlock)) {
        barrier();  // s_sphere written; the previous chunk's slots read
        uint count = min(last - chunk, uint(kShadeBlock));
        if (uint(k) < count) {
            uint entry = header + (chunk + uint(k)) * uint(kCandidateHeader + LIGHT_WORDS);
            culled += block_candidate(entry, k);
#if RECORD_BLOCK_LIGHTS
            for (int w = 0; w < LIGHT_WORDS; ++w)
                recorded[record_offsets[block] + (chunk - first + uint(k)) * uint(LIGHT_WORDS) + uint(w)] =
                    s_lights[k * LIGHT_WORDS + w];
#endif
            for (int w = 0; w < LIGHT_WORDS; ++w) tested += uint(bitCount(candidates[entry + uint(kCandidateHeader + w)]));
        }
        barrier();
        // The candidates the block-level tests left a light, in list order,
        // to the front (in place): the vertices walk only those.
        if (k == 0) {
            int kept = 0;
            for (int j = 0; j < int(count); ++j) {
                bool any = false;
                for (int w = 0; w < LIGHT_WORDS; ++w) any = any || s_lights[j * LIGHT_WORDS + w] != 0u;
                if (!any) continue;
                s_occluder[kept] = s_occluder[j];
                for (int w = 0; w < LIGHT_WORDS; ++w) s_lights[kept * LIGHT_WORDS + w] = s_lights[j * LIGHT_WORDS + w];
                ++kept;
            }
            s_kept = kept;
        }
        barrier();
        if (!in_block) continue;
        for (int j = 0; j < s_kept; ++j) {
            bool any = false;
            for (int w = 0; w < LIGHT_WORDS; ++w) any = any || (s_lights[j * LIGHT_WORDS + w] & live[w]) != 0u;
            if (!any) continue;
            int o = s_occluder[j];
            if (o == seam_partner) continue;  // a seam vertex on its neighbour (CpuRenderer::occluder_factors)
            OccluderAtVertex at = occluder_at_vertex(o, p);
            for (int w = 0; w < LIGHT_WORDS; ++w)
                lookups += shadow_by_occluder(o, at, p, frame, w, s_lights[j * LIGHT_WORDS + w] & live[w], live);
        }
    }

    if (lookups > 0u) atomicAdd(counters[kCounterOccluderLookups], lookups);
    if (tested > 0u) atomicAdd(counters[kCounterBlockPairs], tested);
    if (culled > 0u) atomicAdd(counters[kCounterBlockPairsCulled], culled);
#if RAY_TRACED
    if (g_rays > 0u) atomicAdd(counters[kCounterShadowRays], g_rays);
#endif
    if (!in_block) return;
    vec3 specular;
    vec3 color = point_sum(specular);
    colors[vertex] = vec4(color, 1.0);
#if LAYERED
    colors[u_layer_offset + vertex] = vec4(specular, 1.0);
#endif
}
