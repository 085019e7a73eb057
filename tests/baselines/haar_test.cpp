// Haar wavelets on cube faces: exact inverse, orthonormality, the basis
// functions and their supports, and the area-weighted N-term approximation.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "tools/baselines/haar.h"
#include "tests/random_cases.h"

using namespace rsl;

namespace {

std::vector<float> random_values(size_t count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1, 3);
    std::vector<float> v(count);
    for (float& x : v) x = u(rng);
    return v;
}

double relative_l2(const CubeMap& a, const CubeMap& b) {
    double diff = 0, norm = 0;
    for (int k = 0; k < a.texel_count(); ++k) {
        const DVec3 d = DVec3(a.radiance(k)) - DVec3(b.radiance(k));
        diff += glm::dot(d, d);
        norm += glm::dot(DVec3(b.radiance(k)), DVec3(b.radiance(k)));
    }
    return std::sqrt(diff / norm);
}

}  // namespace

TEST_CASE("Haar: forward then inverse is the identity, on faces and cubes") {
    for (int n : {1, 2, 4, 16, 32}) {
        const auto original = random_values(size_t(6) * n * n * 3, unsigned(n));
        auto data = original;
        haar::forward_cube(data.data(), n, 3);
        if (n > 1) CHECK(data != original);
        haar::inverse_cube(data.data(), n, 3);
        for (size_t k = 0; k < data.size(); ++k) REQUIRE(data[k] == Approx(original[k]).margin(2e-5));
    }
    CHECK_THROWS(haar::forward_cube(std::vector<float>(6 * 9).data(), 3, 1));
}

TEST_CASE("Haar: the transform is orthonormal (Parseval for dot products)") {
    const int n = 16;
    auto a = random_values(size_t(n) * n, 1), b = random_values(size_t(n) * n, 2);
    double dot = 0;
    for (size_t k = 0; k < a.size(); ++k) dot += double(a[k]) * b[k];
    std::vector<float> scratch(a.size());
    haar::forward_face(a.data(), n, 1, scratch.data());
    haar::forward_face(b.data(), n, 1, scratch.data());
    double transformed = 0;
    for (size_t k = 0; k < a.size(); ++k) transformed += double(a[k]) * b[k];
    CHECK(transformed == Approx(dot).epsilon(1e-5));
}

TEST_CASE("Haar: each basis function is ±1/side on a square of the stated support") {
    const int n = 16;
    std::vector<float> basis(size_t(n) * n), scratch(basis.size());
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            std::fill(basis.begin(), basis.end(), 0.0f);
            basis[j * n + i] = 1.0f;
            haar::inverse_face(basis.data(), n, 1, scratch.data());
            const int side = haar::support_side(i, j, n);
            int nonzero = 0, x0 = n, y0 = n, x1 = -1, y1 = -1;
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const float v = basis[y * n + x];
                    if (v == 0.0f) continue;
                    ++nonzero;
                    REQUIRE(std::abs(v) == Approx(1.0 / side).epsilon(1e-6));
                    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
                }
            REQUIRE(nonzero == side * side);
            REQUIRE(x1 - x0 + 1 == side);
            REQUIRE(y1 - y0 + 1 == side);
        }
}

TEST_CASE("Haar lighting: area-weighted N-term error decreases with N and is exact with every term") {
    const int n = 16;
    CubeMap map(n);
    // A sky gradient, a small bright sun and noise: all frequencies present.
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> noise(0, 0.2f);
    const Vec3 sun = glm::normalize(Vec3(0.4f, 0.8f, 0.3f));
    for (int k = 0; k < map.texel_count(); ++k) {
        const Vec3 d = map.texel_direction(k);
        const float sky = 0.5f + 0.5f * d.y;
        const float glow = glm::dot(d, sun) > 0.995f ? 50.0f : 0.0f;
        const Vec2 red_blue_noise = test::random_vec2(noise, rng);
        map.radiance(k) = Color(sky + glow + red_blue_noise.x, sky * 0.8f + glow, 0.3f + glow + red_blue_noise.y);
    }
    haar::LightingApproximation approximation(n);
    haar::SparseLighting lighting;
    double previous = 1e30;
    for (int terms : {1, 5, 10, 20, 30, 60, 100, 300, 1000}) {
        approximation.approximate(map, terms, lighting);
        REQUIRE(int(lighting.size()) == terms);
        const double error = relative_l2(haar::reconstruct(lighting, n), map);
        REQUIRE(error < previous);
        previous = error;
    }
    approximation.approximate(map, map.texel_count(), lighting);
    CHECK(relative_l2(haar::reconstruct(lighting, n), map) < 1e-6);
}

TEST_CASE("Haar lighting: the kept terms are the largest by magnitude × support area") {
    const int n = 8;
    CubeMap map(n);
    const auto values = random_values(size_t(map.texel_count()) * 3, 8);
    for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = Color(values[3 * k], values[3 * k + 1], values[3 * k + 2]);
    haar::LightingApproximation approximation(n);
    haar::SparseLighting lighting;
    approximation.approximate(map, 40, lighting);
    auto weight = [&](int k) {
        const int rest = k % (n * n);
        const int side = haar::support_side(rest % n, rest / n, n);
        const float* c = &approximation.coefficients()[3 * size_t(k)];
        return (0.2126 * std::abs(c[0]) + 0.7152 * std::abs(c[1]) + 0.0722 * std::abs(c[2])) * side * side;
    };
    double smallest_kept = 1e30;
    std::vector<bool> kept(size_t(map.texel_count()), false);
    for (int k : lighting.index) smallest_kept = std::min(smallest_kept, weight(k)), kept[k] = true;
    for (int k = 0; k < map.texel_count(); ++k)
        if (!kept[k]) REQUIRE(weight(k) <= smallest_kept * (1 + 1e-6));
}
