// The sum at a point with the CPU renderer's per-vertex tests
// (src/render/shade_block.cpp), as the vertex pass and the per-pixel pass
// both take it:
//
//  1. light_shares: per light the BRDF and self-visibility (the light's
//     share before the other parts' shadows), for the lights whose square
//     reaches the point's hemisphere;
//  2. per candidate occluder of the part, occluder_at_vertex: the
//     light-independent half of the lookup once (the point in the
//     occluder's frame, the box sides, the bounding cone, the OVDF
//     location), then shadow_by_occluder: the cheap answers per light (the
//     cone, the box, inside, the small-occluder rule) and the tables for
//     the lights left;
//  3. point_sum: Σ share × visibility.
//
// The sum is the RSL paper's (§5.2, Figure 8),
//
//   Σ_lights  2r²·I  ×  BRDF-SAT average  ×  SVDF average  ×  Π_occluders OVDF average,
//
// with the same arithmetic as the CPU renderer (src/render/shade_block.cpp,
// src/brdf/brdf_table.cpp, src/fields/svdf.h, src/fields/ovdf.cpp), so that
// the two agree to float rounding. After shading_data.glsl,
// visibility_fields.glsl and shadow_map_filter.glsl (and, with RAY_TRACED,
// ray_visibility.glsl). The host defines LIGHT_WORDS (32 lights a word),
// LAYERED (some part has a specular table), RAY_TRACED and SHADOW_MAPPED
// (the baselines).

const int kMaxLights = LIGHT_WORDS * 32;

// Light l at world point p: its direction, square half-edge and integral;
// a sphere light that contains p has h = 0 (no share).
struct PointLight {
    vec3 direction;
    float h;
    vec3 integral;
};
PointLight light_at(int l, vec3 p) {
    vec4 a = fetch(u_lights, kLightTexels * l), b = fetch(u_lights, kLightTexels * l + 1);
    PointLight light;  // an environment square: direction, half-edge, 2r²·I
    light.direction = a.xyz;
    light.h = a.w;
    light.integral = b.rgb;
#if LOCAL_LIGHTS
    if (l >= u_environment_lights) {
        // A sphere light: center a.xyz, radius a.w, radiance b.rgb; spot axis c.xyz, cone (b.w, c.w).
        SphereSquare square = sphere_square(p, a.xyz, a.w);
        light.direction = square.direction;
        light.h = square.half_edge;
        light.integral = vec3(0.0);
        if (!square.lit) return light;
        vec4 c = fetch(u_lights, kLightTexels * l + 2);
        light.integral = b.rgb * (square.solid_angle * spot_cone_factor(c.xyz, -light.direction, b.w, c.w));
    }
#endif
    return light;
}

// The environment's exact irradiance at a world normal (as
// environment_irradiance, src/render/frame_setup.cpp): the maps' bilinear
// taps, blended.
vec3 irradiance_taps(int base, CubeNodeTaps taps) {
    vec3 n0 = fetch(u_lights, base + taps.first).rgb, n1 = fetch(u_lights, base + taps.first + 1).rgb;
    vec3 n2 = fetch(u_lights, base + taps.first + taps.row).rgb, n3 = fetch(u_lights, base + taps.first + taps.row + 1).rgb;
    float wx = taps.weight.x, wy = taps.weight.y;
    return (1.0 - wy) * ((1.0 - wx) * n0 + wx * n1) + wy * ((1.0 - wx) * n2 + wx * n3);
}
vec3 environment_irradiance(vec3 world_normal) {
    CubeNodeTaps taps = cube_node_taps(transpose(u_environment_rotation) * world_normal, u_irradiance_resolution);
    vec3 e = u_irradiance_weights.x * irradiance_taps(u_irradiance_first, taps);
    if (u_irradiance_second >= 0 && u_irradiance_weights.y > 0.0)
        e += u_irradiance_weights.y * irradiance_taps(u_irradiance_second, taps);
    return e;
}

// The exact diffuse light's gain g at a point (CpuRenderer::diffuse_light_gains):
// a·(E(n) / Σ_l I_l c_l − 1) over the environment's squares; 0 without it.
// `a`: the part's constant term (kSlotDiffuseLight), or a point's own (pbr_basis.h).
vec3 diffuse_light_gain_at(vec3 a, LocalFrame frame) {
    if (u_irradiance_resolution == 0 || !u_environment_enabled || a == vec3(0.0) || u_environment_lights == 0)
        return vec3(0.0);
    vec3 squares = vec3(0.0);
    for (int l = 0; l < u_environment_lights; ++l) {
        vec4 square = fetch(u_lights, kLightTexels * l);
        vec3 local = frame_to_local(frame, square.xyz);
        if (!square_reaches_hemisphere(local.z, square.w)) continue;
        squares += fetch(u_lights, kLightTexels * l + 1).rgb * square_average_cosine(hemisphere_to_plane(local), square.w);
    }
    vec3 e = environment_irradiance(frame.z);
    return vec3(diffuse_light_gain(a.r, e.r, squares.r), diffuse_light_gain(a.g, e.g, squares.g),
                diffuse_light_gain(a.b, e.b, squares.b));
}

// Self-visibility of the light with direction `direction`, plane point lp in
// the point's frame and half-edge h (g_self_corners).
float self_visibility(vec4 svdf, vec3 direction, vec2 lp, float h) {
    if (g_self_corners == 0) return 1.0;
#if SELF_CORNERS == 1
    return visible_fraction_from_distance(svdf_distance(svdf, g_corner_cluster[0], lp, 0), h);
#else
    if (g_self_corners == 1) return visible_fraction_from_distance(svdf_distance(svdf, g_corner_cluster[0], lp, 0), h);
    float blend = 0.0;
    for (int c = 0; c < 3; ++c) {
        // A corner whose hemisphere the square misses has no share (the
        // CPU's vertex pass queries no such square).
        vec3 local = frame_to_local(g_corner_frame[c], direction);
        if (!square_reaches_hemisphere(local.z, h)) continue;
        float corner = g_corner_cluster[c] < 0
                           ? 1.0
                           : visible_fraction_from_distance(
                                 svdf_distance(svdf, g_corner_cluster[c], hemisphere_to_plane(local), c), h);
        blend += g_corner_weight[c] * corner;
    }
    return blend;
#endif
}

// The frame's candidates (gpu_layout.h pack_block_candidates): parts + 1
// offsets, then per candidate kCandidateHeader + LIGHT_WORDS words.
layout(std430, binding = CANDIDATES_BINDING) readonly buffer Candidates { uint candidates[]; };
// Per part, kCullingStride vec4 (gpu_layout.h pack_part_culling).
layout(std430, binding = PART_CULLING_BINDING) readonly buffer PartCulling { vec4 part_culling[]; };
uniform int u_part_count;
uniform bool u_culling;  // RenderOptions::occluder_culling

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

// Light l's share with a baseline's visibility `lit` in place of the
// fields' (shadow maps, rays): final, no lookups follow (g_visibility < 0).
void final_share(int l, vec3 integral, vec3 brdf, vec3 specular_brdf, float lit) {
    g_share[l] = integral * brdf * lit;
#if LAYERED
    g_specular_share[l] = integral * specular_brdf * lit;
#endif
    g_visibility[l] = -1.0;
}

// A part whose roughness and metallic vary per point (src/shading/pbr_basis.h):
// the point's (roughness, metallic), which the pass sets before light_shares.
vec2 g_pbr_point = vec2(0.0);

// The basis blend at a point (CpuRenderer::pbr_averages): D into `brdf`, the
// specular lobes into `specular_brdf` when the part is layered, else into `brdf`.
void pbr_brdf_average(PbrWeights w, vec2 square, float h, vec3 wo, bool layered, out vec3 brdf,
                      out vec3 specular_brdf) {
    brdf = w.diffuse * brdf_average(u_pbr_basis[0], square, h, wo);
    vec3 lobes = vec3(0.0);
    for (int j = w.level; j <= w.level + 1; ++j) {
        float level = pbr_level_weight(w.level, w.upper, j);
        if (level == 0.0) continue;
        lobes += (level * w.dielectric) * brdf_average(u_pbr_basis[1 + j], square, h, wo);
        if (w.metal != vec3(0.0)) lobes += (level * w.metal) * brdf_average(u_pbr_basis[1 + kPbrLevels + j], square, h, wo);
    }
    specular_brdf = layered ? lobes : vec3(0.0);
    if (!layered) brdf += lobes;
}

// Every light's share and self-visibility at the point (g_share,
// g_visibility); `live`: the lights with a share and some light left.
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
    vec4 pbr = part_texel(part, kSlotPbr);
    bool varies = pbr.w > 0.5;
    PbrWeights weights = pbr_weights(pbr.rgb, g_pbr_point.y, g_pbr_point.x);
    vec3 gain = diffuse_light_gain_at(varies ? weights.diffuse * (1.0 / kPi) : part_texel(part, kSlotDiffuseLight).rgb,
                                      frame);
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
        vec3 brdf, specular_brdf;
        if (varies) {
            pbr_brdf_average(weights, square, light.h, wo, layered, brdf, specular_brdf);
        } else {
            brdf = brdf_average(material, square, light.h, wo);
#if LAYERED
            specular_brdf = layered ? brdf_average(specular_material, square, light.h, wo) : vec3(0.0);
#else
            specular_brdf = vec3(0.0);
#endif
        }
        if (l < u_environment_lights) brdf += gain * square_average_cosine(lp, light.h);
#if SHADOW_MAPPED
        if (u_shadow_maps && l < u_environment_lights) {  // the baseline's visibility, in place of the fields'
            final_share(l, light.integral, brdf, specular_brdf,
                        shadow_visible_fraction(l, light.direction, p, frame, lp, light.h));
            continue;
        }
#endif
        // A square whose BRDF average is 0 adds nothing: no visibility lookups for it (the CPU's adds_nothing).
        if (brdf == vec3(0.0) && specular_brdf == vec3(0.0)) continue;
#if RAY_TRACED
        // The ray-traced baseline: rays in place of SVDF × Π OVDF, for every light (as the CPU's rows).
        final_share(l, light.integral, brdf, specular_brdf,
                    ray_traced_fraction(part, g_local_vertex, l, g_ray_origin, frame, lp, light.h, g_rays));
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

// The light-independent half of a lookup of occluder o at a point.
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

// For one candidate occluder o and the point p: multiplies its factor into
// every light of `bits` (word w of the lights the candidate keeps) that
// still has a share; returns the lookups made.
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

// Σ share × visibility over the lights: the colour, and with LAYERED the
// specular layer into `specular`.
vec3 point_sum(out vec3 specular) {
    vec3 color = vec3(0.0);
    specular = vec3(0.0);
    for (int l = 0; l < kMaxLights; ++l) {
        float visibility = g_visibility[l] < 0.0 ? 1.0 : g_visibility[l];
        color += g_share[l] * visibility;
#if LAYERED
        specular += g_specular_share[l] * visibility;
#endif
    }
    return color;
}
