#pragma once
// Shared helpers of the BRDF tests: a set of materials covering every model
// (sharp and broad lobes), random directions, stratified hemisphere integrals.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "src/brdf/brdf.h"
#include "src/core/hemisphere.h"
#include "tests/random_cases.h"

namespace rsl::test {

inline MaterialDesc material(std::string model, std::map<std::string, std::vector<float>> params) {
    MaterialDesc m;
    m.name = "test_" + model;
    m.model = std::move(model);
    m.params = std::move(params);
    return m;
}

// Every analytic model, including the extremes of its accepted parameter
// range (kd + ks = 1, roughness 1, very sharp lobes).
inline std::vector<MaterialDesc> analytic_materials() {
    return {
        material("lambert", {{"albedo", {1.0f, 0.5f, 0.2f}}}),
        material("phong", {{"kd", {0.3f}}, {"ks", {0.7f}}, {"exponent", {20}}}),
        material("phong", {{"kd", {0.0f}}, {"ks", {1.0f}}, {"exponent", {500}}}),
        material("phong", {{"kd", {0.0f}}, {"ks", {1.0f}}, {"exponent", {0}}}),
        material("blinn_phong", {{"kd", {0.2f}}, {"ks", {0.8f}}, {"exponent", {40}}}),
        material("blinn_phong", {{"ks", {1.0f}}, {"exponent", {1}}}),
        material("blinn_phong", {{"ks", {1.0f}}, {"exponent", {800}}}),
        material("cook_torrance_beckmann", {{"kd", {0.5f}}, {"f0", {0.04f}}, {"roughness", {0.3f}}}),
        material("cook_torrance_beckmann", {{"kd", {1.0f}}, {"f0", {1.0f, 0.8f, 0.3f}}, {"roughness", {1.0f}}}),
        material("cook_torrance_ggx", {{"kd", {1.0f}}, {"f0", {0.04f}}, {"roughness", {0.1f}}}),
        material("cook_torrance_ggx", {{"f0", {1.0f}}, {"roughness", {1.0f}}}),
        material("ward", {{"kd", {0.3f}}, {"ks", {0.7f}}, {"alpha", {0.15f}}}),
        material("ward", {{"ks", {1.0f}}, {"alpha", {0.5f}}}),
        material("ward_anisotropic", {{"kd", {0.2f}}, {"ks", {0.8f}}, {"alpha_x", {0.08f}}, {"alpha_y", {0.3f}}}),
        material("ward_anisotropic", {{"ks", {1.0f}}, {"alpha_x", {0.6f}}, {"alpha_y", {0.2f}}}),
        material("gltf_pbr", {{"base_color", {1.0f, 0.5f, 0.2f}}, {"metallic", {0.0f}}, {"roughness", {0.5f}}}),
        material("gltf_pbr", {{"base_color", {0.9f, 0.6f, 0.3f}}, {"metallic", {1.0f}}, {"roughness", {0.35f}}}),
        material("gltf_pbr", {}),  // glTF's defaults: white, metallic 1, roughness 1
    };
}

inline std::string describe(const MaterialDesc& m) {
    std::string s = m.model;
    for (auto& [k, v] : m.params) {
        s += " " + k + "=";
        for (float x : v) s += std::to_string(x).substr(0, 6) + ",";
    }
    return s;
}

// Uniform direction on the upper hemisphere, polar angle ≤ max_theta.
inline Vec3 random_upper_direction(std::mt19937& rng, float max_theta = 1.5707963f) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float cos_theta = 1.0f - u(rng) * (1.0f - std::cos(max_theta));
    const float phi = 2.0f * kPi * u(rng);
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    return Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
}

// ∫_H² f(ω) dω by jittered stratification of the equal-area disk (dω = 2 dp)
// on an m×m grid over [−1, 1]², with Cochran's pairwise estimate of the
// estimator's standard deviation (adjacent strata paired along x).
struct Estimate {
    double value = 0, stddev = 0;
};
template <typename F>
Estimate stratified_hemisphere_integral(F&& f, int m, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const double cell = 2.0 / m, weight = 2.0 * cell * cell;
    double sum = 0, variance = 0;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; i += 2) {
            double pair[2];
            for (int k = 0; k < 2; ++k) {
                const Vec2 jitter = test::random_vec2(u, rng);
                const Vec2 p(-1.0f + (i + k + jitter.x) * float(cell), -1.0f + (j + jitter.y) * float(cell));
                pair[k] = glm::dot(p, p) < 1.0f ? weight * f(plane_to_hemisphere(p)) : 0.0;
                sum += pair[k];
            }
            // Collapsed strata: Var(y₁ + y₂) ≈ 2 s² with s² = (y₁ − y₂)²/2 (conservative).
            variance += (pair[0] - pair[1]) * (pair[0] - pair[1]);
        }
    return {sum, std::sqrt(variance)};
}

}  // namespace rsl::test
