#pragma once
// Importance sampling of a cube map as the piecewise-constant function the
// ground truth integrates (docs/BASELINES.md, "env-rays").
//
// Texel k is drawn with probability P_k = luminance(L_k)·Ω_k / Σ_j
// luminance(L_j)·Ω_j (black texels never), then a point uniform in its square
// of face coordinates (s, t), of area A = (2/N)² (envmap.h: a face spans
// [−1, 1]²), and the direction d = F(s, t) / |F(s, t)| with F =
// CubeMap::face_direction, whose face axis is ±1 and the other two ±s, ±t, so
// |F|² = 1 + s² + t². The face at unit distance seen from the centre: an area
// ds dt at distance |F| whose normal makes cos γ = 1/|F| with d spans
//
//   dω = ds dt · cos γ / |F|² = ds dt / (1 + s² + t²)^{3/2},
//
// so the direction's density per solid angle is
//
//   pdf(d) = P_k · (1 + s² + t²)^{3/2} / A.
//
// Rows of the 2D warp are (face, j), columns i: CubeMap::index's order.
// Everything here is in the map's frame; a caller turns directions by the
// environment's rotation (which keeps densities).
#include <cmath>
#include <vector>

#include "src/core/envmap.h"
#include "src/trace/sample_distribution.h"

namespace rsl {

class EnvironmentSampler {
public:
    EnvironmentSampler() = default;
    explicit EnvironmentSampler(const CubeMap& map);

    // No texel with light: nothing to sample.
    bool empty() const { return distribution_.empty(); }
    int resolution() const { return n_; }

    struct Sample {
        Vec3 direction{0, 0, 1};  // unit, map frame
        Color radiance{0};        // the texel's L
        float pdf = 0;            // per solid angle
    };
    // u0 picks the row (face, j) and t, u1 the column i and s; both in [0, 1).
    Sample sample(double u0, double u1) const;

    // The density sample() draws the unit map-frame direction with, and the
    // radiance of the texel it points into (written to `radiance`).
    float lookup(const Vec3& direction, Color& radiance) const;
    float pdf(const Vec3& direction) const {
        Color unused;
        return lookup(direction, unused);
    }
    // The probability P_k of texel k (CubeMap::index order).
    float texel_probability(int index) const { return distribution_.probability(index); }

private:
    // (1 + s² + t²)^{3/2}: solid angle → face area.
    static float area_per_solid_angle(float s, float t) {
        const float r2 = 1.0f + s * s + t * t;
        return r2 * std::sqrt(r2);
    }

    int n_ = 0;
    float inverse_texel_area_ = 0;  // 1 / (2/N)²
    std::vector<Color> radiance_;
    PiecewiseConstant2D distribution_;
};

}  // namespace rsl
