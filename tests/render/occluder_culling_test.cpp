// Occluder culling: the bounding-sphere tests against brute-force rays, and
// the renderer's colours with culling on and off.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "src/render/occluder_culling.h"
#include "src/render/cpu_renderer.h"
#include "src/render/square_lights.h"
#include "src/shading/culling.h"
#include "tests/render/render_test_scenes.h"
#include "tests/random_cases.h"

namespace rsl {
namespace {

bool ray_hits_sphere(const Vec3& origin, const Vec3& dir, const BoundingSphere& s, float t_max) {
    const Vec3 oc = origin - s.center;
    const float b = glm::dot(oc, dir), c = glm::dot(oc, oc) - s.radius * s.radius;
    const float disc = b * b - c;
    if (disc < 0) return false;
    const float t1 = -b + std::sqrt(disc);
    const float t0 = -b - std::sqrt(disc);
    return t1 >= 0 && t0 <= t_max;
}

Vec3 random_unit(std::mt19937& rng) {
    std::normal_distribution<float> normal;
    return glm::normalize(test::random_vec3(normal, rng));
}

Vec3 random_in_ball(std::mt19937& rng, float radius) {
    std::uniform_real_distribution<float> u(-1, 1);
    for (;;) {
        const Vec3 p = test::random_vec3(u, rng);
        if (glm::dot(p, p) <= 1) return radius * p;
    }
}

// A direction within `half_angle` of `axis`, uniform over the cone.
Vec3 random_in_cone(std::mt19937& rng, const Vec3& axis, float half_angle) {
    std::uniform_real_distribution<float> u(0, 1);
    const float cos_theta = 1.0f - u(rng) * (1.0f - std::cos(half_angle));
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    const float phi = 2 * kPi * u(rng);
    return Frame::from_normal(axis).to_world(Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta));
}

TEST_CASE("culling tests never cull an occluder that a ray can reach", "[render][culling]") {
    std::mt19937 rng{11};
    std::uniform_real_distribution<float> u(0, 1);
    int culled_directional = 0, culled_sphere = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const BoundingSphere receiver{random_in_ball(rng, 2.0f), 0.1f + u(rng)};
        const BoundingSphere occluder{random_in_ball(rng, 3.0f), 0.1f + u(rng)};
        const Vec3 axis = random_unit(rng);
        const Vec2 draws = test::random_vec2(u, rng);
        const float half_angle = 0.02f + 1.4f * draws.x * draws.y;
        const bool kept_directional = may_shadow_direction(receiver, occluder, axis, half_angle);
        const Vec3 light_center = random_in_ball(rng, 4.0f);
        const float light_radius = 0.05f + 0.3f * u(rng);
        const bool kept_sphere = may_shadow_sphere_light(receiver, occluder, light_center, light_radius);
        culled_directional += !kept_directional;
        culled_sphere += !kept_sphere;
        if (kept_directional && kept_sphere) continue;
        for (int ray = 0; ray < 3000; ++ray) {
            const Vec3 origin = receiver.center + random_in_ball(rng, receiver.radius);
            if (!kept_directional) {
                // The cone's boundary is where a test would be tight: sample it often.
                const float angle = (ray % 2) ? half_angle : half_angle * std::sqrt(u(rng));
                const Vec3 dir = random_in_cone(rng, axis, angle);
                REQUIRE_FALSE(ray_hits_sphere(origin, dir, occluder, 1e30f));
            }
            if (!kept_sphere) {
                const Vec3 target = light_center + random_in_ball(rng, light_radius);
                const float length = glm::length(target - origin);
                if (length > 1e-6f) REQUIRE_FALSE(ray_hits_sphere(origin, (target - origin) / length, occluder, length));
            }
        }
    }
    // The tests do cull: both kinds happen in random configurations.
    CHECK(culled_directional > 40);
    CHECK(culled_sphere > 40);
}

TEST_CASE("the square's cone contains every direction of its square", "[render][culling]") {
    std::mt19937 rng{5};
    std::uniform_real_distribution<float> u(-1, 1);
    for (int trial = 0; trial < 2000; ++trial) {
        const float h = 0.01f + 0.3f * std::abs(u(rng));
        const Vec2 center = 1.2f * test::random_vec2(u, rng);
        const Vec3 c = plane_to_hemisphere(center);
        const float cone = square_cone_half_angle(h);
        for (int s = 0; s < 16; ++s) {
            const Vec2 q = center + h * test::random_vec2(u, rng);
            if (glm::dot(q, q) > 1.0f) continue;  // below the horizon: ρ·cos is 0 there
            const float angle = std::acos(std::clamp(glm::dot(c, plane_to_hemisphere(q)), -1.0f, 1.0f));
            REQUIRE(angle <= cone + 1e-4f);
        }
    }
}

// Whether the ray p + t·w (t > 0) meets the box (slab test).
bool ray_meets_box(const Bounds& box, const Vec3& p, const Vec3& w) {
    float t0 = 0.0f, t1 = 1e30f;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(w[a]) < 1e-12f) {
            if (p[a] < box.lo[a] || p[a] > box.hi[a]) return false;
            continue;
        }
        float ta = (box.lo[a] - p[a]) / w[a], tb = (box.hi[a] - p[a]) / w[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    }
    return t0 <= t1;
}

TEST_CASE("the slab rule clears only squares whose every direction misses the box", "[render][culling]") {
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> u(-1, 1);
    int cleared = 0, blocked_somewhere = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        Bounds box;
        box.extend(test::random_vec3(u, rng));
        box.extend(test::random_vec3(u, rng) * Vec3(1, 0.05f, 1));  // often thin, like a ground plane
        const Vec3 p = 2.5f * test::random_vec3(u, rng);
        // The square in a random receiver frame, its center within reach of the hemisphere.
        const Frame frame = Frame::from_normal(glm::normalize(test::random_vec3(u, rng)));
        const float h = 0.01f + 0.3f * std::abs(u(rng));
        const Vec2 center = 1.1f * test::random_vec2(u, rng);
        const Vec3 light = frame.to_world(plane_to_hemisphere(center));
        if (!clears_box_face(box_sides(box, p), light, square_cone_sine(h))) continue;
        ++cleared;
        for (int b = 0; b < 12; ++b)
            for (int a = 0; a < 12; ++a) {
                const Vec2 q = center + h * Vec2(-1 + (2 * a + 1) / 12.0f, -1 + (2 * b + 1) / 12.0f);
                if (glm::dot(q, q) > 1.0f) continue;  // below the receiver's horizon: weighted 0
                REQUIRE(!ray_meets_box(box, p, frame.to_world(plane_to_hemisphere(q))));
            }
        // The same square from the other side of the box would be blocked somewhere.
        blocked_somewhere += ray_meets_box(box, p, -light);
    }
    CHECK(cleared > 500);
    CHECK(blocked_somewhere > 10);  // measured: 28
}

TEST_CASE("a block's bounding sphere holds its points and is no larger than its box's half-diagonal",
          "[render][culling]") {
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> u(-1, 1);
    for (int trial = 0; trial < 500; ++trial) {
        const int n = 1 + int(255.0f * std::abs(u(rng)));
        const float scale = trial % 2 ? 0.01f : 50.0f;
        const Vec3 offset = 100.0f * test::random_vec3(u, rng);
        std::vector<Vec3> points;
        for (int k = 0; k < n; ++k) points.push_back(offset + scale * test::random_vec3(u, rng));
        shading::PointBox box = shading::point_box(points[0]);
        for (int k = 1; k < n; ++k) box = shading::point_box_add(box, points[k]);
        const Vec3 center = shading::point_box_center(box);
        float r2 = 0;
        for (const Vec3& p : points) r2 = shading::farther_squared(r2, center, p);
        const float radius = shading::bounding_radius(r2);
        // The box and the farthest point in double, independently.
        glm::dvec3 lo(points[0]), hi(points[0]);
        for (const Vec3& p : points) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
        const glm::dvec3 mid = 0.5 * (lo + hi);
        double farthest = 0, farthest_from_mid = 0;  // from the sphere's center, and from the box's exact middle
        for (const Vec3& p : points) {
            farthest = std::max(farthest, glm::distance(glm::dvec3(p), glm::dvec3(center)));
            farthest_from_mid = std::max(farthest_from_mid, glm::distance(glm::dvec3(p), mid));
        }
        CHECK(glm::distance(glm::dvec3(center), mid) <= 1e-6 * (glm::length(mid) + 1.0));
        CHECK(double(radius) >= farthest);  // every point inside
        CHECK(double(radius) <= farthest * (1 + 1e-5) + 2e-6);  // by the padding, no more
        CHECK(farthest_from_mid <= 0.5 * glm::distance(lo, hi) + 1e-9);
    }
}

TEST_CASE("a sphere light's square has the solid angle of the cap it subtends", "[render][culling]") {
    std::mt19937 rng(37);
    std::uniform_real_distribution<float> u(-1, 1);
    int lit = 0, unlit = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const Vec3 x = 3.0f * test::random_vec3(u, rng);
        const Vec3 center = 3.0f * test::random_vec3(u, rng);
        const float radius = 0.001f + 2.0f * std::abs(u(rng));
        const Color radiance(1.0f, 2.0f, 3.0f);
        const SquareLight light = sphere_light_square(x, center, radius, radiance);
        const double distance = glm::distance(glm::dvec3(x), glm::dvec3(center));
        if (distance <= double(radius) * (1 + 1e-6)) {  // inside: not lit
            if (distance < double(radius) * (1 - 1e-6)) {
                ++unlit;
                CHECK(light.solid_angle == 0.0f);
                CHECK(light.half_edge == 0.0f);
                CHECK(light.integral == Color(0.0f));
            }
            continue;
        }
        ++lit;
        // 2π(1 − cos α), sin α = a / d, in double.
        const double sin_alpha = double(radius) / distance;
        const double cap = 2.0 * std::numbers::pi * (1.0 - std::sqrt(1.0 - sin_alpha * sin_alpha));
        CHECK(std::abs(light.solid_angle - cap) <= 1e-5 * cap + 1e-12);
        // The square's plane area (2h)² is half its solid angle.
        const double area = 4.0 * double(light.half_edge) * double(light.half_edge);
        CHECK(std::abs(area - 0.5 * cap) <= 2e-5 * cap + 1e-12);
        const glm::dvec3 direction = (glm::dvec3(center) - glm::dvec3(x)) / distance;
        CHECK(glm::distance(glm::dvec3(light.direction), direction) <= 1e-6);
        CHECK(std::abs(light.integral.b - 3.0 * cap) <= 3e-5 * cap + 1e-12);
    }
    CHECK(lit > 1000);
    CHECK(unlit > 50);
}

// Spheres spread over a plane with fields: some pairs are far apart (beyond
// the outer shell or outside every light's cone), others close.
TEST_CASE("culling does not change the colours", "[render][culling]") {
    Scene scene = test::make_scene("spread", Color(0.6f));
    test::add_part(scene, test::make_plane(8.0f, 16, "ground"));
    const Vec3 spots[] = {{0, 0.3f, 0}, {0.7f, 0.3f, 0.2f}, {-3.0f, 0.3f, 2.5f}, {3.2f, 0.3f, -3.0f}, {-0.4f, 1.2f, 0.1f}};
    for (int i = 0; i < 5; ++i) {
        Transform pose;
        pose.translation = spots[i];
        // Scaled parts too: the cone and slab tests must hold in their frames.
        if (i == 1) pose.scale = Vec3(0.6f);
        if (i == 4) pose.scale = Vec3(1.4f, 0.7f, 1.0f), pose.rotation = glm::angleAxis(0.7f, Vec3(0.6f, 0.8f, 0.0f));
        test::add_part(scene, test::make_icosphere(0.3f, 2, "sphere" + std::to_string(i)), pose);
    }
    LocalLight light;
    light.radius = 0.05f;
    light.power = Color(2.0f);
    light.position = Vec3(0.3f, 0.9f, 0.4f);  // among the spheres
    scene.lights.push_back(light);
    scene.camera.position = Vec3(2, 6, 7);
    PrecomputeSettings& pre = scene.precompute;
    pre.svdf_resolution = 16, pre.svdf_clusters = 8, pre.svdf_vectors = 4, pre.svdf_supersampling = 1;
    pre.ovdf_shells = 4, pre.ovdf_cube_resolution = 8, pre.ovdf_vdt_resolution = 16, pre.ovdf_vectors = 4;
    pre.ovdf_outer_radius = 4.0f;
    FieldBakeOptions bake;
    bake.self_visibility = false;
    const PartFields fields = bake_part_fields(scene, bake);

    // Small and large lights from above and from the side.
    RslSet lights;
    std::mt19937 rng{3};
    std::uniform_real_distribution<float> u(0, 1);
    for (int i = 0; i < 16; ++i) {
        RotatableSquareLight l;
        l.center = glm::normalize(test::random_vec3(u, rng) + Vec3(-0.5f, 0.2f, -0.5f));
        l.half_diagonal = 0.05f + 0.3f * u(rng);
        l.radiance = Color(1.0f + u(rng));
        lights.lights.push_back(l);
    }
    // Culling off also takes the field's own lookup (not the split one), so the
    // comparison checks both the culling and src/render/ovdf_lookup.h.
    RenderOptions with, without;
    without.occluder_culling = false;
    without.fast_occluder_lookups = false;
    CpuRenderer culled(scene, lights, fields, with), full(scene, lights, fields, without);
    for (float t : {0.0f}) {
        culled.set_time(t);
        full.set_time(t);
        const VertexColors a = culled.shade(), b = full.shade();
        CHECK(culled.stats().occluder_pairs_culled > culled.stats().occluder_pairs / 4);
        CHECK(full.stats().occluder_pairs_culled == 0);
        CHECK(culled.stats().occluder_lookups < full.stats().occluder_lookups);
        for (size_t p = 0; p < a.parts.size(); ++p)
            for (size_t v = 0; v < a.parts[p].size(); ++v)
                for (int ch = 0; ch < 3; ++ch)
                    REQUIRE(a.parts[p][v][ch] == Approx(b.parts[p][v][ch]).epsilon(1e-5).margin(1e-7));
        // The occluders matter in this scene.
        RenderOptions none;
        none.occluders = false;
        CpuRenderer unshadowed(scene, lights, fields, none);
        const VertexColors c = unshadowed.shade();
        double change = 0;
        for (size_t v = 0; v < c.parts[0].size(); ++v) change += std::abs(c.parts[0][v].g - a.parts[0][v].g);
        CHECK(change > 1e-3);
    }
}

}  // namespace
}  // namespace rsl
