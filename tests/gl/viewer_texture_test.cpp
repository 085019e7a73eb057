// The viewer's textured display pass (shaders/display.frag.glsl): a glTF
// ground with a base colour texture, under a uniform sky, seen by the viewer
// and formed by the CPU's image formation (rsl::api::Renderer::render_image,
// as `rsl render`), must give the same pixels: the diffuse layer times the
// texture per pixel, plus the specular layer, through the same sRGB curve.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "tools/assets/model.h"
#include "tools/assets/pbr_scene.h"
#include "tools/assets/primitives.h"
#include "rsl/rsl.h"
#include "src/formats/image_file.h"
#include "tools/viewer/viewer.h"
#include "tests/gl/viewer_test_support.h"
#include "tests/png_test_support.h"
#include "tests/test_support.h"

namespace rsl {
namespace {

namespace fs = std::filesystem;

TEST_CASE("the viewer's textured pass shows the CPU image of a textured glTF ground", "[gl-viewer]") {
    const fs::path dir = test::scratch_dir("viewer-texture");
    // A 2 m ground, its 4 × 4 tiles (terracotta, slate, light grout) once over it.
    assets::GeneratedModel model;
    MaterialDesc tiles = assets::gltf_pbr_material("tiles", Color(1.0f), 0.0f, 1.0f);
    tiles.base_color_texture = assets::make_tile_texture(4, 8);
    model.scene.materials = {tiles};
    TriangleMesh ground = assets::grid_plane(2.0f, 2.0f, 24, 24);
    for (const Vec3& p : ground.positions) ground.texcoords.emplace_back(p.x / 2.0f + 0.5f, p.z / 2.0f + 0.5f);
    model.add_node("ground", -1, Vec3(0), ground);
    model.scene.parts.back().material = 0;
    validate_and_complete(model.scene.parts.back().mesh, "tiles.glb");
    assets::write_glb(dir / "tiles.glb", model);
    Image white(64, 32, 3);
    std::fill(white.pixels.begin(), white.pixels.end(), 0.8f);
    write_exr(dir / "white.exr", white);
    const int width = 160, height = 120;
    std::ofstream(dir / "scene.json") << fmt::format(R"({{
  "name": "viewer-texture-test",
  "gltf": "tiles.glb",
  "environment": {{ "file": "white.exr", "resolution": 16 }},
  "camera": {{ "position": [0, 2.0, 1.4], "target": [0, 0, 0.1], "fov_degrees": 40, "width": {}, "height": {} }},
  "subdivision": false,
  "precompute": {{ "svdf": {{ "resolution": 8, "clusters": 4, "vectors": 2, "supersampling": 1 }},
                  "ovdf": {{ "shells": 2, "cube_resolution": 4, "vdt_resolution": 8, "vectors": 2 }} }}
}})",
                                                     width, height);

    gl::ViewerOptions options;
    options.scene = dir / "scene.json";
    options.quick_fields = true;
    options.render.environment_light_count = 20;
    options.render.local_lights = false;  // the viewer's movable light is not in the scene file
    options.width = width, options.height = height;
    options.panel = false;
    options.frames = 2;
    options.exposure = 0.0f;  // ×1: the tiles stay below 1, unclipped
    options.auto_exposure = false;
    options.screenshot = dir / "shot.png";
    gl::run_viewer(options);
    const test::Png shot = test::read_png(options.screenshot);
    REQUIRE(shot.width == width);
    REQUIRE(shot.height == height);

    api::RenderSettings settings;
    settings.lights = 20;
    settings.field_cache = (dir / "cache").string();
    const api::Scene scene = api::Scene::load((dir / "scene.json").string());
    api::Renderer cpu(scene, settings);
    const api::Image image = cpu.render_image({width, height, 1});
    REQUIRE(image.width == width);
    REQUIRE(image.height == height);

    // Pixels whose 3 × 3 neighbourhood the ground covers in the CPU image
    // (edges rasterize differently from ray casting).
    auto covered = [&](int x, int y) {
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int px = x + dx, py = y + dy;
                if (px < 0 || py < 0 || px >= width || py >= height) return false;
                if (image.rgba[4 * (size_t(py) * width + px) + 3] < 1.0f) return false;
            }
        return true;
    };
    int compared = 0, off = 0, terracotta = 0, slate = 0;
    double sum_difference = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            if (!covered(x, y)) continue;
            const float* c = &image.rgba[4 * (size_t(y) * width + x)];
            const unsigned char* s = shot.at(x, y);
            float worst = 0;
            for (int k = 0; k < 3; ++k) {
                const float difference = std::abs(test::srgb_255(c[k]) - float(s[k]));
                worst = std::max(worst, difference);
                sum_difference += difference;
            }
            ++compared;
            if (worst > 6.0f) ++off;  // 8-bit levels
            if (c[0] > 2.0f * c[2]) ++terracotta;
            if (c[2] > c[0]) ++slate;
        }
    const double mean_difference = sum_difference / (3.0 * std::max(compared, 1));
    INFO(compared << " pixels compared, " << off << " off by more than 6 levels, mean difference "
                  << mean_difference << " levels; terracotta " << terracotta << ", slate " << slate);
    // The texture shows in the CPU image (else the comparison proves nothing)...
    REQUIRE(compared > width * height / 2);
    CHECK(terracotta > compared / 10);
    CHECK(slate > compared / 10);
    // ...and the viewer draws the same pixels: a pass without the texture, a
    // texture read as sRGB twice or with the wrong coordinates is tens of
    // levels off over most of the ground.
    CHECK(off <= compared / 50);
    CHECK(mean_difference < 1.5);
    if (!getenv("RSL_KEEP_TEST_FILES")) fs::remove_all(dir);
}

}  // namespace
}  // namespace rsl
