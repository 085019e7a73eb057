#pragma once
// The equal-area hemisphere parameterization of RSL paper §5 and the N×N
// tables defined over it (BRDF SATs, VDTs).
//
//   p(θ, φ) = sinθ / √(1 + cosθ) · (sin φ, cos φ) = √2 sin(θ/2) · (sin φ, cos φ)
//
// with φ the azimuth measured from the local y axis towards x. For a local
// direction ω = (x, y, z) this is p = (ω.x, ω.y) / √(1 + ω.z): Lambert's
// azimuthal equal-area projection. A region of solid angle Ω maps to plane area
// Ω / 2 (dω = 2 dp), so averages are the same in both domains. The upper
// hemisphere maps onto the unit disk; below-horizon directions continue to
// radius √2 (the antipode), so a table's corners outside the disk are
// directions just below the horizon.
#include <algorithm>
#include <cmath>

#include "src/core/math.h"
#include "src/shading/frames.h"
#include "src/shading/squares.h"

namespace rsl {

// Local direction ↔ plane point (the map itself lives in the shading core,
// shared with the GPU: src/shading/shading_core.h).
using shading::hemisphere_to_plane;
using shading::plane_to_hemisphere;

// Plane area ↔ solid angle (the map is equal-area).
inline constexpr float kSolidAnglePerPlaneArea = 2.0f;

// An RSL of half-diagonal r has solid angle 2r²; in the plane it becomes an
// axis-aligned square of the same measure: area r², so half-edge h = r / 2.
// (The paper prints edge √2·r, which does not preserve measure; see docs/design/METHOD.md.)
using shading::square_half_edge_for_rsl;
inline float rsl_solid_angle(float half_diagonal) { return 2.0f * half_diagonal * half_diagonal; }

// An N×N table over [-1, 1]²: texel (i, j), i along x and j along y, has its
// center at (-1 + (i + ½)·2/N, -1 + (j + ½)·2/N) and is stored at j·N + i.
struct PlaneGrid {
    int n = 32;

    float texel_size() const { return 2.0f / n; }
    Vec2 texel_center(int i, int j) const {
        return Vec2(-1.0f + (i + 0.5f) * texel_size(), -1.0f + (j + 0.5f) * texel_size());
    }
    int index(int i, int j) const { return j * n + i; }
    int size() const { return n * n; }
    // Continuous texel coordinates: texel centers at integer + ½.
    Vec2 to_texel_coords(const Vec2& p) const { return (p + Vec2(1.0f)) * (0.5f * n); }
};

}  // namespace rsl
