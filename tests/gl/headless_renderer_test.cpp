// The `rsl render --backend gl` entry point: its own context, the same colours
// as the CPU renderer (a second GL context in the process, as a CLI would have).
#include <catch2/catch.hpp>

#include "src/gl/headless_renderer.h"
#include "tests/gl/gl_test_support.h"
#include "tests/trace/trace_test_scenes.h"

namespace rsl {
namespace {

TEST_CASE("HeadlessGlRenderer shades like the CPU renderer", "[gl-renderer]") {
    Scene scene = test::make_scene("headless", Color(0.6f));
    test::add_part(scene, test::make_plane(2.0f, 6, "ground"));
    Transform lifted;
    lifted.translation = Vec3(0, 0.5f, 0);
    test::add_part(scene, test::make_icosphere(0.3f, 2, "ball"), lifted);
    scene.camera.position = Vec3(0.5f, 1.5f, 2.0f);
    LocalLight light;
    light.position = Vec3(0.3f, 1.2f, 0.2f);
    scene.lights.push_back(light);
    const RslSet lights = test::random_rsls(6, 17);
    const RenderOptions options;
    CpuRenderer cpu(scene, lights, PartFields{}, options);
    gl::HeadlessGlRenderer gpu(scene, lights, PartFields{}, options);
    CHECK(gpu.device().find("OpenGL") != std::string::npos);
    VertexColors colors = gpu.make_output();
    for (const float t : {0.0f, 1.0f}) {
        cpu.set_time(t);
        gpu.set_time(t);
        gpu.shade(colors);
        const test::ColorDifference d = test::compare_colors(colors, cpu.shade(), 1e-3);
        INFO("relative L2 " << d.relative_l2 << ", max relative " << d.max_relative);
        CHECK(d.mean_luminance > 1e-3);
        CHECK(d.relative_l2 < 1e-5);
        CHECK(d.over_tolerance == 0);
    }
}

}  // namespace
}  // namespace rsl
