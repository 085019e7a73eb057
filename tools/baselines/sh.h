#pragma once
// Real spherical harmonics for the SH PRT baseline (Sloan, Kautz, Snyder 2002).
//
// Convention (pinned by tests/baselines/sh_test.cpp): orthonormal real SH with
// the Condon–Shortley phase included, as in Sloan's "Stupid SH tricks":
//
//   Y_l^m  = √2 K_l^m cos(mφ) P_l^m(cos θ)     m > 0
//   Y_l^0  =    K_l^0 P_l^0(cos θ)
//   Y_l^m  = √2 K_l^|m| sin(|m|φ) P_l^|m|(cos θ)   m < 0
//
// with P_l^m carrying (−1)^m and θ, φ the spherical angles about +z, so that
// Y_1^{−1} = −√(3/4π) y, Y_1^0 = √(3/4π) z, Y_1^1 = −√(3/4π) x. Coefficient
// (l, m) sits at index l(l+1)+m; "order n" means bands 0..n−1, n² coefficients.
// Directions are world directions (the axes are only the SH's own; rotations
// carry everything else).
#include <vector>

#include "src/core/envmap.h"
#include "src/core/math.h"

namespace rsl::sh {

inline constexpr int kMaxOrder = 10;  // 100 coefficients
inline constexpr int coefficient_count(int order) { return order * order; }
inline constexpr int index(int l, int m) { return l * (l + 1) + m; }

// All n² basis functions at the unit direction `dir` into out[0 .. n²).
void evaluate(int order, const DVec3& dir, double* out);
std::vector<double> evaluate(int order, const DVec3& dir);

// Σ c_i Y_i(dir) for one channel.
double reconstruct(int order, const double* coefficients, const DVec3& dir);

// Integrals of every basis function over every texel of a cube map of
// resolution N: A[k·n² + i] = ∫_texel k Y_i dω, by a G×G Gauss–Legendre rule in
// face coordinates (the integrand is smooth within a texel, so G = 4 is exact
// to ~1e-12 at N ≥ 8). With these, projecting a piecewise-constant map is
// exact: c_i = Σ_k L_k A_ki; and so is projecting the per-texel transport,
// T_i = Σ_k f_k A_ki, whose product with the lighting tends to Σ_k L_k f_k Ω_k
// (the ground truth's texel sum) as the order grows.
class TexelBasis {
public:
    TexelBasis(int resolution, int order, int gauss_points = 4);
    int resolution() const { return resolution_; }
    int order() const { return order_; }
    int coefficients() const { return coefficient_count(order_); }
    int texel_count() const { return 6 * resolution_ * resolution_; }
    const float* texel(int k) const { return &integrals_[size_t(k) * coefficients()]; }

private:
    int resolution_, order_;
    std::vector<float> integrals_;  // texel-major, float: sums accumulate in double or are short
};

// RGB SH coefficients: coefficient i of channel c at [i·3 + c].
struct ShColor {
    int order = 0;
    std::vector<double> rgb;  // 3·n²
    Color at(int i) const { return Color(float(rgb[3 * i]), float(rgb[3 * i + 1]), float(rgb[3 * i + 2])); }
};

// Exact projection of the piecewise-constant cube map (texel sums).
ShColor project_cube(const CubeMap& map, const TexelBasis& basis);

// Projection of a continuous function by the same per-texel quadrature, for
// tests and references: exact (to the quadrature's ~1e-10) for band-limited f.
template <typename Function>
std::vector<double> project_function(int order, int resolution, int gauss_points, const Function& f);

// ---------------------------------------------------------------- rotation
// Block-diagonal rotation of real SH coefficients (Ivanic & Ruedenberg 1996,
// with the 1998 errata), band by band from the 3×3 rotation. If the function
// is rotated as f'(d) = f(R⁻¹ d) (CubeMap's `rotate` convention), its
// coefficients are c' = D(R) c.
class Rotation {
public:
    Rotation(int order, const glm::dmat3& rotation);
    int order() const { return order_; }
    // Coefficient (l, m ← m') of band l's (2l+1)² block.
    double band(int l, int m, int m_from) const { return blocks_[l][(m + l) * (2 * l + 1) + (m_from + l)]; }
    void apply(const double* in, double* out, int channels = 1) const;  // in ≠ out
    ShColor apply(const ShColor& in) const;

private:
    int order_;
    std::vector<std::vector<double>> blocks_;
};

// ---------------------------------------------------------------- templates
namespace detail {
// Gauss–Legendre nodes and weights on [−1, 1] for G ∈ [1, 8].
void gauss_legendre(int points, double* nodes, double* weights);
// CubeMap::face_direction in double precision (unit).
DVec3 face_direction(int face, double s, double t);
// Calls visit(direction, weight) for the G×G quadrature points of texel k of a
// cube map of resolution N: weight = dω of the point (ds dt / (1+s²+t²)^{3/2}).
template <typename Visit>
void texel_quadrature(int resolution, int k, int gauss_points, const Visit& visit) {
    double nodes[8], weights[8];
    gauss_legendre(gauss_points, nodes, weights);
    const int per_face = resolution * resolution;
    const int face = k / per_face, i = (k % per_face) % resolution, j = (k % per_face) / resolution;
    const double h = 2.0 / resolution;
    for (int b = 0; b < gauss_points; ++b)
        for (int a = 0; a < gauss_points; ++a) {
            const double s = -1.0 + (i + 0.5 * (nodes[a] + 1.0)) * h;
            const double t = -1.0 + (j + 0.5 * (nodes[b] + 1.0)) * h;
            const double r2 = 1.0 + s * s + t * t;
            const double jacobian = 1.0 / (r2 * std::sqrt(r2));
            visit(face_direction(face, s, t), weights[a] * weights[b] * 0.25 * h * h * jacobian);
        }
}
}  // namespace detail

template <typename Function>
std::vector<double> project_function(int order, int resolution, int gauss_points, const Function& f) {
    const int n = coefficient_count(order);
    std::vector<double> c(n, 0.0), y(n);
    for (int k = 0; k < 6 * resolution * resolution; ++k)
        detail::texel_quadrature(resolution, k, gauss_points, [&](const DVec3& dir, double w) {
            evaluate(order, dir, y.data());
            const double value = f(dir) * w;
            for (int i = 0; i < n; ++i) c[i] += value * y[i];
        });
    return c;
}

}  // namespace rsl::sh
