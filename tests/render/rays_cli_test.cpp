// `rsl render --backend rays --ray-samples S`: the program's vertex colours
// are, bit for bit, the ray-traced row made by hand (the CPU renderer with
// ExactVisibility, mode All, jittered, at the frame's time), and no field is
// read or baked.
#include <catch2/catch.hpp>

#include "src/formats/vertex_colors.h"
#include "src/render/cpu_renderer.h"
#include "src/render/exact_visibility.h"
#include "src/render/render_setup.h"
#include "tests/test_support.h"

namespace rsl {
namespace {

namespace fs = std::filesystem;

TEST_CASE("rsl render --backend rays writes the ray-traced row's vertex colours", "[render][cli][rays]") {
    const fs::path dir = test::scratch_dir("rays_cli");
    test::write_text(dir / "ground.obj", test::grid_obj(12, 2.0));
    test::write_text(dir / "box.obj", test::kUnitBoxObj);
    test::write_text(dir / "scene.json", fmt::format(R"({{
  "parts": [ {{ "name": "ground", "obj": "ground.obj" }},
             {{ "name": "box", "obj": "box.obj",
                "animation": {{ "translation": {{ "times": [0, 1], "values": [[0, 0.2, 0], [0.6, 0.5, 0]] }} }} }} ],
  "environment": {{ "file": "{}/assets/generated/sunsky.exr", "resolution": 8 }},
  "camera": {{ "width": 16, "height": 12 }}
}})", RSL_SOURCE_DIR));
    const float t = 0.75f;
    const auto [status, output] = test::run_rsl("render " + (dir / "scene.json").string() +
                                                " --backend rays --ray-samples 3 -k 5 --time 0.75 -o " +
                                                (dir / "out.png").string() + " --vertex-out " +
                                                (dir / "out.rslv").string());
    INFO(output);
    REQUIRE(status == 0);
    CHECK_THAT(output, Catch::Contains("rays shading") && Catch::Contains("M shadow rays"));
    CHECK_THAT(output, Catch::Contains("fields: 0 loaded from the cache, 0 baked"));
    CHECK_FALSE(fs::exists(dir / ".rsl-cache"));
    const VertexColors written = read_vertex_colors(dir / "out.rslv");

    RenderOptions options;
    options.environment_light_count = 5;
    options.self_visibility = options.occluders = false;  // the fields are not the rows'
    const RenderSetup setup = prepare_render(dir / "scene.json", options);
    options.exact_visibility = std::make_shared<ExactVisibility>(*setup.scene, t, ExactVisibilityMode::All, 3, true);
    CpuRenderer row(*setup.scene, setup.environment_lights, PartFields{}, options);
    row.set_time(t);
    const VertexColors expected = row.shade();
    REQUIRE(written.parts.size() == expected.parts.size());
    size_t differing = 0, shadowed = 0;
    for (size_t p = 0; p < expected.parts.size(); ++p) {
        REQUIRE(written.parts[p].size() == expected.parts[p].size());
        for (size_t v = 0; v < expected.parts[p].size(); ++v) differing += written.parts[p][v] != expected.parts[p][v];
    }
    CHECK(differing == 0);
    CHECK(written.producer == "rsl-rays");
    // The box shadows the ground: the rays found something to hide.
    RenderOptions unshadowed = options;
    unshadowed.exact_visibility = nullptr;
    CpuRenderer open_sky(*setup.scene, setup.environment_lights, PartFields{}, unshadowed);
    open_sky.set_time(t);
    const VertexColors lit = open_sky.shade();
    for (size_t v = 0; v < lit.parts[0].size(); ++v) shadowed += written.parts[0][v].g < 0.9f * lit.parts[0][v].g;
    CHECK(shadowed > 0);
}

}  // namespace
}  // namespace rsl
