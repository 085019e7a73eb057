// Real spherical harmonics: evaluation by the Legendre recurrences in
// Cartesian form (no trigonometry), exact texel integrals, and rotation by the
// Ivanic–Ruedenberg recurrences.
#include "tools/baselines/sh.h"

#include <array>
#include <cmath>
#include <numbers>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "src/core/error.h"

namespace rsl::sh {

namespace {

// K_l^m = √((2l+1)/(4π) · (l−m)!/(l+m)!), and the √2 of m ≠ 0 folded in.
struct Normalization {
    std::array<double, kMaxOrder * kMaxOrder> value{};
    Normalization() {
        for (int l = 0; l < kMaxOrder; ++l)
            for (int m = 0; m <= l; ++m) {
                double ratio = 1.0;  // (l−m)!/(l+m)!, as a product (no integer overflow, no integer division)
                for (int k = l - m + 1; k <= l + m; ++k) ratio /= double(k);
                double k_lm = std::sqrt((2.0 * l + 1.0) / (4.0 * std::numbers::pi) * ratio);
                if (m > 0) k_lm *= std::numbers::sqrt2;
                value[index(l, m)] = k_lm;
            }
    }
};
const Normalization& normalization() {
    static const Normalization table;
    return table;
}

}  // namespace

void evaluate(int order, const DVec3& dir, double* out) {
    RSL_CHECK_GE(order, 1);
    RSL_CHECK_LE(order, kMaxOrder);
    const auto& K = normalization().value;
    const double x = dir.x, y = dir.y, z = dir.z;
    // Q_l^m = P_l^m(z) / sin^m θ (CS phase included) and
    // (x + i y)^m = sin^m θ (cos mφ + i sin mφ): their products are the
    // polynomials sin^m θ · P_l^m, free of the pole's singularity.
    double q_mm = 1.0;         // Q_m^m = (−1)^m (2m−1)!!
    double re = 1.0, im = 0.0;  // (x + i y)^m
    for (int m = 0; m < order; ++m) {
        if (m > 0) {
            q_mm *= -(2.0 * m - 1.0);
            const double re_next = re * x - im * y;
            im = re * y + im * x;
            re = re_next;
        }
        double q_prev = 0.0, q = q_mm;  // Q_{l−1}^m, Q_l^m starting at l = m
        for (int l = m; l < order; ++l) {
            if (l == m + 1) {
                q_prev = q;
                q = z * (2.0 * m + 1.0) * q_mm;
            } else if (l > m + 1) {
                const double q_next = ((2.0 * l - 1.0) * z * q - (l + m - 1.0) * q_prev) / double(l - m);
                q_prev = q;
                q = q_next;
            }
            if (m == 0) {
                out[index(l, 0)] = K[index(l, 0)] * q;
            } else {
                out[index(l, m)] = K[index(l, m)] * q * re;
                out[index(l, -m)] = K[index(l, m)] * q * im;
            }
        }
    }
}

std::vector<double> evaluate(int order, const DVec3& dir) {
    std::vector<double> out(size_t(coefficient_count(order)));
    evaluate(order, dir, out.data());
    return out;
}

double reconstruct(int order, const double* coefficients, const DVec3& dir) {
    std::array<double, kMaxOrder * kMaxOrder> y;
    evaluate(order, dir, y.data());
    double sum = 0.0;
    for (int i = 0; i < coefficient_count(order); ++i) sum += coefficients[i] * y[i];
    return sum;
}

namespace detail {

void gauss_legendre(int points, double* nodes, double* weights) {
    RSL_CHECK_GE(points, 1);
    RSL_CHECK_LE(points, 8);
    // Newton on P_G from the Chebyshev guess; converges to machine precision.
    for (int i = 0; i < points; ++i) {
        double x = std::cos(std::numbers::pi * (i + 0.75) / (points + 0.5));
        double derivative = 1.0;
        for (int iteration = 0; iteration < 100; ++iteration) {
            double p0 = 1.0, p1 = x;
            for (int k = 2; k <= points; ++k) {
                const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            if (points == 1) p0 = 1.0, p1 = x;
            derivative = points * (x * p1 - p0) / (x * x - 1.0);
            const double step = p1 / derivative;
            x -= step;
            if (std::abs(step) < 1e-16) break;
        }
        nodes[i] = x;
        weights[i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
}

DVec3 face_direction(int face, double s, double t) {
    DVec3 d;
    switch (face) {
        case 0: d = DVec3(1, -t, -s); break;
        case 1: d = DVec3(-1, -t, s); break;
        case 2: d = DVec3(s, 1, t); break;
        case 3: d = DVec3(s, -1, -t); break;
        case 4: d = DVec3(s, -t, 1); break;
        default: d = DVec3(-s, -t, -1); break;
    }
    return glm::normalize(d);
}

}  // namespace detail

TexelBasis::TexelBasis(int resolution, int order, int gauss_points) : resolution_(resolution), order_(order) {
    RSL_CHECK_GE(resolution, 1);
    RSL_CHECK_GE(order, 1);
    RSL_CHECK_LE(order, kMaxOrder);
    const int n = coefficients();
    integrals_.assign(size_t(texel_count()) * n, 0.0f);
    tbb::parallel_for(tbb::blocked_range<int>(0, texel_count(), 64), [&](const tbb::blocked_range<int>& range) {
        std::array<double, kMaxOrder * kMaxOrder> y, sum;
        for (int k = range.begin(); k != range.end(); ++k) {
            sum.fill(0.0);
            detail::texel_quadrature(resolution, k, gauss_points, [&](const DVec3& dir, double w) {
                evaluate(order, dir, y.data());
                for (int i = 0; i < n; ++i) sum[i] += w * y[i];
            });
            for (int i = 0; i < n; ++i) integrals_[size_t(k) * n + i] = float(sum[i]);
        }
    });
}

ShColor project_cube(const CubeMap& map, const TexelBasis& basis) {
    RSL_CHECK_EQ(map.resolution(), basis.resolution());
    const int n = basis.coefficients();
    ShColor out{basis.order(), std::vector<double>(size_t(3 * n), 0.0)};
    for (int k = 0; k < map.texel_count(); ++k) {
        const Color L = map.radiance(k);
        const float* a = basis.texel(k);
        for (int i = 0; i < n; ++i) {
            out.rgb[3 * i] += double(L.r) * a[i];
            out.rgb[3 * i + 1] += double(L.g) * a[i];
            out.rgb[3 * i + 2] += double(L.b) * a[i];
        }
    }
    return out;
}

// ---------------------------------------------------------------- rotation

namespace {

// Band-l block with centered indices m, m' ∈ [−l, l].
struct Block {
    int l;
    std::vector<double>* data;
    double& operator()(int m, int m_from) const { return (*data)[(m + l) * (2 * l + 1) + (m_from + l)]; }
};

double delta(int a, int b) { return a == b ? 1.0 : 0.0; }

// Ivanic & Ruedenberg's P function: r1 is band 1, prev band l−1.
double P(int i, int a, int b, int l, const Block& r1, const Block& prev) {
    if (b == l) return r1(i, 1) * prev(a, l - 1) - r1(i, -1) * prev(a, -l + 1);
    if (b == -l) return r1(i, 1) * prev(a, -l + 1) + r1(i, -1) * prev(a, l - 1);
    return r1(i, 0) * prev(a, b);
}

}  // namespace

Rotation::Rotation(int order, const glm::dmat3& R) : order_(order), blocks_(size_t(order)) {
    RSL_CHECK_GE(order, 1);
    RSL_CHECK_LE(order, kMaxOrder);
    for (int l = 0; l < order; ++l) blocks_[l].assign(size_t((2 * l + 1) * (2 * l + 1)), 0.0);
    blocks_[0][0] = 1.0;
    if (order == 1) return;
    // Band 1 without the Condon–Shortley phase is (y, z, x) up to one factor,
    // and a linear function a·d rotates to (R a)·d: the block is R in that
    // order. glm is column-major: R[col][row].
    const int axis[3] = {1, 2, 0};  // m = −1, 0, 1 → y, z, x
    const Block r1{1, &blocks_[1]};
    for (int m = -1; m <= 1; ++m)
        for (int mf = -1; mf <= 1; ++mf) r1(m, mf) = R[axis[mf + 1]][axis[m + 1]];
    for (int l = 2; l < order; ++l) {
        const Block prev{l - 1, &blocks_[l - 1]}, cur{l, &blocks_[l]};
        for (int m = -l; m <= l; ++m)
            for (int mf = -l; mf <= l; ++mf) {
                const double d = std::abs(mf) < l ? double((l + mf) * (l - mf)) : double(2 * l * (2 * l - 1));
                const int am = std::abs(m);
                const double u = std::sqrt(double((l + m) * (l - m)) / d);
                const double v = 0.5 * std::sqrt((1.0 + delta(m, 0)) * double((l + am - 1) * (l + am)) / d) *
                                 (1.0 - 2.0 * delta(m, 0));
                const double w = -0.5 * std::sqrt(double((l - am - 1) * (l - am)) / d) * (1.0 - delta(m, 0));
                double value = 0.0;
                if (u != 0.0) value += u * P(0, m, mf, l, r1, prev);
                if (v != 0.0) {
                    double V;
                    if (m == 0)
                        V = P(1, 1, mf, l, r1, prev) + P(-1, -1, mf, l, r1, prev);
                    else if (m > 0)
                        V = P(1, m - 1, mf, l, r1, prev) * std::sqrt(1.0 + delta(m, 1)) -
                            P(-1, -m + 1, mf, l, r1, prev) * (1.0 - delta(m, 1));
                    else
                        V = P(1, m + 1, mf, l, r1, prev) * (1.0 - delta(m, -1)) +
                            P(-1, -m - 1, mf, l, r1, prev) * std::sqrt(1.0 + delta(m, -1));
                    value += v * V;
                }
                if (w != 0.0) {
                    double W;
                    if (m > 0)
                        W = P(1, m + 1, mf, l, r1, prev) + P(-1, -m - 1, mf, l, r1, prev);
                    else
                        W = P(1, m - 1, mf, l, r1, prev) - P(-1, -m + 1, mf, l, r1, prev);
                    value += w * W;
                }
                cur(m, mf) = value;
            }
    }
    // The recurrences are for real SH without the CS phase; ours carry (−1)^m,
    // so every entry changes sign by (−1)^(m + m').
    for (int l = 1; l < order; ++l)
        for (int m = -l; m <= l; ++m)
            for (int mf = -l; mf <= l; ++mf)
                if ((m + mf) % 2 != 0) blocks_[l][(m + l) * (2 * l + 1) + (mf + l)] *= -1.0;
}

void Rotation::apply(const double* in, double* out, int channels) const {
    for (int l = 0; l < order_; ++l) {
        const int width = 2 * l + 1, first = l * l;
        for (int m = 0; m < width; ++m)
            for (int c = 0; c < channels; ++c) {
                double sum = 0.0;
                for (int mf = 0; mf < width; ++mf) sum += blocks_[l][m * width + mf] * in[(first + mf) * channels + c];
                out[(first + m) * channels + c] = sum;
            }
    }
}

ShColor Rotation::apply(const ShColor& in) const {
    RSL_CHECK_EQ(in.order, order_);
    ShColor out{order_, std::vector<double>(in.rgb.size())};
    apply(in.rgb.data(), out.rgb.data(), 3);
    return out;
}

}  // namespace rsl::sh
