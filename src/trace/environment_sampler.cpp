#include "src/trace/environment_sampler.h"

#include <algorithm>
#include <cmath>

namespace rsl {

EnvironmentSampler::EnvironmentSampler(const CubeMap& map)
    : n_(map.resolution()), radiance_(map.radiances()) {
    if (n_ == 0) return;
    const float texel_side = 2.0f / float(n_);
    inverse_texel_area_ = 1.0f / (texel_side * texel_side);
    std::vector<float> weights(size_t(map.texel_count()));
    for (int k = 0; k < map.texel_count(); ++k) {
        const Color& L = radiance_[size_t(k)];
        // Black (or negative) texels add nothing to the integral: never drawn.
        weights[size_t(k)] = (L.r > 0.0f || L.g > 0.0f || L.b > 0.0f) ? std::max(luminance(L), 0.0f) * map.solid_angle(k)
                                                                    : 0.0f;
    }
    distribution_ = PiecewiseConstant2D(6 * n_, n_, weights.data());
}

EnvironmentSampler::Sample EnvironmentSampler::sample(double u0, double u1) const {
    const PiecewiseConstant2D::Cell cell = distribution_.sample(u0, u1);
    const int face = cell.row / n_, j = cell.row % n_, i = cell.column;
    const double side = 2.0 / double(n_);
    const float s = float(-1.0 + (double(i) + cell.column_fraction) * side);
    const float t = float(-1.0 + (double(j) + cell.row_fraction) * side);
    Sample sample;
    sample.direction = glm::normalize(CubeMap::face_direction(face, s, t));
    const int index = cell.row * n_ + i;  // CubeMap::index(face, i, j)
    sample.radiance = radiance_[size_t(index)];
    sample.pdf = distribution_.probability(index) * area_per_solid_angle(s, t) * inverse_texel_area_;
    return sample;
}

float EnvironmentSampler::lookup(const Vec3& direction, Color& radiance) const {
    float s, t;
    const int face = CubeMap::face_coordinates(direction, s, t);
    auto cell = [&](float coord) { return std::clamp(int((coord + 1.0f) * 0.5f * float(n_)), 0, n_ - 1); };
    const int index = (face * n_ + cell(t)) * n_ + cell(s);
    radiance = radiance_[size_t(index)];
    return distribution_.probability(index) * area_per_solid_angle(s, t) * inverse_texel_area_;
}

}  // namespace rsl
