#pragma once
// Helpers of the renderer tests: hand-made fields and small scenes.
#include <functional>
#include <memory>
#include <random>

#include "src/lightfit/scene_lights.h"
#include "tools/assets/pbr_scene.h"
#include "src/fields/svdf.h"
#include "src/lightfit/square_light.h"
#include "src/image/image_formation.h"
#include "src/render/part_fields.h"
#include "src/render/cpu_renderer.h"
#include "src/trace/ground_truth.h"
#include "tests/trace/trace_test_scenes.h"
#include "tests/random_cases.h"

namespace rsl::test {

// An SVDF whose every table is the constant distance `distance`: the visible
// fraction of a square of half-edge h is then clamp(½ + distance / (2h)).
inline std::shared_ptr<const Svdf> constant_svdf(int vertices, float distance, int resolution = 8) {
    auto svdf = std::make_shared<Svdf>();
    svdf->params.resolution = resolution;
    CpcaModel& model = svdf->model;
    model.dims = resolution * resolution;
    model.vectors = 0;
    model.clusters = 1;
    model.tables.assign(size_t(model.dims), distance);
    model.assignment.assign(size_t(vertices), 0);
    return svdf;
}

// A single RSL of center c (unit, world), half-diagonal r, radiance I.
inline RslSet single_rsl(const Vec3& center, float half_diagonal, const Color& radiance) {
    RslSet set;
    RotatableSquareLight light;
    light.center = glm::normalize(center);
    light.half_diagonal = half_diagonal;
    light.radiance = radiance;
    set.lights.push_back(light);
    return set;
}

// Average of cos θ = 1 − |p|² (the equal-area map) over the plane square
// [c ± h]², when it lies inside the unit disk: 1 − |c|² − 2h²/3.
inline float square_average_cosine(const Vec2& c, float h) { return 1.0f - glm::dot(c, c) - 2.0f * h * h / 3.0f; }

// `count` environment RSLs in random directions, half-diagonals uniform in
// [min_half_diagonal, 0.5], radiance up to 2 per channel (fixed seed).
inline RslSet random_rsls(int count, uint32_t seed, float min_half_diagonal = 0.05f) {
    std::mt19937 rng{seed};
    std::normal_distribution<float> normal;
    std::uniform_real_distribution<float> uniform(min_half_diagonal, 0.5f);
    RslSet set;
    for (int i = 0; i < count; ++i) {
        RotatableSquareLight light;
        light.center = glm::normalize(test::random_vec3(normal, rng));
        light.half_diagonal = uniform(rng);
        light.radiance = Color(test::random_vec3(uniform, rng)) * 4.0f;
        set.lights.push_back(light);
    }
    return set;
}

// Dim blue sky above, dark ground below, a bright warm block high on +Z.
inline CubeMap sky_with_sun(int n) {
    CubeMap map(n);
    for (int k = 0; k < map.texel_count(); ++k) {
        const Vec3 d = map.texel_direction(k);
        map.radiance(k) = d.y > 0 ? Color(0.3f, 0.45f, 0.8f) * (0.5f + d.y) : Color(0.05f);
        if (d.y > 0.5f && d.z > 0.45f && std::abs(d.x) < 0.3f) map.radiance(k) = Color(8.0f, 7.0f, 5.0f);
    }
    return map;
}

// Field settings small enough to bake in a test yet fine enough for the
// renderer-vs-truth accuracy tests (32² SVDF, 8 shells of 16² × 32² VDTs).
inline PrecomputeSettings small_accuracy_precompute() {
    PrecomputeSettings pre;
    pre.svdf_resolution = 32, pre.svdf_clusters = 16, pre.svdf_vectors = 6, pre.svdf_supersampling = 2;
    pre.ovdf_shells = 8, pre.ovdf_cube_resolution = 16, pre.ovdf_vdt_resolution = 32, pre.ovdf_vectors = 6;
    return pre;
}

// The per-pixel truth's image (every pixel's hit point shaded exactly).
inline Image per_pixel_truth_image(const GroundTruth& truth, const PinholeCamera& camera) {
    return trace_image(truth.posed(), camera, {}, [&](const RayHit& hit, const Vec3& direction) {
        return truth.shade_hit(hit, direction);
    });
}

// A per-pixel test's setting: the scene at t = 0 under sky_with_sun(16),
// its baked fields, 30 RSLs, the truth, the scene camera and the truth's
// image (the pixel tests of the CPU and the GPU).
struct PixelTestSetting {
    Scene scene;
    CubeMap environment = sky_with_sun(16);
    PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    GroundTruth truth{scene, environment, 0.0f};
    PinholeCamera camera = PinholeCamera::at_time(scene.camera, 0.0f, scene.camera.width, scene.camera.height);
    Image reference = per_pixel_truth_image(truth, camera);
    RslSet lights = fit_environment_lights(environment, 30);
    explicit PixelTestSetting(Scene s) : scene(std::move(s)) {}
};

// A box over a ground of 1 m cells, the camera looking down at its shadow
// under sky_with_sun (the sun high on +Z): the per-pixel shadow tests'
// scene (tests/render/pixel_shading_test.cpp, tests/gl/gl_pixel_pass_test.cpp).
// `textured`: the ground is a glTF material with a tiled base colour
// texture (a layered part: diffuse × texture + specular per pixel).
inline Scene box_over_coarse_ground(bool textured = false) {
    Scene scene = make_scene("pixel_shadows", Color(0.7f));
    TriangleMesh ground = make_plane(6.0f, 6, "ground");  // 1 m cells
    int ground_material = 0;
    if (textured) {
        MaterialDesc tiles = assets::gltf_pbr_material("tiles", Color(0.9f), 0.0f, 0.6f);
        tiles.base_color_texture = assets::make_tile_texture(4, 4);
        scene.materials.push_back(tiles);
        ground_material = 1;
        ground.texcoords.clear();
        for (const Vec3& p : ground.positions) ground.texcoords.emplace_back(p.x / 6.0f + 0.5f, p.z / 6.0f + 0.5f);
    }
    add_part(scene, ground, {}, ground_material);
    Transform lift;
    lift.translation = Vec3(0.2f, 0.6f, -0.3f);
    add_part(scene, make_flat_box(Vec3(0.35f, 0.3f, 0.25f), 4, "box"), lift);
    scene.camera.position = Vec3(0.0f, 4.5f, -3.5f);  // looking down at the shadow (the sun is high on +Z)
    scene.camera.target = Vec3(0.2f, 0.0f, -1.0f);
    scene.camera.width = 160, scene.camera.height = 120;
    scene.precompute = small_accuracy_precompute();
    return scene;
}

// A coarse glossy ball (80 triangles) under sky_with_sun, seen with the sun
// behind it: its highlights and lit rim are narrower than its triangles
// (the per-pixel highlight tests, CPU and GPU). The ball is part 1: part 0,
// a small Lambert cube behind the camera and out of the ball's reach, puts
// the ball's vertices and indices after another part's.
inline Scene coarse_glossy_ball() {
    Scene scene = make_scene("pixel_rim", Color(0.7f));
    scene.materials.push_back(blinn_phong(0.4f, 0.4f, 30.0f));
    Transform behind;
    behind.translation = Vec3(0.0f, 0.0f, -8.0f);
    add_part(scene, make_flat_box(Vec3(0.05f), 1, "cube"), behind);
    add_part(scene, make_icosphere(0.5f, 1, "ball"), {}, 1);
    scene.camera.position = Vec3(0.0f, 0.6f, -2.5f);  // the sun (near (0, 0.7, 0.7)) behind the ball
    scene.camera.target = Vec3(0.0f);
    scene.camera.width = 120, scene.camera.height = 90;
    scene.precompute = small_accuracy_precompute();
    return scene;
}

// Relative L2 of `image` against `reference` over the pixels whose camera ray
// hits a triangle that `in_band` accepts; their count in *pixels.
inline double band_relative_l2(const GroundTruth& truth, const PinholeCamera& camera, const Image& image,
                               const Image& reference, const std::function<bool(const RayHit&)>& in_band,
                               int* pixels) {
    double error2 = 0, norm2 = 0;
    *pixels = 0;
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            const RayHit hit = truth.posed().rays().intersect(camera.eye, camera.direction(x + 0.5f, y + 0.5f));
            if (!hit.hit || !in_band(hit)) continue;
            ++*pixels;
            const Color d = image.rgb(x, y) - reference.rgb(x, y), r = reference.rgb(x, y);
            error2 += glm::dot(d, d), norm2 += glm::dot(r, r);
        }
    return norm2 > 0 ? std::sqrt(error2 / norm2) : 0.0;
}

// band_relative_l2's band: the triangles with a corner flagged in `vertex_flags`.
inline std::function<bool(const RayHit&)> triangles_touching(const TriangleMesh& mesh,
                                                            const std::vector<uint8_t>& vertex_flags) {
    return [&mesh, &vertex_flags](const RayHit& hit) {
        const uint32_t* corner = &mesh.indices[3 * size_t(hit.triangle)];
        return vertex_flags[corner[0]] || vertex_flags[corner[1]] || vertex_flags[corner[2]];
    };
}

// A glossy lens set into a body, one part as exporters often write one: an
// icosphere whose centre lies just in front of a flat box's front face, so
// that a band of its vertices lies inside the box, enclosed by the part itself
// (Svdf::enclosed_vertices), while the pixels of their triangles that the
// camera sees lie outside, lit by the sun (sky_with_sun, high on +Z). The
// lens is the robot's chest light in small (the per-pixel highlight tests,
// CPU and GPU).
inline Scene lens_in_body() {
    Scene scene = make_scene("pixel_lens", Color(0.7f));
    scene.materials.push_back(blinn_phong(0.4f, 0.4f, 30.0f));
    TriangleMesh body = make_flat_box(Vec3(0.4f, 0.3f, 0.15f), 4, "body");
    const TriangleMesh lens = make_icosphere(0.15f, 2, "lens");
    const Vec3 lens_center(0.0f, 0.0f, 0.17f);
    const uint32_t first = uint32_t(body.positions.size());
    for (size_t v = 0; v < lens.positions.size(); ++v) {
        body.positions.push_back(lens.positions[v] + lens_center);
        body.normals.push_back(lens.normals[v]);
        body.tangents.push_back(lens.tangents[v]);
        body.texcoords.emplace_back(0.0f);
    }
    for (const uint32_t index : lens.indices) body.indices.push_back(first + index);
    body.name = "light";
    add_part(scene, std::move(body), {}, 1);
    scene.camera.position = Vec3(0.1f, 0.45f, 1.1f);  // in front, above: the lens's top rim, lit by the sun
    scene.camera.target = Vec3(0.0f, 0.05f, 0.17f);
    scene.camera.width = 120, scene.camera.height = 90;
    scene.precompute = small_accuracy_precompute();
    return scene;
}

}  // namespace rsl::test
