// The GPU renderer against its reference, the CPU renderer: the same sum with
// the same tables, so the vertex colours agree to float rounding.
#include <catch2/catch.hpp>

#include <filesystem>

#include "src/formats/scene_file.h"
#include "src/lightfit/scene_lights.h"
#include "src/render/occluder_shape.h"
#include "src/formats/scene_environment.h"
#include "src/gl/gl_renderer.h"
#include "src/gl/gpu_layout.h"
#include "tools/assets/pbr_scene.h"
#include "src/render/cpu_renderer.h"
#include "tests/gl/gl_test_support.h"
#include "tests/trace/trace_test_scenes.h"
#include "src/shading/shapes.h"

namespace rsl {
namespace {

using test::add_part;
using test::make_icosphere;
using test::make_plane;
using test::make_scene;

// Tolerance per vertex (relative, see compare_colors): float arithmetic in a
// different order (GPU dot products, FMA, log/sqrt of the driver) moves a
// vertex by ~1e-6 relative; 1e-3 leaves room only for the rare vertex on a
// knife edge (a VDT or shell index at a texel boundary), counted separately.
constexpr double kTolerance = 1e-3;

// Ground (a glTF metallic-roughness material), a glossy sphere that moves,
// an anisotropic sphere, two sphere lights and a spot light carried by the
// moving sphere, small real fields.
Scene moving_scene() {
    Scene scene = make_scene("gl", Color(0.7f));
    scene.materials[0].model = "gltf_pbr";
    scene.materials[0].params = {{"base_color", {0.7f, 0.6f, 0.5f}}, {"metallic", {0.2f}}, {"roughness", {0.5f}}};
    scene.materials.push_back(test::blinn_phong(0.4f, 0.3f, 30.0f));
    MaterialDesc brushed;
    brushed.name = "brushed";
    brushed.model = "ward_anisotropic";
    brushed.params = {{"kd", {0.2f, 0.15f, 0.1f}}, {"ks", {0.3f, 0.3f, 0.3f}}, {"alpha_x", {0.1f}}, {"alpha_y", {0.3f}}};
    scene.materials.push_back(brushed);
    add_part(scene, make_plane(3.0f, 12, "ground"));
    Transform big, small;
    big.translation = Vec3(0, 0.45f, 0);
    small.translation = Vec3(0.55f, 0.25f, 0.2f);
    add_part(scene, make_icosphere(0.4f, 2, "big"), big, 1);
    add_part(scene, make_icosphere(0.2f, 2, "small"), small, 2);
    // The big sphere slides over the ground.
    Vec3Track path;
    path.times = {0.0f, 1.0f};
    path.values = {Vec3(0, 0.45f, 0), Vec3(-0.5f, 0.5f, 0.3f)};
    scene.nodes[scene.parts[1].node].translation = path;
    scene.camera.position = Vec3(1.2f, 1.6f, 2.5f);
    scene.camera.target = Vec3(0, 0.3f, 0);
    for (const Vec3 position : {Vec3(-0.6f, 1.2f, 0.4f), Vec3(0.8f, 0.5f, -0.3f)}) {
        LocalLight light;
        light.radius = 0.05f;
        light.power = Color(2.0f, 1.5f, 1.0f);
        light.position = position;
        scene.lights.push_back(light);
    }
    // A spot light on a node that rides on the sliding sphere, 1 above it,
    // pointing down and tilted (glTF's −Z), its cone edge across the ground.
    SceneNode holder;
    holder.name = "spot holder";
    holder.parent = scene.parts[1].node;
    holder.rest.translation = Vec3(0, 1.0f, 0);
    holder.rest.rotation = glm::angleAxis(glm::radians(-70.0f), Vec3(1, 0, 0));
    scene.nodes.push_back(holder);
    LocalLight spot;
    spot.radius = 0.05f;
    spot.power = Color(3.0f);
    spot.node = int(scene.nodes.size()) - 1;
    spot.spot = true;
    spot.inner_cone_radians = 0.3f;
    spot.outer_cone_radians = 0.6f;
    scene.lights.push_back(spot);
    PrecomputeSettings& pre = scene.precompute;
    pre.svdf_resolution = 16, pre.svdf_clusters = 8, pre.svdf_vectors = 4, pre.svdf_supersampling = 1;
    pre.ovdf_shells = 4, pre.ovdf_cube_resolution = 8, pre.ovdf_vdt_resolution = 16, pre.ovdf_vectors = 4;
    return scene;
}

// `discrete_taps`: the exact shapes' 21 taps per square (occluder_shape.h)
// are a discrete test, so a tap that falls on the horizon or on a shape's
// edge to float rounding may land on the other side on the GPU: one tap of
// one light, a few tenths of a percent of one vertex (measured: 1 vertex of
// 697 at 0.5%). Such scenes allow two such vertices.
// `l2_limit`: the relative L2 allowed where no tap is discrete.
void check_against_cpu(const Scene& scene, const EnvironmentLights& lights, const PartFields& fields,
                       const RenderOptions& options, const std::vector<float>& times, bool discrete_taps = false,
                       double l2_limit = 1e-5) {
    test::gl_context();
    CpuRenderer cpu(scene, lights, fields, options);
    gl::GlRenderer gpu(scene, lights, fields, options);
    for (const float t : times) {
        cpu.set_time(t);
        gpu.set_time(t);
        const VertexColors expected = cpu.shade();
        const VertexColors colors = gpu.shade();
        // Both layers of textured parts (their diffuse in `parts`, at unit texture).
        bool cpu_layered = false, gl_layered = false;
        for (size_t p = 0; p < scene.parts.size(); ++p)
            cpu_layered = cpu_layered || expected.layered(p), gl_layered = gl_layered || colors.layered(p);
        CHECK(gl_layered == cpu_layered);
        for (const bool specular : {false, true}) {
            if (specular && !cpu_layered) break;
            const test::ColorDifference d = test::compare_colors(colors, expected, kTolerance, specular);
            INFO("t = " << t << (specular ? " specular layer" : "") << ": relative L2 " << d.relative_l2
                        << ", max relative " << d.max_relative << ", " << d.over_tolerance << " of " << d.vertices
                        << " vertices over " << kTolerance << ", mean value " << d.mean_luminance);
            CHECK(d.mean_luminance > 1e-3);  // a lit scene: the comparison means something
            CHECK(d.relative_l2 < (discrete_taps ? 5e-4 : l2_limit));
            CHECK(d.over_tolerance <= d.vertices / 1000 + (discrete_taps ? 2 : 0));
        }
        CHECK(gpu.stats().occluder_pairs == cpu.stats().occluder_pairs);
        // The CPU's work, no more: the same block-level culling and the same
        // per-vertex tests, so the same lookups but for a test on a knife
        // edge of float rounding.
        const double cpu_lookups = double(cpu.stats().occluder_lookups);
        const double gpu_lookups = double(gpu.stats().occluder_lookups);
        INFO("occluder lookups: CPU " << cpu_lookups << ", GPU " << gpu_lookups);
        CHECK(std::abs(gpu_lookups - cpu_lookups) <= 1e-3 * cpu_lookups + 2.0);
    }
}

TEST_CASE("GL vertex colours equal the CPU renderer's (fields, local lights, iso and aniso BRDFs)", "[gl-renderer]") {
    const Scene scene = moving_scene();
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    check_against_cpu(scene, test::random_rsls(16, 3), fields, RenderOptions{}, {0.0f, 0.5f, 1.0f});
}

TEST_CASE("GL matches the CPU when the parts' fields have rows of different lengths", "[gl-renderer]") {
    // One stride for every field compiles the row loops with a constant
    // count (SVDF_STRIDE, OVDF_STRIDE); fields of 4 and 8 PCA vectors (2 and
    // 3 texels a row) mixed make the shader read each field's own.
    Scene scene = moving_scene();
    const PartFields four = bake_part_fields(scene, FieldBakeOptions{});
    scene.precompute.svdf_vectors = 8, scene.precompute.ovdf_vectors = 8;
    const PartFields eight = bake_part_fields(scene, FieldBakeOptions{});
    PartFields mixed = four;
    for (size_t p = 1; p < scene.parts.size(); p += 2) {
        mixed.self[p] = eight.self[p];
        mixed.occluder[p] = eight.occluder[p];
    }
    const gl::PackedGeometry uniform = gl::pack_geometry(scene, four), varied = gl::pack_geometry(scene, mixed);
    CHECK(uniform.svdf_stride == 2);
    CHECK(uniform.ovdf_stride == 2);
    CHECK(varied.svdf_stride == -1);
    CHECK(varied.ovdf_stride == -1);
    check_against_cpu(scene, test::random_rsls(16, 3), mixed, RenderOptions{}, {0.0f, 0.5f});
}

TEST_CASE("GL shades a textured part in two layers as the CPU does", "[gl-renderer]") {
    // The ground's gltf_pbr material gets a base colour texture: its colours
    // become a diffuse layer at unit texture and a specular layer, each from
    // its own table under the same visibility (both compared above).
    Scene scene = moving_scene();
    scene.materials[0].base_color_texture = assets::make_tile_texture(4, 4);
    TriangleMesh& ground = scene.parts[0].mesh;
    for (const Vec3& p : ground.positions) ground.texcoords.emplace_back(p.x / 3.0f + 0.5f, p.z / 3.0f + 0.5f);
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    test::gl_context();
    gl::GlRenderer gpu(scene, test::random_rsls(16, 3), fields, RenderOptions{});
    const VertexColors colors = gpu.shade();
    REQUIRE(colors.layered(0));  // the GL backend no longer refuses textured parts
    CHECK(!colors.layered(1));
    CHECK(colors.textures[0] == scene.materials[0].base_color_texture);
    check_against_cpu(scene, test::random_rsls(16, 3), fields, RenderOptions{}, {0.0f, 1.0f});
    // Without texture coordinates the part is refused, naming it.
    scene.parts[0].mesh.texcoords.clear();
    gl::GlRenderer bare(scene, test::random_rsls(8, 3), fields, RenderOptions{});
    CHECK_THROWS_WITH(bare.shade(), Catch::Contains("ground"));
}

TEST_CASE("GL adds emission as the CPU does: exactly its radiance at each vertex", "[gl-renderer]") {
    // A textured ground with an emissive texture (its emission in the
    // specular layer) and an evenly glowing glossy sphere.
    Scene scene = moving_scene();
    scene.materials[0].base_color_texture = assets::make_tile_texture(4, 4);
    TriangleMesh& ground = scene.parts[0].mesh;
    for (const Vec3& p : ground.positions) ground.texcoords.emplace_back(p.x / 3.0f + 0.5f, p.z / 3.0f + 0.5f);
    Scene glow = scene;
    glow.materials[0].emissive = Color(0.4f, 0.7f, 1.1f);
    glow.materials[0].emissive_texture = assets::make_tile_texture(2, 3);
    glow.materials[1].emissive = Color(0.3f, 0.1f, 0.05f);
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    const RslSet lights = test::random_rsls(16, 3);
    check_against_cpu(glow, lights, fields, RenderOptions{}, {0.0f, 1.0f});
    test::gl_context();
    gl::GlRenderer with(glow, lights, fields, RenderOptions{}), without(scene, lights, fields, RenderOptions{});
    const VertexColors a = with.shade(), b = without.shade();
    int emitting = 0;
    for (size_t p = 0; p < glow.parts.size(); ++p) {
        const MaterialDesc& m = glow.materials[size_t(glow.parts[p].material)];
        const TriangleMesh& mesh = glow.parts[p].mesh;
        for (size_t v = 0; v < mesh.vertex_count(); ++v) {
            // Written out here: the texture's bilinear sample at the vertex (Texture::sample, tested on its own).
            const Color expected = m.emissive_texture ? m.emissive * m.emissive_texture->sample(mesh.texcoords[v]) : m.emissive;
            const bool layered = a.layered(p);
            const Color total = layered ? a.specular[p][v] : a.parts[p][v];
            const Color added = total - (layered ? b.specular[p][v] : b.parts[p][v]);
            for (int c = 0; c < 3; ++c) {
                INFO("part " << p << " vertex " << v << " channel " << c);
                REQUIRE(std::abs(added[c] - expected[c]) <= 1e-6f * std::max(1.0f, total[c]));
            }
            emitting += expected != Color(0);
        }
    }
    CHECK(emitting > 100);
}

TEST_CASE("GL shades a material whose roughness and metallic vary per point as the CPU does", "[gl-renderer]") {
    // The ground's gltf_pbr material gets a metallic-roughness texture
    // (src/brdf/pbr_basis.h): roughness 0.15–0.95 and metallic 0–1 vary per
    // vertex, shaded from the basis tables; alone, then with a base colour
    // texture (two layers), then after an edit of its roughness factor.
    Scene scene = moving_scene();
    auto texture = std::make_shared<Texture>();
    texture->name = "metallic_roughness";
    texture->image = Image(4, 4, 3);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) texture->image.set_rgb(i, j, Color(1.0f, 0.15f + 0.25f * float(i), float(j) / 3.0f));
    scene.materials[0].params["roughness"] = {1.0f};
    scene.materials[0].params["metallic"] = {1.0f};
    scene.materials[0].metallic_roughness_texture = texture;
    TriangleMesh& ground = scene.parts[0].mesh;
    for (const Vec3& p : ground.positions) ground.texcoords.emplace_back(p.x / 3.0f + 0.5f, p.z / 3.0f + 0.5f);
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    check_against_cpu(scene, test::random_rsls(16, 3), fields, RenderOptions{}, {0.0f, 1.0f});
    scene.materials[0].base_color_texture = assets::make_tile_texture(4, 4);
    check_against_cpu(scene, test::random_rsls(16, 3), fields, RenderOptions{}, {0.5f});

    test::gl_context();
    const RslSet lights = test::random_rsls(8, 5);
    CpuRenderer cpu(scene, lights, fields, RenderOptions{});
    gl::GlRenderer gpu(scene, lights, fields, RenderOptions{});
    for (VertexRenderer* r : {static_cast<VertexRenderer*>(&cpu), static_cast<VertexRenderer*>(&gpu)})
        r->set_material_parameter(scene.materials[0].name, "roughness", {0.5f});
    for (const bool specular : {false, true}) {
        const test::ColorDifference d = test::compare_colors(gpu.shade(), cpu.shade(), kTolerance, specular);
        INFO("after the edit" << (specular ? ", specular layer" : "") << ": relative L2 " << d.relative_l2);
        CHECK(d.relative_l2 < 1e-5);
    }
}

TEST_CASE("GL matches the CPU with hundreds of parts (occluder lists, no part limit)", "[gl-renderer]") {
    // 200 small spheres on a ground, one shared field: far beyond the 32
    // parts that bit masks once allowed, with lists of varying length.
    Scene scene = make_scene("crowd", Color(0.6f));
    add_part(scene, make_plane(6.0f, 24, "ground"));
    const TriangleMesh ball = make_icosphere(0.1f, 1, "ball");
    for (int i = 0; i < 200; ++i) {
        Transform pose;
        // Turned and jittered: on an exact grid, directions between ball
        // vertices and neighbours' centres fall on cube-face edges, where the
        // CPU and the GPU may round to different faces.
        pose.translation = Vec3(0.3f * float(i % 20) - 2.85f + 0.013f * float(i % 7),
                                0.12f + 0.06f * float(i % 3), 0.3f * float(i / 20) - 1.35f + 0.011f * float(i % 5));
        pose.rotation = glm::angleAxis(0.37f * float(i), glm::normalize(Vec3(1, 2, 3)));
        add_part(scene, ball, pose);
    }
    scene.camera.position = Vec3(0, 4, 5);
    scene.precompute.ovdf_shells = 4, scene.precompute.ovdf_cube_resolution = 8;
    scene.precompute.ovdf_vdt_resolution = 16, scene.precompute.ovdf_vectors = 4, scene.precompute.ovdf_outer_radius = 4.0f;
    Scene two = make_scene("two", Color(0.6f));
    add_part(two, ball);
    add_part(two, ball);
    two.precompute = scene.precompute;
    FieldBakeOptions bake;
    bake.self_visibility = false;
    const PartFields ball_fields = bake_part_fields(two, bake);
    PartFields fields;
    fields.self.assign(scene.parts.size(), nullptr);
    fields.occluder.assign(scene.parts.size(), ball_fields.occluder[0]);
    // The ground gets the balls' field here, not its own: with exact shapes
    // its rectangle would be culled by a ball-sized bounding cone on the CPU
    // and not on the GPU. This test is about the lists (exact shapes off).
    RenderOptions lists_only;
    lists_only.exact_shapes = false;
    check_against_cpu(scene, test::random_rsls(12, 5), fields, lists_only, {0.0f});
    // The shared field goes up once: the tables of 200 instances are those of one.
    PartFields shared_two;
    shared_two.occluder.assign(2, ball_fields.occluder[0]);
    const gl::PackedGeometry many = gl::pack_geometry(scene, fields), one = gl::pack_geometry(two, shared_two);
    CHECK(many.ovdf_tables.size() == one.ovdf_tables.size());
    CHECK(many.ovdf_frames.size() == one.ovdf_frames.size());
}

TEST_CASE("GL matches the CPU with each visibility factor switched off", "[gl-renderer]") {
    const Scene scene = moving_scene();
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    const RslSet lights = test::random_rsls(8, 5);
    RenderOptions options;
    SECTION("no self-visibility") { options.self_visibility = false; }
    SECTION("no occluders") { options.occluders = false; }
    SECTION("no culling") { options.occluder_culling = false; }
    SECTION("the ground's OVDF, not its rectangle") { options.exact_shapes = false; }
    SECTION("local lights only") { options.environment = false; }
    SECTION("environment only") { options.local_lights = false; }
    check_against_cpu(scene, lights, fields, options, {0.25f});
}

// A box tumbling over the ground, a second box resting on the ground and a
// sphere just above that box: the ground's rectangle and both boxes shadow
// the others by shape (src/render/occluder_shape.h), including at the
// box-on-ground contact.
TEST_CASE("GL matches the CPU with occluders of exact shape (a ground, boxes, contacts)", "[gl-renderer]") {
    Scene scene = test::make_scene("shapes", Color(0.6f));
    add_part(scene, make_plane(4.0f, 16, "ground"));
    Transform resting, tumbling, ball;
    resting.translation = Vec3(0.3f, 0.3f, 0.0f);
    add_part(scene, test::make_flat_box(Vec3(0.4f, 0.3f, 0.35f), 4, "resting"), resting);
    tumbling.translation = Vec3(-0.6f, 0.8f, 0.2f);
    add_part(scene, test::make_flat_box(Vec3(0.25f, 0.15f, 0.2f), 3, "tumbling"), tumbling);
    ball.translation = Vec3(0.3f, 0.83f, 0.0f);
    add_part(scene, make_icosphere(0.2f, 2, "ball"), ball);
    QuatTrack spin;
    spin.times = {0.0f, 1.0f};
    spin.values = {Quat(1, 0, 0, 0), glm::angleAxis(1.2f, glm::normalize(Vec3(1, 1, 0)))};
    scene.nodes[scene.parts[2].node].rotation = spin;
    scene.camera.position = Vec3(1.5f, 1.6f, 2.2f);
    scene.camera.target = Vec3(0, 0.3f, 0);
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    // All three shapes found, on both sides.
    CHECK(find_occluder_shape(scene.parts[0].mesh).kind == shading::kShapeRectangle);
    CHECK(find_occluder_shape(scene.parts[1].mesh).kind == shading::kShapeBox);
    CHECK(find_occluder_shape(scene.parts[3].mesh).kind == shading::kShapeNone);
    RenderOptions options;
    options.exact_shapes = true;
    check_against_cpu(scene, test::random_rsls(16, 7), fields, options, {0.0f, 0.6f}, true);
}

TEST_CASE("GL matches the CPU under a blend of two environments", "[gl-renderer]") {
    Scene scene = moving_scene();
    scene.environment.second_file = "second.exr";  // only its presence matters: the sets are given
    scene.environment.blend_period_seconds = 8.0f;
    scene.environment.rotation_degrees_per_second = 15.0f;
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    // t = 4/3: second map weight 0.25; t = 4: the second set alone.
    check_against_cpu(scene, EnvironmentLights(test::random_rsls(8, 3), test::random_rsls(6, 11)), fields,
                      RenderOptions{}, {0.0f, 4.0f / 3.0f, 4.0f});
}

TEST_CASE("GL matches the CPU under a glTF sun (a light of the sun's size) and a uniform sky", "[gl-renderer]") {
    Scene scene = moving_scene();
    SceneNode sun;
    sun.name = "sun";
    sun.rest.rotation = glm::angleAxis(glm::radians(-50.0f), glm::normalize(Vec3(1, 0.3f, 0)));
    scene.nodes.push_back(sun);
    scene.environment.suns.push_back(SunLight{"sun", int(scene.nodes.size()) - 1, Color(3.0f, 2.8f, 2.5f)});
    scene.environment.uniform = Color(0.2f);
    const CubeMap environment = scene_environment_map(scene, 16);
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    const RslSet lights = fit_scene_lights(scene, environment, 30);
    REQUIRE(lights.lights.size() == 31);  // the sky's 30 and the sun
    // The sun gives most of the light through a square about a texel wide.
    // Read from the corner sums, their float rounding (about 1e-4 of the
    // texel's value, rounded differently on the GPU) made GL and CPU differ
    // by 2e-5; read from the texels it overlaps (shading::square_taps), they
    // agree to 2e-7–4e-7 with 64² × 32 tables and to 5e-6 with the default
    // 96² × 64 (measured), with the visibility factors off as with them.
    check_against_cpu(scene, lights, fields, RenderOptions{}, {0.0f, 0.5f}, false, 1e-5);
    RenderOptions unshadowed;
    unshadowed.self_visibility = unshadowed.occluders = false;
    check_against_cpu(scene, lights, fields, unshadowed, {0.0f}, false, 1e-5);
}

TEST_CASE("GL material edits re-upload only the changed table and match the CPU", "[gl-renderer]") {
    test::gl_context();
    const Scene scene = moving_scene();
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    const RslSet lights = test::random_rsls(8, 5);
    CpuRenderer cpu(scene, lights, fields, RenderOptions{});
    gl::GlRenderer gpu(scene, lights, fields, RenderOptions{});
    auto compare = [&](const char* what) {
        cpu.set_time(0.5f);
        gpu.set_time(0.5f);
        const test::ColorDifference d = test::compare_colors(gpu.shade(), cpu.shade(), kTolerance);
        INFO(what << ": relative L2 " << d.relative_l2 << ", " << d.over_tolerance << " vertices over tolerance");
        CHECK(d.relative_l2 < 1e-5);
        CHECK(d.over_tolerance <= d.vertices / 1000);
    };
    compare("as loaded");
    REQUIRE(gpu.material_uploads().full == 1);
    // A parameter edit of the same model: in place, one table.
    for (VertexRenderer* r : {static_cast<VertexRenderer*>(&cpu), static_cast<VertexRenderer*>(&gpu)})
        r->set_material_parameter("glossy", "exponent", {80.0f});
    compare("glossy exponent 80");
    CHECK(gpu.material_uploads().full == 1);
    CHECK(gpu.material_uploads().tables == 1);
    // The edited CPU renderer equals one built on the edited scene.
    Scene edited = scene;
    edited.materials[1].params["exponent"] = {80.0f};
    CpuRenderer fresh(edited, lights, fields, RenderOptions{});
    fresh.set_time(0.5f);
    CHECK(test::compare_colors(cpu.shade(), fresh.shade(), 1e-7).max_relative == 0.0);
    // Swapping a part onto a table already uploaded uploads nothing.
    for (VertexRenderer* r : {static_cast<VertexRenderer*>(&cpu), static_cast<VertexRenderer*>(&gpu)})
        r->set_part_material("small", "glossy");
    compare("small sphere in glossy");
    CHECK(gpu.material_uploads().tables == 1);
    // Unknown names are errors that say which.
    CHECK_THROWS_WITH(cpu.set_material_parameter("nope", "exponent", {2.0f}), Catch::Contains("nope"));
    CHECK_THROWS_WITH(gpu.set_part_material("small", "nope"), Catch::Contains("nope"));
    CHECK_THROWS_WITH(gpu.set_material_parameter("glossy", "exponent", {-1.0f}), Catch::Contains("exponent"));
    compare("after refused edits");
}

TEST_CASE("GL matches the CPU on the robot over several frames with local lights", "[gl-robot]") {
    const std::filesystem::path path = std::filesystem::path(RSL_SOURCE_DIR) / "assets/scenes/robot.json";
    if (!std::filesystem::exists(std::filesystem::path(RSL_SOURCE_DIR) / "assets/generated/robot.glb")) {
        WARN("SKIPPED: assets/generated/robot.glb is missing (build the generated_assets target)");
        return;
    }
    Scene scene = load_scene(path);
    // Tiny fields so that the bake takes seconds; the lookups are the same code.
    PrecomputeSettings& pre = scene.precompute;
    pre.svdf_resolution = 8, pre.svdf_clusters = 16, pre.svdf_vectors = 3, pre.svdf_supersampling = 1;
    pre.ovdf_shells = 3, pre.ovdf_cube_resolution = 4, pre.ovdf_vdt_resolution = 8, pre.ovdf_vectors = 3;
    for (const Vec3 position : {Vec3(0.6f, 1.4f, 0.5f), Vec3(-0.5f, 0.3f, 0.6f)}) {
        LocalLight light;
        light.radius = 0.04f;
        light.power = Color(3.0f);
        light.position = position;
        scene.lights.push_back(light);
    }
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    RenderOptions options;
    options.brdf_table.resolution = 16, options.brdf_table.view_samples = 8;
    check_against_cpu(scene, test::random_rsls(12, 11), fields, options, {0.0f, 0.4f, 1.3f});
}

}  // namespace
}  // namespace rsl
