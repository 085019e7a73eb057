// The viewer end to end (under xvfb-run, llvmpipe): a screenshot of a sphere
// over a ground plane under an overcast sky is not blank and shows the
// sphere's shadow — ground pixels next to the sphere's foot are darker than
// open ground. (viewer_sky_test.cpp checks the sky behind them.)
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "src/gl/viewer.h"
#include "tests/gl/viewer_test_support.h"
#include "tests/png_test_support.h"
#include "tests/trace/trace_test_scenes.h"

namespace rsl {
namespace {

namespace fs = std::filesystem;

TEST_CASE("rsl view writes a screenshot that shows the scene and its shadows", "[gl-viewer]") {
    const fs::path overcast = fs::path(RSL_SOURCE_DIR) / "assets/generated/overcast.exr";
    if (!fs::exists(overcast)) {
        WARN("SKIPPED: assets/generated/overcast.exr is missing (build the generated_assets target)");
        return;
    }
    const fs::path dir = fs::temp_directory_path() / fmt::format("rsl_viewer_test_{}", ::getpid());
    fs::create_directories(dir);
    test::write_obj(dir / "ground.obj", test::make_plane(4.0f, 24, "ground"));
    test::write_obj(dir / "ball.obj", test::make_icosphere(0.4f, 3, "ball"));
    const Vec3 eye(0.0f, 2.2f, 3.0f), target(0.0f, 0.3f, 0.0f);
    std::ofstream(dir / "scene.json") << fmt::format(R"({{
  "name": "viewer-test",
  "parts": [
    {{ "name": "ground", "obj": "ground.obj", "material": "white" }},
    {{ "name": "ball", "obj": "ball.obj", "material": "white",
      "transform": {{ "translation": [0, 0.45, 0] }} }}
  ],
  "materials": {{ "white": {{ "model": "lambert", "albedo": [0.7, 0.7, 0.7] }} }},
  "environment": {{ "file": "{}", "resolution": 16 }},
  "camera": {{ "position": [{}, {}, {}], "target": [{}, {}, {}], "fov_degrees": 40, "width": 320, "height": 240 }}
}})",
                                                     overcast.string(), eye.x, eye.y, eye.z, target.x, target.y,
                                                     target.z);
    gl::ViewerOptions options;
    options.scene = dir / "scene.json";
    options.quick_fields = true;
    options.render.environment_lights = 20;
    options.render.local_lights = false;  // the viewer adds a movable light; judge the sky's shadow alone
    options.width = 320, options.height = 240;
    options.panel = false;
    options.frames = 2;
    options.screenshot = dir / "shot.png";
    gl::run_viewer(options);

    const test::Png shot = test::read_png(options.screenshot);
    const int width = shot.width, height = shot.height;
    REQUIRE(width == 320);
    REQUIRE(height == 240);
    auto luma = [&](const Vec2& p) {
        const unsigned char* c = shot.at(std::clamp(int(p.x), 0, width - 1), std::clamp(int(p.y), 0, height - 1));
        // Linear luminance (undo the display pass's sRGB curve), 0..255.
        return 0.2126f * test::linear_255(c[0]) + 0.7152f * test::linear_255(c[1]) + 0.0722f * test::linear_255(c[2]);
    };
    // Not blank: the ball and the ground are lit, far above the old clear
    // colour (0.05 linear, 12.75 here); the background is the sky now.
    const float ball = luma(test::project(Vec3(0, 0.85f, 0.0f), eye, target, 40, width, height));
    const float open_ground = luma(test::project(Vec3(1.3f, 0, 0.6f), eye, target, 40, width, height));
    // Beside the ball's foot (in front of it, as the camera sees it): the
    // ball hides much of the overcast sky there.
    const float shadowed_ground = luma(test::project(Vec3(0.0f, 0, 0.3f), eye, target, 40, width, height));
    INFO("ball " << ball << ", open ground " << open_ground << ", ground beside the ball " << shadowed_ground);
    CHECK(open_ground > 12.75f + 50.0f);
    CHECK(ball > 12.75f + 50.0f);
    CHECK(shadowed_ground < 0.7f * open_ground);
    if (!getenv("RSL_KEEP_TEST_FILES")) fs::remove_all(dir);
}

}  // namespace
}  // namespace rsl
