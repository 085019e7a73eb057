// A scene's environment (src/formats/scene_environment.h): the map is the file
// or black plus a uniform sky; a sun stays out of it, and its direction in
// the map's frame turns back the environment's rotation at the start.
#include <catch2/catch.hpp>

#include <glm/gtc/quaternion.hpp>

#include "src/formats/scene_environment.h"
#include "tests/trace/trace_test_scenes.h"

namespace rsl {
namespace {

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

TEST_CASE("the scene's map: the file or black, and a uniform sky; suns against the environment's rotation",
          "[environment]") {
    // The node turned −60° about x: its +Z (towards the sun) is (0, sin 60°, cos 60°).
    const Quat turn = glm::angleAxis(glm::radians(-60.0f), Vec3(1, 0, 0));
    Scene scene = scene_with_sun(turn, Color(4.0f));
    const Vec3 towards(0.0f, std::sin(glm::radians(60.0f)), std::cos(glm::radians(60.0f)));
    REQUIRE(glm::length(scene.environment.suns[0].direction_at(scene, 0.0f) - towards) < 1e-5f);
    CHECK(glm::length(sun_direction_in_map(scene, scene.environment.suns[0]) - towards) < 1e-5f);
    CHECK(scene.environment.present());
    CHECK(describe_environment(scene.environment) == "sun 'sun'");
    CHECK(scene_environment_map(scene, 8).energy() == DVec3(0.0));  // the sun is a light, not a texel

    scene.environment.uniform = Color(0.5f, 0.25f, 0.5f);
    CHECK(describe_environment(scene.environment) == "a uniform sky of radiance (0.5, 0.25, 0.5) + sun 'sun'");
    const CubeMap sky = scene_environment_map(scene, 16);
    CHECK(sky.resolution() == 16);
    for (int k = 0; k < sky.texel_count(); k += 97) CHECK(sky.radiance(k) == Color(0.5f, 0.25f, 0.5f));
    CHECK(sky.energy().g == Approx(0.25 * 4.0 * kPi).epsilon(1e-5));

    // A turning environment: the map turns with rotation_at(t), so the sun's
    // map direction turned by the rotation at the start is where its node
    // puts it then, and later it turns with the map.
    scene.environment.rotation_axis = Vec3(0, 1, 0);
    scene.environment.rotation_degrees = 90.0f;
    scene.environment.rotation_degrees_per_second = 10.0f;
    scene.animation.start = 1.5f;
    const Vec3 in_map = sun_direction_in_map(scene, scene.environment.suns[0]);
    CHECK(glm::length(scene.environment.rotation_at(1.5f) * in_map - towards) < 1e-5f);
    CHECK(glm::length(in_map - towards) > 0.5f);  // 105° about y: elsewhere in the map

    // No sun and no sky: nothing lights the scene; an empty map is black.
    Scene dark = test::make_scene("dark");
    CHECK_FALSE(dark.environment.present());
    CHECK(describe_environment(dark.environment) == "none");
    CHECK(scene_environment_map(dark, 8).energy() == DVec3(0.0));
}

}  // namespace rsl
