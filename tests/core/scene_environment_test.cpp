// A scene's environment as one map (src/core/scene_environment.h): a sun adds
// exactly its irradiance, in the texel around its direction, placed against
// the environment's rotation; a uniform sky adds its radiance everywhere.
#include <catch2/catch.hpp>

#include <random>

#include <glm/gtc/quaternion.hpp>

#include "src/core/scene_environment.h"
#include "tests/trace/trace_test_scenes.h"

namespace rsl {
namespace {

// Irradiance on a surface facing `normal`: Σ L·Ω·max(0, cos), in double.
DVec3 irradiance(const CubeMap& map, const Vec3& normal) {
    DVec3 e(0.0);
    for (int k = 0; k < map.texel_count(); ++k)
        e += DVec3(map.radiance(k)) * double(map.solid_angle(k)) *
             double(std::max(0.0f, glm::dot(map.texel_direction(k), normal)));
    return e;
}

// A scene with a sun on a node turned by `rotation` (it shines along the node's −Z).
Scene scene_with_sun(const Quat& rotation, const Color& irradiance_rgb) {
    Scene scene = test::make_scene("sun");
    SceneNode node;
    node.name = "sun";
    node.rest.rotation = rotation;
    scene.nodes.push_back(node);
    scene.environment.suns.push_back(SunLight{"sun", int(scene.nodes.size()) - 1, irradiance_rgb});
    scene.environment.resolution = 16;
    return scene;
}

}  // namespace

TEST_CASE("a sun adds exactly its irradiance, in the texel around its direction", "[environment]") {
    std::mt19937 rng(5);
    std::normal_distribution<float> gauss;
    for (int n : {4, 16, 32})
        for (int k = 0; k < 40; ++k) {
            const Vec3 d = glm::normalize(Vec3(gauss(rng), gauss(rng), gauss(rng)));
            const Color e(3.0f, 2.0f, 0.5f);
            CubeMap map = test::constant_cube(n, Color(0.25f));
            const DVec3 before = map.energy();
            add_sun(map, d, e);
            INFO("N = " << n << ", direction " << d.x << ", " << d.y << ", " << d.z);
            const DVec3 added = map.energy() - before;
            for (int c = 0; c < 3; ++c) CHECK(added[c] == Approx(e[c]).epsilon(1e-5));
            // Only the texel around d changed.
            const int texel = map.index_of(d);
            for (int t = 0; t < map.texel_count(); ++t)
                if (t != texel) REQUIRE(map.radiance(t) == Color(0.25f));
            // A surface facing the sun receives E (the texel's cosines within
            // its half-width: 1 − cos(half the texel's angle) at N = 4 is 3%).
            const DVec3 facing = irradiance(map, d) - irradiance(test::constant_cube(n, Color(0.25f)), d);
            CHECK(facing.r == Approx(e.r).epsilon(n == 4 ? 0.1 : 0.01));
        }
}

TEST_CASE("the scene's map: the file or black, a uniform sky, suns against the environment's rotation",
          "[environment]") {
    // The node turned −60° about x: its +Z (towards the sun) is (0, sin 60°, cos 60°).
    const Quat turn = glm::angleAxis(glm::radians(-60.0f), Vec3(1, 0, 0));
    Scene scene = scene_with_sun(turn, Color(4.0f));
    const Vec3 towards(0.0f, std::sin(glm::radians(60.0f)), std::cos(glm::radians(60.0f)));
    REQUIRE(glm::length(scene.environment.suns[0].direction_at(scene, 0.0f) - towards) < 1e-5f);
    CHECK(scene.environment.present());
    CHECK(describe_environment(scene.environment) == "sun 'sun'");

    scene.environment.uniform = Color(0.5f);
    CHECK(describe_environment(scene.environment) == "a uniform sky of radiance 0.5 + sun 'sun'");
    const CubeMap plain = scene_environment_map(scene, 16);
    CHECK(plain.resolution() == 16);
    CHECK(plain.radiance(plain.index_of(towards)).r > 100.0f);
    CHECK(plain.radiance(plain.index_of(-towards)) == Color(0.5f));
    const DVec3 energy = plain.energy();
    CHECK(energy.g == Approx(4.0 + 0.5 * 4.0 * kPi).epsilon(1e-4));

    // A turning environment: the map turns with rotation_at(t), and the sun
    // is where the node puts it at the start.
    scene.environment.rotation_axis = Vec3(0, 1, 0);
    scene.environment.rotation_degrees = 90.0f;
    scene.environment.rotation_degrees_per_second = 10.0f;
    scene.animation.start = 1.5f;
    const CubeMap turned = scene_environment_map(scene, 16);
    const CubeMap world = rotate(turned, scene.environment.rotation_at(1.5f));
    int brightest = 0;
    for (int k = 1; k < world.texel_count(); ++k)
        if (world.radiance(k).r > world.radiance(brightest).r) brightest = k;
    // Within a texel or so of the sun's direction (rotate() resamples).
    CHECK(glm::dot(world.texel_direction(brightest), towards) > std::cos(2.5f * kPi / 2.0f / 16.0f));

    // A sun too bright for one texel is refused by name (not by the fit, as a texel).
    scene.environment.suns[0].irradiance = Color(1e13f, 1.0f, 1.0f);
    scene.source = "sunny.gltf";
    CHECK_THROWS_WITH(scene_environment_map(scene, 16), Catch::StartsWith("sunny.gltf: sun 'sun': irradiance 1e+13"));

    // No sun and no sky: nothing lights the scene; an empty map is black.
    Scene dark = test::make_scene("dark");
    CHECK_FALSE(dark.environment.present());
    CHECK(describe_environment(dark.environment) == "none");
    CHECK(scene_environment_map(dark, 8).energy() == DVec3(0.0));
}

}  // namespace rsl
