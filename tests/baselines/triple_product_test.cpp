// The wavelet triple product (Ng 2004) against brute-force texel sums and the
// ground truth; the BRDF slice tables against exact slices.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "src/frame/error_metrics.h"
#include "tests/baselines/scene_helpers.h"
#include "tools/baselines/haar.h"
#include "tools/baselines/triple_product.h"

using namespace rsl;
using namespace rsl::test;

namespace {

// Three random cube functions, in texels and in Haar coefficients, with their
// non-zero coefficient lists: `density` is the fraction of non-zero
// coefficients (1: dense texel noise).
struct RandomTriple {
    int n;
    std::vector<Color> a_texels, c_texels, a_coefficients, c_coefficients;
    std::vector<float> b_texels, b_coefficients;
    std::vector<int32_t> a_index, c_index;
    std::vector<uint32_t> b_index;

    RandomTriple(int resolution, double density, uint32_t seed) : n(resolution) {
        const size_t count = size_t(6) * n * n;
        std::mt19937 rng(seed);
        std::uniform_real_distribution<float> value(-1.0f, 1.0f);
        std::bernoulli_distribution keep(density);
        auto draw = [&] { return keep(rng) ? value(rng) : 0.0f; };
        a_coefficients.resize(count), c_coefficients.resize(count), b_coefficients.resize(count);
        for (size_t k = 0; k < count; ++k) {
            a_coefficients[k] = Color(draw(), draw(), draw());
            b_coefficients[k] = draw();
            c_coefficients[k] = Color(draw(), draw(), draw());
        }
        a_texels = inverse(a_coefficients), c_texels = inverse(c_coefficients);
        b_texels = b_coefficients;
        haar::inverse_cube(b_texels.data(), n, 1);
        for (size_t k = 0; k < count; ++k) {
            if (a_coefficients[k] != Color(0.0f)) a_index.push_back(int32_t(k));
            if (b_coefficients[k] != 0.0f) b_index.push_back(uint32_t(k));
            if (c_coefficients[k] != Color(0.0f)) c_index.push_back(int32_t(k));
        }
    }
    std::vector<Color> inverse(std::vector<Color> coefficients) const {
        haar::inverse_cube(reinterpret_cast<float*>(coefficients.data()), n, 3);
        return coefficients;
    }
    DVec3 brute_force() const {
        DVec3 sum(0.0);
        for (size_t k = 0; k < a_texels.size(); ++k) sum += DVec3(a_texels[k]) * double(b_texels[k]) * DVec3(c_texels[k]);
        return sum;
    }
    std::vector<Color> a_values() const {
        std::vector<Color> values;
        for (int32_t k : a_index) values.push_back(a_coefficients[size_t(k)]);
        return values;
    }
};

// |x − y| relative to the scale of the sum's terms (a random sum can nearly cancel).
double relative_to(const DVec3& x, const DVec3& y, double scale) { return glm::length(x - y) / std::max(scale, 1e-12); }

}  // namespace

TEST_CASE("Tripling coefficients: the Haar triple product is the texel sum Σ a b c", "[triple]") {
    for (int n : {1, 2, 4, 8}) {
        for (double density : {1.0, 0.3, 0.05}) {
            for (uint32_t seed : {1u, 2u, 3u}) {
                const RandomTriple triple(n, density, seed * 7919u + uint32_t(n));
                triple::PreparedLighting lighting(n);
                const std::vector<Color> a_values = triple.a_values();
                lighting.prepare(triple.a_index.data(), a_values.data(), a_values.size());
                DVec3 scale(0.0);
                for (size_t k = 0; k < triple.a_texels.size(); ++k)
                    scale += glm::abs(DVec3(triple.a_texels[k]) * double(triple.b_texels[k]) * DVec3(triple.c_texels[k]));
                const DVec3 expected = triple.brute_force();
                INFO("N = " << n << ", density " << density << ", seed " << seed);
                // The BRDF factor as a sparse list (either list may be the sparser) and as dense.
                for (bool dense_brdf : {false, true}) {
                    triple::Factors factors;
                    factors.visibility_dense = triple.b_coefficients.data();
                    factors.visibility_index = triple.b_index.data();
                    factors.visibility_count = triple.b_index.size();
                    factors.brdf_dense = triple.c_coefficients.data();
                    factors.brdf_index = dense_brdf ? nullptr : triple.c_index.data();
                    factors.brdf_count = triple.c_index.size();
                    const DVec3 got(triple::evaluate(lighting, factors));
                    CHECK(relative_to(got, expected, glm::length(scale)) < 1e-5);
                }
            }
        }
    }
}

TEST_CASE("Tripling coefficients: one triple at a time matches its texel sum (every case of the theorem)", "[triple]") {
    // Single coefficients a = e_i, b = e_j, c = e_l at N = 4 on one face: the
    // evaluation must give C_ijl for every (i, j, l), zero or not.
    const int n = 4, count = 6 * n * n;
    triple::PreparedLighting lighting(n);
    std::vector<float> b(count, 0.0f);
    std::vector<Color> c(count, Color(0.0f));
    int nonzero = 0;
    for (int32_t i = 0; i < n * n; ++i) {
        const Color one(1.0f);
        lighting.prepare(&i, &one, 1);
        std::vector<float> ti(count, 0.0f);
        ti[i] = 1.0f;
        haar::inverse_cube(ti.data(), n, 1);
        for (uint32_t j = 0; j < uint32_t(n * n); ++j)
            for (int32_t l = 0; l < n * n; ++l) {
                std::vector<float> tj(count, 0.0f), tl(count, 0.0f);
                tj[j] = 1.0f, tl[l] = 1.0f;
                haar::inverse_cube(tj.data(), n, 1), haar::inverse_cube(tl.data(), n, 1);
                double expected = 0;
                for (int k = 0; k < count; ++k) expected += double(ti[k]) * tj[k] * tl[k];
                b[j] = 1.0f, c[l] = Color(1.0f);
                triple::Factors factors{b.data(), &j, 1, c.data(), &l, 1};
                const double got = triple::evaluate(lighting, factors).r;
                b[j] = 0.0f, c[l] = Color(0.0f);
                if (std::abs(expected) > 1e-6) ++nonzero;
                INFO("i " << i << " j " << j << " l " << l);
                REQUIRE(got == Approx(expected).margin(1e-6));
            }
    }
    CHECK(nonzero > n * n);  // the check saw many non-zero tripling coefficients
}
