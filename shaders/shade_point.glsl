// The shading sum at one point (RSL paper §5.2, Figure 8):
//
//   Σ_lights  2r²·I  ×  BRDF-SAT average  ×  SVDF average  ×  Π_occluders OVDF average
//
// with the same arithmetic as the CPU renderer (src/render/shade_block.cpp,
// src/brdf/brdf_table.cpp, src/fields/svdf.h, src/fields/ovdf.cpp), so that the two
// agree to float rounding. After shading_data.glsl (the data and the BRDF
// average) and visibility_fields.glsl (SVDF, OVDF, exact shapes).
// Two passes run it: the vertex pass (shade_blocks.comp.glsl, one
// invocation per vertex, which takes its functions apart to share the
// light-independent half of each lookup) and the per-pixel pass (shade_pixels.*.glsl, the
// parts shaded per pixel drawn from the camera).
//
// With u_shadow_maps (RenderOptions::shadow_maps, a competitor baseline;
// docs/design/GPU_DESIGN.md "Shadow-mapped visibility") every environment light's
// visibility comes from its depth map instead (shadow_visible_fraction).

// ---- the shadow-mapped baseline (shading_core.h "shadow maps") ----

// Lit fraction of environment light `layer` (centre direction L) over its
// square (plane centre lp, half-edge h) at world point p, shading frame
// `frame` (columns x, y, z = normal). The taps are the square's own
// directions (shadow_tap_point) above the horizon; a ray along one reaches
// the blockers' depth at `distance` × its slope across the map. PCF assumes
// the distance (u_pcf_depth); PCSS searches blockers and takes their mean
// distance (blocker_distance). Each texel a tap reads is compared with the
// receiver's own tangent plane at the texel's centre (the receiver-plane
// depth bias), less a constant bias.
struct ShadowReceiver {
    vec3 q;         // the receiver in the map: (u, v, depth)
    vec2 gradient;  // its tangent plane's depth per unit map offset
    float bias;     // depth units
    int layer;
};
vec2 g_shadow_slope[kShadowTaps];

// Texel t of the receiver's map: 1 (nothing in front) outside it.
float shadow_depth(ShadowReceiver r, ivec2 t) {
    if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, ivec2(u_shadow_resolution)))) return 1.0;
    return texelFetch(u_shadow_depths, ivec3(t, r.layer), 0).r;
}
// The receiver's tangent plane at texel t's centre: a texel nearer than
// this less the bias blocks.
float shadow_plane(ShadowReceiver r, ivec2 t) {
    vec2 center = (vec2(t) + 0.5) * u_shadow_texel;
    return r.q.z + dot(center - r.q.xy, r.gradient);
}
// Lit share at map point uv, bilinear over the four nearest texels.
float shadow_lit(ShadowReceiver r, vec2 uv) {
    vec2 t = uv * float(u_shadow_resolution) - 0.5;
    vec2 base = floor(t);
    vec2 f = t - base;
    float lit = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 texel = ivec2(base) + ivec2(k & 1, k >> 1);
        float weight = ((k & 1) == 0 ? 1.0 - f.x : f.x) * ((k >> 1) == 0 ? 1.0 - f.y : f.y);
        if (shadow_depth(r, texel) >= shadow_plane(r, texel) - r.bias) lit += weight;
    }
    return lit;
}

// PCSS's blocker search: the mean distance (depth units) from the blockers
// that the taps at `distance` × slope find down to the receiver's tangent
// plane below each (not to the receiver itself: a blocker plane tilted
// against the light, found far to the side, would read as near), or 0 when
// they find none.
float blocker_distance(ShadowReceiver r, int taps, float distance) {
    float sum = 0.0;
    int blockers = 0;
    for (int k = 0; k < taps; ++k) {
        ivec2 texel = ivec2(floor((r.q.xy + distance * g_shadow_slope[k]) * float(u_shadow_resolution)));
        float depth = shadow_depth(r, texel), plane = shadow_plane(r, texel);
        if (depth < plane - r.bias) {
            sum += plane - depth;
            ++blockers;
        }
    }
    return blockers == 0 ? 0.0 : sum / float(blockers);
}

float shadow_visible_fraction(int layer, vec3 light, vec3 p, LocalFrame frame, vec2 lp, float h) {
    LocalFrame m = shadow_map_frame(light);
    ShadowReceiver r;
    r.q = shadow_map_point(m, u_shadow_sphere.xyz, u_shadow_sphere.w, p);
    r.gradient = shadow_receiver_gradient(m, frame.z);
    r.bias = kShadowDepthBiasTexels * u_shadow_texel;
    r.layer = layer;
    int taps = 0;
    for (int i = 0; i < kShadowTaps; ++i) {
        vec2 point = shadow_tap_point(lp, h, i);
        if (dot(point, point) >= 1.0) continue;  // below the horizon: the BRDF average is 0 there
        g_shadow_slope[taps++] = shadow_map_slope(m, frame_to_world(frame, plane_to_hemisphere(point)));
    }
    if (taps == 0) return 1.0;
    float distance = u_pcf_depth;
    if (u_shadow_pcss) {
        // Over the widest footprint: rays up to the map's near face (depth 0).
        distance = blocker_distance(r, taps, r.q.z);
        if (distance == 0.0) return 1.0;
    }
    float lit = 0.0;
    for (int k = 0; k < taps; ++k) lit += shadow_lit(r, r.q.xy + distance * g_shadow_slope[k]);
    return lit / float(taps);
}

// ---- the sum ----

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
        vec3 to_center = a.xyz - p;
        float distance = length(to_center);
        light.h = 0.0;
        light.integral = vec3(0.0);
        light.direction = vec3(0.0, 0.0, 1.0);
        if (!(distance > a.w)) return light;
        light.direction = to_center / distance;
        float solid_angle = sphere_cap_solid_angle(a.w, distance);
        light.h = half_edge_for_solid_angle(solid_angle);
        vec4 c = fetch(u_lights, kLightTexels * l + 2);
        light.integral = b.rgb * (solid_angle * spot_cone_factor(c.xyz, -light.direction, b.w, c.w));
    }
#endif
    return light;
}

struct PointShade {
    vec3 color;     // the diffuse sum at unit texture (textured parts), else the whole sum
    vec3 specular;  // textured parts (kSlotSpecular.w = 1): the specular table's sum
};

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

// The sum at world point p of `part`, shading frame `frame` (rows: tangent,
// bitangent, normal: frame_from_normal_tangent), towards u_camera, with self_visibility's factor.
PointShade shade_point(int part, vec3 p, LocalFrame frame) {
    vec4 material = part_texel(part, kSlotMaterial);
    vec4 specular_material = part_texel(part, kSlotSpecular);
    bool layered = specular_material.w > 0.5;
    vec4 svdf = part_texel(part, kSlotSvdf);
    bool isotropic = material.y > 0.5;
    vec3 wo = frame_to_local(frame, normalize(u_camera - p));
    vec2 alignment = view_alignment(wo);

    PointShade result;
    result.color = vec3(0.0);
    result.specular = vec3(0.0);
    if (!(wo.z > 0.0)) return result;
    int first = u_environment_enabled ? 0 : u_environment_lights;
    int last = u_local_enabled ? u_light_count : u_environment_lights;
    for (int l = first; l < last; ++l) {
        PointLight light = light_at(l, p);
        vec3 direction = light.direction;
        float h = light.h;
        vec3 integral = light.integral;
        vec3 local = frame_to_local(frame, direction);
        vec2 lp = hemisphere_to_plane(local);
        if (!(h > 0.0f) || !square_reaches_hemisphere(local.z, h)) continue;
        vec2 square = isotropic ? to_view_aligned(lp, alignment) : lp;
        vec3 brdf = brdf_average(material, square, h, wo);
        vec3 specular_brdf = layered ? brdf_average(specular_material, square, h, wo) : vec3(0.0);
        if (u_shadow_maps && l < u_environment_lights) {  // the baseline's visibility, in place of the fields'
            float lit = shadow_visible_fraction(l, direction, p, frame, lp, h);
            result.color += integral * brdf * lit;
            result.specular += integral * specular_brdf * lit;
            continue;
        }
        float visibility = self_visibility(svdf, direction, lp, h);
        int slot = part * u_light_count + l;
        int list_end = int(list_texel(slot + 1));
        for (int e = int(list_texel(slot)); e < list_end; ++e) {
            if (!(visibility > 0.0)) break;
            int o = int(list_texel(e));
            mat4 inverse = mat4(part_texel(o, kSlotInverse), part_texel(o, kSlotInverse + 1),
                                part_texel(o, kSlotInverse + 2), part_texel(o, kSlotInverse + 3));
            vec3 point = (inverse * vec4(p, 1.0)).xyz;
            vec3 dir = normalize(mat3(inverse) * direction);
            if (clears_box(o, point, mat3(inverse) * direction, mat3(inverse), h)) continue;
            vec4 shape = part_texel(o, kSlotShape);
            visibility *= shape.w > 0.5 ? exact_shape_fraction(o, shape, point, frame, mat3(inverse), lp, h)
                                        : ovdf_visible_fraction(o, point, dir, h);
        }
        result.color += integral * brdf * visibility;
        result.specular += integral * specular_brdf * visibility;
    }
    return result;
}
