// The public API (include/rsl/rsl.h) renders what the `rsl` program renders:
// the same vertex colours, image and ground truth, bit for bit, for the same
// scene file; and a frame posed through the API equals the frame of a scene
// file that says the same pose.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <regex>

#include "rsl/rsl.h"
#include "src/core/math.h"
#include "tests/api/api_test_scene.h"
#include "tools/assets/model.h"
#include "tools/assets/pbr_scene.h"
#include "tools/assets/primitives.h"

namespace rsl {
namespace {

using api::Renderer;
using api::Scene;

// The number after `label` in `text` (e.g. "relative L2: 0.0123 …").
double number_after(const std::string& text, const std::string& label) {
    const size_t at = text.find(label);
    REQUIRE(at != std::string::npos);
    return std::strtod(text.c_str() + at + label.size(), nullptr);
}

void require_same_colors(const api::VertexColors& a, const api::VertexColors& b) {
    REQUIRE(a.part_names == b.part_names);
    REQUIRE(a.part_offsets == b.part_offsets);
    REQUIRE(a.rgb.size() == b.rgb.size());
    // On a mismatch, where and by how much: this test has failed now and then
    // inside full ctest runs only, and its message is all a CI log keeps.
    size_t differing = 0, first = 0;
    float largest = 0.0f;
    for (size_t i = 0; i < a.rgb.size(); ++i) {
        if (a.rgb[i] == b.rgb[i]) continue;
        if (differing++ == 0) first = i;
        largest = std::max(largest, std::abs(a.rgb[i] - b.rgb[i]));
    }
    const size_t vertex = first / 3;
    const size_t part = size_t(std::upper_bound(a.part_offsets.begin(), a.part_offsets.end(), vertex) -
                               a.part_offsets.begin()) - 1;
    INFO(differing << " of " << a.rgb.size() << " values differ, the largest by " << largest << "; the first: vertex "
                   << vertex << " (part " << (part < a.part_names.size() ? a.part_names[part] : "?") << "), "
                   << a.rgb[first] << " vs " << b.rgb[first]);
    REQUIRE(differing == 0);
}

double max_value(const api::VertexColors& c) {
    double m = 0;
    for (float x : c.rgb) m = std::max(m, double(x));
    return m;
}

TEST_CASE("the API's frame, image and truth are rsl render's and rsl truth's, bit for bit", "[api]") {
    const auto folder = test::scratch_dir("api-cli");
    const auto scene_file = test::write_api_scene(folder, "scene.json");
    const std::string out = folder.string();
    const auto [render_status, render_text] = test::run_rsl(fmt::format(
        "render {} --time 0.25 --lights 12 -q -o {}/cli.exr --vertex-out {}/cli.rslv", scene_file.string(), out, out));
    REQUIRE(render_status == 0);
    const auto [truth_status, truth_text] = test::run_rsl(
        fmt::format("truth {} --time 0.25 -q -o {}/truth.exr --vertex-out {}/truth.rslv", scene_file.string(), out, out));
    REQUIRE(truth_status == 0);

    api::RenderSettings settings;
    settings.lights = 12;
    Renderer renderer(Scene::load(scene_file.string()), settings);
    CHECK(renderer.setup().fields_baked == 0);  // rsl render baked them into the scene's cache
    CHECK(renderer.setup().fields_loaded == 4);
    renderer.set_time(0.25f);
    const api::VertexColors colors = renderer.shade();
    CHECK(colors.producer == "rsl-cpu");
    require_same_colors(colors, api::read_vertex_colors(out + "/cli.rslv"));
    REQUIRE(max_value(colors) > 0.01);  // lit: the comparison is not of two black frames
    // The renderer's image (its floor with per-pixel shadows) is rsl render's.
    const api::Image image = renderer.render_image();
    const api::Image cli_image = api::read_image(out + "/cli.exr");
    REQUIRE(image.width == 96);
    REQUIRE(image.height == 72);
    REQUIRE(image.rgba == cli_image.rgba);
    // form_image draws the colours alone: the blend, as rsl render with neither per-pixel pass.
    REQUIRE(test::run_rsl(fmt::format("render {} --time 0.25 --lights 12 -q --pixel-shadows off "
                                      "--no-pixel-highlights -o {}/blend.exr",
                                      scene_file.string(), out))
                .first == 0);
    CHECK(renderer.form_image(colors).rgba == api::read_image(out + "/blend.exr").rgba);
    // The paper's sum, as `rsl render --no-exact-diffuse-light`: other colours, the CLI's.
    REQUIRE(test::run_rsl(fmt::format("render {} --time 0.25 --lights 12 -q --no-exact-diffuse-light -o {}/paper.exr "
                                      "--vertex-out {}/paper.rslv",
                                      scene_file.string(), out, out))
                .first == 0);
    api::RenderSettings paper_settings = settings;
    paper_settings.exact_diffuse_light = false;
    Renderer paper(Scene::load(scene_file.string()), paper_settings);
    paper.set_time(0.25f);
    const api::VertexColors paper_colors = paper.shade();
    require_same_colors(paper_colors, api::read_vertex_colors(out + "/paper.rslv"));
    CHECK(api::compare(paper_colors, colors).relative_l2 > 1e-3);

    const api::VertexColors truth = renderer.truth();
    require_same_colors(truth, api::read_vertex_colors(out + "/truth.rslv"));
    // `rsl compare` prints six significant digits of the same number.
    const auto [compare_status, compare_text] = test::run_rsl(fmt::format("compare {0}/cli.rslv {0}/truth.rslv", out));
    REQUIRE(compare_status == 0);
    const api::VertexError error = api::compare(colors, truth);
    CHECK(error.relative_l2 == Approx(number_after(compare_text, "relative L2: ")).epsilon(1e-5));
    // The objects (all but the floor: the orb) and the worst part, as rsl compare prints them.
    CHECK(error.object_parts == 1);
    CHECK(error.worst_part == "orb");
    CHECK(error.objects_relative_l2 == Approx(number_after(compare_text, "objects: relative L2 ")).epsilon(1e-5));
    CHECK(error.worst_relative_l2 == Approx(number_after(compare_text, "part orb: relative L2 ")).epsilon(1e-5));
    CHECK(api::compare(colors, truth, {"orb", "floor"}).object_parts == 0);
    CHECK(error.relative_l2 > 0.001);  // an RSL frame is not the truth…
    CHECK(error.relative_l2 < 0.25);   // …but close to it
    const auto [image_status, image_text] = test::run_rsl(fmt::format("compare {0}/cli.exr {0}/truth.exr", out));
    REQUIRE(image_status == 0);
    const api::ImageError image_error = api::compare(image, api::read_image(out + "/truth.exr"));
    CHECK(image_error.relative_l2 == Approx(number_after(image_text, "relative L2: ")).epsilon(1e-5));
    CHECK(image_error.relative_h1 == Approx(number_after(image_text, "relative H1: ")).epsilon(1e-5));
}

TEST_CASE("poses, environment rotation, camera and materials set in code equal a scene file saying the same", "[api]") {
    const auto folder = test::scratch_dir("api-pose");
    const auto rest_file = test::write_api_scene(folder, "rest.json");
    test::ApiSceneOptions moved;
    moved.orb_transform = R"({ "translation": [0.25, 0.05, -0.1], "rotation_axis_angle": [0.3, 1, 0.2, 35], "scale": [1.2, 0.9, 1.1] })";
    moved.environment_rotation = R"({ "axis": [0.2, 1, 0], "degrees": 75, "degrees_per_second": 0 })";
    moved.floor_albedo = "[0.2, 0.6, 0.3]";
    moved.camera = R"("position": [-0.7, 0.9, 1.2], "target": [0.1, 0.15, 0])";
    const auto moved_file = test::write_api_scene(folder, "moved.json", moved);

    Renderer expected(Scene::load(moved_file.string()));
    expected.set_time(0.4f);
    const api::VertexColors expected_colors = expected.shade();

    Renderer renderer(Scene::load(rest_file.string()));
    renderer.set_time(0.4f);
    const api::VertexColors rest_colors = renderer.shade();
    const glm::quat q = glm::angleAxis(glm::radians(35.0f), glm::normalize(glm::vec3(0.3f, 1, 0.2f)));
    renderer.set_part_pose("orb", api::Pose{{0.25f, 0.05f, -0.1f}, {q.w, q.x, q.y, q.z}, {1.2f, 0.9f, 1.1f}});
    renderer.set_environment_rotation({0.2f, 1, 0}, 75);
    renderer.set_camera({{-0.7f, 0.9f, 1.2f}, {0.1f, 0.15f, 0}, {0, 1, 0}, 36, 96, 72});
    renderer.set_material_parameter("floor", "albedo", {0.2f, 0.6f, 0.3f});
    const api::VertexColors colors = renderer.shade();
    CHECK(api::compare(rest_colors, expected_colors).relative_l2 > 0.05);  // the edits change the frame a lot…
    require_same_colors(colors, expected_colors);                        // …into the file's frame exactly
    REQUIRE(renderer.form_image(colors).rgba == expected.form_image(expected_colors).rgba);
    // The ground truth sees the same edits.
    require_same_colors(renderer.truth(), expected.truth());

    // The part stays where it was put while time moves on; a swapped
    // material shades as the file's assignment would.
    renderer.set_time(0.9f);
    expected.set_time(0.9f);
    renderer.set_part_material("floor", "clay");
    expected.set_part_material("floor", "clay");
    require_same_colors(renderer.shade(), expected.shade());
    const auto m = renderer.part_transform(0);
    CHECK(m[12] == Approx(0.25f));
    CHECK(m[13] == Approx(0.05f));
    CHECK(m[14] == Approx(-0.1f));
}

TEST_CASE("the API's rays backend is rsl render --backend rays, bit for bit, with no fields", "[api][rays]") {
    const auto folder = test::scratch_dir("api-rays");
    const auto scene_file = test::write_api_scene(folder, "scene.json");
    const std::string out = folder.string();
    const auto [status, text] = test::run_rsl(
        fmt::format("render {} --backend rays --ray-samples 2 --time 0.25 --lights 12 -q -o {}/cli.exr "
                    "--vertex-out {}/cli.rslv", scene_file.string(), out, out));
    INFO(text);
    REQUIRE(status == 0);

    api::RenderSettings settings;
    settings.lights = 12;
    settings.backend = "rays";
    settings.ray_samples = 2;
    Renderer renderer(Scene::load(scene_file.string()), settings);
    CHECK(renderer.backend() == "rays");
    CHECK(renderer.setup().fields_loaded + renderer.setup().fields_baked == 0);
    renderer.set_time(0.25f);
    const api::VertexColors colors = renderer.shade();
    CHECK(colors.producer == "rsl-rays");
    require_same_colors(colors, api::read_vertex_colors(out + "/cli.rslv"));
    REQUIRE(max_value(colors) > 0.01);
    CHECK(renderer.render_image().rgba == api::read_image(out + "/cli.exr").rgba);
    // Another S traces other rays: the setting reaches the renderer.
    settings.ray_samples = 1;
    Renderer one_ray(Scene::load(scene_file.string()), settings);
    one_ray.set_time(0.25f);
    CHECK(one_ray.shade().rgb != colors.rgb);

    const std::vector<std::string> backends = api::build_info().backends;
    CHECK(std::find(backends.begin(), backends.end(), "rays") != backends.end());
    settings.ray_samples = 17;
    CHECK(test::error_of([&] { Renderer(Scene::load(scene_file.string()), settings); }) ==
          "ray_samples 17: expected S of 1 to 16 (S×S rays per vertex and light)");
    settings.backend = "cpu";
    settings.ray_samples = 2;
    CHECK(test::error_of([&] { Renderer(Scene::load(scene_file.string()), settings); }) ==
          "ray_samples 2: the cpu backend traces no rays (backends that do: rays)");
}

TEST_CASE("the API's errors carry the message rsl prints", "[api]") {
    const auto folder = test::scratch_dir("api-errors");
    const std::string missing = (folder / "missing.json").string();
    const auto [status, text] = test::run_rsl(fmt::format("truth {} -q -o {}/x.exr", missing, folder.string()));
    REQUIRE(status == 1);
    const std::string message = test::error_of([&] { Scene::load(missing); });
    REQUIRE(!message.empty());
    CHECK(text == "rsl: error: " + message + "\n");

    // A scene whose environment file is not there: the message of rsl render.
    test::write_api_scene(folder, "scene.json");
    std::string json = test::read_bytes(folder / "scene.json");
    json.replace(json.find("sunsky.exr"), 10, "nowhere.exr");
    test::write_text(folder / "broken.json", json);
    const auto [render_status, render_text] =
        test::run_rsl(fmt::format("render {}/broken.json -q -o {}/x.exr", folder.string(), folder.string()));
    REQUIRE(render_status == 1);
    const std::string render_message =
        test::error_of([&] { Renderer(Scene::load((folder / "broken.json").string())); });
    CHECK(render_message.find("nowhere.exr") != std::string::npos);
    CHECK(render_text == "rsl: error: " + render_message + "\n");

    Renderer renderer(Scene::load((folder / "scene.json").string()));
    CHECK(test::error_of([&] { renderer.set_part_pose("ball", {}); }) ==
          "no part 'ball' in scene 'api-test' (parts: orb, floor)");
    CHECK(test::error_of([&] { renderer.set_part_material("floor", "gold"); }).find("no material named 'gold'") !=
          std::string::npos);
    CHECK(test::error_of([&] { renderer.gl_color_buffer(); }).find("gl-current") != std::string::npos);
    CHECK(test::error_of([&] { renderer.set_part_pose(0, api::Pose{{0, 0, 0}, {1, 0, 0, 0}, {1, -1, 1}}); })
              .find("must be positive") != std::string::npos);
}

}  // namespace
}  // namespace rsl

namespace rsl {
namespace {

// A .glb of a floor and a ball whose gltf_pbr material "mr" has a
// metallic-roughness texture, its roughness factor `roughness`, and a scene
// file naming it.
std::filesystem::path write_textured_scene(const std::filesystem::path& folder, const std::string& name,
                                           float roughness) {
    assets::GeneratedModel model;
    MaterialDesc m = assets::gltf_pbr_material("mr", Color(0.9f, 0.7f, 0.4f), 1.0f, roughness);
    auto texture = std::make_shared<Texture>();
    texture->name = "mr.png";
    texture->image = Image(4, 4, 3);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) texture->image.set_rgb(i, j, Color(1.0f, 0.3f + 0.2f * float(i), float(j % 2)));
    m.metallic_roughness_texture = texture;
    model.scene.materials = {m};
    TriangleMesh floor = assets::grid_plane(1.6f, 1.6f, 16, 16);
    for (const Vec3& p : floor.positions) floor.texcoords.emplace_back(p.x / 1.6f + 0.5f, p.z / 1.6f + 0.5f);
    model.add_node("floor", -1, Vec3(0), floor);
    TriangleMesh ball = assets::sphere(0.25f, 0.05f);
    for (const Vec3& p : ball.positions) ball.texcoords.emplace_back(p.x * 2 + 0.5f, p.y * 2 + 0.5f);
    model.add_node("ball", -1, Vec3(0, 0.3f, 0), ball);
    for (Part& part : model.scene.parts) {
        part.material = 0;
        validate_and_complete(part.mesh, name + ".glb");
    }
    assets::write_glb(folder / (name + ".glb"), model);
    const std::string generated = std::string(RSL_SOURCE_DIR) + "/assets/generated";
    const auto path = folder / (name + ".json");
    test::write_text(path, fmt::format(R"({{
  "name": "{1}", "gltf": "{1}.glb",
  "environment": {{ "file": "{0}/sunsky.exr", "resolution": 12 }},
  "camera": {{ "position": [0.9, 0.75, 1.3], "target": [0, 0.2, 0], "up": [0, 1, 0], "fov_degrees": 36, "width": 96, "height": 72 }},
  "subdivision": false,
  "precompute": {{
    "svdf": {{ "resolution": 8, "clusters": 16, "vectors": 4, "supersampling": 1 }},
    "ovdf": {{ "shells": 4, "inner_radius": 0.4, "outer_radius": 6.0, "cube_resolution": 6, "vdt_resolution": 8, "vectors": 4 }}
  }}
}}
)", generated, name));
    return path;
}

TEST_CASE("the API edits a material with a metallic-roughness texture as any other", "[api]") {
    const auto folder = test::scratch_dir("api-metallic-roughness");
    Renderer renderer(Scene::load(write_textured_scene(folder, "rough", 1.0f).string()));
    Renderer expected(Scene::load(write_textured_scene(folder, "half", 0.5f).string()));
    const api::VertexColors before = renderer.shade();
    renderer.set_material_parameter("mr", "roughness", {0.5f});
    const api::VertexColors colors = renderer.shade();
    CHECK(api::compare(before, colors).relative_l2 > 0.01);  // the texture's roughness halved
    require_same_colors(colors, expected.shade());
    require_same_colors(renderer.truth(), expected.truth());
}

}  // namespace
}  // namespace rsl
