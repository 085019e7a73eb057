#pragma once
// Visibility distance tables (RSL paper §4.3; DESIGN.md "visibility distance
// tables").
//
// A visibility map is an N×N table over the equal-area plane [-1, 1]² (see
// src/core/hemisphere.h) holding, per texel, the visible fraction ("coverage")
// in [0, 1]. Its VDT D(p) is the signed Euclidean distance from p to the
// visible/blocked boundary, in PLANE units, positive where visible. The visible
// fraction of an axis-aligned square of half-edge h centered at p is then
//
//     V̄ ≈ clamp(½ + D(p) / (2h), 0, 1)            (exact for a straight edge
//                                                    parallel to a square edge)
//
// with D bilinearly interpolated between texel centers.
//
// Where the boundary lies (pinned by tests/fields/vdt_test.cpp):
//  * Binary mode: a texel is visible iff coverage ≥ ½, and the boundary runs
//    along texel edges. A texel's value is the distance from its center to the
//    nearest texel center of the opposite class, minus half a texel. For a
//    half-plane map this is exactly the distance to the edge line, so the
//    formula above is exact there.
//  * Coverage-aware mode: texels that contain the boundary ("sites": fractional
//    coverage, or a 4-neighbour of the opposite class) place it inside
//    themselves from their coverage and the local coverage gradient (the
//    anti-aliased distance transform of Gustavson & Strand 2011); every other
//    texel takes the distance to its nearest site's center plus that site's
//    offset. With exactly binary input both modes give the same table on
//    half-planes.
// Distances come from the exact Felzenszwalb–Huttenlocher (2012) transform:
// a separable 1D lower envelope of parabolas, with the nearest site tracked.
#include <cstdint>
#include <vector>

#include "src/core/hemisphere.h"

namespace rsl {

enum class VdtMode : uint8_t { Binary = 0, CoverageAware = 1 };

// Value given to a table whose map has no boundary (all visible or all
// blocked), in plane units: larger than any square's half-edge, so the
// fraction is exactly 0 or 1.
inline constexpr float kVdtNoBoundaryDistance = 4.0f;

// Scratch space so that tables can be computed in a hot loop without allocating.
struct VdtWorkspace {
    std::vector<float> column_dist2, envelope_z, parabola_f, offset;
    std::vector<int> column_site, envelope_v, site_of;
    std::vector<uint8_t> is_site;
    void reserve(int n);
};

// coverage: n×n visible fractions (stored j·n + i). vdt: n×n output, plane units.
void compute_vdt(int n, const float* coverage, float* vdt, VdtMode mode, VdtWorkspace& workspace);
std::vector<float> compute_vdt(int n, const std::vector<float>& coverage, VdtMode mode);

// Bilinear interpolation between texel centers; outside the outermost centers
// the edge value is held. Four taps (index, weight) so that compressed tables
// reconstruct only the texels they need.
struct BilinearTaps {
    int index[4];
    float weight[4];
};
inline BilinearTaps bilinear_taps(int n, const Vec2& p) {
    // Texel centers sit at integer coordinates after the −½ shift.
    const float hi = float(n - 1);
    const float u = std::clamp((p.x + 1.0f) * (0.5f * float(n)) - 0.5f, 0.0f, hi);
    const float v = std::clamp((p.y + 1.0f) * (0.5f * float(n)) - 0.5f, 0.0f, hi);
    const int i0 = std::min(int(u), n - 2);
    const int j0 = std::min(int(v), n - 2);
    const float fx = u - float(i0), fy = v - float(j0);
    BilinearTaps taps;
    const int base = j0 * n + i0;
    taps.index[0] = base;
    taps.index[1] = base + 1;
    taps.index[2] = base + n;
    taps.index[3] = base + n + 1;
    taps.weight[0] = (1 - fx) * (1 - fy);
    taps.weight[1] = fx * (1 - fy);
    taps.weight[2] = (1 - fx) * fy;
    taps.weight[3] = fx * fy;
    return taps;
}

inline float sample_bilinear(int n, const float* table, const Vec2& p) {
    const BilinearTaps taps = bilinear_taps(n, p);
    float sum = 0;
    for (int k = 0; k < 4; ++k) sum += taps.weight[k] * table[taps.index[k]];
    return sum;
}

// Plane point of a local direction for table lookups: hemisphere_to_plane,
// except at (and numerically near) the antipode of the pole, whose image is
// the whole circle |p| = √2; any point out there reads the table's far corner.
inline Vec2 lookup_plane_point(const Vec3& local) {
    if (local.z < -0.9999f) return Vec2(1.5f, 1.5f);
    return hemisphere_to_plane(local);
}

// The VDT rule: visible fraction of a square of half-edge h whose center has
// interpolated distance d.
inline float visible_fraction_from_distance(float d, float half_edge) {
    return std::clamp(0.5f + d / (2.0f * half_edge), 0.0f, 1.0f);
}

inline float vdt_visible_fraction(int n, const float* vdt, const Vec2& center, float half_edge) {
    return visible_fraction_from_distance(sample_bilinear(n, vdt, center), half_edge);
}

// Reference: the exact mean of the piecewise-constant map over the part of the
// square [center ± h] inside [-1, 1]² (what a summed-area table of the same
// map gives). Brute force over the texels the square touches.
double exact_square_fraction(int n, const float* coverage, const Vec2& center, float half_edge);

}  // namespace rsl
