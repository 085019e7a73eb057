// The exact irradiance over normals (src/lightfit/irradiance.h) against a
// brute-force integral of the map over sub-texel points, and its bilinear
// lookup against the nodes it interpolates.
#include <random>

#include <catch2/catch.hpp>

#include "src/lightfit/irradiance.h"
#include "src/shading/diffuse_light.h"
#include "tests/random_cases.h"

using namespace rsl;

namespace {

CubeMap sky_and_sun(int n) {
    CubeMap map(n);
    for (int k = 0; k < map.texel_count(); ++k) {
        const Vec3 d = map.texel_direction(k);
        map.radiance(k) = d.y > 0 ? Color(0.3f, 0.45f, 0.8f) * (0.5f + d.y) : Color(0.05f, 0.04f, 0.03f);
        if (d.y > 0.5f && d.z > 0.45f && std::abs(d.x) < 0.3f) map.radiance(k) = Color(8.0f, 7.0f, 5.0f);
    }
    return map;
}

// ∫ L(ω) max(0, n·ω) dω with `sub`² points per texel, each its cell's exact solid angle.
Color brute_force_irradiance(const CubeMap& map, const Vec3& n, int sub) {
    DVec3 sum(0.0);
    const int res = map.resolution();
    for (int k = 0; k < map.texel_count(); ++k) {
        const CubeTexel t = map.texel(k);
        for (int a = 0; a < sub; ++a)
            for (int b = 0; b < sub; ++b) {
                const double s0 = -1.0 + 2.0 * (t.i + double(a) / sub) / res, s1 = s0 + 2.0 / (res * sub);
                const double t0 = -1.0 + 2.0 * (t.j + double(b) / sub) / res, t1 = t0 + 2.0 / (res * sub);
                const double omega = cube_face_solid_angle(s0, t0, s1, t1);
                const Vec3 d = CubeMap::face_direction(t.face, float(0.5 * (s0 + s1)), float(0.5 * (t0 + t1)));
                sum += DVec3(map.radiance(k)) * (omega * std::max(0.0, double(glm::dot(n, d))));
            }
    }
    return Color(sum);
}

}  // namespace

TEST_CASE("irradiance map: nodes and lookups equal the brute-force integral", "[lightfit][irradiance]") {
    const CubeMap map = sky_and_sun(16);
    const IrradianceMap irradiance = irradiance_map(map, 32);
    std::mt19937 rng(7);
    double worst = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const Vec3 n = test::random_unit_vector(rng);
        const Color truth = brute_force_irradiance(map, n, 4);
        const Color got = irradiance.at(n);
        for (int c = 0; c < 3; ++c) {
            const double error = std::abs(double(got[c]) - truth[c]) / (truth[c] + 1e-3);
            worst = std::max(worst, error);
            INFO("normal " << n.x << " " << n.y << " " << n.z << " channel " << c << ": map " << got[c]
                           << ", brute force " << truth[c]);
            CHECK(error < 0.02);  // bilinear between 33² nodes a face: worst 1.5% over 5,000 normals
        }
    }
    WARN("worst relative error " << worst);
}

TEST_CASE("irradiance map: a map above 64² summed by blocks agrees with the texels' own sum", "[lightfit][irradiance]") {
    const CubeMap map = sky_and_sun(128);
    const IrradianceMap irradiance = irradiance_map(map, 32);
    std::mt19937 rng(5);
    for (int trial = 0; trial < 60; ++trial) {
        const Vec3 n = test::random_unit_vector(rng);
        const Color truth = brute_force_irradiance(map, n, 1);
        const Color got = irradiance.at(n);
        for (int c = 0; c < 3; ++c) {
            INFO("normal " << n.x << " " << n.y << " " << n.z << ": map " << got[c] << ", texels " << truth[c]);
            CHECK(std::abs(double(got[c]) - truth[c]) < 0.01 * (truth[c] + 1e-3));
        }
    }
}

TEST_CASE("irradiance map: the lookup at a node is the node, and the faces agree at their edges",
          "[lightfit][irradiance]") {
    const IrradianceMap irradiance = irradiance_map(sky_and_sun(8), 8);
    for (int node = 0; node < int(irradiance.nodes.size()); ++node) {
        const Vec3 d = irradiance.node_direction(node);
        const Color got = irradiance.at(d), want = irradiance.nodes[size_t(node)];
        INFO("node " << node << ": lookup " << got.r << ", node " << want.r);
        CHECK(std::abs(got.r - want.r) <= 1e-4f * want.r + 1e-6f);
    }
}

TEST_CASE("irradiance map: a sun adds irradiance × the cosine", "[lightfit][irradiance]") {
    IrradianceMap irradiance = irradiance_map(CubeMap(4), 32);
    const Vec3 sun = glm::normalize(Vec3(0.3f, 0.8f, -0.2f));
    add_directional_irradiance(irradiance, sun, Color(2.0f, 1.0f, 0.5f));
    std::mt19937 rng(3);
    for (int trial = 0; trial < 100; ++trial) {
        const Vec3 n = test::random_unit_vector(rng);
        const float want = 2.0f * std::max(glm::dot(n, sun), 0.0f);
        INFO("cosine " << glm::dot(n, sun) << ": lookup " << irradiance.at(n).r << ", exact " << want);
        // Bilinear across the cosine's kink, 33² nodes a face: worst 1.14% of the sun over 5,000 normals.
        CHECK(std::abs(irradiance.at(n).r - want) < 0.03f);
    }
}

TEST_CASE("square_average_cosine is the clamped cosine's mean over the square, across the horizon too",
          "[lightfit][irradiance]") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    int crossing = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const Vec2 c = 1.1f * test::random_vec2(uniform, rng);
        const float h = trial % 3 == 0 ? 0.002f + 0.01f * std::abs(uniform(rng)) : 0.02f + 0.4f * std::abs(uniform(rng));
        double sum = 0;
        const int steps = 400;
        for (int a = 0; a < steps; ++a)
            for (int b = 0; b < steps; ++b) {
                const double x = c.x + h * (2.0 * (a + 0.5) / steps - 1.0), y = c.y + h * (2.0 * (b + 0.5) / steps - 1.0);
                sum += std::max(0.0, 1.0 - x * x - y * y);  // cos θ in the hemisphere plane, 0 below the horizon
            }
        const double want = sum / (double(steps) * steps);
        const float got = shading::square_average_cosine(c, h);
        crossing += glm::length(c) + std::sqrt(2.0f) * h > 1.0f && glm::length(c) - std::sqrt(2.0f) * h < 1.0f;
        INFO("centre " << c.x << " " << c.y << ", half-edge " << h << ": " << got << " against " << want);
        CHECK(std::abs(got - want) < 2e-4 + 1e-3 * want);
    }
    CHECK(crossing > 50);  // the cases cover the horizon's clipping
}
