// The GL backend with a skinned mesh (docs/design/SKINNING.md): the frame's
// posed vertices uploaded in place of the bind pose shade as the CPU's.
#include <catch2/catch.hpp>

#include "src/formats/scene_file.h"
#include "src/gl/gl_renderer.h"
#include "src/render/cpu_renderer.h"
#include "tests/gl/gl_test_support.h"
#include "tests/render/render_test_scenes.h"
#include "tests/test_support.h"
#include "tools/assets/skinned_tube.h"

namespace rsl {

TEST_CASE("GL matches the CPU on a skinned tube bending over a ground", "[gl-renderer]") {
    const std::filesystem::path dir = test::scratch_dir("gl_skinning");
    assets::TubeOptions options;
    options.joints = 3;
    options.spacing = 0.04f;
    options.turn_degrees = 30;
    assets::write_glb(dir / "tube.glb", assets::make_bending_tube(options));
    Scene scene = load_scene(dir / "tube.glb");
    scene.source.clear();
    PrecomputeSettings& pre = scene.precompute;
    pre.svdf_resolution = 16, pre.svdf_clusters = 16, pre.svdf_vectors = 4, pre.svdf_supersampling = 2;
    pre.ovdf_shells = 8, pre.ovdf_cube_resolution = 8, pre.ovdf_vdt_resolution = 16, pre.ovdf_vectors = 4;
    test::add_part(scene, test::make_plane(3.0f, 24, "ground"));
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    const RslSet lights = test::random_rsls(16, 5);
    test::gl_context();
    CpuRenderer cpu(scene, lights, fields, RenderOptions{});
    gl::GlRenderer gpu(scene, lights, fields, RenderOptions{});
    double moved = 0;
    VertexColors first;
    for (const float t : {0.0f, 0.6f, 1.0f, 1.5f}) {
        cpu.set_time(t);
        gpu.set_time(t);
        const VertexColors expected = cpu.shade();
        const VertexColors colors = gpu.shade();
        const test::ColorDifference d = test::compare_colors(colors, expected, 1e-3);
        INFO("t = " << t << ": relative L2 " << d.relative_l2 << ", max relative " << d.max_relative << ", "
                    << d.over_tolerance << " of " << d.vertices << " vertices over 1e-3");
        CHECK(d.mean_luminance > 1e-3);
        CHECK(d.relative_l2 < 1e-5);
        CHECK(d.over_tolerance <= d.vertices / 1000);
        if (t == 0.0f) first = expected;
        else moved = std::max(moved, test::compare_colors(expected, first, 1e-3).relative_l2);
    }
    CHECK(moved > 0.01);  // the pose changes the shading: the comparison covers posed vertices
    // GPU rays trace rigid parts only: refused, naming the reason.
    RenderOptions rays;
    rays.gpu_rays.enabled = true;
    CHECK_THROWS_WITH(gl::GlRenderer(scene, lights, fields, rays), Catch::Contains("skinned parts"));
}

}  // namespace rsl
