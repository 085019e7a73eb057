// The shadow-mapped baseline's filter (RenderOptions::shadow_maps, a
// competitor baseline; docs/design/GPU_DESIGN.md "Shadow-mapped
// visibility"): with u_shadow_maps every environment light's visibility
// comes from its depth map (shadow_visible_fraction) instead of the fields.
// After shading_data.glsl and visibility_fields.glsl.

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
