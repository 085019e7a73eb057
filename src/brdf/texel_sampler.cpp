#include "src/brdf/texel_sampler.h"

#include <cmath>

#include "src/core/error.h"

namespace rsl {

TexelSampler::TexelSampler(const PlaneGrid& grid, int interior, int edge) : grid_(grid) {
    RSL_CHECK_GE(interior, 1);
    RSL_CHECK_GE(edge, interior);
    const int n = grid.n;
    const float size = grid.texel_size();
    texel_begin_.reserve(grid.size() + 1);
    texel_weight_.reserve(grid.size());
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            texel_begin_.push_back(static_cast<int>(directions_.size()));
            const Vec2 lo(-1.0f + i * size, -1.0f + j * size), hi = lo + Vec2(size);
            // Nearest and farthest points of the texel from the origin decide
            // whether the horizon (the unit circle) crosses it.
            const Vec2 nearest = glm::clamp(Vec2(0.0f), lo, hi);
            const Vec2 farthest(std::max(std::abs(lo.x), std::abs(hi.x)), std::max(std::abs(lo.y), std::abs(hi.y)));
            const bool outside = glm::dot(nearest, nearest) >= 1.0f;
            const bool inside = glm::dot(farthest, farthest) <= 1.0f;
            const int s = inside ? interior : edge;
            texel_weight_.push_back(outside ? 0.0f : 1.0f / static_cast<float>(s * s));
            if (outside) continue;
            for (int b = 0; b < s; ++b)
                for (int a = 0; a < s; ++a) {
                    const Vec2 p = lo + Vec2((a + 0.5f) / s, (b + 0.5f) / s) * size;
                    if (glm::dot(p, p) < 1.0f) directions_.push_back(plane_to_hemisphere(p));
                }
        }
    texel_begin_.push_back(static_cast<int>(directions_.size()));
}

void TexelSampler::texel_averages(const Brdf& brdf, const Vec3& wo, Color* out) const {
    for (int t = 0; t < grid_.size(); ++t) {
        Color sum(0.0f);
        for (int k = texel_begin_[t]; k < texel_begin_[t + 1]; ++k) {
            const Vec3& wi = directions_[k];
            sum += brdf.eval(wi, wo) * wi.z;
        }
        out[t] = sum * texel_weight_[t];
    }
}

}  // namespace rsl
