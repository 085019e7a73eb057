#pragma once
// Lights as the runtime sees them: squares in a vertex's local hemisphere
// (DESIGN.md "Rotatable square lights", "Local lights").
//
// An environment RSL ⟨c, r, I⟩ is the same for every vertex: solid angle 2r²,
// light integral 2r²·I, and in the local equal-area plane an axis-aligned
// square of area r² centered at p(c): half-edge h = r / 2
// (square_half_edge_for_rsl).
//
// A sphere light of radius a at distance d is, for one vertex, a square light
// of the solid angle of the cap it subtends, Ω = 2π(1 − cos α) with sin α = a/d
// (the exact cap rather than πa²/d², which overestimates it by up to 2× as
// the light comes close), centered on the light's direction, with the sphere's
// radiance L = Φ / (4π² a²) (sphere_light_radiance, as the ground truth). Its
// plane square has area Ω / 2, so half-edge h = ½·√(Ω / 2).
#include <algorithm>
#include <cmath>

#include "src/core/hemisphere.h"
#include "src/core/math.h"
#include "src/core/mesh.h"

namespace rsl {

// One square light at one vertex (or at every vertex, for an RSL).
struct SquareLight {
    Vec3 direction{0, 0, 1};  // unit, world space
    float half_edge = 0;      // plane units
    float solid_angle = 0;    // steradians
    Color integral{0};        // ∫ L dω over the square: solid_angle × radiance
};

inline float half_edge_for_solid_angle(float solid_angle) { return 0.5f * std::sqrt(0.5f * solid_angle); }

// Solid angle of the cap subtended by a sphere of radius a at distance d > a:
// 2π(1 − cos α), written as 2π sin²α / (1 + cos α) to avoid cancellation.
inline float sphere_cap_solid_angle(float radius, float distance) {
    const float sin2 = std::min(1.0f, (radius / distance) * (radius / distance));
    return 2.0f * kPi * sin2 / (1.0f + std::sqrt(1.0f - sin2));
}

// The square light a sphere light (center, radius, radiance) makes at point x.
// A point inside the sphere is not lit by it (integral 0), as in the truth.
inline SquareLight sphere_light_square(const Vec3& x, const Vec3& center, float radius, const Color& radiance) {
    SquareLight light;
    const Vec3 to_center = center - x;
    const float distance = glm::length(to_center);
    if (!(distance > radius)) return light;
    light.direction = to_center / distance;
    light.solid_angle = sphere_cap_solid_angle(radius, distance);
    light.half_edge = half_edge_for_solid_angle(light.solid_angle);
    light.integral = radiance * light.solid_angle;
    return light;
}

// Half-angle of a cone around the light's direction that contains the part of
// its square above any vertex's horizon, whatever the vertex's frame. The
// square's points lie within plane distance √2·h of its center, and the plane
// segment from the center to any of them stays within plane radius
// ρ_max = min(√2, 1 + √2·h) (hemisphere.h: ρ = √2·sin(θ/2)). The inverse map
// stretches lengths by at most √2 / cos(θ/2) (radially; tangentially it
// shrinks), so the angle from the center is at most √2·h · √2 / cos(θ_max/2).
inline float square_cone_half_angle(float half_edge) {
    const float rho_max = std::min(std::numbers::sqrt2_v<float>, 1.0f + std::numbers::sqrt2_v<float> * half_edge);
    const float sin_half = rho_max / std::numbers::sqrt2_v<float>;
    const float cos_half = std::sqrt(std::max(0.0f, 1.0f - sin_half * sin_half));
    if (cos_half < 1e-3f) return kPi;
    return std::min(kPi, 2.0f * half_edge / cos_half);
}

// The slab rule of the occluder factor: a part lies in its bounding box, so a
// receiver beyond one of the box's faces (side s_a = ±1 along axis a, 0 when
// within the slab) is unshadowed by it from every direction that leaves that
// face's plane outwards. A square of half-edge h around the unit direction L
// (both in the part's frame) does so when some s_a·L_a ≥ sin β(h), β =
// square_cone_half_angle(h): its directions are within β of L. Then the
// factor is exactly 1, whatever the OVDF's interpolation says (both renderers
// apply it, with and without culling; docs/RENDERER.md).
inline bool clears_box_face(const Vec3& sides, const Vec3& light, float sin_beta) {
    return std::max({sides.x * light.x, sides.y * light.y, sides.z * light.z}) >= sin_beta;
}
// The same for a world direction w given as inverse_linear·w (not normalized)
// and the lengths of inverse_linear's rows: the face normals are those rows,
// so the test holds in the world whatever the part's scale.
inline bool clears_box_face(const Vec3& sides, const Vec3& inverse_linear_light, const Vec3& face_scale,
                            float sin_beta) {
    return clears_box_face(sides, inverse_linear_light / face_scale, sin_beta);
}
inline float square_cone_sine(float half_edge) {
    const float beta = square_cone_half_angle(half_edge);
    return beta >= 0.5f * kPi ? 2.0f : std::sin(beta);  // 2: never clears
}
inline Vec3 box_sides(const Bounds& box, const Vec3& p) {
    const auto side = [](float x, float lo, float hi) { return x > hi ? 1.0f : x < lo ? -1.0f : 0.0f; };
    return Vec3(side(p.x, box.lo.x, box.hi.x), side(p.y, box.lo.y, box.hi.y), side(p.z, box.lo.z, box.hi.z));
}

// Whether a square of half-edge h centered on local direction w can overlap the
// upper hemisphere (the unit disk): |p(w)| = √(1 − w.z) must be < 1 + √2·h.
inline bool square_reaches_hemisphere(float local_z, float half_edge) {
    const float reach = 1.0f + std::numbers::sqrt2_v<float> * half_edge;
    return local_z > 1.0f - reach * reach;
}

}  // namespace rsl
