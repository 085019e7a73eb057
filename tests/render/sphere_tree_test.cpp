// The occluder search: the sphere tree against brute force, and a scene of
// 1,000 parts (no part-count cliff) whose culled colours match a render that
// looks every occluder up.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include "src/render/cpu_renderer.h"
#include "src/render/sphere_tree.h"
#include "tests/render/render_test_scenes.h"
#include "tests/random_cases.h"

namespace rsl {
namespace {

TEST_CASE("the sphere tree finds exactly the overlapping spheres", "[render][culling]") {
    std::mt19937 rng{5};
    std::uniform_real_distribution<float> u(0, 1);
    SphereTree tree;
    size_t hits = 0;
    for (const int count : {0, 1, 3, 4, 5, 17, 200, 1000}) {
        std::vector<BoundingSphere> spheres(static_cast<size_t>(count));
        for (BoundingSphere& s : spheres) {
            s.center = 20.0f * (test::random_vec3(u, rng) * Vec3(1, 1, 0.2f));
            const Vec3 draws = test::random_vec3(u, rng);
            s.radius = 0.05f + 3.0f * draws.x * draws.y * draws.z;  // a few large reaches among small ones
        }
        tree.build(spheres);
        for (int q = 0; q < 100; ++q) {
            const BoundingSphere query{20.0f * (test::random_vec3(u, rng) * Vec3(1, 1, 0.2f)), 0.01f + 2.0f * u(rng)};
            std::vector<int> found{-7};  // appended after what is there
            tree.overlapping(query, found);
            REQUIRE(found.front() == -7);
            found.erase(found.begin());
            std::vector<int> expected;
            for (int i = 0; i < count; ++i) {
                const float gap = glm::length(query.center - spheres[size_t(i)].center) - query.radius - spheres[size_t(i)].radius;
                // The tree's margin (1e-5 relative) may add near-ties only.
                if (gap <= 0.0f) expected.push_back(i);
                else if (gap <= 1e-4f * (query.radius + spheres[size_t(i)].radius))
                    expected.push_back(std::find(found.begin(), found.end(), i) != found.end() ? i : -1);
            }
            expected.erase(std::remove(expected.begin(), expected.end(), -1), expected.end());
            REQUIRE(found == expected);  // ascending, no duplicates
            hits += found.size();
        }
    }
    CHECK(hits > 1000);  // the queries do find spheres
}

TEST_CASE("1,000 parts shade as with every occluder looked up", "[render][culling][scale]") {
    // A 40 × 25 grid of small spheres, 0.3 apart, each reaching 4 radii
    // (so each shadows its neighbours), on a ground, under 4 lights.
    Scene scene = test::make_scene("crowd", Color(0.6f));
    test::add_part(scene, test::make_plane(14.0f, 28, "ground"));
    const TriangleMesh ball = test::make_icosphere(0.1f, 0, "ball");
    for (int i = 0; i < 1000; ++i) {
        Transform pose;
        pose.translation = Vec3(0.3f * float(i % 40) - 6.0f, 0.12f + 0.05f * float(i % 3), 0.3f * float(i / 40) - 3.75f);
        pose.rotation = glm::angleAxis(0.1f * float(i), glm::normalize(Vec3(1, 2, 3)));
        test::add_part(scene, ball, pose);
    }
    scene.camera.position = Vec3(0, 8, 9);
    PrecomputeSettings& pre = scene.precompute;
    pre.ovdf_shells = 4, pre.ovdf_cube_resolution = 8, pre.ovdf_vdt_resolution = 16, pre.ovdf_vectors = 4;
    pre.ovdf_outer_radius = 4.0f;
    // One baked field for the ball, shared by every instance (their meshes are equal).
    Scene two = test::make_scene("two", Color(0.6f));
    test::add_part(two, ball);
    test::add_part(two, ball);  // a single part would bake no occluder field
    two.precompute = pre;
    FieldBakeOptions bake;
    bake.self_visibility = false;
    const PartFields ball_fields = bake_part_fields(two, bake);
    REQUIRE(ball_fields.occluder[0]);
    PartFields fields;
    fields.self.assign(scene.parts.size(), nullptr);
    fields.occluder.assign(scene.parts.size(), ball_fields.occluder[0]);
    fields.occluder[0] = nullptr;  // the ground casts no shadow here

    RslSet lights;
    for (const Vec3& d : {Vec3(0.3f, 1, 0.2f), Vec3(-1, 0.4f, 0.3f), Vec3(0.2f, 0.3f, -1), Vec3(0, 1, 0)}) {
        RotatableSquareLight l;
        l.center = glm::normalize(d);
        l.half_diagonal = 0.15f;
        l.radiance = Color(1.5f);
        lights.lights.push_back(l);
    }
    RenderOptions with, without;
    without.occluder_culling = false;
    CpuRenderer culled(scene, lights, fields, with), full(scene, lights, fields, without);
    culled.set_time(0);
    full.set_time(0);
    const VertexColors a = culled.shade(), b = full.shade();
    // The search keeps only neighbours: far fewer than 999 candidates per receiver.
    const OccluderLists& lists = culled.frame().occluder_lists();
    CHECK(lists.candidates < 40 * scene.parts.size());
    CHECK(culled.stats().occluder_lookups * 20 < full.stats().occluder_lookups);
    size_t shadowed = 0;
    for (size_t p = 0; p < a.parts.size(); ++p)
        for (size_t v = 0; v < a.parts[p].size(); ++v)
            for (int ch = 0; ch < 3; ++ch) {
                REQUIRE(a.parts[p][v][ch] == Approx(b.parts[p][v][ch]).epsilon(1e-5).margin(1e-7));
            }
    // The occluders matter: without them the balls are brighter.
    RenderOptions none;
    none.occluders = false;
    CpuRenderer unshadowed(scene, lights, fields, none);
    const VertexColors c = unshadowed.shade();
    for (size_t p = 1; p < a.parts.size(); ++p)
        for (size_t v = 0; v < a.parts[p].size(); ++v) shadowed += c.parts[p][v].g > a.parts[p][v].g + 1e-4f;
    CHECK(shadowed > 300);  // 686 of the balls' 12,000 vertices
}

}  // namespace
}  // namespace rsl
