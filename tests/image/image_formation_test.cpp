// Image formation: the pinhole camera's geometry, exact interpolation of
// per-vertex colours, coverage in alpha, refusal of mismatched colours, and
// the tiles of ray packets against one ray at a time.
#include <atomic>
#include <random>

#include <catch2/catch.hpp>

#include "src/core/error.h"
#include "src/image/image_formation.h"
#include "tests/trace/trace_test_scenes.h"
#include "tests/random_cases.h"

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

namespace {

// A plane under three spheres posed by their rest transforms (several
// instances), seen so that the top of the image is background.
Scene packet_test_scene() {
    Scene scene = test::make_scene("packets");
    test::add_part(scene, test::make_plane(4.0f, 6));
    Transform a, b, c;
    a.translation = Vec3(-0.8f, 0.5f, 0.2f);
    b.translation = Vec3(0.7f, 0.35f, -0.4f);
    b.rotation = glm::angleAxis(0.7f, glm::normalize(Vec3(1, 2, 0.5f)));
    b.scale = Vec3(1.3f, 0.8f, 1.0f);
    c.translation = Vec3(0.1f, 0.9f, 0.9f);
    test::add_part(scene, test::make_icosphere(0.5f, 2, "a"), a);
    test::add_part(scene, test::make_icosphere(0.45f, 3, "b"), b);
    test::add_part(scene, test::make_icosphere(0.25f, 1, "c"), c);
    scene.camera.position = Vec3(0.4f, 1.3f, 3.6f);
    scene.camera.target = Vec3(0.0f, 0.45f, 0.0f);
    scene.camera.fov_y_degrees = 50;
    return scene;
}

}  // namespace

TEST_CASE("Tiles of ray packets give the image of one ray at a time: same hits, same sums", "[trace][image]") {
    const Scene scene = packet_test_scene();
    const PosedScene posed(scene);
    VertexColors colors;
    colors.scene_name = scene.name;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> uni(0, 1);
    for (const Part& part : scene.parts) {
        colors.add_part(part.name, part.mesh.vertex_count());
        for (Color& c : colors.parts.back()) c = test::random_vec3(uni, rng);
    }
    // The hit's identity as a colour: any other hit (or a miss) shows; sums of
    // small integers are exact, so the images must be equal bit for bit.
    auto identity = [](const RayHit& hit, const Vec3&) {
        return Color(float(hit.instance + 1), float(hit.triangle), 1.0f);
    };
    // Sizes that are not multiples of the tiles (8, 4 or 2 pixels) or packets.
    for (const auto& [width, height] : {std::pair{37, 29}, std::pair{9, 5}, std::pair{1, 1}, std::pair{64, 48}})
        for (int samples : {1, 2, 3}) {
            INFO(width << "x" << height << ", " << samples << "x" << samples << " samples per pixel");
            const PinholeCamera camera = PinholeCamera::at_time(scene.camera, 0.0f, width, height);
            ImageFormationOptions options;
            options.samples_per_side = samples;
            std::atomic<int> bad_normals{0};
            std::atomic<size_t> last_done{0}, last_total{0};
            const Image hits = trace_image(posed, camera, options, [&](const RayHit& hit, const Vec3& dir) {
                // trace_image's shaders get the hit's geometric normal.
                if (std::abs(glm::length(hit.geometric_normal) - 1.0f) > 1e-5f) ++bad_normals;
                return identity(hit, dir);
            }, [&](size_t done, size_t total) {
                last_done = std::max(last_done.load(), done);
                last_total = total;
            });
            REQUIRE(bad_normals == 0);
            REQUIRE(last_done == size_t(width) * height);
            REQUIRE(last_total == size_t(width) * height);
            const Image expected_hits = trace_image_one_ray_at_a_time(posed, camera, options, identity);
            REQUIRE(hits.pixels == expected_hits.pixels);

            // Interpolated vertex colours: the same hits, so the same colours
            // up to the rounding of the packet kernels' barycentrics.
            const Image image = form_image(posed, camera, colors, options);
            const Image expected = trace_image_one_ray_at_a_time(posed, camera, options, [&](const RayHit& hit, const Vec3&) {
                return interpolate_vertex_colors(scene, colors, hit);
            });
            int covered = 0, empty = 0;
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) {
                    const float* got = image.at(x, y);
                    const float* want = expected.at(x, y);
                    REQUIRE(got[3] == want[3]);
                    for (int c = 0; c < 3; ++c) REQUIRE(got[c] == Approx(want[c]).margin(1e-5));
                    covered += want[3] == 1.0f;
                    empty += want[3] == 0.0f;
                }
            if (width * height > 100) {  // the scene fills part of the image
                REQUIRE(covered > width * height / 4);
                REQUIRE(empty > width * height / 20);
            }
        }

    // An opaque background fills the uncovered samples, also in the tiles.
    ImageFormationOptions opaque;
    opaque.samples_per_side = 2;
    opaque.opaque_background = true;
    opaque.background = Color(0.25f, 0.5f, 2.0f);
    const PinholeCamera camera = PinholeCamera::at_time(scene.camera, 0.0f, 23, 17);
    REQUIRE(trace_image(posed, camera, opaque, identity).pixels ==
            trace_image_one_ray_at_a_time(posed, camera, opaque, identity).pixels);
}

TEST_CASE("the environment fills the uncovered share of each pixel, seen through the camera and turned to the map",
          "[frame][image][background]") {
    // Each cube face a colour of its own, by the dominant axis of its texels' directions.
    const auto face_color = [](const Vec3& d) {
        const Vec3 a = glm::abs(d);
        if (a.x >= a.y && a.x >= a.z) return d.x > 0 ? Color(1, 0, 0) : Color(0, 1, 0);
        if (a.y >= a.z) return d.y > 0 ? Color(0, 0, 1) : Color(2, 2, 0);
        return d.z > 0 ? Color(0, 3, 3) : Color(4, 0, 4);
    };
    CubeMap map(4);
    for (int i = 0; i < 6 * 4 * 4; ++i) map.radiance(i) = face_color(map.texel_direction(i));

    Camera up;  // looking straight up, 20° field of view: every ray lies within the +y face
    up.position = Vec3(0);
    up.target = Vec3(0, 1, 0);
    up.up = Vec3(0, 0, -1);
    up.fov_y_degrees = 20;
    const PinholeCamera camera = PinholeCamera::at_time(up, 0.0f, 6, 4);
    Image image(6, 4, 4);
    float* partly = image.at(2, 1);  // a pixel a part covers by a quarter (premultiplied colour)
    partly[0] = 0.1f;
    partly[1] = 0.2f;
    partly[2] = 0.3f;
    partly[3] = 0.25f;
    for (const bool turned : {false, true}) {
        INFO("turned " << turned);
        Image filled = image;
        // Turned by 180° about x, the camera's +y sees the map's −y face.
        const Mat3 to_map = turned ? Mat3(1, 0, 0, 0, -1, 0, 0, 0, -1) : Mat3(1.0f);
        fill_environment_background(filled, camera, 3, map, to_map);
        const Color sky = turned ? Color(2, 2, 0) : Color(0, 0, 1);
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 6; ++x) {
                const Color expected = x == 2 && y == 1 ? Color(0.1f, 0.2f, 0.3f) + 0.75f * sky : sky;
                INFO(x << ", " << y);
                CHECK(filled.rgb(x, y).r == Approx(expected.r));
                CHECK(filled.rgb(x, y).g == Approx(expected.g));
                CHECK(filled.rgb(x, y).b == Approx(expected.b));
                CHECK(filled.at(x, y)[3] == 1.0f);
            }
    }
}
