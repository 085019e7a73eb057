// Accuracy smoke test: the RSL renderer against the Embree ground truth on a
// small scene (a sphere over a plane under a sky with a bright sun-like block).
#include <catch2/catch.hpp>

#include "src/lightfit/scene_lights.h"
#include "src/frame/error_metrics.h"
#include "src/render/cpu_renderer.h"
#include "src/trace/ground_truth.h"
#include "tests/render/render_test_scenes.h"

namespace rsl {
namespace {

double relative_l2(const VertexColors& a, const VertexColors& reference) {
    return compare_vertex_colors(a, reference).total.relative_l2();
}

TEST_CASE("RSL renderer vs ground truth on a sphere over a plane", "[render][accuracy]") {
    Scene scene = test::make_scene("accuracy", Color(0.7f));
    test::add_part(scene, test::make_plane(3.0f, 24, "ground"));
    Transform pose;
    pose.translation = Vec3(0, 0.45f, 0);
    test::add_part(scene, test::make_icosphere(0.4f, 3, "ball"), pose);
    scene.camera.position = Vec3(1.2f, 1.8f, 2.5f);
    scene.camera.target = Vec3(0, 0.3f, 0);
    scene.precompute = test::small_accuracy_precompute();
    const CubeMap environment = test::sky_with_sun(16);

    const VertexColors truth = GroundTruth(scene, environment, 0.0f).shade_vertices();
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    // Bounds: the goals (≤ 10% at K = 30, ≤ 5% at K = 100 on the robot)
    // with these low-resolution fields measured 4.7%, 4.7% and 3.9% at
    // K = 10, 30, 100, against 16–18% without any visibility; a wrong factor
    // (a missing cosine, a frame mix-up, a lost occluder) costs far more.
    const std::pair<int, double> cases[] = {{10, 0.08}, {30, 0.07}, {100, 0.06}};
    for (const auto& [k, bound] : cases) {
        CpuRenderer renderer(scene, fit_environment_lights(environment, k), fields, RenderOptions{});
        const double error = relative_l2(renderer.shade(), truth);
        RenderOptions no_visibility;
        no_visibility.self_visibility = no_visibility.occluders = false;
        CpuRenderer unshadowed(scene, fit_environment_lights(environment, k), fields, no_visibility);
        const double unshadowed_error = relative_l2(unshadowed.shade(), truth);
        INFO("K=" << k << ": relative L2 " << error << ", without visibility " << unshadowed_error);
        CHECK(error < bound);
        CHECK(error < 0.5 * unshadowed_error);
    }
}

}  // namespace
}  // namespace rsl
