#pragma once
// Lights as squares in the local hemisphere map (RSL paper §3–4;
// docs/design/METHOD.md "Rotatable square lights"), and the slab rule that
// culls an occluder's box against a light's square (src/render/square_lights.h).
#include "src/shading/frames.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

// An RSL of half-diagonal r (solid angle 2r²) is the plane square of area r²:
// half-edge r / 2 (measure preserving; docs/design/METHOD.md "Rotatable square lights").
RSL_SHARED float square_half_edge_for_rsl(float half_diagonal) { return 0.5f * half_diagonal; }
// A square of solid angle Ω has plane area Ω / 2.
RSL_SHARED float half_edge_for_solid_angle(float solid_angle) { return 0.5f * sqrt(0.5f * solid_angle); }
// The cap a sphere of radius a subtends at distance d > a: 2π(1 − cos α),
// written 2π sin²α / (1 + cos α) against cancellation.
RSL_SHARED float sphere_cap_solid_angle(float radius, float distance) {
    float sin2 = min(1.0f, (radius / distance) * (radius / distance));
    return 2.0f * kPi * sin2 / (1.0f + sqrt(1.0f - sin2));
}
// A sphere light (center, radius) at point x as a square light
// (docs/design/METHOD.md "Local lights"): its unit direction, the exact
// cap's solid angle and the square's half-edge. A point inside the sphere
// is not lit by it (lit false, solid angle and half-edge 0, direction +z),
// as in the truth. The radiance and a spot's cone are the caller's.
struct SphereSquare {
    vec3 direction;
    float solid_angle;
    float half_edge;
    bool lit;
};
RSL_SHARED SphereSquare sphere_square(vec3 x, vec3 center, float radius) {
    SphereSquare s;
    s.direction = vec3(0.0f, 0.0f, 1.0f);
    s.solid_angle = 0.0f;
    s.half_edge = 0.0f;
    s.lit = false;
    vec3 to_center = center - x;
    float distance = length(to_center);
    if (!(distance > radius)) return s;
    s.direction = to_center / distance;
    s.solid_angle = sphere_cap_solid_angle(radius, distance);
    s.half_edge = half_edge_for_solid_angle(s.solid_angle);
    s.lit = true;
    return s;
}
// A spot light's cone (glTF KHR_lights_punctual's smooth falloff): what
// reaches a point in unit direction w from the light (light → point) is
// scaled by clamp(dot(axis, w)·scale + offset, 0, 1)², with
// scale = 1 / max(1e-3, cos θ_inner − cos θ_outer), offset = −cos θ_outer · scale
// (spot_cone_scale_offset, src/core/sphere_light.h): 1 inside the inner
// cone, 0 outside the outer one. A point light is scale 0, offset 1.
RSL_SHARED float spot_cone_factor(vec3 axis, vec3 light_to_point, float scale, float offset) {
    float f = clamp(dot(axis, light_to_point) * scale + offset, 0.0f, 1.0f);
    return f * f;
}
// Whether a square of half-edge h centred on local direction w can overlap
// the upper hemisphere: |p(w)| = √(1 − w.z) < 1 + √2·h.
RSL_SHARED bool square_reaches_hemisphere(float local_z, float half_edge) {
    float reach = 1.0f + kSqrt2 * half_edge;
    return local_z > 1.0f - reach * reach;
}

// Isotropic tables are view-aligned: the local frame turned about the normal
// so that the view lies in the y–z plane. (cos φ_o, sin φ_o) of the local
// view wo; (1, 0) for a view along the normal.
RSL_SHARED vec2 view_alignment(vec3 wo) {
    float len2 = wo.x * wo.x + wo.y * wo.y;
    float inv = len2 > 1e-16f ? 1.0f / sqrt(len2) : 0.0f;
    return vec2(len2 > 1e-16f ? wo.y * inv : 1.0f, wo.x * inv);
}
// A plane point in the view-aligned frame, for alignment (cos φ_o, sin φ_o).
RSL_SHARED vec2 to_view_aligned(vec2 p, vec2 alignment) {
    return vec2(p.x * alignment.x - p.y * alignment.y, p.x * alignment.y + p.y * alignment.x);
}

// ---- the slab rule ----

// Half-angle of a cone around the light's direction holding the part of its
// square above any vertex's horizon, whatever the frame: the square's points
// lie within √2·h of its centre, along segments within plane radius ρ_max =
// min(√2, 1 + √2·h), and the inverse map stretches lengths by at most
// √2 / cos(θ_max / 2) (ρ = √2·sin(θ/2)).
RSL_SHARED float square_cone_half_angle(float half_edge) {
    float rho_max = min(kSqrt2, 1.0f + kSqrt2 * half_edge);
    float sin_half = rho_max / kSqrt2;
    float cos_half = sqrt(max(0.0f, 1.0f - sin_half * sin_half));
    if (cos_half < 1e-3f) return kPi;
    return min(kPi, 2.0f * half_edge / cos_half);
}
// sin β for the slab rule; 2 (never clears) once β reaches π/2.
RSL_SHARED float square_cone_sine(float half_edge) {
    float beta = square_cone_half_angle(half_edge);
    return beta >= 0.5f * kPi ? 2.0f : sin(beta);
}
// Which side of the slab [lo, hi] x lies on: 1 above, −1 below, 0 within.
RSL_SHARED float box_side(float x, float lo, float hi) { return x > hi ? 1.0f : (x < lo ? -1.0f : 0.0f); }
RSL_SHARED vec3 box_sides(vec3 lo, vec3 hi, vec3 p) {
    return vec3(box_side(p.x, lo.x, hi.x), box_side(p.y, lo.y, hi.y), box_side(p.z, lo.z, hi.z));
}
// The slab rule: a receiver beyond a face of the occluder's bounding box
// (sides, in the part's frame) is unshadowed by it from a square whose
// directions all leave that face's plane outwards: some s_a·L_a ≥ sin β(h).
RSL_SHARED bool clears_box_face(vec3 sides, vec3 light, float sin_beta) {
    return max(sides.x * light.x, max(sides.y * light.y, sides.z * light.z)) >= sin_beta;
}
// The world form: light = inverse_linear·(world direction), not normalized,
// and face_scale = the lengths of inverse_linear's rows (the faces' world
// normals), so that the test holds for scaled parts too.
RSL_SHARED bool clears_box_face_scaled(vec3 sides, vec3 inverse_linear_light, vec3 face_scale, float sin_beta) {
    return clears_box_face(sides, inverse_linear_light / face_scale, sin_beta);
}

// RSL_GLSL_END

}  // namespace rsl::shading
