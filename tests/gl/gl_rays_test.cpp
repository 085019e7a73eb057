// The GL ray-traced baseline (RenderOptions::gpu_rays) against the CPU's
// (RenderOptions::exact_visibility, jittered): the same rays from the same
// seeds, traced by the GPU's BVH and by Embree, so the vertex colours agree
// but where a ray grazes an edge and the two traversals decide it apart.
#include <catch2/catch.hpp>

#include <filesystem>

#include "src/core/error.h"
#include "src/formats/scene_file.h"
#include "src/gl/gl_renderer.h"
#include "src/render/cpu_renderer.h"
#include "src/render/exact_visibility.h"
#include "tests/gl/gl_test_support.h"
#include "tests/trace/trace_test_scenes.h"

namespace rsl {
namespace {

using test::add_part;
using test::make_flat_box;
using test::make_icosphere;
using test::make_plane;
using test::make_scene;

// A ground, a sphere that slides over it, a glossy sphere and a box that
// rests on the ground (its bottom vertices on the ground's surface: the
// border rule of PosedScene::vertex).
Scene rays_scene() {
    Scene scene = make_scene("gl rays", Color(0.7f));
    scene.materials.push_back(test::blinn_phong(0.4f, 0.3f, 30.0f));
    add_part(scene, make_plane(3.0f, 16, "ground"));
    Transform big, small, box;
    big.translation = Vec3(0, 0.45f, 0);
    small.translation = Vec3(0.55f, 0.25f, 0.2f);
    box.translation = Vec3(-0.6f, 0.2f, -0.5f);
    add_part(scene, make_icosphere(0.4f, 3, "big"), big, 1);
    add_part(scene, make_icosphere(0.2f, 2, "small"), small, 0);
    add_part(scene, make_flat_box(Vec3(0.3f, 0.2f, 0.25f), 4, "box"), box, 0);
    Vec3Track path;
    path.times = {0.0f, 1.0f};
    path.values = {Vec3(0, 0.45f, 0), Vec3(-0.5f, 0.5f, 0.3f)};
    scene.nodes[scene.parts[1].node].translation = path;
    scene.camera.position = Vec3(1.2f, 1.6f, 2.5f);
    scene.camera.target = Vec3(0, 0.3f, 0);
    return scene;
}

// Per time and S: the GL renderer's colours against the CPU's with the
// same rays. A vertex differs only where at least one of its rays did, so
// the vertices that differ bound the rays that did: at most 1 in 10⁴.
void check_rays_against_cpu(const Scene& scene, const EnvironmentLights& lights, const std::vector<float>& times,
                            const std::vector<int>& sides) {
    test::gl_context();
    RenderOptions options;
    options.local_lights = false;
    for (const int side : sides) {
        RenderOptions gl_options = options;
        gl_options.gpu_rays.enabled = true;
        gl_options.gpu_rays.samples_per_side = side;
        gl::GlRenderer gpu(scene, lights, PartFields{}, gl_options);
        for (const float t : times) {
            RenderOptions cpu_options = options;
            cpu_options.exact_visibility = std::make_shared<ExactVisibility>(scene, t, ExactVisibilityMode::All, side, true);
            CpuRenderer cpu(scene, lights, PartFields{}, cpu_options);
            cpu.set_time(t);
            gpu.set_time(t);
            const VertexColors expected = cpu.shade();
            const VertexColors colors = gpu.shade();
            const test::ColorDifference d = test::compare_colors(colors, expected, 1e-4);
            const double rays = double(cpu.stats().shadow_rays);
            INFO("S = " << side << ", t = " << t << ": " << d.over_tolerance << " of " << d.vertices
                        << " vertices differ (relative L2 " << d.relative_l2 << "); rays CPU " << rays << ", GPU "
                        << gpu.stats().shadow_rays);
            CHECK(d.mean_luminance > 1e-3);
            CHECK(rays > 2.0 * double(d.vertices));
            CHECK(double(gpu.stats().shadow_rays) == Approx(rays).epsilon(1e-4));
            CHECK(double(d.over_tolerance) <= 1e-4 * rays);
            CHECK(d.relative_l2 < 2e-3);
            WARN("S = " << side << ", t = " << t << ": " << d.over_tolerance << " of " << d.vertices
                        << " vertices differ from the CPU's rays, " << rays << " rays");
        }
    }
}

TEST_CASE("GL ray-traced visibility traces the CPU ray rows' rays", "[gl-rays]") {
    check_rays_against_cpu(rays_scene(), test::random_rsls(24, 5), {0.0f, 0.7f}, {1, 2});
}

TEST_CASE("GL ray-traced visibility: many instances of one mesh", "[gl-rays]") {
    Scene scene = make_scene("gl rays instanced", Color(0.6f));
    add_part(scene, make_plane(4.0f, 24, "ground"));
    const TriangleMesh ball = make_icosphere(0.12f, 2, "ball");
    for (int i = 0; i < 48; ++i) {
        Transform pose;
        pose.translation = Vec3(-1.5f + 0.45f * float(i % 8), 0.12f + 0.3f * float(i % 3), -1.2f + 0.45f * float(i / 8));
        pose.scale = Vec3(1.0f + 0.1f * float(i % 4));
        add_part(scene, ball, pose);
    }
    check_rays_against_cpu(scene, test::random_rsls(16, 9), {0.0f}, {2});
}

// The shipped robot (25 parts, 87,651 vertices, a glTF exporter's file): the
// rays of 30 RSLs at S = 1, about 2 M of them, at two poses.
TEST_CASE("GL ray-traced visibility traces the CPU's rays on the robot", "[gl-rays]") {
    const std::filesystem::path source(RSL_SOURCE_DIR);
    if (!std::filesystem::exists(source / "assets/generated/robot.glb")) {
        WARN("SKIPPED: assets/generated/robot.glb is missing (build the generated_assets target)");
        return;
    }
    const Scene scene = load_scene(source / "assets/scenes/robot.json");
    check_rays_against_cpu(scene, test::random_rsls(30, 4), {0.0f, 0.6f}, {1});
}

TEST_CASE("GL ray-traced visibility: options out of range and the CPU renderer are refused", "[gl-rays]") {
    test::gl_context();
    const Scene scene = rays_scene();
    RenderOptions options;
    options.gpu_rays.enabled = true;
    for (const int side : {0, 17}) {
        options.gpu_rays.samples_per_side = side;
        CHECK_THROWS_AS(gl::GlRenderer(scene, test::random_rsls(4, 1), PartFields{}, options), Error);
    }
    options.gpu_rays.samples_per_side = 2;
    CHECK_THROWS_WITH(CpuRenderer(scene, test::random_rsls(4, 1), PartFields{}, options),
                      Catch::Contains("GL backend only"));
    options.shadow_maps.enabled = true;
    CHECK_THROWS_WITH(gl::GlRenderer(scene, test::random_rsls(4, 1), PartFields{}, options),
                      Catch::Contains("enable one"));
}

}  // namespace
}  // namespace rsl
