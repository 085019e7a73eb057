#pragma once
// The occluder field's table lookup (shadow fields, Zhou et al. 2005;
// src/fields/ovdf.h, docs/design/FIELDS.md): shells, cube faces, samples, the
// bounding cone and its zoom, the distance bounds, and the cone's culling test.
#include "src/shading/interpolation.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

// Where an OVDF's bounding cone edge lies in a zoomed table ([-1, 1]²).
RSL_CONST float kOvdfZoomEdge = 0.75f;
// The cone radius used where there is no cone (inside the bounding sphere).
RSL_CONST float kOvdfNoCone = 1e6f;
RSL_CONST int kCubeFaces = 6;

// The natural log of a positive normal float to 1.2e-7 (absolute where
// |log x| < 1, relative above; tests/fields/ovdf_test.cpp), the same
// arithmetic in both renderers and, unlike the libraries' log, in a loop the
// CPU vectorizes (its near-point locations, src/fields/ovdf_near.cpp). x = m·2^e
// with m in [√½, √2): log x = e·ln 2 + 2·atanh(s), s = (m − 1)/(m + 1), |s| ≤
// 0.172, whose series to s⁹ leaves 1e-9.
RSL_SHARED float portable_log(float x) {
    int bits = floatBitsToInt(x);
    int exponent = ((bits >> 23) & 255) - 127;
    float m = intBitsToFloat((bits & 8388607) | 1065353216);  // the mantissa in [1, 2)
    bool high = m > 1.41421356f;
    m = high ? 0.5f * m : m;
    exponent = high ? exponent + 1 : exponent;
    float s = (m - 1.0f) / (m + 1.0f);
    float s2 = s * s;
    float series = 0.222222222f;  // 2/9, 2/7, 2/5, 2/3, 2: 2·atanh(s)/s
    series = series * s2 + 0.285714286f;
    series = series * s2 + 0.4f;
    series = series * s2 + 0.666666667f;
    series = series * s2 + 2.0f;
    return float(exponent) * 0.693147181f + s * series;
}
// Continuous shell index of distance ratio d / R between the inner and the
// outer shell radii (× R): spacing 0 geometric, 1 linear, 2 inverse radius.
RSL_SHARED float ovdf_shell_coordinate(int spacing, int shells, float inner, float outer, float ratio) {
    float last = float(shells - 1);
    if (spacing == 0) return last * portable_log(max(ratio, 1e-6f) / inner) / portable_log(outer / inner);
    if (spacing == 1) return last * (ratio - inner) / (outer - inner);
    return last * (1.0f / max(ratio, 1e-6f) - 1.0f / inner) / (1.0f / outer - 1.0f / inner);
}
// The two shells around a shell coordinate (clamped inside): the lower one
// and the upper one's weight.
RSL_SHARED LerpPair ovdf_shell_pair(float coordinate, int shells) { return sample_lerp(coordinate, shells); }

// The cube face whose normal is nearest to the unit direction (the first on
// ties), and the cosine to it.
struct CubeFace {
    int face;
    float cosine;
};
RSL_SHARED CubeFace cube_face(vec3 dir, const vec3 normals[6]) {
    CubeFace c;
    c.face = 0;
    c.cosine = -2.0f;
    for (int f = 0; f < kCubeFaces; ++f) {
        float d = dot(dir, normals[f]);
        if (d > c.cosine) {
            c.face = f;
            c.cosine = d;
        }
    }
    return c;
}
// The four sample taps (i, j) of an n×n face around unit direction dir and
// their bilinear weights: (i, j), (i+1, j), (i, j+1), (i+1, j+1). s, t: the
// face's axes; cosine: dir's cosine to the face normal.
struct SampleTaps {
    ivec4 i;
    ivec4 j;
    vec4 weight;
};
RSL_SHARED SampleTaps ovdf_sample_taps(vec3 dir, float cosine, vec3 s, vec3 t, int n) {
    float hi = float(n - 1);
    float inverse_cosine = 1.0f / cosine;
    float x = clamp((dot(dir, s) * inverse_cosine + 1.0f) * 0.5f * float(n) - 0.5f, 0.0f, hi);
    float y = clamp((dot(dir, t) * inverse_cosine + 1.0f) * 0.5f * float(n) - 0.5f, 0.0f, hi);
    int i0 = min(int(x), n - 2);
    int j0 = min(int(y), n - 2);
    float fx = x - float(i0);
    float fy = y - float(j0);
    SampleTaps taps;
    // Whole-vector arithmetic: the CPU builds and copies them in registers.
    taps.i = ivec4(i0) + ivec4(0, 1, 0, 1);
    taps.j = ivec4(j0) + ivec4(0, 0, 1, 1);
    taps.weight = vec4((1.0f - fx) * (1.0f - fy), fx * (1.0f - fy), (1.0f - fx) * fy, fx * fy);
    return taps;
}
// Sample (shell, face, i, j) of faces of n×n samples, and its PCA segment
// (each face split m×m).
RSL_SHARED int ovdf_sample_index(int shell, int face, int i, int j, int n) {
    return ((shell * kCubeFaces + face) * n + j) * n + i;
}
RSL_SHARED int ovdf_segment_of(int shell, int face, int i, int j, int n, int m) {
    return ((shell * kCubeFaces + face) * m + j * m / n) * m + i * m / n;
}

// Plane radius of the bounding cone of a part of bounding radius R seen from
// distance d > R: √2·sin(½·asin x) = x / √(1 + √(1 − x²)), x = R/d — square
// roots only, which GLSL evaluates as C++ does (its asin is approximate).
RSL_SHARED float ovdf_cone_radius(float distance, float radius) {
    float x = min(radius / max(distance, 1e-30f), 1.0f);
    return x / sqrt(1.0f + sqrt(1.0f - x * x));
}
// A shell's zoomed table: table point = zoom × plane point, so that the
// bounding cone's edge maps to kOvdfZoomEdge (src/fields/ovdf.h). Inside the
// bounding sphere there is no cone: the part may lie in any direction, the
// ones away from its centre too (|p| up to √2, the antipode), so the table
// is zoomed out by 1/√2 to hold the whole sphere of directions in its
// inscribed disk. (At zoom 1 only the square's corners reached past |p| = 1,
// and every other direction away from the centre read the edge texel, the
// horizon: a chair in the middle of a room read the room's walls when it
// looked out of the room's open side.)
struct OvdfZoom {
    float zoom;
    float cone;  // plane radius of the bounding cone's edge
};
RSL_CONST float kOvdfInsideZoom = 0.70710678f;
RSL_SHARED OvdfZoom ovdf_zoom(float distance, float radius) {
    OvdfZoom z;
    z.zoom = kOvdfInsideZoom;
    z.cone = kOvdfNoCone;
    if (distance <= radius) return z;
    z.cone = ovdf_cone_radius(distance, radius);
    z.zoom = max(1.0f, kOvdfZoomEdge / z.cone);
    return z;
}
// A shell's distance in plane units from its table value (table units) at a
// plane point of radius `radial`: the part lies in the cone, D ≥ |p| − e.
RSL_SHARED float ovdf_plane_distance(float table_distance, OvdfZoom z, float radial) {
    return max(table_distance / z.zoom, radial - z.cone);
}
// The same with the table value already scaled by the shell's weight w > 0
// (w·D′), giving w × the shell's distance: the renderers' form.
RSL_SHARED float ovdf_weighted_plane_distance(float weighted_table_distance, float weight, OvdfZoom z, float radial) {
    return max(weighted_table_distance / z.zoom, weight * (radial - z.cone));
}
// The same bound with the cone seen from the receiver itself, after the
// shells' blend (exact, tighter than the nearer shell's).
RSL_SHARED float ovdf_receiver_distance(float blended, float radial, float cone) {
    return max(blended, radial - cone);
}
// The straight-edge rule (visible_fraction_from_distance) takes the shadow's
// edge for a line across the square: a square much larger than the part's
// silhouette near its edge loses half of itself to a part that covers a
// sliver of it. The part cannot shadow more of the square than its whole
// silhouette: `occluded_area`, the samples' blended shadowed area of their
// tables in plane units (Ovdf::occluded_area), bounds the shadowed share of
// the square of half-edge h. kOvdfNoAreaBound: no bound (a receiver inside
// the part stays dark).
RSL_CONST float kOvdfNoAreaBound = 3.0e38f;
RSL_SHARED float ovdf_area_bound(float visible, float occluded_area, float h) {
    return max(visible, 1.0f - occluded_area / (4.0f * h * h));
}
// The receiver's own bounding cone test: whether the lookup certainly gives 1
// for a light at cosine cos_to_center from the pole (|p|² = 1 − cos) and a
// square of half-edge h: the square lies beyond |p| − cone ≥ h. Branch-free,
// for the CPU's vectorized loops; the GPU runs it before each lookup.
RSL_SHARED bool ovdf_unshadowed(float cos_to_center, float cone, float half_edge) {
    float limit = half_edge + cone;
    return cos_to_center <= 1.0f - limit * limit;
}

// RSL_GLSL_END

}  // namespace rsl::shading
