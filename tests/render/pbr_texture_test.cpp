// Materials whose roughness and metallic vary over a surface (a glTF
// metallicRoughnessTexture, src/brdf/pbr_basis.h) in the CPU renderer:
// against the same material without variation, against the truth that reads
// the same texture, per vertex and per pixel; and through a .glb.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "src/brdf/pbr_basis.h"
#include "src/formats/scene_file.h"
#include "src/image/error_metrics.h"
#include "src/image/image_formation.h"
#include "src/lightfit/scene_lights.h"
#include "src/render/cpu_renderer.h"
#include "src/trace/ground_truth.h"
#include "tests/render/render_test_scenes.h"
#include "tests/test_support.h"
#include "tools/assets/model.h"
#include "tools/assets/pbr_scene.h"

namespace rsl {
namespace {

// A w×h texture of G (roughness) and B (metallic) from f(i, j).
template <typename F>
std::shared_ptr<Texture> metallic_roughness(int w, int h, F&& f, TextureFilter filter = TextureFilter::Bilinear) {
    auto t = std::make_shared<Texture>();
    t->name = "metallic_roughness";
    t->filter = filter;
    t->image = Image(w, h, 3);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const Vec2 gb = f(i, j);
            t->image.set_rgb(i, j, Color(1.0f, gb.x, gb.y));
        }
    return t;
}

// Spherical texture coordinates of a mesh around the origin.
void spherical_texcoords(TriangleMesh& mesh) {
    mesh.texcoords.clear();
    for (const Vec3& p : mesh.positions) {
        const Vec3 d = glm::normalize(p);
        mesh.texcoords.emplace_back(0.5f + std::atan2(d.z, d.x) / (2 * std::numbers::pi_v<float>),
                                    std::acos(std::clamp(d.y, -1.0f, 1.0f)) / std::numbers::pi_v<float>);
    }
}

// A ball over a ground, both of `material` (index 1); the camera sees the
// sun's highlight on the ground.
Scene ball_over_ground(const MaterialDesc& material) {
    Scene scene = test::make_scene("pbr_texture", Color(0.7f));
    scene.materials.push_back(material);
    TriangleMesh ground = test::make_plane(4.0f, 24, "ground");
    ground.texcoords.clear();
    for (const Vec3& p : ground.positions) ground.texcoords.emplace_back(p.x / 4.0f + 0.5f, p.z / 4.0f + 0.5f);
    test::add_part(scene, ground, {}, 1);
    TriangleMesh ball = test::make_icosphere(0.5f, 3, "ball");
    spherical_texcoords(ball);
    Transform lift;
    lift.translation = Vec3(0.0f, 0.6f, 0.3f);
    test::add_part(scene, ball, lift, 1);
    scene.camera.position = Vec3(0.0f, 2.5f, -3.0f);
    scene.camera.target = Vec3(0.0f, 0.3f, 0.0f);
    scene.camera.width = 96, scene.camera.height = 72;
    scene.precompute = test::small_accuracy_precompute();
    return scene;
}

VertexColors render(const Scene& scene, const RslSet& lights, const PartFields& fields) {
    CpuRenderer renderer(scene, lights, fields, RenderOptions{});
    return renderer.shade();
}

TEST_CASE("A uniform metallic-roughness texture renders as the material with those values", "[render][pbr_texture]") {
    // Roughness 0.5 · 0.6 = 0.3 (a basis level) and metallic 0.5 (between the
    // ends: the blend is exact in metallic), with and without a base colour texture.
    const CubeMap environment = test::sky_with_sun(16);
    const RslSet lights = fit_environment_lights(environment, 30);
    for (const bool layered : {false, true}) {
        MaterialDesc plain = assets::gltf_pbr_material("plain", Color(0.9f, 0.6f, 0.3f), 0.5f, 0.3f);
        if (layered) plain.base_color_texture = assets::make_tile_texture(4, 4);
        MaterialDesc textured = plain;
        textured.params["roughness"] = {0.5f};
        textured.params["metallic"] = {1.0f};
        textured.metallic_roughness_texture = metallic_roughness(2, 2, [](int, int) { return Vec2(0.6f, 0.5f); });
        const Scene a = ball_over_ground(plain), b = ball_over_ground(textured);
        const PartFields fields = bake_part_fields(a, FieldBakeOptions{});
        const VertexColors ca = render(a, lights, fields), cb = render(b, lights, fields);
        REQUIRE(cb.layered(0) == layered);
        double worst = 0;
        for (size_t p = 0; p < ca.parts.size(); ++p)
            for (size_t v = 0; v < ca.parts[p].size(); ++v) {
                const Color x = ca.parts[p][v] + (layered ? ca.specular[p][v] : Color(0));
                const Color y = cb.parts[p][v] + (layered ? cb.specular[p][v] : Color(0));
                worst = std::max(worst, double(glm::length(x - y) / std::max(glm::length(x), 1e-3f)));
            }
        INFO("layered " << layered << ": worst relative difference " << worst);
        CHECK(worst < 3e-3);
    }
}

TEST_CASE("A metallic-roughness texture: RSL renderer vs the truth that reads the same texture", "[render][pbr_texture][accuracy]") {
    // Texels of roughness 0.25–0.95, halfway between the basis levels (the
    // blend's worst case), metallic 0 or 1, read nearest: every vertex has
    // one of 16 (roughness, metallic) pairs. The reference is the same scene
    // rendered with each pair as an untextured material (its own table),
    // each vertex taking the render of its pair: the texture's own cost.
    const auto texels = metallic_roughness(8, 8, [](int i, int j) {
        return Vec2(0.25f + 0.1f * float((i + j) % 8), float((i / 2) % 2));
    }, TextureFilter::Nearest);
    const Color base(0.95f, 0.75f, 0.45f);
    MaterialDesc textured = assets::gltf_pbr_material("texels", base, 1.0f, 1.0f);
    textured.metallic_roughness_texture = texels;
    const CubeMap environment = test::sky_with_sun(16);
    const RslSet lights = fit_environment_lights(environment, 30);
    const Scene scene = ball_over_ground(textured);
    const GroundTruth truth(scene, environment, 0.0f);
    const VertexColors truth_colors = truth.shade_vertices();
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    CpuRenderer renderer(scene, lights, fields, RenderOptions{});
    renderer.keep_image_terms(true);
    const VertexColors colors = renderer.shade();

    VertexColors untextured = colors;
    std::vector<std::vector<PbrPoint>> points;
    for (const Part& part : scene.parts) points.push_back(pbr_points(textured, part.mesh));
    int pairs = 0;
    for (int r = 0; r < 8; ++r)
        for (int m = 0; m < 2; ++m) {
            const float roughness = 0.25f + 0.1f * float(r), metallic = float(m);
            const Scene uniform_scene = ball_over_ground(assets::gltf_pbr_material("uniform", base, metallic, roughness));
            const VertexColors uniform = render(uniform_scene, lights, fields);
            for (size_t p = 0; p < points.size(); ++p)
                for (size_t v = 0; v < points[p].size(); ++v)
                    if (points[p][v].roughness == roughness && points[p][v].metallic == metallic)
                        untextured.parts[p][v] = uniform.parts[p][v], ++pairs;
        }
    size_t vertices = 0;
    for (const auto& part : points) vertices += part.size();
    REQUIRE(size_t(pairs) == vertices);  // every vertex has one of the pairs
    const double error = compare_vertex_colors(colors, truth_colors).total.relative_l2();
    const double reference = compare_vertex_colors(untextured, truth_colors).total.relative_l2();
    // Per pixel: roughness and metallic from the texture at each pixel.
    const PinholeCamera camera = PinholeCamera::at_time(scene.camera, 0.0f, scene.camera.width, scene.camera.height);
    const double pixels = compare_images(form_image(truth.posed(), camera, colors, {},
                                                    renderer.pixel_shading(colors, truth.posed())),
                                         test::per_pixel_truth_image(truth, camera))
                              .pixels.relative_l2();
    INFO("vertices: textured " << error << ", untextured materials " << reference << "; pixels " << pixels);
    WARN("vertices: textured " << error << ", untextured materials " << reference << "; pixels " << pixels);
    CHECK(error <= 1.2 * reference);
    CHECK(pixels < 0.06);
}

TEST_CASE("A metallic-roughness texture through a .glb: linear values, nearest filter, one texcoord set",
          "[render][pbr_texture]") {
    assets::GeneratedModel model;
    MaterialDesc m = assets::gltf_pbr_material("checker", Color(0.8f), 1.0f, 1.0f);
    m.metallic_roughness_texture = metallic_roughness(
        4, 4, [](int i, int j) { return Vec2(float(i) / 3.0f, float(j) / 3.0f); }, TextureFilter::Nearest);
    model.scene.materials = {m};
    TriangleMesh plane = test::make_plane(2.0f, 4, "ground");
    for (const Vec3& p : plane.positions) plane.texcoords.emplace_back(p.x / 2.0f + 0.5f, p.z / 2.0f + 0.5f);
    model.add_node("ground", -1, Vec3(0), plane);
    model.scene.parts[0].material = 0;
    const auto path = test::scratch_dir("pbr_texture_glb") / "checker.glb";
    validate_and_complete(model.scene.parts[0].mesh, path);
    assets::write_glb(path, model);
    const Scene scene = load_scene(path);
    const MaterialDesc& loaded = scene.materials[size_t(scene.parts[0].material)];
    REQUIRE(loaded.metallic_roughness_texture);
    CHECK(varies_per_point(loaded));
    CHECK(loaded.metallic_roughness_texture->filter == TextureFilter::Nearest);
    const Image& a = loaded.metallic_roughness_texture->image;
    const Image& b = m.metallic_roughness_texture->image;
    REQUIRE(a.pixels.size() == b.pixels.size());
    // Linear 8-bit (no sRGB curve): within half a code value.
    for (size_t i = 0; i < a.pixels.size(); ++i) REQUIRE(a.pixels[i] == Approx(b.pixels[i]).margin(0.5 / 255));
}

}  // namespace
}  // namespace rsl
