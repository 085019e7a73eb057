#pragma once
// Occluder culling's conservative tests (docs/design/RENDERER.md "Culling"),
// shared by the CPU renderer's blocks and the GPU's workgroups so that both
// skip exactly the same (block, light, occluder) lookups. Spheres are
// (center, radius) in a vec4. A test that says "cannot shadow" must hold for
// every point of the receiver sphere and every direction of the light;
// tests/render/occluder_culling_test.cpp pins them against brute-force rays.
#include "src/shading/glsl_subset.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

// Whether a ray from some point of `receiver`, in some direction within
// `half_angle` of the unit `direction`, can meet `occluder`.
//
// Such a ray y = x + sω stays in the region where the axial coordinate
// a = (y − c)·d ≥ −r and the distance from the axis is ≤ r + (a + r)·tan β
// (c, r: the receiver sphere; s·cos γ ≤ a + r and s·sin γ ≤ (a + r)·tan β).
// The occluder sphere (center axial a_o, lateral q_o, radius R) can reach it
// only if a_o + R ≥ −r and q_o − R ≤ r + (a_o + R + r)·tan β.
RSL_SHARED bool may_shadow_direction(vec4 receiver, vec4 occluder, vec3 direction, float half_angle) {
    if (half_angle >= 0.5f * kPi - 1e-3f) return true;  // the cone is a half-space or more: keep
    vec3 v = vec3(occluder) - vec3(receiver);
    float axial = dot(v, direction);
    float far_axial = axial + occluder.w;
    if (far_axial < -receiver.w) return false;  // entirely behind the receiver
    float lateral = length(v - axial * direction);
    return lateral - occluder.w <= receiver.w + (far_axial + receiver.w) * tan(half_angle);
}

// Whether the receiver sphere lies entirely outside an occluder field's reach
// (beyond its outer shell the field is exactly 1).
RSL_SHARED bool beyond_reach(vec4 receiver, vec4 reach) {
    return length(vec3(receiver) - vec3(reach)) - receiver.w > reach.w;
}

// A sphere moved by a rigid (possibly uniformly scaled) transform; for a
// non-uniform scale the radius grows by the largest axis scale (conservative).
RSL_SHARED vec4 transform_sphere(mat4 m, vec4 sphere) {
    mat3 l = mat3(m);
    float scale = max(length(l[0]), max(length(l[1]), length(l[2])));
    vec4 moved = m * vec4(vec3(sphere), 1.0f);
    return vec4(vec3(moved), sphere.w * scale);
}

// How far any point's direction to a part can turn from a block center's
// (asin(r / d)), plus a margin of 1e-3 rad for rounding, as cosine and sine.
struct BlockSpread {
    float cosine;
    float sine;
};
// The spread of a block of radius r whose center lies at distance d > r from
// the part's, with no trigonometric call (asin, then the sum's cos a·cos δ −
// sin a·sin δ and sin a·cos δ + cos a·sin δ): a pixel shaded per pixel is a
// block of its own, and its asinf and sincosf for every occluder near it
// were 4% of a dense scene's image.
RSL_CONST float kBlockSpreadMarginCos = 0.99999952f;  // of 1e-3 rad
RSL_CONST float kBlockSpreadMarginSin = 0.00099999983f;
RSL_SHARED BlockSpread block_spread(float radius, float distance) {
    float s = min(1.0f, radius / distance);
    float c = sqrt(max(0.0f, 1.0f - s * s));
    BlockSpread spread;
    spread.cosine = c * kBlockSpreadMarginCos - s * kBlockSpreadMarginSin;
    spread.sine = s * kBlockSpreadMarginCos + c * kBlockSpreadMarginSin;
    return spread;
}

// Whether an environment light (unit world direction, square half-edge h)
// clears the part's bounding cone at every vertex of the block: `pole`, the
// unit direction from the block's center to the part's, `spread`, how far a
// vertex's pole can turn from it, and `cone`, the largest cone plane radius
// of any vertex (negative: some vertex may lie in the bounding sphere). Then
// every vertex's ovdf_unshadowed test passes, with a margin for rounding.
//
// The angle test angle(light, pole) ≥ needed + spread' (spread' = spread +
// 1e-3, cos_needed = 1 − (h + cone)²) in cosines, without acos: a
// rotation by more than π − spread' is none (needed ≥ π − spread' ⟺
// cos_needed ≤ −cos spread'), else the light's cosine must be at most
// cos(needed + spread').
RSL_SHARED bool block_unshadowed(vec3 pole, BlockSpread spread, float cone, vec3 light, float half_edge) {
    if (cone < 0.0f) return false;
    float limit = half_edge + cone;
    float cos_needed = 1.0f - limit * limit;  // the angle to the pole each vertex needs, as a cosine
    if (cos_needed <= -spread.cosine) return false;  // the cone and square cover every direction
    float sin_needed = sqrt(max(0.0f, 1.0f - cos_needed * cos_needed));
    return dot(light, pole) <= cos_needed * spread.cosine - sin_needed * spread.sine;
}

// A block's bounding sphere for block-level culling: the center of its
// points' box, the radius to the farthest point, padded for rounding. Each
// side loops over the points where it keeps them (the CPU's block scratch,
// a workgroup's shared memory), in two passes:
//   box = point_box(p₀), then box = point_box_add(box, p_k);
//   c = point_box_center(box); r² = farther_squared(r², c, p_k) from r² = 0;
//   sphere = vec4(c, bounding_radius(r²)).
struct PointBox {
    vec3 lo;
    vec3 hi;
};
RSL_SHARED PointBox point_box(vec3 p) {
    PointBox box;
    box.lo = p;
    box.hi = p;
    return box;
}
RSL_SHARED PointBox point_box_add(PointBox box, vec3 p) {
    box.lo = min(box.lo, p);
    box.hi = max(box.hi, p);
    return box;
}
RSL_SHARED vec3 point_box_center(PointBox box) { return 0.5f * (box.lo + box.hi); }
RSL_SHARED float farther_squared(float r2, vec3 center, vec3 p) {
    vec3 d = p - center;
    return max(r2, dot(d, d));
}
RSL_SHARED float bounding_radius(float farthest_squared) { return sqrt(farthest_squared) * (1.0f + 1e-6f) + 1e-6f; }

// RSL_GLSL_END

}  // namespace rsl::shading
