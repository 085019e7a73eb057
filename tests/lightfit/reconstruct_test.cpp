// Rasterizing RSLs back into a cube map, the reconstruction error, the preview.
#include <random>

#include <catch2/catch.hpp>

#include "src/lightfit/decompose.h"
#include "src/lightfit/reconstruct.h"
#include "src/lightfit/square_fit.h"
#include "tests/random_cases.h"

using namespace rsl;
using namespace rsl::lightfit;

TEST_CASE("a rasterized RSL covers its solid angle 2r² and keeps its energy", "[lightfit][reconstruct]") {
    std::mt19937 rng(9);
    std::normal_distribution<float> g;
    std::uniform_real_distribution<float> radius(0.08f, 0.6f);
    for (int trial = 0; trial < 12; ++trial) {
        RslSet set;
        set.lights.push_back({glm::normalize(test::random_vec3(g, rng)), radius(rng), Color(1.0f, 2.0f, 3.0f)});
        for (SquareTurns turns : {SquareTurns::kAligned, SquareTurns::kAveraged}) {
            const CubeMap map = reconstruct(set, 32, turns, 6);
            INFO("trial " << trial << ", r " << set.lights[0].half_diagonal << ", turns " << int(turns));
            const DVec3 energy = map.energy(), expected = set.total_energy();
            // Only the texels the square's boundary crosses are estimated.
            for (int ch = 0; ch < 3; ++ch) CHECK(energy[ch] == Approx(expected[ch]).epsilon(0.02));
        }
    }
}

TEST_CASE("the aligned square is a square in the fit chart, edge √2·r", "[lightfit][reconstruct]") {
    RslSet set;
    const Vec3 center = glm::normalize(Vec3(0.2f, 0.1f, 1.0f));
    const float r = 0.3f;
    set.lights.push_back({center, r, Color(1.0f)});
    const CubeMap map = reconstruct(set, 64, SquareTurns::kAligned, 4);
    const Frame frame = Frame::from_normal_tangent(center, Vec3(0, 1, 0));
    const float h = r / std::sqrt(2.0f);
    int checked = 0;
    for (int k = 0; k < map.texel_count(); ++k) {
        const Vec2 q = fit_chart(frame, map.texel_direction(k));
        const float margin = 1.5f * std::sqrt(map.solid_angle(k));  // texels the boundary crosses
        if (std::max(std::abs(q.x), std::abs(q.y)) < h - margin) {
            CHECK(map.radiance(k).r == Approx(1.0f));
            ++checked;
        } else if (std::max(std::abs(q.x), std::abs(q.y)) > h + margin) {
            CHECK(map.radiance(k).r == 0.0f);
        }
    }
    CHECK(checked > 50);
}

TEST_CASE("relative L2 error is zero for the map itself and one for black", "[lightfit][reconstruct]") {
    CubeMap map(8);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0.0f, 5.0f);
    for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = Color(test::random_vec3(u, rng));
    CHECK(relative_l2_error(map, map) == 0.0);
    CHECK(relative_l2_error(map, CubeMap(8)) == Approx(1.0));
    CubeMap doubled = map;
    for (auto& c : doubled.radiances()) c *= 2.0f;
    CHECK(relative_l2_error(map, doubled) == Approx(1.0).epsilon(1e-6));
}

TEST_CASE("more lights reconstruct a smooth map better", "[lightfit][reconstruct]") {
    CubeMap map(16);
    for (int k = 0; k < map.texel_count(); ++k) {
        const Vec3 d = map.texel_direction(k);
        map.radiance(k) = Color(1.0f + 0.8f * d.y, 1.0f + 0.5f * d.x, 1.0f - 0.3f * d.z) * (1.5f + std::sin(4 * d.x));
    }
    double previous = 1e9;
    for (int k : {6, 24, 96}) {
        const RslSet set = decompose(map, {.lights = k});
        const double error = relative_l2_error(map, reconstruct(set, 16));
        INFO(k << " lights: relative L2 " << error);
        CHECK(error < previous);
        CHECK(error < 0.6);
        previous = error;
    }
}

TEST_CASE("the fit preview has the map, the regions and the reconstruction side by side",
          "[lightfit][reconstruct]") {
    CubeMap map(8);
    for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = Color(0.2f + 0.1f * (k % 7));
    const RslSet set = decompose(map, {.lights = 10});
    const Image preview = fit_preview(map, set, 128);
    REQUIRE(preview.width == 3 * 128);
    REQUIRE(preview.height == 64);
    int boundary = 0, differs = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 128; ++x) {
            const Color left = preview.rgb(x, y), middle = preview.rgb(128 + x, y);
            if (middle != left) {
                ++differs;
                boundary += middle == Color(0.1f, 1.0f, 0.1f);
            }
        }
    CHECK(boundary > 64);         // 10 regions have long boundaries
    CHECK(boundary == differs);   // the middle panel is the map except on boundaries
}
