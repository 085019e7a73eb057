// The rays backend (src/render/ray_traced_renderer.h): built through
// make_renderer, it shades every frame bit for bit as the ray-traced rows of
// `rsl baselines --many-light` were made by hand — the CPU renderer with
// ExactVisibility (mode All, jittered) posed at the frame's time — follows a
// moving part and a part moved by an edit between frames, and needs no fields.
#include <catch2/catch.hpp>

#include <filesystem>

#include "src/backend/render_session.h"
#include "src/render/cpu_renderer.h"
#include "src/render/exact_visibility.h"
#include "tests/api/api_test_scene.h"

namespace rsl {
namespace {

namespace fs = std::filesystem;

// The generated orb rising from a floor grid under the sun and sky: its
// shadow on the floor moves between frames. A folder per test case: ctest
// runs them side by side, and one bakes into its scene's cache.
fs::path rising_orb_scene(const std::string& name) {
    const fs::path folder = fs::path(RSL_BINARY_DIR) / "rays-backend-test" / name;
    fs::create_directories(folder);
    test::write_text(folder / "floor.obj", test::floor_obj(24, 0.8f));
    test::write_text(folder / "scene.json", fmt::format(R"({{
  "parts": [
    {{ "name": "orb", "obj": "{0}/orb.obj", "material": "steel",
       "animation": {{ "translation": {{ "times": [0, 1], "values": [[0, 0, 0], [0.3, 0.4, -0.2]] }} }} }},
    {{ "name": "floor", "obj": "floor.obj", "material": "floor" }}
  ],
  "materials": {{
    "steel": {{ "model": "phong", "kd": [0.3, 0.3, 0.32], "ks": [0.4, 0.4, 0.4], "exponent": 5 }},
    "floor": {{ "model": "lambert", "albedo": [0.55, 0.53, 0.5] }}
  }},
  "environment": {{ "file": "{0}/sunsky.exr", "resolution": 12 }},
  "camera": {{ "width": 32, "height": 24 }},
  "subdivision": false,
  "precompute": {{
    "svdf": {{ "resolution": 8, "clusters": 16, "vectors": 4, "supersampling": 1 }},
    "ovdf": {{ "shells": 4, "inner_radius": 0.4, "outer_radius": 6.0, "cube_resolution": 6, "vdt_resolution": 8, "vectors": 4 }}
  }}
}}
)", std::string(RSL_SOURCE_DIR) + "/assets/generated"));
    return folder / "scene.json";
}

// Small BRDF tables: every renderer here builds its own (the test's time).
RenderOptions small_options(int lights) {
    RenderOptions options;
    options.environment_light_count = lights;
    options.local_lights = false;
    options.brdf_table.resolution = 24, options.brdf_table.view_samples = 8;
    return options;
}

// How many vertex colours differ between a and b (which must have the same parts).
size_t differing(const VertexColors& a, const VertexColors& b) {
    REQUIRE(a.parts.size() == b.parts.size());
    size_t count = 0;
    for (size_t p = 0; p < a.parts.size(); ++p) {
        REQUIRE(a.parts[p].size() == b.parts[p].size());
        for (size_t v = 0; v < a.parts[p].size(); ++v) count += a.parts[p][v] != b.parts[p][v];
    }
    return count;
}

// A ray-traced row of the many-light experiment, as it was made by hand.
VertexColors row_by_hand(const Scene& scene, const EnvironmentLights& lights, RenderOptions options, float t,
                         int samples, size_t* rays = nullptr) {
    options.exact_visibility = std::make_shared<ExactVisibility>(scene, t, ExactVisibilityMode::All, samples, true);
    CpuRenderer renderer(scene, lights, PartFields{}, options);
    renderer.set_time(t);
    VertexColors colors = renderer.shade();
    if (rays) *rays = renderer.stats().shadow_rays;
    return colors;
}

TEST_CASE("The rays backend shades as the ray-traced rows, bit for bit, at every frame", "[backend][rays]") {
    const RenderOptions options = small_options(8);
    const RenderSetup setup = prepare_render(rising_orb_scene("rows"), options);
    const Scene& scene = *setup.scene;
    for (const int samples : {1, 2}) {
        RenderOptions o = options;
        o.ray_samples = samples;
        // The fields a caller may pass are not used.
        const auto renderer = make_renderer(Backend::Rays, scene, setup.environment_lights, setup.fields, o);
        CHECK(renderer->backend() == "rays");
        VertexColors colors = renderer->make_output();
        for (const float t : {0.0f, 0.45f, 0.9f, 0.45f}) {
            INFO("S = " << samples << ", t = " << t);
            renderer->set_time(t);
            renderer->shade(colors);
            size_t rays = 0;
            const VertexColors expected = row_by_hand(scene, setup.environment_lights, options, t, samples, &rays);
            CHECK(differing(colors, expected) == 0);
            CHECK(renderer->stats().shadow_rays == rays);
            CHECK(rays > 0);
            // The frame matters: the rays posed at t = 0 shade another frame.
            if (t != 0.0f) CHECK(differing(colors, row_by_hand(scene, setup.environment_lights, options, 0.0f, samples)) > 0);
        }
    }
}

TEST_CASE("The rays backend follows a part moved between frames at the same time", "[backend][rays]") {
    RenderOptions options = small_options(6);
    options.ray_samples = 2;
    RenderSetup setup = prepare_render(rising_orb_scene("moved"), options);
    Scene& scene = *setup.scene;
    const auto renderer = make_renderer(Backend::Rays, scene, setup.environment_lights, PartFields{}, options);
    renderer->set_time(0.3f);
    const VertexColors before = renderer->shade();
    // The orb's node moved as the API's set_part_pose moves it: its animation dropped, a rest transform set.
    SceneNode& node = scene.nodes[size_t(scene.parts[0].node)];
    node.translation.reset();
    node.rest.translation = Vec3(-0.25f, 0.1f, 0.3f);
    renderer->set_time(0.3f);
    const VertexColors after = renderer->shade();
    CHECK(differing(after, row_by_hand(scene, setup.environment_lights, options, 0.3f, 2)) == 0);
    CHECK(differing(after, before) > 0);
}

TEST_CASE("A session of the rays backend bakes no fields and refuses a bad S", "[backend][rays]") {
    const fs::path path = rising_orb_scene("session");
    fs::remove_all(path.parent_path() / ".rsl-cache");
    RenderOptions options = small_options(6);
    options.ray_samples = 2;
    RenderSession session(path, options, Backend::Rays);
    CHECK(session.setup().fields_loaded + session.setup().fields_baked == 0);
    CHECK_FALSE(fs::exists(path.parent_path() / ".rsl-cache"));
    CHECK(session.renderer().backend() == "rays");
    const VertexColors& colors = session.shade(0.5f, false);
    CHECK(differing(colors, row_by_hand(session.scene(), session.setup().environment_lights, options, 0.5f, 2)) == 0);

    // Capabilities, not names: rays takes ray samples and no fields.
    const BackendCapabilities rays = backend_capabilities(Backend::Rays);
    CHECK(rays.standalone);
    CHECK(rays.ray_samples);
    CHECK_FALSE(rays.fields);
    CHECK(backends_with(&BackendCapabilities::ray_samples) == std::vector<std::string>{"rays"});
    CHECK(backend_capabilities(Backend::Cpu).fields);
    CHECK(parse_backend("rays") == Backend::Rays);
    CHECK(backend_name(Backend::Rays) == "rays");

    for (const int bad : {0, RenderOptions::kMaxRaySamples + 1}) {
        RenderOptions o = options;
        o.ray_samples = bad;
        CHECK_THROWS_WITH(make_renderer(Backend::Rays, session.scene(), session.setup().environment_lights,
                                        PartFields{}, o),
                          Catch::Contains(path.string()) && Catch::Contains("ray samples per side is outside [1, 16]"));
    }
}

}  // namespace
}  // namespace rsl
