#pragma once
// The exact diffuse light (docs/design/RENDERER.md "Exact diffuse light"):
// a part's constant BRDF term a shades with the environment's exact
// irradiance E(n), its shadows taken from the squares as a ratio,
//
//   a · E(n) · Σ_l I_l c_l V_l / Σ_l I_l c_l,   c_l = the cosine's average over square l,
//
// which equals the squares' own a · Σ_l I_l c_l V_l (the share the BRDF
// table holds) plus g · Σ_l I_l c_l V_l with the per-point gain
// g = a · (E(n) / Σ_l I_l c_l − 1): each light's BRDF average gains g · c_l.
// E is tabulated on a cube of normals (src/lightfit/irradiance.h) and read
// bilinearly here.
#include "src/shading/glsl_subset.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

// ∫ max(0, 1 − x² − y²) dy over y ∈ [y0, y1] at abscissa x: the cosine
// (cos θ = 1 − |p|² in the hemisphere plane) over one column of a square,
// zero outside the unit disk (below the horizon). Branch-free, so that the
// CPU's loops over many squares vectorize.
RSL_SHARED float cosine_column(float x, float y0, float y1) {
    float w = sqrt(max(1.0f - x * x, 0.0f));
    float a = max(y0, -w);
    float b = a + max(min(y1, w) - a, 0.0f);
    return (1.0f - x * x) * (b - a) - (b * b * b - a * a * a) * 0.33333334f;
}
// The columns' integral over [a, b] (0 when b ≤ a), where no edge of the
// square meets the disk's edge: 3-point Gauss–Legendre, exact where the
// square's edges bound the columns (a quadratic) and within 0.1% of the
// square's mean where the disk does (tests/lightfit/irradiance_test.cpp).
RSL_SHARED float cosine_columns(float a, float b, float y0, float y1) {
    float m = 0.5f * (a + b), r = 0.5f * max(b - a, 0.0f), u = 0.77459667f * r;
    return r * (0.88888889f * cosine_column(m, y0, y1) +
                0.55555556f * (cosine_column(m - u, y0, y1) + cosine_column(m + u, y0, y1)));
}
// A mean cosine below 1e-5 counts as 0: a square that barely grazes the
// horizon adds nothing, and rounding cannot make one renderer look its
// visibility up when the other does not.
RSL_CONST float kCosineFloor = 1e-5f;
RSL_SHARED float cosine_floor(float c) { return c > kCosineFloor ? c : 0.0f; }
// The mean of the clamped cosine over a square of centre c and half-edge h > 0
// that straddles the horizon: the columns between the x where the disk's
// edge crosses the square's two y edges (±√(1 − y²), sorted), and the square's
// x edges, each stretch smooth.
RSL_SHARED float square_average_cosine_across(vec2 c, float h) {
    float lo = max(c.x - h, -1.0f), hi = max(min(c.x + h, 1.0f), lo);
    float y0 = c.y - h, y1 = c.y + h;
    float e0 = sqrt(max(1.0f - y0 * y0, 0.0f)), e1 = sqrt(max(1.0f - y1 * y1, 0.0f));
    float k0 = clamp(-max(e0, e1), lo, hi), k1 = clamp(-min(e0, e1), lo, hi);
    float k2 = clamp(min(e0, e1), lo, hi), k3 = clamp(max(e0, e1), lo, hi);
    float sum = cosine_columns(lo, k0, y0, y1) + cosine_columns(k0, k1, y0, y1) + cosine_columns(k1, k2, y0, y1) +
                cosine_columns(k2, k3, y0, y1) + cosine_columns(k3, hi, y0, y1);
    return cosine_floor(sum / (4.0f * h * h));
}
// Where the square of centre c and half-edge h lies against the unit disk
// (the horizon): 0 inside it, 1 across its edge, 2 outside. Its corner
// farthest from the origin is (|c.x| + h, |c.y| + h), its nearest point
// (max(|c.x| − h, 0), max(|c.y| − h, 0)).
RSL_SHARED int square_against_disk(vec2 c, float h) {
    float fx = abs(c.x) + h, fy = abs(c.y) + h;
    float nx = max(abs(c.x) - h, 0.0f), ny = max(abs(c.y) - h, 0.0f);
    return fx * fx + fy * fy <= 1.0f ? 0 : (nx * nx + ny * ny < 1.0f ? 1 : 2);
}
// The average of cos θ over the square of centre c and half-edge h in the
// hemisphere plane (dω = 2 dp), the cosine clamped at the horizon as the
// BRDF tables clamp it: 1 − |c|² − 2h²/3 for a square inside the unit disk.
RSL_SHARED float square_average_cosine(vec2 c, float h) {
    if (!(h > 0.0f)) return cosine_floor(1.0f - dot(c, c));
    int where = square_against_disk(c, h);
    if (where == 0) return cosine_floor(1.0f - dot(c, c) - 0.6666667f * h * h);
    return where == 1 ? square_average_cosine_across(c, h) : 0.0f;
}

// The gain g of one channel: a · (E / U − 1), 0 where the squares bring no
// cosine-weighted light (U = Σ I c).
RSL_SHARED float diffuse_light_gain(float constant_term, float irradiance, float squares) {
    return squares > 0.0f ? constant_term * (irradiance / squares - 1.0f) : 0.0f;
}

// A cube of normals tabulated at its nodes: per face (M + 1)² nodes at face
// coordinates (s, t) = (−1 + 2i/M, −1 + 2j/M), face-major, row j, column i;
// the faces as CubeMap's (src/core/envmap.cpp). The taps of direction d:
// nodes first, first + 1, first + M + 1, first + M + 2 with bilinear weights.
struct CubeNodeTaps {
    int first;
    int row;
    vec2 weight;  // the upper neighbours' weights along i and j
};
RSL_SHARED CubeNodeTaps cube_node_taps(vec3 d, int m) {
    float ax = abs(d.x), ay = abs(d.y), az = abs(d.z);
    int face = 0;
    float major = ax, s = 0.0f, t = 0.0f;
    if (ax >= ay && ax >= az) {
        face = d.x > 0.0f ? 0 : 1;
        s = d.x > 0.0f ? -d.z : d.z;
        t = -d.y;
    } else if (ay >= az) {
        face = d.y > 0.0f ? 2 : 3;
        major = ay;
        s = d.x;
        t = d.y > 0.0f ? d.z : -d.z;
    } else {
        face = d.z > 0.0f ? 4 : 5;
        major = az;
        s = d.z > 0.0f ? d.x : -d.x;
        t = -d.y;
    }
    float inv = major > 0.0f ? 1.0f / major : 0.0f;
    float x = clamp((s * inv + 1.0f) * 0.5f * float(m), 0.0f, float(m));
    float y = clamp((t * inv + 1.0f) * 0.5f * float(m), 0.0f, float(m));
    int i = min(int(x), m - 1), j = min(int(y), m - 1);
    CubeNodeTaps taps;
    taps.row = m + 1;
    taps.first = (face * (m + 1) + j) * (m + 1) + i;
    taps.weight = vec2(x - float(i), y - float(j));
    return taps;
}

// RSL_GLSL_END

}  // namespace rsl::shading
