#include <random>

#include <catch2/catch.hpp>

#include "src/core/hemisphere.h"
#include "tests/random_cases.h"

using namespace rsl;

TEST_CASE("hemisphere map: round trip over the sphere", "[hemisphere]") {
    std::mt19937 rng(7);
    std::normal_distribution<float> g;
    for (int k = 0; k < 10000; ++k) {
        Vec3 w = glm::normalize(test::random_vec3(g, rng));
        if (w.z < -0.99f) continue;  // near the antipode (a circle, not a point) float loses precision
        Vec2 p = hemisphere_to_plane(w);
        REQUIRE(glm::length(p) <= std::sqrt(2.0f) + 1e-5f);
        CHECK((w.z >= 0) == (glm::length(p) <= 1.0f + 1e-6f));
        Vec3 back = plane_to_hemisphere(p);
        CHECK(glm::length(back - w) < 2e-3f);
    }
}

TEST_CASE("hemisphere map matches the paper's formula", "[hemisphere]") {
    for (float theta : {0.1f, 0.7f, 1.2f, 1.5f})
        for (float phi : {0.0f, 1.0f, 2.5f, 4.0f}) {
            // φ measured from the local y axis towards x.
            Vec3 w(std::sin(theta) * std::sin(phi), std::sin(theta) * std::cos(phi), std::cos(theta));
            Vec2 p = hemisphere_to_plane(w);
            float s = std::sin(theta) / std::sqrt(1 + std::cos(theta));
            CHECK(p.x == Approx(s * std::sin(phi)).margin(1e-6));
            CHECK(p.y == Approx(s * std::cos(phi)).margin(1e-6));
            CHECK(s == Approx(std::sqrt(2.0f) * std::sin(theta / 2)).margin(1e-6));
        }
}

TEST_CASE("hemisphere map is equal-area: dω = 2 dp", "[hemisphere]") {
    // Solid angle of a polar cap θ ≤ Θ is 2π(1 − cosΘ); its image is a disk of
    // radius √(1 − cosΘ), area π(1 − cosΘ).
    for (float big_theta : {0.2f, 0.8f, 1.5707963f}) {
        float rho = std::sqrt(1 - std::cos(big_theta));
        float cap = 2 * kPi * (1 - std::cos(big_theta));
        CHECK(cap == Approx(kSolidAnglePerPlaneArea * kPi * rho * rho).epsilon(1e-6));
    }
    // And numerically for a small off-axis square: map its corners' Jacobian.
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-0.6f, 0.6f);
    for (int k = 0; k < 200; ++k) {
        Vec2 p = test::random_vec2(u, rng);
        const float h = 1e-3f;
        Vec3 a = plane_to_hemisphere(p), bx = plane_to_hemisphere(p + Vec2(h, 0)),
             by = plane_to_hemisphere(p + Vec2(0, h));
        float solid = glm::length(glm::cross(bx - a, by - a));
        CHECK(solid / (h * h) == Approx(kSolidAnglePerPlaneArea).epsilon(5e-3));
    }
}

TEST_CASE("RSL square keeps the region's measure", "[hemisphere]") {
    for (float r : {0.02f, 0.1f, 0.5f}) {
        float h = square_half_edge_for_rsl(r);
        CHECK((2 * h) * (2 * h) * kSolidAnglePerPlaneArea == Approx(rsl_solid_angle(r)));
    }
}
