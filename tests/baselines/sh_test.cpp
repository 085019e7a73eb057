// Spherical harmonics: the pinned convention, orthonormality, exact projection
// of band-limited functions and of piecewise-constant cube maps, rotation.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "tools/baselines/sh.h"
#include "tests/random_cases.h"

using namespace rsl;

namespace {

DVec3 random_direction(std::mt19937& rng) {
    std::normal_distribution<double> g;
    return glm::normalize(test::random_dvec3(g, rng));
}

glm::dmat3 random_rotation(std::mt19937& rng) {
    std::normal_distribution<double> g;
    const glm::dquat q = glm::normalize(test::random_dquat(g, rng));
    return glm::mat3_cast(q);
}

// Reference: std::sph_legendre(l, m, θ) = (−1)^m K_l^m P_l^m(cos θ), CS phase included.
double reference_y(int l, int m, const DVec3& d) {
    const double theta = std::acos(std::clamp(d.z, -1.0, 1.0)), phi = std::atan2(d.y, d.x);
    const int am = std::abs(m);
    const double s = std::sph_legendre(unsigned(l), unsigned(am), theta);
    if (m == 0) return s;
    return std::numbers::sqrt2 * s * (m > 0 ? std::cos(am * phi) : std::sin(am * phi));
}

}  // namespace

TEST_CASE("SH convention: Condon–Shortley phase, pinned band 0 and band 1") {
    const DVec3 d = glm::normalize(DVec3(0.3, -0.5, 0.8));
    const auto y = sh::evaluate(2, d);
    const double c0 = 0.5 / std::sqrt(std::numbers::pi), c1 = std::sqrt(3.0 / (4.0 * std::numbers::pi));
    CHECK(y[0] == Approx(c0).epsilon(1e-14));
    CHECK(y[sh::index(1, -1)] == Approx(-c1 * d.y).epsilon(1e-14));
    CHECK(y[sh::index(1, 0)] == Approx(c1 * d.z).epsilon(1e-14));
    CHECK(y[sh::index(1, 1)] == Approx(-c1 * d.x).epsilon(1e-14));
}

TEST_CASE("SH evaluation matches the std::sph_legendre reference up to order 10") {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 200; ++trial) {
        DVec3 d = random_direction(rng);
        if (trial == 0) d = DVec3(0, 0, 1);  // the pole
        if (trial == 1) d = DVec3(0, 0, -1);
        const auto y = sh::evaluate(sh::kMaxOrder, d);
        for (int l = 0; l < sh::kMaxOrder; ++l)
            for (int m = -l; m <= l; ++m) REQUIRE(y[sh::index(l, m)] == Approx(reference_y(l, m, d)).margin(1e-12));
    }
}

TEST_CASE("SH basis is orthonormal under the texel quadrature") {
    const int order = sh::kMaxOrder, n = order * order;
    std::vector<double> gram(size_t(n * n), 0.0), y(n);
    for (int k = 0; k < 6 * 8 * 8; ++k)
        sh::detail::texel_quadrature(8, k, 6, [&](const DVec3& d, double w) {
            sh::evaluate(order, d, y.data());
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) gram[i * n + j] += w * y[i] * y[j];
        });
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) REQUIRE(gram[i * n + j] == Approx(i == j ? 1.0 : 0.0).margin(1e-7));
}

TEST_CASE("SH projection and reconstruction of band-limited functions are exact") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int order : {3, 5, 10}) {
        std::vector<double> truth(size_t(order * order));
        for (double& c : truth) c = u(rng);
        auto f = [&](const DVec3& d) { return sh::reconstruct(order, truth.data(), d); };
        // Projection onto a higher order must find zeros above the band limit.
        const int project_order = std::min(order + 1, sh::kMaxOrder);
        const auto c = sh::project_function(project_order, 8, 5, f);
        for (int i = 0; i < project_order * project_order; ++i)
            REQUIRE(c[i] == Approx(i < order * order ? truth[i] : 0.0).margin(1e-5));
        for (int trial = 0; trial < 50; ++trial) {
            const DVec3 d = random_direction(rng);
            REQUIRE(sh::reconstruct(order, c.data(), d) == Approx(f(d)).margin(1e-5));
        }
    }
}

TEST_CASE("SH texel basis: cube-map projection is the exact integral of the piecewise-constant map") {
    const int n = 4, order = 6;
    CubeMap map(n);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0, 2);
    for (auto& L : map.radiances()) L = Color(test::random_vec3(u, rng));
    const sh::TexelBasis basis(n, order);
    const sh::ShColor c = sh::project_cube(map, basis);
    // Reference: the midpoint rule on S×S sub-cells of every texel with exact
    // sub-cell solid angles, Richardson-extrapolated from S = 16 and 32
    // (its error is O(1/S²)), independent of the Gauss rule under test.
    auto midpoint = [&](int sub) {
        std::vector<double> sum(size_t(3 * order * order), 0.0), y(size_t(order * order));
        for (int k = 0; k < map.texel_count(); ++k) {
            const CubeTexel t = map.texel(k);
            const double h = 2.0 / (n * sub);
            for (int b = 0; b < sub; ++b)
                for (int a = 0; a < sub; ++a) {
                    const double s0 = -1.0 + (t.i * sub + a) * h, t0 = -1.0 + (t.j * sub + b) * h;
                    const double w = cube_face_solid_angle(s0, t0, s0 + h, t0 + h);
                    sh::evaluate(order, sh::detail::face_direction(t.face, s0 + h / 2, t0 + h / 2), y.data());
                    for (int i = 0; i < order * order; ++i)
                        for (int ch = 0; ch < 3; ++ch) sum[3 * i + ch] += w * y[i] * map.radiance(k)[ch];
                }
        }
        return sum;
    };
    const auto coarse = midpoint(16), fine = midpoint(32);
    std::vector<double> reference(fine.size());
    for (size_t i = 0; i < fine.size(); ++i) reference[i] = (4.0 * fine[i] - coarse[i]) / 3.0;
    for (size_t i = 0; i < reference.size(); ++i) REQUIRE(c.rgb[i] == Approx(reference[i]).margin(2e-5));
    // The DC term is the energy: c_0 = ∫ L / (2√π).
    CHECK(c.rgb[0] == Approx(map.energy().x * 0.5 / std::sqrt(std::numbers::pi)).epsilon(1e-5));
}

TEST_CASE("SH rotation: rotated coefficients evaluate the rotated function") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    const int order = sh::kMaxOrder, n = order * order;
    for (int trial = 0; trial < 20; ++trial) {
        const glm::dmat3 R = random_rotation(rng);
        const sh::Rotation rotation(order, R);
        std::vector<double> c(n), rotated(n);
        for (double& x : c) x = u(rng);
        rotation.apply(c.data(), rotated.data());
        for (int k = 0; k < 20; ++k) {
            const DVec3 d = random_direction(rng);
            // f'(R d) = f(d)
            REQUIRE(sh::reconstruct(order, rotated.data(), R * d) ==
                    Approx(sh::reconstruct(order, c.data(), d)).margin(1e-9));
        }
    }
}

TEST_CASE("SH rotation agrees with re-projecting the rotated function") {
    std::mt19937 rng(9);
    const int order = 8;
    // A smooth, not band-limited function: a sharp-ish lobe plus a tilt.
    const DVec3 axis = glm::normalize(DVec3(0.2, 0.7, -0.4));
    auto f = [&](const DVec3& d) { return std::exp(4.0 * (glm::dot(d, axis) - 1.0)) + 0.3 * d.x; };
    const glm::dmat3 R = random_rotation(rng);
    const glm::dmat3 R_inverse = glm::transpose(R);
    const auto c = sh::project_function(order, 8, 5, f);
    const auto reprojected = sh::project_function(order, 8, 5, [&](const DVec3& d) { return f(R_inverse * d); });
    std::vector<double> rotated(c.size());
    sh::Rotation(order, R).apply(c.data(), rotated.data());
    for (size_t i = 0; i < c.size(); ++i) REQUIRE(rotated[i] == Approx(reprojected[i]).margin(1e-6));
}

TEST_CASE("SH rotation agrees with re-projecting a rotated cube map (resampling-limited)") {
    // rsl::rotate resamples the map, so agreement is to the resampling error;
    // a smooth map keeps that small, and a wrong rotation (R instead of R⁻¹)
    // is off by far more.
    const int n = 32, order = 4;
    CubeMap map(n);
    const Vec3 axis = glm::normalize(Vec3(0.5f, 0.8f, 0.1f));
    for (int k = 0; k < map.texel_count(); ++k) {
        const float c = glm::dot(map.texel_direction(k), axis);
        map.radiance(k) = Color(1.0f + c, 1.0f + c * c, std::exp(2.0f * (c - 1.0f)));
    }
    const glm::dmat3 R = glm::mat3_cast(glm::angleAxis(1.1, glm::normalize(glm::dvec3(0.3, 1.0, -0.2))));
    const sh::TexelBasis basis(n, order);
    const sh::ShColor rotated = sh::Rotation(order, R).apply(sh::project_cube(map, basis));
    const sh::ShColor reprojected = sh::project_cube(rotate(map, Mat3(R)), basis);
    const sh::ShColor wrong = sh::Rotation(order, glm::transpose(R)).apply(sh::project_cube(map, basis));
    double error = 0, wrong_error = 0, norm = 0;
    for (size_t i = 0; i < rotated.rgb.size(); ++i) {
        error += std::pow(rotated.rgb[i] - reprojected.rgb[i], 2);
        wrong_error += std::pow(wrong.rgb[i] - reprojected.rgb[i], 2);
        norm += std::pow(reprojected.rgb[i], 2);
    }
    CHECK(std::sqrt(error / norm) < 5e-3);
    CHECK(std::sqrt(wrong_error / norm) > 0.1);
}
