#include "src/brdf/brdf_table.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "src/brdf/texel_sampler.h"
#include "src/core/error.h"

namespace rsl {

std::vector<Vec3> BrdfTable::slice_views(bool isotropic, int v) {
    std::vector<Vec3> views;
    if (isotropic) {
        for (int k = 0; k < v; ++k) views.push_back(plane_to_hemisphere(Vec2(0.0f, (float(k) + 0.5f) / float(v))));
        return views;
    }
    const float max_radius = (float(v) - 0.5f) / float(v);
    const PlaneGrid view_grid{v};
    for (int j = 0; j < v; ++j)
        for (int i = 0; i < v; ++i) {
            Vec2 q = view_grid.texel_center(i, j);
            const float len = glm::length(q);
            if (len > max_radius) q *= max_radius / len;
            views.push_back(plane_to_hemisphere(q));
        }
    return views;
}

std::shared_ptr<const BrdfTable> BrdfTable::build(const Brdf& brdf, const BrdfTableOptions& options) {
    RSL_CHECK_GE(options.resolution, 4);  // a small square reads 4 texels per axis (brdf_sat.h)
    RSL_CHECK_GE(options.view_samples, 2);
    std::shared_ptr<BrdfTable> table(new BrdfTable());
    table->isotropic_ = brdf.isotropic();
    table->options_ = options;
    if (!table->isotropic_) table->options_.view_samples = std::min(options.view_samples, options.anisotropic_view_samples);
    table->grid_ = PlaneGrid{options.resolution};
    table->slice_views_ = slice_views(table->isotropic_, table->options_.view_samples);
    const int slices = table->slice_count();
    const size_t texels = table->grid_.size();
    const size_t corners = static_cast<size_t>(options.resolution + 1) * (options.resolution + 1);
    table->slice_floats_ = corners * 2 * 3;
    std::vector<Color> texel_averages(slices * texels);
    table->lookup_.resize(slices * table->slice_floats_);
    table->offsets_.resize(slices);

    const TexelSampler sampler(table->grid_, options.interior_supersampling, options.edge_supersampling);
    tbb::parallel_for(tbb::blocked_range<int>(0, slices), [&](const tbb::blocked_range<int>& range) {
        for (int s = range.begin(); s < range.end(); ++s) {
            Color* slice = texel_averages.data() + s * texels;
            sampler.texel_averages(brdf, table->slice_views_[s], slice);
            table->store_slice(s, slice);
        }
    });
    table->last_slice_ = slices - 1;
    const float* last = table->lookup_.data() + table->last_slice_ * table->slice_floats_;
    table->last_slice_padded_.assign(last, last + table->slice_floats_);
    table->last_slice_padded_.resize(table->slice_floats_ + 8, 0.0f);
    table->detect_view_independence();
    return table;
}

// Bitwise-equal texels give bitwise-equal corner sums and offsets
// (store_slice is deterministic), and the texels are in the slice's entries:
// where the entries are equal, one slice stands for all of them exactly.
void BrdfTable::detect_view_independence() {
    view_independent_ = true;
    for (size_t f = slice_floats_; f < lookup_.size() && view_independent_; ++f)
        view_independent_ = lookup_[f] == lookup_[f % slice_floats_];
}

void BrdfTable::store_slice(int s, const Color* texels) {
    const int n = grid_.n;
    DVec3 mean(0.0);
    if (options_.storage == SatStorage::FloatMeanOffset) {
        for (int t = 0; t < grid_.size(); ++t) mean += DVec3(texels[t]);
        mean /= static_cast<double>(grid_.size());
    }
    offsets_[s] = Color(mean);
    // The offset actually added back at lookup is the float one; subtract exactly that.
    const DVec3 offset(offsets_[s]);
    const size_t row = static_cast<size_t>(n + 1) * 3;  // lookup_data()'s layout
    float* const slice = lookup_.data() + static_cast<size_t>(s) * slice_floats_;
    float* const texel_layer = slice + (n + 1) * row;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const Color& texel = texels[grid_.index(i, j)];
            float* entry = texel_layer + static_cast<size_t>(j) * row + static_cast<size_t>(i) * 3;
            entry[0] = texel.r, entry[1] = texel.g, entry[2] = texel.b;
        }
    std::vector<DVec3> row_above(n + 1, DVec3(0.0));  // S(·, b−1), double
    for (int b = 0; b <= n; ++b) {
        DVec3 row_sum(0.0);
        for (int a = 0; a <= n; ++a) {
            if (b > 0 && a > 0) row_sum += DVec3(texels[grid_.index(a - 1, b - 1)]);
            const DVec3 sum = row_above[a] + row_sum;
            if (b > 0) row_above[a] = sum;
            const DVec3 stored = sum - offset * static_cast<double>(a) * static_cast<double>(b);
            float* corner = slice + static_cast<size_t>(b) * row + static_cast<size_t>(a) * 3;
            for (int c = 0; c < 3; ++c) corner[c] = static_cast<float>(stored[c]);
        }
    }
}

size_t BrdfTable::memory_bytes() const {
    return (lookup_.size() + last_slice_padded_.size()) * sizeof(float) + offsets_.size() * sizeof(Color) +
           slice_views_.size() * sizeof(Vec3);
}

}  // namespace rsl
