// A glTF sun (a directional light, EnvironmentDesc::suns) is a light of its
// own, of the sun's size (fit_scene_lights), and a direction of the ground
// truth: the renderer casts its shadow where the truth does.
#include <catch2/catch.hpp>

#include <glm/gtc/quaternion.hpp>

#include "src/lightfit/scene_lights.h"
#include "src/formats/scene_environment.h"
#include "src/image/error_metrics.h"
#include "src/render/cpu_renderer.h"
#include "src/trace/ground_truth.h"
#include "tests/render/render_test_scenes.h"

namespace rsl {
namespace {

// The ground vertex nearest to `point`.
size_t nearest_vertex(const TriangleMesh& mesh, const Vec3& point) {
    size_t best = 0;
    for (size_t v = 1; v < mesh.positions.size(); ++v)
        if (glm::length(mesh.positions[v] - point) < glm::length(mesh.positions[best] - point)) best = v;
    return best;
}

}  // namespace

TEST_CASE("a sun lights the scene and casts its shadow where the truth does", "[render][sun][accuracy]") {
    // A box 0.6 m over a fine ground, a dim uniform sky and a sun 60° high
    // towards +Z (its node turned −60° about x, shining along its −Z).
    Scene scene = test::make_scene("sun", Color(0.7f));
    scene.source.clear();
    test::add_part(scene, test::make_plane(4.0f, 40, "ground"));
    Transform lift;
    lift.translation = Vec3(0.0f, 0.6f, 0.0f);
    test::add_part(scene, test::make_flat_box(Vec3(0.3f, 0.1f, 0.3f), 4, "box"), lift);
    SceneNode sun_node;
    sun_node.name = "sun";
    sun_node.rest.rotation = glm::angleAxis(glm::radians(-60.0f), Vec3(1, 0, 0));
    scene.nodes.push_back(sun_node);
    const Color sun_irradiance(3.0f);
    scene.environment.suns.push_back(SunLight{"sun", int(scene.nodes.size()) - 1, sun_irradiance});
    scene.environment.uniform = Color(0.2f);
    scene.environment.resolution = 32;
    scene.precompute = test::small_accuracy_precompute();
    const Vec3 towards_sun = scene.environment.suns[0].direction_at(scene, 0.0f);
    REQUIRE(towards_sun.y == Approx(std::sin(glm::radians(60.0f))));

    const CubeMap environment = scene_environment_map(scene, scene.environment.resolution);
    CHECK(environment.energy().r == Approx(0.2 * 4.0 * kPi).epsilon(1e-5));  // the sky alone
    const RslSet lights = fit_scene_lights(scene, environment, 30);
    // The map's 30 lights, then the sun's: at its direction, the sun's solid
    // angle, its integral the irradiance.
    REQUIRE(lights.lights.size() == 31);
    const RotatableSquareLight& sun = lights.lights.back();
    CHECK(glm::length(sun.center - towards_sun) < 1e-6f);
    CHECK(sun.solid_angle() == Approx(kPi * kSunAngularRadius * kSunAngularRadius).epsilon(1e-5));
    CHECK(sun.light_integral().g == Approx(3.0).epsilon(1e-5));
    // The suns alone (a scene file without a map): a black map fits no light.
    CHECK(fit_environment_lights(CubeMap(8), 30).lights.empty());
    const RslSet suns_only = fit_scene_lights(scene, CubeMap(8), 30);
    REQUIRE(suns_only.lights.size() == 1);
    CHECK(suns_only.lights[0].center == sun.center);
    CHECK(sun_lights(scene).size() == 1);
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    const VertexColors rsl = CpuRenderer(scene, lights, fields, RenderOptions{}).shade();
    const VertexColors truth = GroundTruth(scene, environment, 0.0f).shade_vertices();
    const VertexErrorReport report = compare_vertex_colors(rsl, truth);
    const ObjectErrorReport objects = object_errors(report);

    // The box's shadow centre on the ground, and a point in the open.
    const TriangleMesh& ground = scene.parts[0].mesh;
    const Vec3 box_bottom(0.0f, 0.5f, 0.0f);
    const Vec3 shadow = box_bottom - towards_sun * (box_bottom.y / towards_sun.y);
    const size_t in_shadow = nearest_vertex(ground, shadow), in_sun = nearest_vertex(ground, Vec3(1.5f, 0, 1.5f));
    const float lit_rsl = luminance(rsl.parts[0][in_sun]), dark_rsl = luminance(rsl.parts[0][in_shadow]);
    const float lit_truth = luminance(truth.parts[0][in_sun]), dark_truth = luminance(truth.parts[0][in_shadow]);
    // Lambert 0.7 in the open: (0.7 / π)·(E·sin 60° + π·0.2) = 0.72.
    const float expected_lit = 0.7f / kPi * (3.0f * std::sin(glm::radians(60.0f)) + kPi * 0.2f);
    INFO("relative L2 all " << report.total.relative_l2() << ", objects " << objects.objects.relative_l2()
                             << "; ground in the sun " << lit_rsl << " (truth " << lit_truth << ", expected "
                             << expected_lit << "), in the box's shadow " << dark_rsl << " (truth " << dark_truth << ")");
    CHECK(lit_truth == Approx(expected_lit).epsilon(0.02));
    CHECK(lit_rsl == Approx(lit_truth).epsilon(0.03));
    // The sun's share (0.58 of 0.72) is gone in the shadow, in both (a hard
    // shadow: the sun's 0.27° against the box's 37° seen from the ground).
    CHECK(dark_truth < 0.35f * lit_truth);
    CHECK(dark_rsl < 0.35f * lit_rsl);
    CHECK(dark_rsl == Approx(dark_truth).margin(0.05f * lit_truth));
    CHECK(report.total.relative_l2() < 0.1);
    CHECK(objects.objects.relative_l2() < 0.1);
}

}  // namespace rsl
