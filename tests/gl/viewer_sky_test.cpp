// The viewer's background is the environment (tools/viewer/skybox.h): in a
// screenshot, every sky pixel is the sRGB-encoded radiance of the cube-map
// texel its view ray meets, after the environment's rotation at that time, so
// two screenshots a quarter turn apart show the map turned.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "src/core/envmap.h"
#include "src/formats/environment_file.h"
#include "tools/viewer/viewer.h"
#include "tests/gl/viewer_test_support.h"
#include "tests/png_test_support.h"
#include "tests/test_support.h"
#include "tests/trace/trace_test_scenes.h"

namespace rsl {
namespace {

namespace fs = std::filesystem;

test::Png screenshot(const fs::path& scene, float time, float exposure, const fs::path& png) {
    gl::ViewerOptions options;
    options.scene = scene;
    options.quick_fields = true;
    options.render.environment_light_count = 8;
    options.width = 160, options.height = 120;
    options.panel = false;
    options.frames = 1;
    options.start_time = time;
    options.exposure = exposure;
    options.auto_exposure = false;
    options.screenshot = png;
    gl::run_viewer(options);
    return test::read_png(png);
}

TEST_CASE("the viewer draws the environment behind the scene, turning with it", "[gl-viewer]") {
    const fs::path sky = fs::path(RSL_SOURCE_DIR) / "assets/generated/sunsky.exr";
    if (!fs::exists(sky)) {
        WARN("SKIPPED: assets/generated/sunsky.exr is missing (build the generated_assets target)");
        return;
    }
    const fs::path dir = test::scratch_dir("viewer-sky");
    test::write_obj(dir / "ground.obj", test::make_plane(1.0f, 4, "ground"));
    const Vec3 eye(0.0f, 1.0f, 3.0f), target(0.0f, 0.9f, 0.0f);
    const int resolution = 8;  // big texels
    std::ofstream(dir / "scene.json") << fmt::format(R"({{
  "name": "viewer-sky-test",
  "parts": [ {{ "name": "ground", "obj": "ground.obj", "material": "white" }} ],
  "materials": {{ "white": {{ "model": "lambert", "albedo": [0.7, 0.7, 0.7] }} }},
  "environment": {{ "file": "{}", "resolution": {},
                    "rotation": {{ "axis": [1, 0, 0], "degrees": 0, "degrees_per_second": 90 }} }},
  "camera": {{ "position": [{}, {}, {}], "target": [{}, {}, {}], "fov_degrees": 60, "width": 160, "height": 120 }},
  "animation": {{ "start": 0, "end": 10, "fps": 24 }}
}})",
                                                     sky.string(), resolution, eye.x, eye.y, eye.z, target.x, target.y,
                                                     target.z);
    const CubeMap map = load_environment(sky, resolution);
    EnvironmentDesc environment;
    environment.rotation_axis = Vec3(1, 0, 0);  // tilts the sky: its gradient moves
    environment.rotation_degrees_per_second = 90;
    // An exposure that puts the sky's median texel mid-range: neither black nor clipped.
    std::vector<float> luminances;
    for (const Color& c : map.radiances()) luminances.push_back(luminance(c));
    std::nth_element(luminances.begin(), luminances.begin() + luminances.size() / 2, luminances.end());
    const float exposure = std::log2(0.25f / luminances[luminances.size() / 2]);

    const int width = 160, height = 120;
    const Mat4 inverse = glm::inverse(test::viewer_view_projection(eye, target, 60, width, height));
    // The 8-bit colour the background should have at pixel position (px, py) at time t.
    auto expected = [&](float px, float py, float t) {
        const Vec4 far = inverse * Vec4(2.0f * px / width - 1.0f, 1.0f - 2.0f * py / height, 1.0f, 1.0f);
        const Vec3 direction = glm::normalize(Vec3(far) / far.w - eye);
        const Color radiance = map.lookup(glm::transpose(environment.rotation_at(t)) * direction) * std::exp2(exposure);
        return Vec3(test::srgb_255(radiance.r), test::srgb_255(radiance.g), test::srgb_255(radiance.b));
    };
    // A pixel matches when it is the expected colour at its center or half a
    // pixel away (its ray may fall on either side of a texel border).
    auto matches = [&](const test::Png& shot, int x, int y, float t) {
        const unsigned char* c = shot.at(x, y);
        for (const Vec2 offset : {Vec2(0.5f), Vec2(0.0f), Vec2(1.0f), Vec2(0.0f, 1.0f), Vec2(1.0f, 0.0f)}) {
            const Vec3 e = expected(float(x) + offset.x, float(y) + offset.y, t);
            if (std::abs(c[0] - e.r) <= 3 && std::abs(c[1] - e.g) <= 3 && std::abs(c[2] - e.b) <= 3) return true;
        }
        return false;
    };
    const test::Png at_0 = screenshot(dir / "scene.json", 0.0f, exposure, dir / "t0.png");
    const test::Png at_1 = screenshot(dir / "scene.json", 1.0f, exposure, dir / "t1.png");
    REQUIRE(at_0.width == width);
    REQUIRE(at_0.height == height);
    // The upper third looks above the ground plane (1 m square, below the eye): sky only.
    int samples = 0, match_0 = 0, match_1 = 0, turned_0 = 0, mid_range = 0;
    for (int y = 2; y < height / 3; y += 3)
        for (int x = 1; x < width - 1; x += 3) {
            ++samples;
            match_0 += matches(at_0, x, y, 0.0f);
            match_1 += matches(at_1, x, y, 1.0f);
            turned_0 += matches(at_1, x, y, 0.0f);
            const Vec3 e = expected(x + 0.5f, y + 0.5f, 0.0f);
            mid_range += e.g > 10 && e.g < 245;
        }
    INFO(samples << " sky pixels: " << match_0 << " match at t = 0, " << match_1 << " at t = 1 (90°), " << turned_0
                 << " of t = 1 match t = 0's sky; " << mid_range << " expected mid-range");
    CHECK(mid_range > samples / 2);          // the comparison is of real colours
    CHECK(match_0 >= samples * 95 / 100);
    CHECK(match_1 >= samples * 95 / 100);
    CHECK(turned_0 < samples * 70 / 100);    // a quarter turn later the sky has moved
}

}  // namespace
}  // namespace rsl
