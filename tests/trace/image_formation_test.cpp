// Image formation: the pinhole camera's geometry, exact interpolation of
// per-vertex colours, coverage in alpha, and refusal of mismatched colours.
#include <catch2/catch.hpp>

#include "src/core/error.h"
#include "src/trace/image_formation.h"
#include "tests/trace/trace_test_scenes.h"

using namespace rsl;

TEST_CASE("Pinhole camera: center ray forward, edges at half the field of view", "[trace][image]") {
    Camera camera;
    camera.position = Vec3(1, 2, 3);
    camera.target = Vec3(1, 0, -1);
    camera.fov_y_degrees = 50;
    const PinholeCamera c = PinholeCamera::at_time(camera, 0.0f, 200, 100);
    REQUIRE(glm::length(c.direction(100, 50) - c.forward) < 1e-6f);
    const float half_fov = glm::radians(25.0f);
    REQUIRE(std::acos(glm::dot(c.direction(100, 0), c.forward)) == Approx(half_fov).epsilon(1e-5));
    REQUIRE(std::acos(glm::dot(c.direction(100, 100), c.forward)) == Approx(half_fov).epsilon(1e-5));
    // Row 0 is the top: its ray points further up than the bottom row's.
    REQUIRE(c.direction(100, 0).y > c.direction(100, 100).y);
    // Square pixels: the horizontal half-extent is aspect × the vertical one.
    const float tan_x = std::tan(std::acos(glm::dot(c.direction(200, 50), c.forward)));
    REQUIRE(tan_x == Approx(2.0f * std::tan(half_fov)).epsilon(1e-5));
    REQUIRE(glm::dot(glm::cross(c.right, c.up), -c.forward) == Approx(1.0f));  // right-handed
}

TEST_CASE("Per-vertex colours are interpolated exactly and coverage goes to alpha", "[trace][image]") {
    Scene scene = test::make_scene("image");
    test::add_part(scene, test::make_plane(2.0f, 5));
    scene.camera.position = Vec3(0.3f, 3.0f, 2.0f);
    scene.camera.target = Vec3(0.0f, 0.0f, 0.2f);
    scene.camera.fov_y_degrees = 45;
    const PosedScene posed(scene);
    // A colour linear in position: barycentric interpolation reproduces it exactly.
    auto field = [](Vec3 p) { return Color(1.0f + p.x, 2.0f - p.z, 0.5f + 0.25f * p.x + 0.5f * p.z); };
    VertexColors colors;
    colors.scene_name = scene.name;
    colors.add_part("plane", scene.parts[0].mesh.vertex_count());
    for (size_t v = 0; v < colors.parts[0].size(); ++v) colors.parts[0][v] = field(scene.parts[0].mesh.positions[v]);

    const PinholeCamera camera = PinholeCamera::at_time(scene.camera, 0.0f, 64, 48);
    const Image image = form_image(posed, camera, colors);
    REQUIRE(image.channels == 4);
    int covered = 0, empty = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const Vec3 dir = camera.direction(x + 0.5f, y + 0.5f);
            const RayHit hit = posed.rays().intersect(camera.eye, dir);
            const float* px = image.at(x, y);
            if (!hit.hit) {
                ++empty;
                REQUIRE(px[3] == 0.0f);
                REQUIRE(px[0] == 0.0f);
                continue;
            }
            ++covered;
            REQUIRE(px[3] == 1.0f);
            const Color expected = field(camera.eye + hit.t * dir);
            REQUIRE(px[0] == Approx(expected.r).margin(1e-4));
            REQUIRE(px[1] == Approx(expected.g).margin(1e-4));
            REQUIRE(px[2] == Approx(expected.b).margin(1e-4));
        }
    REQUIRE(covered > 100);
    REQUIRE(empty > 100);

    // 4×4 samples: edge pixels are partly covered, colour premultiplied by coverage.
    ImageFormationOptions supersampled;
    supersampled.samples_per_side = 4;
    const Image smooth = form_image(posed, camera, colors, supersampled);
    int partial = 0;
    for (int y = 0; y < smooth.height; ++y)
        for (int x = 0; x < smooth.width; ++x) {
            const float alpha = smooth.at(x, y)[3];
            if (alpha > 0.0f && alpha < 1.0f) ++partial;
            REQUIRE(smooth.at(x, y)[1] <= alpha * 3.01f);  // green ≤ 3 where fully covered
        }
    REQUIRE(partial > 10);

    // An opaque background fills the uncovered samples.
    ImageFormationOptions opaque;
    opaque.opaque_background = true;
    opaque.background = Color(0.25f);
    const Image filled = form_image(posed, camera, colors, opaque);
    REQUIRE(filled.at(0, 0)[3] == 1.0f);

    VertexColors wrong = colors;
    wrong.parts[0].pop_back();
    REQUIRE_THROWS_AS(form_image(posed, camera, wrong), Error);
}
