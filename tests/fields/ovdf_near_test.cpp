// Ovdf::locate_near (src/fields/ovdf_near.cpp), the vectorized near half of a
// receiver's location, against locate() and occluded_area_at() one point at
// a time: which points are near (between the bounding sphere and the outer
// shell), and there the same cone, blended occluded area and pole, over
// random batches of every size up to a block, at every distance and on the
// cube faces' seams, for an asymmetric part with and without areas.
#include <cmath>
#include <iomanip>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "tools/assets/primitives.h"
#include "src/fields/ovdf.h"
#include "src/shading/ovdf_tables.h"
#include "tests/random_cases.h"

using namespace rsl;

namespace {

struct NearBatch {
    std::vector<float> x, y, z, cone, area, pole_x, pole_y, pole_z;
    std::vector<int32_t> near;
    explicit NearBatch(int n)
        : x(n), y(n), z(n), cone(n), area(n), pole_x(n), pole_y(n), pole_z(n), near(n) {}
    OvdfNearPoints view(int count) {
        OvdfNearPoints p;
        p.count = count;
        p.x = x.data(), p.y = y.data(), p.z = z.data();
        p.cone = cone.data(), p.occluded_area = area.data();
        p.pole_x = pole_x.data(), p.pole_y = pole_y.data(), p.pole_z = pole_z.data();
        p.near = near.data();
        return p;
    }
};

// A direction near a cube edge or corner now and then, where the face choice
// and the taps' clamps decide.
Vec3 random_direction(std::mt19937& rng) {
    std::normal_distribution<float> normal;
    std::uniform_int_distribution<int> pick(0, 3);
    Vec3 d = test::random_vec3(normal, rng);
    if (pick(rng) == 0) {
        const Vec3 n = test::random_vec3(normal, rng);
        d = Vec3(1.0f, 1.0f + 1e-4f * n.x, 0.3f * n.y) * (n.z < 0 ? -1.0f : 1.0f);
    }
    if (pick(rng) == 0) {
        const Vec2 n = test::random_vec2(normal, rng);
        d = Vec3(1.0f + 1e-4f * n.x, -1.0f, 1.0f + 1e-4f * n.y);
    }
    return glm::normalize(d);
}

void check_batches(const Ovdf& field, uint32_t seed, int* near_points, int* other_points) {
    std::mt19937 rng{seed};
    std::uniform_real_distribution<float> uniform(0, 1);
    std::uniform_int_distribution<int> size(1, 256);
    NearBatch batch(256);
    const float outer = field.shell_radius(field.params.shells - 1);
    for (int round = 0; round < 60; ++round) {
        const int count = size(rng);
        for (int j = 0; j < count; ++j) {
            // From the center to past the outer shell, the sphere's surface often.
            const float d = uniform(rng) < 0.1f ? field.radius * (1.0f + 1e-6f * (uniform(rng) - 0.5f))
                                                : 1.2f * outer * uniform(rng);
            const Vec3 p = field.center + d * random_direction(rng);
            batch.x[j] = p.x, batch.y[j] = p.y, batch.z[j] = p.z;
        }
        field.locate_near(batch.view(count));
        for (int j = 0; j < count; ++j) {
            const Vec3 p(batch.x[j], batch.y[j], batch.z[j]);
            const float d = glm::length(p - field.center);
            const bool near = d < outer && !(d < field.radius) && d > 0.0f;
            INFO("point " << j << " of " << count << std::setprecision(9) << ", d = " << d << " (R = " << field.radius << ", outer " << outer << ")");
            REQUIRE(bool(batch.near[j]) == near);
            if (!near) {
                ++*other_points;
                continue;
            }
            ++*near_points;
            const OvdfLocation at = field.locate(p, d);
            CHECK(batch.cone[j] == ovdf_zoom(d, field.radius).cone);
            const float area = field.occluded_area_at(at);
            CHECK(batch.area[j] == area);
            const Vec3 pole(batch.pole_x[j], batch.pole_y[j], batch.pole_z[j]);
            CHECK(glm::length(pole - at.aligned.z) < 1e-6f);
        }
    }
}

TEST_CASE("OVDF near points located in a batch equal locate() one at a time", "[ovdf]") {
    // Asymmetric and off the origin, so that the areas differ by direction and shell.
    TriangleMesh mesh = assets::rounded_box(Vec3(0.6f, 0.25f, 0.35f), 0.05f, 0.08f);
    for (Vec3& p : mesh.positions) p += Vec3(0.3f, -0.1f, 0.2f);
    OvdfParams params;
    params.shells = 5, params.cube_resolution = 8, params.vdt_resolution = 8, params.vectors = 4;
    params.inner_radius = 0.5f, params.outer_radius = 6.0f;
    Ovdf field = bake_ovdf(mesh, params);
    REQUIRE(!field.occluded_area.empty());
    int near_points = 0, other_points = 0;
    check_batches(field, 7, &near_points, &other_points);
    CHECK(near_points > 3000);
    CHECK(other_points > 1000);

    SECTION("a field without areas has no bound") {
        field.occluded_area.clear();
        NearBatch batch(1);
        const Vec3 p = field.center + Vec3(0, 0, 2.0f * field.radius);
        batch.x[0] = p.x, batch.y[0] = p.y, batch.z[0] = p.z;
        field.locate_near(batch.view(1));
        REQUIRE(batch.near[0] == 1);
        CHECK(batch.area[0] == shading::kOvdfNoAreaBound);
    }
}

}  // namespace
