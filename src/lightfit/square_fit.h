#pragma once
// Fitting one region of a cube map with a rotatable square light (RSL paper
// §4.1.1, Eq. 7):
//
//   minimize over c, r:   |S′| · E_θ[ ∫_{S′} (T − F_θ)² dω ],   S′ = S ∪ O_r,
//   θ ∈ {0, π/8, π/4, 3π/8},  I = ∫_S L dω / 2r²  (energy preservation, per channel)
//
// The chart. Around a center c we use Lambert's azimuthal equal-area projection
// scaled by √2, q(ω) = √2 · (ω′x, ω′y) / √(1 + ω′z) with ω′ = ω in a frame whose
// z is c. Plane area equals solid angle in this chart (dq = dω) and near c
// distances equal angles. The RSL is the square of half-diagonal r (edge √2·r,
// area 2r²) centred at the origin of the chart, turned by θ; O_r is the disk of
// radius r that all turns cover. It is the same measure as the runtime's square
// of half-edge r/2 in the unscaled hemisphere plane (src/core/hemisphere.h).
//
// Making the integral cheap. T is zero outside S and F is I on the square, so
//   ∫_{S′}(T − F_θ)² = Σ_ch ∫_S L² − 2 I·∫_{S∩Q_θ} L + |I|²·2r²
// needs the region's texels only: no texel outside S is visited. A texel enters
// as a box of side √Ω_k around its chart position, aligned with the turned
// square, so its covered fraction is a product of two 1D overlaps: continuous
// and piecewise linear in c and r, which keeps the search well behaved down to
// squares smaller than one texel. |S ∩ O_r| uses the same box against the disk.
//
// The search. c starts at the region's energy-weighted centroid; r is found by
// a log-spaced grid and golden-section refinement; then (optionally) c moves by
// a shrinking pattern search in the chart and r is refined again.
#include <array>
#include <span>
#include <vector>

#include "src/core/envmap.h"

namespace rsl::lightfit {

inline constexpr std::array<float, 4> kFitTurns = {0.0f, kPi / 8, kPi / 4, 3 * kPi / 8};

// What the fit needs of each texel, gathered once from the cube map.
struct FitTexel {
    Vec3 direction;
    float solid_angle;
    Color radiance;
    float footprint;  // √Ω: side of the texel's box in the chart
};

std::vector<FitTexel> make_fit_texels(const CubeMap& map);

// Sums over a region that merge by addition (so a merged pair's statistics
// cost O(1)).
struct RegionStats {
    DVec3 energy{0.0};               // Σ L Ω, per channel
    double squared_radiance = 0;     // Σ |L|² Ω  (∫_S T², summed over channels)
    double solid_angle = 0;          // Σ Ω
    std::array<DVec3, 3> radiance_weighted_direction{};  // per channel: Σ L_ch Ω d
    DVec3 area_weighted_direction{0.0};                  // Σ Ω d
    int texel_count = 0;

    static RegionStats of_texel(const FitTexel& texel);
    RegionStats& operator+=(const RegionStats& other);
    friend RegionStats operator+(RegionStats a, const RegionStats& b) { return a += b; }

    // Centroid weighted by each texel's energy projected on the region's colour
    // (E·L_k Ω_k); the area centroid for a black region. Unit length.
    Vec3 energy_centroid() const;
};

struct SquareFit {
    Vec3 center{0, 0, 1};
    float half_diagonal = 0;
    Color radiance{0};
    double error = 0;  // |S′|·E_θ[∫(T − F_θ)²], absolute (radiance² · sr²)
};

struct FitOptions {
    bool refine_center = true;  // pattern search for c after the centroid start
    int radius_grid = 8;        // log-spaced r samples before golden section
    int golden_steps = 8;       // golden-section iterations on r
};

// Holds scratch buffers (one per thread); fit() allocates only when a region
// is larger than any seen before.
class SquareFitter {
public:
    // Fits the region made of texels `a` ∪ `b` (disjoint index lists) whose
    // statistics are `stats`.
    SquareFit fit(std::span<const FitTexel> texels, const RegionStats& stats, std::span<const int> a,
                  std::span<const int> b = {}, const FitOptions& options = {});

    // The objective at a given center and half-diagonal (for tests and tools).
    double objective(std::span<const FitTexel> texels, const RegionStats& stats, std::span<const int> region,
                     const Vec3& center, float half_diagonal);

private:
    void gather(std::span<const FitTexel> texels, const RegionStats& stats, const Frame& frame,
                std::span<const int> a, std::span<const int> b);
    // Objective with the chart origin moved to `offset` (chart coordinates).
    double evaluate(float half_diagonal, Vec2 offset) const;
    float best_radius(float lo, float hi, Vec2 offset, int grid, int golden_steps, double* error) const;

    // Region constants of the current gather.
    double energy_norm2_ = 0, squared_radiance_ = 0, solid_angle_ = 0;
    // Per texel (SoA): chart position, coordinates along each turn's axes,
    // box side and its inverse, weight E·L_k Ω_k, solid angle.
    std::vector<float> x_, y_, side_, inv_side_, weight_, omega_;
    std::array<std::vector<float>, kFitTurns.size()> u_, v_;
    static constexpr size_t kLanes = 8;  // the SoA arrays are padded to a multiple of this
    size_t padded_count_ = 0;
    float min_side_ = 0, max_side_ = 0, max_radius_ = 0;
};

// The chart about `frame.z` (see above) and its inverse.
Vec2 fit_chart(const Frame& frame, const Vec3& direction);
Vec3 fit_chart_inverse(const Frame& frame, const Vec2& q);

}  // namespace rsl::lightfit
