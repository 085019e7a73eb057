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
//  3. per vertex and light, the BRDF and self-visibility (the light's share
//     before the other parts' shadows);
//  4. per vertex and candidate, the light-independent half of the lookup
//     once (the point in the occluder's frame, the box sides, the bounding
//     cone, and on first need the OVDF location), then each of the
//     candidate's lights that the vertex's own tests keep;
//  5. the sum, into the vertex-colour buffer the display pass draws.
//
// The host prepends MAX_STRIDE, SVDF_STRIDE, OVDF_STRIDE, SHADE_BLOCK, LIGHT_WORDS (32 lights a word), LAYERED
// (some part has a specular table), RECORD_BLOCK_LIGHTS (tests only), RAY_TRACED (the
// ray-traced baseline, RenderOptions::gpu_rays), SHADOW_MAPPED (the shadow-map baseline
// may be on), LOCAL_LIGHTS (the frame has sphere lights), MAX_SLICES (BRDF slices per average),
// the layout constants, the shading core,
// shading_data.glsl, visibility_fields.glsl, shade_point.glsl and, with RAY_TRACED,
// bvh_traverse.glsl and ray_visibility.glsl.

layout(local_size_x = SHADE_BLOCK) in;  // kShadeBlock: a layout takes a literal
// A software rasterizer (llvmpipe) runs both sides of every branch, uniform
// or not: what a pass cannot need is left out at compile time (the defines).

// Per block: (part, first entry of block_vertices, vertex count, 0).
layout(std430, binding = 0) readonly buffer Blocks { ivec4 blocks[]; };
// Per block entry: the vertex's index in the vertex rectangle.
layout(std430, binding = 1) readonly buffer BlockVertices { int block_vertices[]; };
// The frame's candidates (gpu_layout.h pack_block_candidates): parts + 1
// offsets, then per candidate kCandidateHeader + LIGHT_WORDS words.
layout(std430, binding = 2) readonly buffer Candidates { uint candidates[]; };
// Per part, kCullingStride vec4 (gpu_layout.h pack_part_culling).
layout(std430, binding = 3) readonly buffer PartCulling { vec4 part_culling[]; };
// kCounter* (atomic sums over the frame).
layout(std430, binding = 4) buffer Counters { uint counters[]; };
// Per vertex its colour; with LAYERED the specular layer from u_layer_offset.
layout(std430, binding = 5) writeonly buffer Colors { vec4 colors[]; };

#if RECORD_BLOCK_LIGHTS
// GlRenderer::block_candidate_lights: per block, from its offset, each
// candidate's light words after the block-level tests.
layout(std430, binding = 6) writeonly buffer Recorded { uint recorded[]; };
layout(std430, binding = 7) readonly buffer RecordOffsets { uint record_offsets[]; };
#endif

uniform int u_block_count;
uniform int u_part_count;
uniform int u_layer_offset;
uniform bool u_culling;  // RenderOptions::occluder_culling

const int kMaxLights = LIGHT_WORDS * 32;

shared vec3 s_point[kShadeBlock];
shared vec4 s_sphere;
shared int s_occluder[kShadeBlock];
shared uint s_lights[kShadeBlock * LIGHT_WORDS];
shared int s_kept;  // the chunk's candidates with a light left after the block-level tests

// Per vertex and light: the visibility so far (0: no share, or black; < 0:
// the share is final, shadow-mapped), and the share before visibility.
float g_visibility[kMaxLights];
vec3 g_share[kMaxLights];
#if LAYERED
vec3 g_specular_share[kMaxLights];
#endif
#if RAY_TRACED
// The vertex's rays: where they start, its index in its part (the seed's), the rays traced.
vec3 g_ray_origin;
int g_local_vertex;
uint g_rays = 0u;
#endif

// Step 1: the block sphere (box center, farthest vertex), as shade_block.
void block_sphere(int n) {
    vec3 lo = s_point[0], hi = lo;
    for (int k = 1; k < n; ++k) {
        lo = min(lo, s_point[k]);
        hi = max(hi, s_point[k]);
    }
    vec3 center = 0.5 * (lo + hi);
    float r2 = 0.0;
    for (int k = 0; k < n; ++k) {
        vec3 d = s_point[k] - center;
        r2 = max(r2, dot(d, d));
    }
    s_sphere = vec4(center, sqrt(r2) * (1.0 + 1e-6) + 1e-6);
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

// Step 3: every light's share and self-visibility at the vertex; returns
// whether the vertex sees any light at all.
void light_shares(int part, vec3 p, LocalFrame frame, inout uint live[LIGHT_WORDS]) {
    for (int w = 0; w < LIGHT_WORDS; ++w) live[w] = 0u;
    for (int l = 0; l < kMaxLights; ++l) {
        g_visibility[l] = 0.0;
        g_share[l] = vec3(0.0);
#if LAYERED
        g_specular_share[l] = vec3(0.0);
#endif
    }
    vec4 material = part_texel(part, kSlotMaterial);
    vec4 specular_material = part_texel(part, kSlotSpecular);
    bool layered = specular_material.w > 0.5;
    vec4 svdf = part_texel(part, kSlotSvdf);
    bool isotropic = material.y > 0.5;
    vec3 wo = frame_to_local(frame, normalize(u_camera - p));
    if (!(wo.z > 0.0)) return;
    vec2 alignment = view_alignment(wo);
    int first = u_environment_enabled ? 0 : u_environment_lights;
    int last = u_local_enabled ? u_light_count : u_environment_lights;
    // The lights whose square reaches the vertex's hemisphere first, then
    // the shares of those alone: the loop's turns are the most any lane
    // has, not every light (see shadow_by_occluder).
    uint reaching[LIGHT_WORDS];
    for (int w = 0; w < LIGHT_WORDS; ++w) reaching[w] = 0u;
    for (int l = first; l < last; ++l) {
        PointLight light = light_at(l, p);
        if (light.h > 0.0f && square_reaches_hemisphere(frame_to_local(frame, light.direction).z, light.h))
            reaching[l / 32] |= 1u << uint(l % 32);
    }
    for (int w = 0; w < LIGHT_WORDS; ++w)
    for (uint left = reaching[w]; left != 0u; left &= left - 1u) {
        int l = w * 32 + findLSB(left);
        PointLight light = light_at(l, p);
        vec3 local = frame_to_local(frame, light.direction);
        vec2 lp = hemisphere_to_plane(local);
        vec2 square = isotropic ? to_view_aligned(lp, alignment) : lp;
        vec3 brdf = brdf_average(material, square, light.h, wo);
#if LAYERED
        vec3 specular_brdf = layered ? brdf_average(specular_material, square, light.h, wo) : vec3(0.0);
#else
        vec3 specular_brdf = vec3(0.0);
#endif
#if SHADOW_MAPPED
        if (u_shadow_maps && l < u_environment_lights) {  // the baseline's visibility, in place of the fields'
            float lit = shadow_visible_fraction(l, light.direction, p, frame, lp, light.h);
            g_share[l] = light.integral * brdf * lit;
#if LAYERED
            g_specular_share[l] = light.integral * specular_brdf * lit;
#endif
            g_visibility[l] = -1.0;
            continue;
        }
#endif
        // A square whose BRDF average is 0 adds nothing: no visibility lookups for it (the CPU's adds_nothing).
        if (brdf == vec3(0.0) && specular_brdf == vec3(0.0)) continue;
#if RAY_TRACED
        // The ray-traced baseline: rays in place of SVDF × Π OVDF, for every light (as the CPU's rows).
        float lit = ray_traced_fraction(part, g_local_vertex, l, g_ray_origin, frame, lp, light.h, g_rays);
        g_share[l] = light.integral * brdf * lit;
#if LAYERED
        g_specular_share[l] = light.integral * specular_brdf * lit;
#endif
        g_visibility[l] = -1.0;
        continue;
#endif
        g_share[l] = light.integral * brdf;
#if LAYERED
        g_specular_share[l] = light.integral * specular_brdf;
#endif
        g_visibility[l] = self_visibility(svdf, light.direction, lp, light.h);
        if (g_visibility[l] > 0.0) live[l / 32] |= 1u << uint(l % 32);
    }
}

// Step 4 for one candidate occluder o and the vertex at p: multiplies its
// factor into every light of `bits` (the block's, word w) that still has a
// share; returns the lookups made.
struct OccluderAtVertex {
    mat4 inverse;
    vec3 point;      // the vertex in the occluder's frame
    vec3 sides;      // box_sides
    vec3 face_scale; // the lengths of inverse_linear's rows (clears_box_face_scaled)
    vec3 pole;       // unit, towards the occluder's field center (0 beyond its outer shell)
    float cone;      // its bounding cone's plane radius; kOvdfNoCone: no cone test
    vec4 shape;      // kSlotShape: an exact shape when w > 0
    OvdfReceiver receiver;
};

OccluderAtVertex occluder_at_vertex(int o, vec3 p) {
    OccluderAtVertex v;
    v.inverse = mat4(part_texel(o, kSlotInverse), part_texel(o, kSlotInverse + 1), part_texel(o, kSlotInverse + 2),
                     part_texel(o, kSlotInverse + 3));
    v.point = (v.inverse * vec4(p, 1.0)).xyz;
    v.sides = box_sides(part_texel(o, kSlotBoxLow).xyz, part_texel(o, kSlotBoxHigh).xyz, v.point);
    mat3 rows = transpose(mat3(v.inverse));
    v.face_scale = vec3(length(rows[0]), length(rows[1]), length(rows[2]));
    vec4 center = part_texel(o, kSlotOvdfCenter);
    float outer = part_texel(o, kSlotOvdfBases).w;
    vec3 offset = v.point - center.xyz;
    float d = length(offset);
    bool inside = d < outer;
    v.pole = inside && d > 0.0 ? -offset / d : vec3(0.0);
    bool cones = u_culling && part_culling[o * kCullingStride + kCullingFlags].y > 0.5;
    v.cone = !cones ? kOvdfNoCone : (inside ? (d <= center.w ? kOvdfNoCone : ovdf_cone_radius(d, center.w)) : -1.0);
    v.shape = part_texel(o, kSlotShape);
    // The OVDF location once per (vertex, occluder), before the lights: a
    // software rasterizer would run a lazy one at every light.
    v.receiver = ovdf_locate(o, v.point);
    return v;
}

uint shadow_by_occluder(int o, inout OccluderAtVertex v, vec3 p, LocalFrame frame, int w, uint bits,
                        inout uint live[LIGHT_WORDS]) {
    mat3 inverse_linear = mat3(v.inverse);
    // The cheap answers first, in one loop over the lights: the vertex's own
    // culling tests, a receiver inside the part (0), the small-occluder rule
    // alone; the lights left for the tables (or an exact shape) after, in a
    // loop of their own. A software rasterizer runs every loop for the most
    // turns any lane of its vector takes and runs both sides of an `if`,
    // so the tables' reads must not ride in the loop of every light.
    bool shape = v.shape.w > 0.5;
    uint lookups = 0u, needed = 0u;
    for (uint left = bits; left != 0u; left &= left - 1u) {
        int bit = findLSB(left);
        int l = w * 32 + bit;
        PointLight light = light_at(l, p);
        vec3 toward = inverse_linear * light.direction;  // not normalized
        vec3 dir = normalize(toward);
        if (ovdf_unshadowed(dot(dir, v.pole), v.cone, light.h)) continue;
        if (clears_box_face_scaled(v.sides, toward, v.face_scale, square_cone_sine(light.h))) continue;
        ++lookups;
        if (shape) {
            needed |= 1u << uint(bit);
            continue;
        }
        if (v.receiver.kind == kOvdfOutside) continue;  // its factor is 1
        OvdfSmall small = ovdf_receiver_small(v.receiver, dir, light.h);
        if (v.receiver.kind == kOvdfLocated && small.weight < 1.0f) {
            needed |= 1u << uint(bit);
            continue;
        }
        g_visibility[l] *= v.receiver.kind == kOvdfInside ? 0.0f : small.fraction;
        if (!(g_visibility[l] > 0.0)) live[w] &= ~(1u << uint(bit));
    }
    for (; needed != 0u; needed &= needed - 1u) {
        int bit = findLSB(needed);
        int l = w * 32 + bit;
        PointLight light = light_at(l, p);
        float fraction;
        if (shape) {
            vec2 lp = hemisphere_to_plane(frame_to_local(frame, light.direction));
            fraction = exact_shape_fraction(o, v.shape, v.point, frame, inverse_linear, lp, light.h);
        } else {
            vec3 dir = normalize(inverse_linear * light.direction);
            fraction = ovdf_receiver_tables(o, v.receiver, dir, light.h, ovdf_receiver_small(v.receiver, dir, light.h));
        }
        g_visibility[l] *= fraction;
        if (!(g_visibility[l] > 0.0)) live[w] &= ~(1u << uint(bit));
    }
    return lookups;
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
    if (in_block) {
        vertex = block_vertices[record.y + k];
        ivec2 texel = ivec2(vertex & (kArrayWidth - 1), vertex >> kArrayShift);
        vec4 position = texelFetch(u_positions, texel, 0);
        vec4 normal = texelFetch(u_normals, texel, 0);
        vec3 tangent = texelFetch(u_tangents, texel, 0).xyz;
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
    vec3 color = vec3(0.0), specular = vec3(0.0);
    for (int l = 0; l < kMaxLights; ++l) {
        float visibility = g_visibility[l] < 0.0 ? 1.0 : g_visibility[l];
        color += g_share[l] * visibility;
#if LAYERED
        specular += g_specular_share[l] * visibility;
#endif
    }
    colors[vertex] = vec4(color, 1.0);
#if LAYERED
    colors[u_layer_offset + vertex] = vec4(specular, 1.0);
#endif
}
