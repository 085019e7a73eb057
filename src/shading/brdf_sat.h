#pragma once
// BRDF summed-area tables (RSL paper §4.1; src/brdf/brdf_table_lookup.cpp):
// the corner taps of a square and the view samples' interpolation.
#include "src/shading/frames.h"
#include "src/shading/interpolation.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

// The SAT corner pair bracketing coordinate x ∈ [0, n], and the upper one's weight.
RSL_SHARED LerpPair corner_bracket(float x, int n) {
    LerpPair b;
    b.lower = min(int(x), n - 1);
    b.upper_weight = x - float(b.lower);
    return b;
}

// A table slice holds its corner sums S(a, b) (SAT) and its texels, each
// (N + 1)² RGB entries (the texels' last row and column zero;
// BrdfTable::lookup_data()). A square up to kMaxTexelSquareTexels texels wide reads the 4×4 texels
// around it, each weighted by its overlap: the same integral as the corner
// sums' (both take a texel as constant), without their cancellation. The
// corner sums of a neighbourhood are large next to a small square's
// integral, so their float rounding, which two renderers' different sums
// round differently, would be a visible share of a sun's average
// (docs/design/BRDF.md "Small squares").
RSL_CONST float kMaxTexelSquareTexels = 3.0f;

// The 4×4 taps of a square (centre c, half-edge h, plane units) on an n×n
// table. Corner sums: along x the corners bracketing the right edge
// (weights 1 − f, f) and the left edge (f − 1, −f); the same along y; the
// integral is Σ wx[m]·wy[l]·S(ax[m], by[l]) plus the mean offset × the
// clipped area. Texels: four texels from the one holding the left edge,
// each weighted by its overlap with the square. Either way ax = (a, a + 1,
// a′, a′ + 1) and by likewise: two pairs of neighbours per axis.
struct SquareTaps {
    ivec4 ax;
    ivec4 by;
    vec4 wx;
    vec4 wy;
    int texels;           // 1: ax, by index the texels; 0: the corner sums
    float clipped_area;   // texel units: the square's area inside [0, n]²
    float offset_area;    // the weight of the slice's mean offset: clipped_area on the SAT, 0 on texels
    float inv_full_area;  // 1 / (the whole square's area in texel units)
};
// A square narrower than a table texel (a sun's) is read as one texel wide:
// the table holds texel averages, so nothing finer is there to read.
// kMinSquareTexels: the narrowest square's edge in table texels (half-edge
// kMinSquareTexels / n in plane units, where a texel is 2 / n wide).
RSL_CONST float kMinSquareTexels = 1.0f;
// The overlap of texels first, …, first + 3 with [lo, hi] (texel units).
RSL_SHARED vec4 texel_overlaps(int first, float lo, float hi) {
    vec4 w;
    for (int k = 0; k < 4; ++k) w[k] = max(min(hi, float(first + k + 1)) - max(lo, float(first + k)), 0.0f);
    return w;
}
RSL_SHARED SquareTaps square_taps(vec2 c, float half_edge, int n) {
    float scale = 0.5f * float(n);  // plane → texel units
    float h = max(half_edge, kMinSquareTexels / float(n));
    float x0 = clamp((c.x - h + 1.0f) * scale, 0.0f, float(n));
    float x1 = clamp((c.x + h + 1.0f) * scale, 0.0f, float(n));
    float y0 = clamp((c.y - h + 1.0f) * scale, 0.0f, float(n));
    float y1 = clamp((c.y + h + 1.0f) * scale, 0.0f, float(n));
    float edge = 2.0f * h * scale;
    SquareTaps t;
    t.clipped_area = (x1 - x0) * (y1 - y0);
    t.inv_full_area = 1.0f / (edge * edge);
    if (edge <= kMaxTexelSquareTexels) {
        // Four texels reach past the right edge (edge ≤ 3); the first is at
        // most n − 3, so that the last is at most the zero column n.
        int a = min(int(x0), n - 3), b = min(int(y0), n - 3);
        t.ax = ivec4(a, a + 1, a + 2, a + 3);
        t.by = ivec4(b, b + 1, b + 2, b + 3);
        t.wx = texel_overlaps(a, x0, x1);
        t.wy = texel_overlaps(b, y0, y1);
        t.texels = 1;
        t.offset_area = 0.0f;
        return t;
    }
    LerpPair a0 = corner_bracket(x0, n);
    LerpPair a1 = corner_bracket(x1, n);
    LerpPair b0 = corner_bracket(y0, n);
    LerpPair b1 = corner_bracket(y1, n);
    t.ax = ivec4(a1.lower, a1.lower + 1, a0.lower, a0.lower + 1);
    t.wx = vec4(1.0f - a1.upper_weight, a1.upper_weight, a0.upper_weight - 1.0f, -a0.upper_weight);
    t.by = ivec4(b1.lower, b1.lower + 1, b0.lower, b0.lower + 1);
    t.wy = vec4(1.0f - b1.upper_weight, b1.upper_weight, b0.upper_weight - 1.0f, -b0.upper_weight);
    t.texels = 0;
    t.offset_area = t.clipped_area;
    return t;
}

// The v view samples lie at (k + ½)/v: a view coordinate u is sample
// position t = u·v − ½ (sample_lerp).
// Isotropic tables: the view's slice coordinate, linear in its plane radius √(1 − cos θ_o).
RSL_SHARED float isotropic_view_coordinate(float view_z, int v) {
    return sqrt(clamp(1.0f - view_z, 0.0f, 1.0f)) * float(v) - 0.5f;
}
// Anisotropic tables: a plane coordinate x ∈ [-1, 1] on the grid of v view
// samples (sample_lerp's t; samples at texel centres).
RSL_SHARED float view_grid_coordinate(float x, int v) { return (x + 1.0f) * 0.5f * float(v) - 0.5f; }
// Anisotropic tables: the view's plane point, clamped to the horizon (unit disk).
RSL_SHARED vec2 anisotropic_view_point(vec3 view) {
    vec2 p = hemisphere_to_plane(vec3(view.x, view.y, max(view.z, -0.999f)));
    float len2 = dot(p, p);
    if (len2 > 1.0f) p = p / sqrt(len2);
    return p;
}

// RSL_GLSL_END

}  // namespace rsl::shading
