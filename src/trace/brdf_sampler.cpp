#include "src/trace/brdf_sampler.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "src/brdf/brdf_table.h"
#include "src/brdf/texel_sampler.h"
#include "src/core/error.h"
#include "src/shading/brdf_sat.h"

namespace rsl {

namespace {

// Which texels of an N×N grid over [−1, 1]² reach into the open unit disk.
std::vector<bool> texels_in_disk(int n) {
    std::vector<bool> inside(size_t(n) * n);
    const float side = 2.0f / float(n);
    auto nearest = [&](int k) {  // the coordinate of texel row/column k nearest 0
        const float lo = -1.0f + float(k) * side, hi = lo + side;
        return lo > 0.0f ? lo : (hi < 0.0f ? hi : 0.0f);
    };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) inside[size_t(j) * n + i] = nearest(i) * nearest(i) + nearest(j) * nearest(j) < 1.0f;
    return inside;
}

// Linear interpolation between samples at integer coordinates 0 … count − 1:
// the lower sample and the upper one's weight, clamped at both ends.
void lerp_pair(float x, int count, int& lower, float& upper_weight) {
    x = std::clamp(x, 0.0f, float(count - 1));
    lower = std::min(int(x), count - 2);
    upper_weight = x - float(lower);
}

}  // namespace

BrdfSampler::BrdfSampler(const Brdf& brdf, const BrdfSamplerOptions& options)
    : options_(options), isotropic_(brdf.isotropic()), n_(options.resolution) {
    RSL_CHECK_GE(options.resolution, 2);
    RSL_CHECK_GE(options.views, 2);
    RSL_CHECK_GE(options.defensive_share, 0.0f);
    const float side = 2.0f / float(n_);
    inverse_texel_measure_ = 1.0f / (side * side * kSolidAnglePerPlaneArea);
    build_slices(brdf, BrdfTable::slice_views(isotropic_, options.views));
}

// Tabulates every slice (in parallel), adds the defensive share, and keeps
// one slice when all are equal (Lambert: the view does not matter).
void BrdfSampler::build_slices(const Brdf& brdf, const std::vector<Vec3>& views) {
    const PlaneGrid grid{n_};
    const size_t texels = size_t(grid.size());
    const TexelSampler sampler(grid, options_.interior_supersampling, options_.edge_supersampling);
    std::vector<std::vector<float>> weights(views.size(), std::vector<float>(texels));
    tbb::parallel_for(size_t(0), views.size(), [&](size_t s) {
        std::vector<Color> averages(texels);
        sampler.texel_averages(brdf, views[s], averages.data());
        for (size_t t = 0; t < texels; ++t) weights[s][t] = std::max(luminance(averages[t]), 0.0f);
    });
    const std::vector<bool> in_disk = texels_in_disk(n_);
    const double disk_texels = double(std::count(in_disk.begin(), in_disk.end(), true));
    std::vector<double> means(views.size());
    double mean_of_all = 0.0;
    for (size_t s = 0; s < views.size(); ++s) {
        double sum = 0.0;
        for (float w : weights[s]) sum += double(w);
        means[s] = sum / disk_texels;
        mean_of_all += means[s] / double(views.size());
    }
    empty_ = !(mean_of_all > 0.0);
    if (empty_) return;
    for (size_t s = 0; s < views.size(); ++s) {
        // A slice the lobe misses entirely (a grazing view) still gets a density.
        const float floor = float(options_.defensive_share * (means[s] > 0.0 ? means[s] : mean_of_all));
        for (size_t t = 0; t < texels; ++t)
            if (in_disk[t]) weights[s][t] += floor;
    }
    const bool all_equal = std::all_of(weights.begin(), weights.end(), [&](const auto& w) { return w == weights[0]; });
    const size_t kept = all_equal ? 1 : views.size();
    slices_.clear();
    for (size_t s = 0; s < kept; ++s) slices_.emplace_back(n_, n_, weights[s].data());
}

BrdfSampler::View BrdfSampler::view(const Vec3& wo) const {
    View v;
    const float len2 = wo.x * wo.x + wo.y * wo.y;
    if (isotropic_ && len2 > 1e-16f) {
        const float s = 1.0f / std::sqrt(len2);
        v.sin_phi = wo.x * s, v.cos_phi = wo.y * s;  // as to_view_aligned
    }
    if (slices_.size() == 1) return v;
    const int views = options_.views;
    int lower = 0, column = 0;
    float f = 0, g = 0;
    if (isotropic_) {
        lerp_pair(shading::isotropic_view_coordinate(wo.z, views), views, lower, f);
        v.count = 2;
        v.slices[0] = lower, v.weights[0] = 1.0f - f;
        v.slices[1] = lower + 1, v.weights[1] = f;
    } else {
        const Vec2 q = shading::anisotropic_view_point(wo);
        lerp_pair(shading::view_grid_coordinate(q.x, views), views, column, f);
        lerp_pair(shading::view_grid_coordinate(q.y, views), views, lower, g);
        v.count = 4;
        for (int k = 0; k < 4; ++k) {
            const int di = k & 1, dj = k >> 1;
            v.slices[k] = (lower + dj) * views + column + di;
            v.weights[k] = (di ? f : 1.0f - f) * (dj ? g : 1.0f - g);
        }
    }
    // Slices of weight zero are never drawn: keep the others only.
    int kept = 0;
    for (int k = 0; k < v.count; ++k)
        if (v.weights[k] > 0.0f) v.slices[kept] = v.slices[k], v.weights[kept++] = v.weights[k];
    v.count = kept;
    return v;
}

// Isotropic tables: the view-aligned frame (to_view_aligned) and back.
Vec3 BrdfSampler::to_table_frame(const View& v, const Vec3& w) const {
    if (!isotropic_) return w;
    return Vec3(w.x * v.cos_phi - w.y * v.sin_phi, w.x * v.sin_phi + w.y * v.cos_phi, w.z);
}
Vec3 BrdfSampler::from_table_frame(const View& v, const Vec3& w) const {
    if (!isotropic_) return w;
    return Vec3(w.x * v.cos_phi + w.y * v.sin_phi, -w.x * v.sin_phi + w.y * v.cos_phi, w.z);
}

float BrdfSampler::texel_density(const View& v, int cell) const {
    float p = 0.0f;
    for (int k = 0; k < v.count; ++k) p += v.weights[k] * slices_[size_t(v.slices[k])].probability(cell);
    return p * inverse_texel_measure_;
}

bool BrdfSampler::sample(const View& v, double u0, double u1, double u2, Vec3& wi, float& pdf) const {
    int chosen = v.count - 1;
    double below = 0.0;
    for (int k = 0; k + 1 < v.count; ++k) {
        below += double(v.weights[k]);
        if (u2 < below) {
            chosen = k;
            break;
        }
    }
    const PiecewiseConstant2D::Cell cell = slices_[size_t(v.slices[chosen])].sample(u0, u1);
    const double side = 2.0 / double(n_);
    const Vec2 p(float(-1.0 + (double(cell.column) + cell.column_fraction) * side),
                 float(-1.0 + (double(cell.row) + cell.row_fraction) * side));
    if (!(glm::dot(p, p) < 1.0f)) return false;
    wi = from_table_frame(v, plane_to_hemisphere(p));
    pdf = texel_density(v, cell.row * n_ + cell.column);
    return true;
}

float BrdfSampler::pdf(const View& v, const Vec3& wi) const {
    if (!(wi.z > 0.0f)) return 0.0f;
    const Vec2 p = hemisphere_to_plane(to_table_frame(v, wi));
    auto cell = [&](float coord) { return std::clamp(int((coord + 1.0f) * 0.5f * float(n_)), 0, n_ - 1); };
    return texel_density(v, cell(p.y) * n_ + cell(p.x));
}

}  // namespace rsl
