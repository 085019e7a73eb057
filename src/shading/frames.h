#pragma once
// Local frames and the equal-area hemisphere map (RSL paper §5;
// docs/design/METHOD.md): the coordinates every table is read in.
#include "src/shading/glsl_subset.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

// Any unit vector orthogonal to n (Duff et al. 2017, branchless ONB).
RSL_SHARED vec3 any_orthonormal(vec3 n) {
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float b = n.x * n.y * a;
    return vec3(1.0f + s * n.x * n.x * a, s * b, -s * n.x);
}

// Local frame: z = the normal, x = the tangent orthogonalized (Gram–Schmidt),
// any orthonormal x when the tangent is missing or parallel, y = z × x.
struct LocalFrame {
    vec3 x;
    vec3 y;
    vec3 z;
};
RSL_SHARED LocalFrame frame_from_normal_tangent(vec3 n, vec3 t) {
    LocalFrame f;
    f.z = normalize(n);
    vec3 x = t - f.z * dot(f.z, t);
    float len2 = dot(x, x);
    f.x = len2 > 1e-12f ? x * (1.0f / sqrt(len2)) : any_orthonormal(f.z);  // one division, not three
    f.y = cross(f.z, f.x);
    return f;
}
RSL_SHARED vec3 frame_to_local(LocalFrame f, vec3 v) { return vec3(dot(v, f.x), dot(v, f.y), dot(v, f.z)); }
RSL_SHARED vec3 frame_to_world(LocalFrame f, vec3 v) { return f.x * v.x + f.y * v.y + f.z * v.z; }

// Local direction (unit, anywhere but the exact antipode) → plane point
// p = (x, y) / √(1 + z), Lambert's azimuthal equal-area map.
RSL_SHARED vec2 hemisphere_to_plane(vec3 w) {
    float s = 1.0f / sqrt(max(1.0f + w.z, 1e-12f));
    return vec2(w.x * s, w.y * s);
}
// Plane point with |p| ≤ √2 → unit local direction (|p| < 1: above the horizon).
RSL_SHARED vec3 plane_to_hemisphere(vec2 p) {
    float rho2 = min(dot(p, p), 2.0f);
    float s = sqrt(max(2.0f - rho2, 0.0f));  // √(1 + cosθ)
    return vec3(p.x * s, p.y * s, 1.0f - rho2);
}
// hemisphere_to_plane for table lookups: at (and numerically near) the
// antipode, whose image is the whole circle |p| = √2, the table's far corner.
RSL_SHARED vec2 lookup_plane_point(vec3 local) {
    if (local.z < -0.9999f) return vec2(1.5f, 1.5f);
    return hemisphere_to_plane(local);
}

// RSL_GLSL_END

}  // namespace rsl::shading
