// glTF metallic-roughness materials and base colour textures end to end: a
// scene written with tinygltf's writer as an exporter writes it (embedded
// PNG, three materials), loaded back, rendered by the CPU RSL renderer and
// compared with the Embree truth, per vertex and per pixel.
#include <catch2/catch.hpp>

#include "src/formats/scene_file.h"
#include "src/lightfit/scene_lights.h"
#include "tools/assets/model.h"
#include "tools/assets/pbr_scene.h"
#include "src/image/error_metrics.h"
#include "src/image/image_formation.h"
#include "src/render/cpu_renderer.h"
#include "src/trace/ground_truth.h"
#include "tests/render/render_test_scenes.h"
#include "tests/test_support.h"

namespace rsl {
namespace {

using assets::gltf_pbr_material;

// The scene written to `path` as a .glb: a textured rough ground, a gold
// metal ball, a glossy white dielectric ball.
void write_pbr_glb(const std::filesystem::path& path) {
    assets::GeneratedModel model;
    Scene& s = model.scene;
    MaterialDesc ground = gltf_pbr_material("ground", Color(1.0f), 0.0f, 0.7f);
    ground.base_color_texture = assets::make_tile_texture(4, 4);
    s.materials = {ground, gltf_pbr_material("gold", Color(1.0f, 0.78f, 0.34f), 1.0f, 0.35f),
                   gltf_pbr_material("plastic", Color(0.9f), 0.0f, 0.3f)};
    TriangleMesh plane = test::make_plane(3.0f, 24, "ground");
    for (const Vec3& p : plane.positions) plane.texcoords.emplace_back((p.x / 3.0f + 0.5f) * 2, (p.z / 3.0f + 0.5f) * 2);
    model.add_node("ground", -1, Vec3(0), plane);
    model.add_node("gold", -1, Vec3(-0.45f, 0.4f, 0), test::make_icosphere(0.38f, 3, "gold"));
    model.add_node("plastic", -1, Vec3(0.45f, 0.4f, 0.1f), test::make_icosphere(0.38f, 3, "plastic"));
    for (size_t p = 0; p < s.parts.size(); ++p) s.parts[p].material = int(p);
    for (Part& part : s.parts) validate_and_complete(part.mesh, path);
    assets::write_glb(path, model);
}

TEST_CASE("glTF materials and an embedded base colour texture load as gltf_pbr", "[render][pbr]") {
    // The gallery's scene, written by tinygltf's writer and read back.
    const assets::GeneratedModel model = assets::make_pbr_showcase();
    const auto path = test::scratch_dir("pbr_load") / "pbr.glb";
    assets::write_glb(path, model);
    const Scene scene = load_scene(path);
    REQUIRE(scene.parts.size() == model.scene.parts.size());
    int textured = 0;
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const MaterialDesc& loaded = scene.materials[size_t(scene.parts[p].material)];
        const MaterialDesc& written = model.scene.materials[size_t(model.scene.parts[p].material)];
        INFO("part " << scene.parts[p].name);
        CHECK(loaded.name == written.name);
        CHECK(loaded.model == "gltf_pbr");
        CHECK(loaded.params == written.params);
        CHECK(bool(loaded.base_color_texture) == bool(written.base_color_texture));
        CHECK(scene.parts[p].mesh.texcoords == model.scene.parts[p].mesh.texcoords);
        if (!loaded.base_color_texture) continue;
        ++textured;
        const Image& a = loaded.base_color_texture->image;
        const Image& b = written.base_color_texture->image;
        REQUIRE(a.width == b.width);
        REQUIRE(a.height == b.height);
        // sRGB 8-bit round trip: within half a code value (< 0.004 in linear below 1).
        for (size_t i = 0; i < a.pixels.size(); ++i) REQUIRE(a.pixels[i] == Approx(b.pixels[i]).margin(0.004));
        CHECK(loaded.base_color_texture->wrap_s == TextureWrap::Repeat);
    }
    CHECK(textured == 1);
    // Materials are shared by every part that uses them, and tables by equal parameters.
    const MaterialLibrary library = MaterialLibrary::from_scene(scene);
    // The built-in default (unused), the 5 glTF materials, the textured one's second lobe.
    CHECK(library.distinct_table_count() == 1 + 5 + 1);
}

TEST_CASE("textures: bilinear between texel centers, the three wrap modes", "[render][pbr]") {
    Texture t;
    t.image = Image(2, 1, 3);
    t.image.set_rgb(0, 0, Color(0));
    t.image.set_rgb(1, 0, Color(1));
    CHECK(t.sample(Vec2(0.25f, 0.5f)).r == Approx(0.0f).margin(1e-6));
    CHECK(t.sample(Vec2(0.5f, 0.5f)).r == Approx(0.5f));
    CHECK(t.sample(Vec2(0.75f, 0.5f)).r == Approx(1.0f));
    CHECK(t.sample(Vec2(1.0f, 0.5f)).r == Approx(0.5f));   // repeat: halfway back to texel 0
    CHECK(t.sample(Vec2(3.75f, 7.5f)).r == Approx(1.0f));  // repeat far out
    t.wrap_s = TextureWrap::ClampToEdge;
    CHECK(t.sample(Vec2(1.0f, 0.5f)).r == Approx(1.0f));
    CHECK(t.sample(Vec2(-2.0f, 0.5f)).r == Approx(0.0f).margin(1e-6));
    t.wrap_s = TextureWrap::MirroredRepeat;
    CHECK(t.sample(Vec2(1.25f, 0.5f)).r == Approx(1.0f));  // mirrored: texel 1 again
    CHECK(t.sample(Vec2(1.75f, 0.5f)).r == Approx(0.0f).margin(1e-6));
}

TEST_CASE("gltf_pbr parts with a base colour texture: RSL renderer vs ground truth", "[render][pbr][accuracy]") {
    const auto path = test::scratch_dir("pbr_render") / "pbr.glb";
    write_pbr_glb(path);
    Scene scene = load_scene(path);
    scene.camera.position = Vec3(0.3f, 1.6f, 2.6f);
    scene.camera.target = Vec3(0, 0.3f, 0);
    scene.precompute = test::small_accuracy_precompute();
    const CubeMap environment = test::sky_with_sun(16);

    const GroundTruth truth(scene, environment, 0.0f);
    const VertexColors truth_vertices = truth.shade_vertices();
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    CpuRenderer renderer(scene, fit_environment_lights(environment, 30), fields, RenderOptions{});
    const VertexColors colors = renderer.shade();
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        CHECK(colors.layered(p) == (scene.parts[p].name == "ground"));
        CHECK(truth_vertices.layered(p) == colors.layered(p));
    }
    const VertexErrorReport vertices = compare_vertex_colors(colors, truth_vertices);
    for (size_t p = 0; p < scene.parts.size(); ++p)
        INFO(vertices.part_names[p] << ": relative L2 " << vertices.parts[p].relative_l2());
    INFO("all vertices: relative L2 " << vertices.total.relative_l2());
    CHECK(vertices.total.relative_l2() < 0.08);
    // The specular layer is no small part of the textured ground's light.
    double diffuse = 0, specular = 0;
    for (size_t v = 0; v < colors.parts[0].size(); ++v)
        diffuse += luminance(truth_vertices.parts[0][v]), specular += luminance(truth_vertices.specular[0][v]);
    INFO("ground: diffuse " << diffuse << " specular " << specular);
    CHECK(specular > 0.01 * diffuse);

    // Per pixel: the truth samples the texture at every primary hit; the RSL
    // image multiplies the interpolated diffuse sum by the same texture.
    const PinholeCamera camera = PinholeCamera::at_time(scene.camera, 0.0f, 96, 72);
    const Image truth_image = trace_image(truth.posed(), camera, {}, [&](const RayHit& hit, const Vec3& dir) {
        return truth.shade_hit(hit, dir);
    });
    const Image rsl_image = form_image(truth.posed(), camera, colors);
    const Image flat_image = form_image(truth.posed(), camera, colors.at_unit_texture());
    const double error = compare_images(rsl_image, truth_image).pixels.relative_l2();
    const double untextured = compare_images(flat_image, truth_image).pixels.relative_l2();
    INFO("image relative L2 " << error << ", without the texture " << untextured);
    CHECK(error < 0.10);
    CHECK(error < 0.4 * untextured);
    // The truth's own vertex image with the texture is close to its per-pixel image.
    CHECK(compare_images(form_image(truth.posed(), camera, truth_vertices), truth_image).pixels.relative_l2() < 0.06);
}

}  // namespace
}  // namespace rsl
