#include "src/lightfit/square_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "src/core/error.h"

namespace rsl::lightfit {

namespace {
constexpr float kSqrt2 = std::numbers::sqrt2_v<float>;
// Chart radius of the antipode; no square reaches beyond it.
constexpr float kChartLimit = 2.0f;

// Length of [a − s/2, a + s/2] ∩ [−h, h], divided by s, for a ≥ 0: the fraction
// of a box of side s centred at a that lies within half-width h.
inline float box_overlap(float a, float h, float side, float inv_side) {
    const float hi = std::min(a + 0.5f * side, h);
    const float lo = std::max(a - 0.5f * side, -h);
    return std::max(hi - lo, 0.0f) * inv_side;
}

struct Turn {
    float cos, sin;
};
const std::array<Turn, kFitTurns.size()> kTurns = [] {
    std::array<Turn, kFitTurns.size()> turns{};
    for (size_t j = 0; j < kFitTurns.size(); ++j) turns[j] = {std::cos(kFitTurns[j]), std::sin(kFitTurns[j])};
    return turns;
}();
}  // namespace

Vec2 fit_chart(const Frame& frame, const Vec3& direction) {
    const Vec3 local = frame.to_local(direction);
    const float scale = kSqrt2 / std::sqrt(std::max(1.0f + local.z, 1e-12f));
    return Vec2(local.x * scale, local.y * scale);
}

Vec3 fit_chart_inverse(const Frame& frame, const Vec2& q) {
    const Vec2 p = q / kSqrt2;  // the unscaled hemisphere plane
    const float rho2 = std::min(glm::dot(p, p), 2.0f);
    const float s = std::sqrt(std::max(2.0f - rho2, 0.0f));
    return glm::normalize(frame.to_world(Vec3(p.x * s, p.y * s, 1.0f - rho2)));
}

std::vector<FitTexel> make_fit_texels(const CubeMap& map) {
    std::vector<FitTexel> texels(map.texel_count());
    for (int k = 0; k < map.texel_count(); ++k) {
        const float omega = map.solid_angle(k);
        texels[k] = {map.texel_direction(k), omega, map.radiance(k), std::sqrt(omega)};
    }
    return texels;
}

RegionStats RegionStats::of_texel(const FitTexel& t) {
    RegionStats s;
    const DVec3 d(t.direction);
    const DVec3 energy = DVec3(t.radiance) * double(t.solid_angle);
    s.energy = energy;
    s.squared_radiance = glm::dot(DVec3(t.radiance), DVec3(t.radiance)) * t.solid_angle;
    s.solid_angle = t.solid_angle;
    for (int ch = 0; ch < 3; ++ch) s.radiance_weighted_direction[ch] = energy[ch] * d;
    s.area_weighted_direction = double(t.solid_angle) * d;
    s.texel_count = 1;
    return s;
}

RegionStats& RegionStats::operator+=(const RegionStats& o) {
    energy += o.energy;
    squared_radiance += o.squared_radiance;
    solid_angle += o.solid_angle;
    for (int ch = 0; ch < 3; ++ch) radiance_weighted_direction[ch] += o.radiance_weighted_direction[ch];
    area_weighted_direction += o.area_weighted_direction;
    texel_count += o.texel_count;
    return *this;
}

Vec3 RegionStats::energy_centroid() const {
    DVec3 sum(0.0);
    for (int ch = 0; ch < 3; ++ch) sum += energy[ch] * radiance_weighted_direction[ch];
    const double weight = glm::dot(energy, energy) * solid_angle;  // scale of Σ (E·LΩ)
    if (glm::length(sum) > 1e-9 * weight && weight > 0) return Vec3(glm::normalize(sum));
    if (glm::length(area_weighted_direction) > 1e-12) return Vec3(glm::normalize(area_weighted_direction));
    return Vec3(0, 0, 1);  // a region covering the sphere symmetrically: any center is as good
}

void SquareFitter::gather(std::span<const FitTexel> texels, const RegionStats& stats, const Frame& frame,
                          std::span<const int> a, std::span<const int> b) {
    const size_t n = a.size() + b.size();
    padded_count_ = (n + kLanes - 1) / kLanes * kLanes;
    for (auto* v : {&x_, &y_, &side_, &inv_side_, &weight_, &omega_}) v->resize(padded_count_);
    for (auto& v : u_) v.resize(padded_count_);
    for (auto& v : v_) v.resize(padded_count_);
    // Padding texels weigh nothing and cover nothing.
    for (size_t k = n; k < padded_count_; ++k) {
        x_[k] = y_[k] = weight_[k] = omega_[k] = 0.0f;
        side_[k] = inv_side_[k] = 1.0f;
        for (size_t j = 0; j < kTurns.size(); ++j) u_[j][k] = v_[j][k] = 0.0f;
    }
    energy_norm2_ = glm::dot(stats.energy, stats.energy);
    squared_radiance_ = stats.squared_radiance;
    solid_angle_ = stats.solid_angle;
    const Vec3 energy(stats.energy);
    min_side_ = std::numeric_limits<float>::max();
    max_side_ = 0;
    max_radius_ = 0;
    size_t k = 0;
    for (auto list : {a, b}) {
        for (int index : list) {
            const FitTexel& t = texels[index];
            const Vec2 q = fit_chart(frame, t.direction);
            x_[k] = q.x;
            y_[k] = q.y;
            side_[k] = t.footprint;
            inv_side_[k] = 1.0f / t.footprint;
            weight_[k] = glm::dot(energy, t.radiance) * t.solid_angle;
            omega_[k] = t.solid_angle;
            for (size_t j = 0; j < kTurns.size(); ++j) {
                u_[j][k] = q.x * kTurns[j].cos + q.y * kTurns[j].sin;
                v_[j][k] = -q.x * kTurns[j].sin + q.y * kTurns[j].cos;
            }
            min_side_ = std::min(min_side_, t.footprint);
            max_side_ = std::max(max_side_, t.footprint);
            max_radius_ = std::max(max_radius_, glm::length(q));
            ++k;
        }
    }
}

// The hot loop of the fit (it vectorizes because everything builds with
// -fno-math-errno, CMakeLists.txt).
double SquareFitter::evaluate(float r, Vec2 offset) const {
    const float h = r / kSqrt2;  // half-edge of the square
    // A box far smaller than the disk is covered along the tangent direction
    // once r exceeds a few sides; for tiny disks this factor makes the covered
    // area πr² (radial 2r/s × tangential (π/2)·r/s).
    const float tangential_scale = 0.5f * kPi * r;
    std::array<float, kTurns.size()> ou{}, ov{};
    for (size_t j = 0; j < kTurns.size(); ++j) {
        ou[j] = offset.x * kTurns[j].cos + offset.y * kTurns[j].sin;
        ov[j] = -offset.x * kTurns[j].sin + offset.y * kTurns[j].cos;
    }
    const float* u0 = u_[0].data(); const float* u1 = u_[1].data();
    const float* u2 = u_[2].data(); const float* u3 = u_[3].data();
    const float* v0 = v_[0].data(); const float* v1 = v_[1].data();
    const float* v2 = v_[2].data(); const float* v3 = v_[3].data();
    const float *x = x_.data(), *y = y_.data(), *side = side_.data(), *inv_side = inv_side_.data();
    const float *weight = weight_.data(), *omega = omega_.data();
    // kLanes independent float sums (the arrays are padded to a multiple of
    // kLanes with zero weights) let the compiler vectorize the loop; they go
    // into doubles every kFlush texels so float sums stay short.
    constexpr size_t kFlush = 32 * kLanes;
    double covered_weight = 0, disk_overlap = 0;
    for (size_t start = 0; start < padded_count_; start += kFlush) {
        const size_t end = std::min(padded_count_, start + kFlush);
        float square_sum[kLanes] = {}, disk_sum[kLanes] = {};
        for (size_t base = start; base < end; base += kLanes)
            for (size_t lane = 0; lane < kLanes; ++lane) {
                const size_t k = base + lane;
                const float s = side[k], is = inv_side[k];
                const float cover =
                    box_overlap(std::abs(u0[k] - ou[0]), h, s, is) * box_overlap(std::abs(v0[k] - ov[0]), h, s, is) +
                    box_overlap(std::abs(u1[k] - ou[1]), h, s, is) * box_overlap(std::abs(v1[k] - ov[1]), h, s, is) +
                    box_overlap(std::abs(u2[k] - ou[2]), h, s, is) * box_overlap(std::abs(v2[k] - ov[2]), h, s, is) +
                    box_overlap(std::abs(u3[k] - ou[3]), h, s, is) * box_overlap(std::abs(v3[k] - ov[3]), h, s, is);
                square_sum[lane] += weight[k] * cover;
                const float dx = x[k] - offset.x, dy = y[k] - offset.y;
                const float radius = std::sqrt(dx * dx + dy * dy);
                disk_sum[lane] += omega[k] * box_overlap(radius, r, s, is) * std::min(1.0f, tangential_scale * is);
            }
        for (size_t lane = 0; lane < kLanes; ++lane) covered_weight += square_sum[lane], disk_overlap += disk_sum[lane];
    }
    covered_weight *= 1.0 / kTurns.size();
    const double r2 = double(r) * r;
    const double extended_area = std::max(solid_angle_ + kPi * r2 - disk_overlap, std::max(solid_angle_, kPi * r2));
    const double mean_squared_error = std::max(0.0, squared_radiance_ + (energy_norm2_ - 2.0 * covered_weight) / (2.0 * r2));
    return extended_area * mean_squared_error;
}

float SquareFitter::best_radius(float lo, float hi, Vec2 offset, int grid, int golden_steps, double* error) const {
    grid = std::max(grid, 2);
    const double log_lo = std::log(lo), log_hi = std::log(hi);
    const double step = (log_hi - log_lo) / (grid - 1);
    double best_error = std::numeric_limits<double>::max();
    int best = 0;
    for (int i = 0; i < grid; ++i) {
        const double e = evaluate(float(std::exp(log_lo + i * step)), offset);
        if (e < best_error) best_error = e, best = i;
    }
    double best_log = log_lo + best * step;
    // Golden section on log r within the neighbours of the best grid point.
    double a = log_lo + std::max(best - 1, 0) * step, b = log_lo + std::min(best + 1, grid - 1) * step;
    constexpr double kInvPhi = 0.6180339887498949;
    double c = b - kInvPhi * (b - a), d = a + kInvPhi * (b - a);
    double fc = evaluate(float(std::exp(c)), offset), fd = evaluate(float(std::exp(d)), offset);
    for (int it = 0; it < golden_steps; ++it) {
        if (fc < fd) {
            b = d, d = c, fd = fc;
            c = b - kInvPhi * (b - a);
            fc = evaluate(float(std::exp(c)), offset);
        } else {
            a = c, c = d, fc = fd;
            d = a + kInvPhi * (b - a);
            fd = evaluate(float(std::exp(d)), offset);
        }
    }
    if (fc < best_error) best_error = fc, best_log = c;
    if (fd < best_error) best_error = fd, best_log = d;
    *error = best_error;
    return float(std::exp(best_log));
}

SquareFit SquareFitter::fit(std::span<const FitTexel> texels, const RegionStats& stats, std::span<const int> a,
                            std::span<const int> b, const FitOptions& options) {
    RSL_CHECK_EQ(stats.texel_count, int(a.size() + b.size()));
    RSL_CHECK_GT(stats.texel_count, 0);
    SquareFit result;
    const Frame frame = Frame::from_normal(stats.energy_centroid());
    result.center = frame.z;
    if (glm::dot(stats.energy, stats.energy) <= 0.0) {  // black: any square of the region's size fits exactly
        result.half_diagonal = float(std::sqrt(stats.solid_angle / 2.0));
        return result;
    }
    gather(texels, stats, frame, a, b);
    const float lo = 0.3f * min_side_;
    const float hi = std::max(std::min(kChartLimit, kSqrt2 * (max_radius_ + 0.5f * max_side_)), 2.0f * lo);
    double error = 0;
    float r = best_radius(lo, hi, Vec2(0), options.radius_grid, options.golden_steps, &error);
    Vec2 offset(0);
    if (options.refine_center) {
        // Pattern search: move the center by a shrinking step along the chart
        // axes while that lowers the objective at the current r.
        float step = 0.25f * r;
        const float min_step = 0.03f * r;
        for (int moves = 0; moves < 24 && step >= min_step; ++moves) {
            bool improved = false;
            for (Vec2 dir : {Vec2(1, 0), Vec2(-1, 0), Vec2(0, 1), Vec2(0, -1)}) {
                const Vec2 candidate = offset + step * dir;
                const double e = evaluate(r, candidate);
                if (e < error) {
                    error = e, offset = candidate, improved = true;
                    break;
                }
            }
            if (!improved) step *= 0.5f;
        }
        double refined_error = 0;
        const float refined = best_radius(0.8f * r, std::min(1.25f * r, kChartLimit), offset, 3, 5, &refined_error);
        if (refined_error < error) error = refined_error, r = refined;
        result.center = fit_chart_inverse(frame, offset);
    }
    result.half_diagonal = r;
    result.error = error;
    result.radiance = Color(stats.energy / (2.0 * double(r) * r));
    return result;
}

double SquareFitter::objective(std::span<const FitTexel> texels, const RegionStats& stats,
                               std::span<const int> region, const Vec3& center, float half_diagonal) {
    gather(texels, stats, Frame::from_normal(center), region, {});
    return evaluate(half_diagonal, Vec2(0));
}

}  // namespace rsl::lightfit
