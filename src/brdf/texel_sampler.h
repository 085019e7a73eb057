#pragma once
// Texel averages of ρ·cosθ_i over the equal-area N×N grid (src/core/hemisphere.h)
// for one view direction: the content of one slice of a BRDF table.
//
// Each texel's value is the AVERAGE of ρ·cos over the texel's square in the
// plane (midpoint rule on S×S sub-squares), with the part outside the unit disk
// (below the horizon) counted as 0. Texels the horizon crosses get a finer S so
// that their partial coverage is integrated, not guessed from the center. With
// averages (not point samples) in the table, a texel-aligned square's SAT
// average is exactly the mean of the texels it covers.
#include <vector>

#include "src/brdf/brdf.h"
#include "src/core/hemisphere.h"

namespace rsl {

class TexelSampler {
public:
    // interior/edge: sub-samples per texel side inside the disk / on texels the
    // unit circle crosses. Texels entirely outside the disk have no samples.
    TexelSampler(const PlaneGrid& grid, int interior, int edge);

    // Writes grid.size() RGB texel averages (index j·N + i) for view `wo`
    // (unit, local frame of the table) into out[0 .. grid.size()).
    void texel_averages(const Brdf& brdf, const Vec3& wo, Color* out) const;

    const PlaneGrid& grid() const { return grid_; }
    size_t sample_count() const { return directions_.size(); }

private:
    PlaneGrid grid_;
    std::vector<Vec3> directions_;      // sub-sample light directions, grouped by texel
    std::vector<int> texel_begin_;      // samples of texel t: [texel_begin_[t], texel_begin_[t+1])
    std::vector<float> texel_weight_;   // 1 / (S·S) of the texel: outside-disk samples count as 0
};

}  // namespace rsl
