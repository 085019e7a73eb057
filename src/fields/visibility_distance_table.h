#pragma once
// Visibility distance tables (RSL paper §4.3; docs/design/METHOD.md "visibility distance
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
// Where the boundary lies (pinned by tests/fields/visibility_distance_table_test.cpp):
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
#include "src/shading/frames.h"
#include "src/shading/interpolation.h"
#include "src/shading/vdt.h"

namespace rsl {

enum class VdtMode : uint8_t { Binary = 0, CoverageAware = 1 };

// Value given to a table whose map has no boundary (all visible or all
// blocked), in plane units: larger than any square's half-edge, so the
// fraction is exactly 0 or 1 (shading core).
using shading::kVdtNoBoundaryDistance;

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
// reconstruct only the texels they need (shading core, shared with the GPU).
using shading::BilinearTaps;
using shading::bilinear_taps;

inline float sample_bilinear(int n, const float* table, const Vec2& p) {
    const BilinearTaps taps = bilinear_taps(n, p);
    float sum = 0;
    for (int k = 0; k < 4; ++k) sum += taps.weight[k] * table[taps.index[k]];
    return sum;
}

// The lookup plane point (antipode → the far corner) and the VDT rule
// clamp(½ + d / 2h): shading core.
using shading::lookup_plane_point;
using shading::visible_fraction_from_distance;

inline float vdt_visible_fraction(int n, const float* vdt, const Vec2& center, float half_edge) {
    return visible_fraction_from_distance(sample_bilinear(n, vdt, center), half_edge);
}

// Reference: the exact mean of the piecewise-constant map over the part of the
// square [center ± h] inside [-1, 1]² (what a summed-area table of the same
// map gives). Brute force over the texels the square touches.
double exact_square_fraction(int n, const float* coverage, const Vec2& center, float half_edge);

}  // namespace rsl
