#pragma once
// The shadow-mapped baseline's filter (the GL renderer's competitor,
// src/gl/shadow_map_pass.h; docs/design/GPU_DESIGN.md "Shadow-mapped visibility").
#include "src/shading/frames.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

// Not part of the RSL sum: a competitor's visibility factor for environment
// lights (RenderOptions::shadow_maps, docs/design/GPU_DESIGN.md "Shadow-mapped visibility").
// One orthographic depth map per light along its centre direction L, over a
// sphere that holds the posed scene; the filter's taps are the light
// square's own directions (the grid of exact_visibility.h), each moved across
// the map by how far it travels towards the light.

// The filter's taps: a Fibonacci lattice of kShadowTaps points over the
// square (point i at ((i + ½)/n, ((i·step mod n) + ½)/n) of the unit
// square): no two taps share a row or a column, so a straight shadow edge
// crossing the square moves the lit fraction in steps of about 1/n, where
// a 5×5 grid steps by 1/5 when the edge runs along its rows.
RSL_CONST int kShadowTaps = 21;
RSL_CONST int kShadowLatticeStep = 13;
// Bias, in texels (1 / resolution: the same length across and in depth,
// see shadow_map_point). Each texel a tap reads is compared with the
// receiver's own tangent plane at the texel's centre (the receiver-plane
// depth bias: a large kernel on a plane tilted to the light would otherwise
// shadow the plane itself), less this constant for the depth's
// interpolation and the facets around the vertex. The receiver is not moved
// off its surface along its normal: that moved shadow edges by the offset ×
// tan θ (1.5 texels doubled tests/gl/shadow_map_test.cpp's error at 30°).
RSL_CONST float kShadowDepthBiasTexels = 1.0f;
// Least cosine to L used in a tap's slope and the receiver plane's gradient,
// so that grazing directions and planes stay finite.
RSL_CONST float kShadowMinCosine = 0.2f;

// The map's axes for the unit light direction L (towards the light): x =
// any_orthonormal(L), y = L × x, z = L.
RSL_SHARED LocalFrame shadow_map_frame(vec3 light) {
    LocalFrame m;
    m.z = light;
    m.x = any_orthonormal(light);
    m.y = cross(light, m.x);
    return m;
}
// A world point in the map of the sphere (centre, radius) along axes m: (u, v)
// ∈ [0, 1]² across, depth ∈ [0, 1] from the sphere's point nearest the light.
// All three scale by 0.5 / radius, so a map offset and a depth difference
// are the same length (a texel is 1 / resolution in both).
RSL_SHARED vec3 shadow_map_point(LocalFrame m, vec3 center, float radius, vec3 world) {
    vec3 d = frame_to_local(m, world - center);
    float s = 0.5f / radius;
    return vec3(0.5f + s * d.x, 0.5f + s * d.y, 0.5f - s * d.z);
}
// The map offset per unit of depth travelled towards the light along world
// direction w: a ray leaving the receiver along w reaches depth d − Δ at map
// offset Δ × slope.
RSL_SHARED vec2 shadow_map_slope(LocalFrame m, vec3 w) {
    vec3 d = frame_to_local(m, w);
    return vec2(d.x, d.y) / max(d.z, kShadowMinCosine);
}
// The receiver's tangent plane (world normal n) in the map: its depth
// change per unit map offset.
RSL_SHARED vec2 shadow_receiver_gradient(LocalFrame m, vec3 n) {
    vec3 d = frame_to_local(m, n);
    return vec2(d.x, d.y) / max(d.z, kShadowMinCosine);
}
// Tap i of the lattice over the plane square (centre c, half-edge h).
RSL_SHARED vec2 shadow_tap_point(vec2 c, float half_edge, int i) {
    float n = float(kShadowTaps);
    float u = (float(i) + 0.5f) / n;
    float v = (float((i * kShadowLatticeStep) % kShadowTaps) + 0.5f) / n;
    return c + half_edge * vec2(2.0f * u - 1.0f, 2.0f * v - 1.0f);
}

// RSL_GLSL_END

}  // namespace rsl::shading
