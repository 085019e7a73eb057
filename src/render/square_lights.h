#pragma once
// Lights as the runtime sees them: squares in a vertex's local hemisphere
// (docs/design/METHOD.md "Rotatable square lights", "Local lights").
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
#include "src/shading/squares.h"

namespace rsl {

// One square light at one vertex (or at every vertex, for an RSL).
struct SquareLight {
    Vec3 direction{0, 0, 1};  // unit, world space
    float half_edge = 0;      // plane units
    float solid_angle = 0;    // steradians
    Color integral{0};        // ∫ L dω over the square: solid_angle × radiance
};

// The square's half-edge for a solid angle and the exact cap of a sphere
// light: the shading core (src/shading/shading_core.h), shared with the GPU.
using shading::half_edge_for_solid_angle;
using shading::sphere_cap_solid_angle;

// The square light a sphere light (center, radius, radiance) makes at point x.
// A point inside the sphere is not lit by it (integral 0), as in the truth.
// The square is the shading core's (shading::sphere_square), shared with the GPU.
inline SquareLight sphere_light_square(const Vec3& x, const Vec3& center, float radius, const Color& radiance) {
    SquareLight light;
    const shading::SphereSquare square = shading::sphere_square(x, center, radius);
    if (!square.lit) return light;
    light.direction = square.direction;
    light.solid_angle = square.solid_angle;
    light.half_edge = square.half_edge;
    light.integral = radiance * light.solid_angle;
    return light;
}

// The slab rule of the occluder factor: a part lies in its bounding box, so a
// receiver beyond one of the box's faces (side s_a = ±1 along axis a, 0 when
// within the slab) is unshadowed by it from every direction that leaves that
// face's plane outwards; a square of half-edge h around L does so when some
// s_a·L_a ≥ sin β(h), β = square_cone_half_angle(h). Then the factor is
// exactly 1, whatever the OVDF's interpolation says (both renderers apply it,
// with and without culling; docs/design/RENDERER.md). The formulas are the shading
// core's (shared with the GPU); clears_box_face_scaled is the world form.
using shading::box_side;
using shading::clears_box_face;
using shading::clears_box_face_scaled;
using shading::square_cone_half_angle;
using shading::square_cone_sine;
using shading::square_reaches_hemisphere;

inline Vec3 box_sides(const Bounds& box, const Vec3& p) { return shading::box_sides(box.lo, box.hi, p); }

}  // namespace rsl
