#include "src/brdf/brdf_table.h"

#include <cmath>

#include <tbb/parallel_for.h>

#include "src/brdf/texel_sampler.h"
#include "src/core/error.h"

namespace rsl {

// The 4×4 SAT corner taps of one square: along x, the two corners bracketing
// the right edge (weights +(1−f), +f) and the left edge (−(1−f), −f); the same
// along y. The integral over the square is Σ_m Σ_n wx[m]·wy[n]·S(ax[m], by[n]).
struct BrdfTable::Taps {
    int ax[4], by[4];
    float wx[4], wy[4];
    float clipped_area;   // texel units: area of the square inside [0, N]²
    float inv_full_area;  // 1 / (full square area in texel units)
};

namespace {

// Corner pair bracketing coordinate x ∈ [0, n], with the weight of the upper one.
inline void bracket(float x, int n, int& lower, float& upper_weight) {
    lower = std::min(static_cast<int>(x), n - 1);
    upper_weight = x - static_cast<float>(lower);
}

// Radius of the view in the plane, |p(ω_o)| = √(1 − cosθ_o), clamped to the disk.
inline float view_plane_radius(float cos_theta) { return std::sqrt(std::clamp(1.0f - cos_theta, 0.0f, 1.0f)); }

// Linear interpolation between V samples at (k + ½)/V of a coordinate in [0, 1]
// scaled by V (t = u·V − ½), clamped to the first and last sample.
inline void sample_lerp(float t, int v, int& k0, float& w) {
    t = std::clamp(t, 0.0f, static_cast<float>(v - 1));
    k0 = std::min(static_cast<int>(t), v - 2);
    w = t - static_cast<float>(k0);
}

}  // namespace

std::shared_ptr<const BrdfTable> BrdfTable::build(const Brdf& brdf, const BrdfTableOptions& options) {
    RSL_CHECK_GE(options.resolution, 2);
    RSL_CHECK_GE(options.view_samples, 2);
    std::shared_ptr<BrdfTable> table(new BrdfTable());
    table->isotropic_ = brdf.isotropic();
    table->options_ = options;
    table->grid_ = PlaneGrid{options.resolution};
    const int v = options.view_samples;
    // The last isotropic sample's radius; anisotropic grid points beyond it are pulled in to it.
    const float max_radius = (v - 0.5f) / v;
    if (table->isotropic_) {
        for (int k = 0; k < v; ++k) table->slice_views_.push_back(plane_to_hemisphere(Vec2(0.0f, (k + 0.5f) / v)));
    } else {
        const PlaneGrid view_grid{v};
        for (int j = 0; j < v; ++j)
            for (int i = 0; i < v; ++i) {
                Vec2 q = view_grid.texel_center(i, j);
                const float len = glm::length(q);
                if (len > max_radius) q *= max_radius / len;
                table->slice_views_.push_back(plane_to_hemisphere(q));
            }
    }
    const int slices = table->slice_count();
    const size_t texels = table->grid_.size();
    const size_t corners = static_cast<size_t>(options.resolution + 1) * (options.resolution + 1);
    table->texels_.resize(slices * texels);
    table->sat_.resize(slices * corners * 3);
    table->offsets_.resize(slices);

    const TexelSampler sampler(table->grid_, options.interior_supersampling, options.edge_supersampling);
    tbb::parallel_for(tbb::blocked_range<int>(0, slices), [&](const tbb::blocked_range<int>& range) {
        for (int s = range.begin(); s < range.end(); ++s) {
            Color* slice = table->texels_.data() + s * texels;
            sampler.texel_averages(brdf, table->slice_views_[s], slice);
            table->store_slice(s, slice);
        }
    });
    return table;
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
    float* out = sat_.data() + static_cast<size_t>(s) * (n + 1) * (n + 1) * 3;
    std::vector<DVec3> row_above(n + 1, DVec3(0.0));  // S(·, b−1), double
    for (int b = 0; b <= n; ++b) {
        DVec3 row_sum(0.0);
        for (int a = 0; a <= n; ++a) {
            if (b > 0 && a > 0) row_sum += DVec3(texels[grid_.index(a - 1, b - 1)]);
            const DVec3 sum = row_above[a] + row_sum;
            if (b > 0) row_above[a] = sum;
            const DVec3 stored = sum - offset * static_cast<double>(a) * static_cast<double>(b);
            float* corner = out + (static_cast<size_t>(b) * (n + 1) + a) * 3;
            for (int c = 0; c < 3; ++c) corner[c] = static_cast<float>(stored[c]);
        }
    }
}

BrdfTable::Taps BrdfTable::taps(float cx, float cy, float h) const {
    const int n = grid_.n;
    const float scale = 0.5f * static_cast<float>(n);  // plane → texel units
    h = std::max(h, 1e-6f);
    const float x0 = std::clamp((cx - h + 1.0f) * scale, 0.0f, float(n));
    const float x1 = std::clamp((cx + h + 1.0f) * scale, 0.0f, float(n));
    const float y0 = std::clamp((cy - h + 1.0f) * scale, 0.0f, float(n));
    const float y1 = std::clamp((cy + h + 1.0f) * scale, 0.0f, float(n));
    Taps t;
    int a0, a1, b0, b1;
    float f0, f1, g0, g1;
    bracket(x0, n, a0, f0);
    bracket(x1, n, a1, f1);
    bracket(y0, n, b0, g0);
    bracket(y1, n, b1, g1);
    t.ax[0] = a1, t.ax[1] = a1 + 1, t.ax[2] = a0, t.ax[3] = a0 + 1;
    t.wx[0] = 1.0f - f1, t.wx[1] = f1, t.wx[2] = f0 - 1.0f, t.wx[3] = -f0;
    t.by[0] = b1, t.by[1] = b1 + 1, t.by[2] = b0, t.by[3] = b0 + 1;
    t.wy[0] = 1.0f - g1, t.wy[1] = g1, t.wy[2] = g0 - 1.0f, t.wy[3] = -g0;
    t.clipped_area = (x1 - x0) * (y1 - y0);
    const float edge = 2.0f * h * scale;
    t.inv_full_area = 1.0f / (edge * edge);
    return t;
}

Color BrdfTable::slice_integral(int s, const Taps& t) const {
    const int stride = grid_.n + 1;
    const float* base = sat_.data() + static_cast<size_t>(s) * stride * stride * 3;
    float r = 0.0f, g = 0.0f, b = 0.0f;
    for (int n = 0; n < 4; ++n) {
        const float* row = base + static_cast<size_t>(t.by[n]) * stride * 3;
        for (int m = 0; m < 4; ++m) {
            const float w = t.wx[m] * t.wy[n];
            const float* c = row + t.ax[m] * 3;
            r += w * c[0];
            g += w * c[1];
            b += w * c[2];
        }
    }
    return Color(r, g, b) + offsets_[s] * t.clipped_area;
}

BrdfTable::ViewWeights BrdfTable::view_weights(float vx, float vy, float vz) const {
    const int v = options_.view_samples;
    ViewWeights out;
    if (isotropic_) {
        int k0;
        float w;
        sample_lerp(view_plane_radius(vz) * v - 0.5f, v, k0, w);
        out.slice[0] = k0, out.slice[1] = k0 + 1;
        out.weight[0] = 1.0f - w, out.weight[1] = w;
        out.count = 2;
        return out;
    }
    Vec2 p = hemisphere_to_plane(Vec3(vx, vy, std::max(vz, -0.999f)));
    const float len2 = glm::dot(p, p);
    if (len2 > 1.0f) p /= std::sqrt(len2);  // below the horizon: clamp to it
    int i0, j0;
    float wi, wj;
    sample_lerp((p.x + 1.0f) * 0.5f * v - 0.5f, v, i0, wi);
    sample_lerp((p.y + 1.0f) * 0.5f * v - 0.5f, v, j0, wj);
    out.slice[0] = j0 * v + i0, out.slice[1] = j0 * v + i0 + 1;
    out.slice[2] = (j0 + 1) * v + i0, out.slice[3] = (j0 + 1) * v + i0 + 1;
    out.weight[0] = (1 - wi) * (1 - wj), out.weight[1] = wi * (1 - wj);
    out.weight[2] = (1 - wi) * wj, out.weight[3] = wi * wj;
    out.count = 4;
    return out;
}

Color BrdfTable::slice_square_average(int s, const Vec2& center, float half_edge) const {
    const Taps t = taps(center.x, center.y, half_edge);
    if (t.clipped_area <= 0.0f) return Color(0.0f);
    return slice_integral(s, t) * t.inv_full_area;
}

Color BrdfTable::square_average(const Vec2& center, float half_edge, const Vec3& view) const {
    const Taps t = taps(center.x, center.y, half_edge);
    if (t.clipped_area <= 0.0f) return Color(0.0f);  // entirely outside the table (FMA would leave ±ulp residues)
    const ViewWeights vw = view_weights(view.x, view.y, view.z);
    Color sum(0.0f);
    for (int k = 0; k < vw.count; ++k) sum += vw.weight[k] * slice_integral(vw.slice[k], t);
    return sum * t.inv_full_area;
}

void BrdfTable::square_average_batch(const SquareQueries& q, const ColorOutputs& out) const {
    for (size_t k = 0; k < q.count; ++k) {
        const float h = q.half_edge ? q.half_edge[k] : q.uniform_half_edge;
        const Taps t = taps(q.center_x[k], q.center_y[k], h);
        if (t.clipped_area <= 0.0f) {
            out.r[k] = out.g[k] = out.b[k] = 0.0f;
            continue;
        }
        const ViewWeights vw = isotropic_ ? view_weights(0.0f, 0.0f, q.view_z[k])
                                          : view_weights(q.view_x[k], q.view_y[k], q.view_z[k]);
        Color sum(0.0f);
        for (int i = 0; i < vw.count; ++i) sum += vw.weight[i] * slice_integral(vw.slice[i], t);
        sum *= t.inv_full_area;
        out.r[k] = sum.r;
        out.g[k] = sum.g;
        out.b[k] = sum.b;
    }
}

size_t BrdfTable::memory_bytes() const {
    return sat_.size() * sizeof(float) + texels_.size() * sizeof(Color) + offsets_.size() * sizeof(Color) +
           slice_views_.size() * sizeof(Vec3);
}

}  // namespace rsl
