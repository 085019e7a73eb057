// The viewer end to end (under xvfb-run, llvmpipe): a screenshot of a sphere
// over a ground plane under an overcast sky is not blank and shows the
// sphere's shadow — ground pixels next to the sphere's foot are darker than
// open ground. (viewer_sky_test.cpp checks the sky behind them.)
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <vector>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "src/core/error.h"
#include "tools/viewer/viewer.h"
#include "tests/gl/viewer_test_support.h"
#include "tests/png_test_support.h"
#include "tests/trace/trace_test_scenes.h"

namespace rsl {
namespace {

namespace fs = std::filesystem;

const Vec3 kEye(0.0f, 2.2f, 3.0f), kTarget(0.0f, 0.3f, 0.0f);

// A ball over a ground plane under the overcast sky, in a new folder; its scene file.
fs::path write_ball_scene(const fs::path& dir, const fs::path& overcast) {
    fs::create_directories(dir);
    test::write_obj(dir / "ground.obj", test::make_plane(4.0f, 24, "ground"));
    test::write_obj(dir / "ball.obj", test::make_icosphere(0.4f, 3, "ball"));
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
                                                     overcast.string(), kEye.x, kEye.y, kEye.z, kTarget.x, kTarget.y,
                                                     kTarget.z);
    return dir / "scene.json";
}

// The viewer's options for a 320×240 screenshot of `scene` after two frames.
gl::ViewerOptions screenshot_options(const fs::path& scene, const fs::path& shot) {
    gl::ViewerOptions options;
    options.scene = scene;
    options.quick_fields = true;
    options.render.environment_light_count = 20;
    options.render.local_lights = false;  // the viewer adds a movable light; judge the sky's shadow alone
    options.width = 320, options.height = 240;
    options.panel = false;
    options.frames = 2;
    options.screenshot = shot;
    return options;
}

// Linear luminance (the display pass's sRGB curve undone), 0..255, at the pixel where `point` projects.
float luma_at(const test::Png& shot, const Vec3& point) {
    const Vec2 p = test::project(point, kEye, kTarget, 40, shot.width, shot.height);
    const unsigned char* c = shot.at(std::clamp(int(p.x), 0, shot.width - 1), std::clamp(int(p.y), 0, shot.height - 1));
    return 0.2126f * test::linear_255(c[0]) + 0.7152f * test::linear_255(c[1]) + 0.0722f * test::linear_255(c[2]);
}

TEST_CASE("rsl view writes a screenshot that shows the scene and its shadows", "[gl-viewer]") {
    const fs::path overcast = fs::path(RSL_SOURCE_DIR) / "assets/generated/overcast.exr";
    if (!fs::exists(overcast)) {
        WARN("SKIPPED: assets/generated/overcast.exr is missing (build the generated_assets target)");
        return;
    }
    const fs::path dir = fs::temp_directory_path() / fmt::format("rsl_viewer_test_{}", ::getpid());
    const gl::ViewerOptions options = screenshot_options(write_ball_scene(dir, overcast), dir / "shot.png");
    gl::run_viewer(options);

    const test::Png shot = test::read_png(options.screenshot);
    REQUIRE(shot.width == 320);
    REQUIRE(shot.height == 240);
    // Not blank: the ball and the ground are lit, far above the old clear
    // colour (0.05 linear, 12.75 here); the background is the sky now.
    const float ball = luma_at(shot, Vec3(0, 0.85f, 0.0f));
    const float open_ground = luma_at(shot, Vec3(1.3f, 0, 0.6f));
    // Beside the ball's foot (in front of it, as the camera sees it): the
    // ball hides much of the overcast sky there.
    const float shadowed_ground = luma_at(shot, Vec3(0.0f, 0, 0.3f));
    INFO("ball " << ball << ", open ground " << open_ground << ", ground beside the ball " << shadowed_ground);
    CHECK(open_ground > 12.75f + 50.0f);
    CHECK(ball > 12.75f + 50.0f);
    CHECK(shadowed_ground < 0.7f * open_ground);
    if (!getenv("RSL_KEEP_TEST_FILES")) fs::remove_all(dir);
}

// Screenshot mode reports every frame, and on a software renderer (xvfb's
// llvmpipe) the fallback shrinks a 640×480 window to 480×360 and says so;
// on a GPU nothing changes.
TEST_CASE("rsl view's screenshot mode reports each frame and shrinks on software OpenGL", "[gl-viewer]") {
    const fs::path overcast = fs::path(RSL_SOURCE_DIR) / "assets/generated/overcast.exr";
    if (!fs::exists(overcast)) {
        WARN("SKIPPED: assets/generated/overcast.exr is missing (build the generated_assets target)");
        return;
    }
    const fs::path dir = fs::temp_directory_path() / fmt::format("rsl_viewer_fallback_test_{}", ::getpid());
    gl::ViewerOptions options = screenshot_options(write_ball_scene(dir, overcast), dir / "small.png");
    options.width = 640, options.height = 480;
    options.frames = 3;
    options.software_fallback = true;
    std::vector<int> frames;
    std::string context;
    int fallback_width = 0, fallback_height = 0;
    options.notice = [&](const std::string& line) { context = line; };
    options.software_fallback_applied = [&](int w, int h) { fallback_width = w, fallback_height = h; };
    options.frame_done = [&](int frame, int total, double seconds) {
        CHECK(total == 3);
        CHECK(seconds > 0.0);
        frames.push_back(frame);
    };
    gl::run_viewer(options);

    CHECK(frames == std::vector<int>{1, 2, 3});
    const test::Png shot = test::read_png(options.screenshot);
    const bool software = context.find("llvmpipe") != std::string::npos || context.find("softpipe") != std::string::npos;
    INFO(context);
    if (software) {
        CHECK(fallback_width == 480);
        CHECK(fallback_height == 360);
        CHECK(shot.width == 480);
        CHECK(shot.height == 360);
    } else {
        CHECK(fallback_width == 0);
        CHECK(shot.width == 640);
    }
    // Still the scene: the ball lit above the clear colour.
    CHECK(luma_at(shot, Vec3(0, 0.85f, 0.0f)) > 12.75f + 50.0f);
    if (!getenv("RSL_KEEP_TEST_FILES")) fs::remove_all(dir);
}

// The split view: RSL on the left, the GPU ray-traced reference on the
// right, a light seam between. Both halves show the ball's shadow, and
// agree on open ground (the same light integrals and BRDF averages; only
// the visibility differs, and open ground sees the whole sky either way).
TEST_CASE("rsl view's split view shows RSL and the ray-traced reference side by side", "[gl-viewer]") {
    const fs::path overcast = fs::path(RSL_SOURCE_DIR) / "assets/generated/overcast.exr";
    if (!fs::exists(overcast)) {
        WARN("SKIPPED: assets/generated/overcast.exr is missing (build the generated_assets target)");
        return;
    }
    const fs::path dir = fs::temp_directory_path() / fmt::format("rsl_viewer_split_test_{}", ::getpid());
    gl::ViewerOptions options = screenshot_options(write_ball_scene(dir, overcast), dir / "split.png");
    options.view = gl::ViewMode::Split;
    options.reference_rays = 4;
    gl::run_viewer(options);

    const test::Png shot = test::read_png(options.screenshot);
    REQUIRE(shot.width == 320);
    const unsigned char* seam = shot.at(shot.width / 2, shot.height - 5);
    CHECK(int(seam[0]) > 200);
    for (const float side : {-1.0f, 1.0f}) {  // left: RSL, right: rays
        const float open_ground = luma_at(shot, Vec3(1.3f * side, 0, 0.6f));
        const float shadowed_ground = luma_at(shot, Vec3(0.3f * side, 0, 0.3f));
        INFO((side < 0 ? "RSL" : "rays") << ": open ground " << open_ground << ", beside the ball " << shadowed_ground);
        CHECK(open_ground > 12.75f + 50.0f);
        CHECK(shadowed_ground < 0.85f * open_ground);
    }
    const float rsl = luma_at(shot, Vec3(-1.3f, 0, 0.6f)), rays = luma_at(shot, Vec3(1.3f, 0, 0.6f));
    INFO("open ground: RSL " << rsl << ", rays " << rays);
    CHECK(rays == Approx(rsl).epsilon(0.1));
    CHECK_THROWS_AS(gl::parse_view_mode("both"), Error);
    if (!getenv("RSL_KEEP_TEST_FILES")) fs::remove_all(dir);
}

}  // namespace
}  // namespace rsl
