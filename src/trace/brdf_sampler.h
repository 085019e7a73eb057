#pragma once
// Importance sampling of ρ·cos for any BRDF model (analytic, measured,
// anisotropic) from a tabulation on the equal-area hemisphere grid
// (src/core/hemisphere.h: p = (ω.x, ω.y)/√(1 + ω.z), dω = 2 dp), laid out
// as BrdfTable's slices (src/brdf/brdf_table.h): isotropic models in the
// view-aligned frame at V polar views (plane radii (k + ½)/V), anisotropic
// ones in the tangent frame at the V×V view-grid texel centres.
//
// Each slice is a piecewise-constant distribution over its N×N texels with
// weight luminance(texel average of ρ·cos) (TexelSampler), plus a small
// defensive share spread over the texels that reach into the unit disk, so
// that every direction above the horizon has a density even where a sharp
// lobe slipped between the tabulation's sub-samples. A view's proposal is
// the mixture of its 2 (isotropic: linear in the plane radius) or 4
// (anisotropic: bilinear) neighbouring slices with their interpolation
// weights w_s: a slice drawn with probability w_s, a texel from it, a point
// uniform in the texel, mapped to the hemisphere. So
//
//   pdf(ω) = Σ_s w_s · P_s(texel of ω) / (texel area · 2),   texel area (2/N)².
//
// Points outside the unit disk map below the horizon, where ρ·cos is zero:
// such a sample is drawn (and counts in the estimator's sample count) but
// contributes nothing. The proposal only has to be positive where ρ·cos is:
// estimators evaluate the exact model, never this table.
#include <vector>

#include "src/brdf/brdf.h"
#include "src/core/hemisphere.h"
#include "src/trace/sample_distribution.h"

namespace rsl {

struct BrdfSamplerOptions {
    int resolution = 32;  // N: texels per side of a slice's equal-area grid
    int views = 16;       // V: isotropic V polar views, anisotropic V×V
    int interior_supersampling = 2;  // TexelSampler's sub-samples per texel side inside the disk
    int edge_supersampling = 4;      // ... on texels the horizon crosses
    // The share of each slice's weight spread evenly over the texels that
    // reach into the disk (a defensive mixture: any lobe has a density).
    float defensive_share = 0.02f;
};

class BrdfSampler {
public:
    BrdfSampler(const Brdf& brdf, const BrdfSamplerOptions& options = {});

    bool isotropic() const { return isotropic_; }
    // ρ·cos tabulated zero everywhere (a black material): nothing to sample.
    bool empty() const { return empty_; }
    int resolution() const { return n_; }
    int slice_count() const { return int(slices_.size()); }
    const BrdfSamplerOptions& options() const { return options_; }

    // The proposal for one view (unit, local frame): its slices, their
    // weights, and (isotropic) the turn into the view-aligned frame.
    struct View {
        int slices[4] = {0, 0, 0, 0};
        float weights[4] = {1, 0, 0, 0};
        int count = 1;
        float sin_phi = 0, cos_phi = 1;  // the view's azimuth (isotropic tables)
    };
    View view(const Vec3& wo) const;

    // A direction wi (local frame) drawn from the view's proposal with
    // uniforms u0, u1 (the texel and the point in it; stratify these) and
    // u2 (the slice), and its density. False (wi and pdf untouched) when the
    // point fell outside the unit disk: below the horizon, no contribution.
    bool sample(const View& view, double u0, double u1, double u2, Vec3& wi, float& pdf) const;
    // The density of local direction wi under the view's proposal (0 below the horizon).
    float pdf(const View& view, const Vec3& wi) const;

private:
    void build_slices(const Brdf& brdf, const std::vector<Vec3>& slice_views);
    Vec3 from_table_frame(const View& view, const Vec3& w) const;
    Vec3 to_table_frame(const View& view, const Vec3& w) const;
    float texel_density(const View& view, int cell) const;

    BrdfSamplerOptions options_;
    bool isotropic_ = true;
    bool empty_ = true;
    int n_ = 0;
    float inverse_texel_measure_ = 0;  // 1 / (texel area · 2): probability → density per solid angle
    std::vector<PiecewiseConstant2D> slices_;  // one: view-independent (every slice the same)
};

}  // namespace rsl
