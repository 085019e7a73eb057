// The public API's scene built in code (meshes, transforms, materials) is the
// scene a file describes; poses from matrices; progress of the fit and bakes.
#include <catch2/catch.hpp>

#include <mutex>
#include <random>

#include "rsl/rsl.h"
#include "src/core/scene.h"
#include "tests/api/api_test_scene.h"
#include "tests/random_cases.h"

namespace rsl {
namespace {

using api::Renderer;
using api::Scene;

TEST_CASE("a scene built in code renders as the same scene loaded from its file", "[api]") {
    const auto folder = test::scratch_dir("api-built");
    const auto file = test::write_api_scene(folder, "scene.json");
    const Scene loaded = Scene::load(file.string());

    Scene built("api-test");
    built.add_material({"steel", "phong", {{"kd", {0.3f, 0.3f, 0.32f}}, {"ks", {0.4f, 0.4f, 0.4f}}, {"exponent", {30}}}, ""});
    built.add_material({"floor", "lambert", {{"albedo", {0.55f, 0.53f, 0.5f}}}, ""});
    built.add_material({"clay", "lambert", {{"albedo", {0.7f, 0.4f, 0.3f}}}, ""});
    built.add_part("orb", loaded.part_mesh(0), "steel");
    built.add_part("floor", loaded.part_mesh(1), "floor");
    built.set_environment(std::string(RSL_SOURCE_DIR) + "/assets/generated/sunsky.exr", 12);
    built.set_environment_rotation({0, 1, 0}, 30, 40);
    built.set_camera(loaded.camera());
    built.set_precompute(loaded.precompute());
    REQUIRE(built.part_vertex_counts() == loaded.part_vertex_counts());
    REQUIRE(built.vertex_count() > 3000);

    api::RenderSettings settings;
    settings.lights = 10;
    settings.field_cache = (folder / "built-cache").string();
    Renderer from_code(built, settings);
    CHECK(from_code.setup().fields_baked == 4);
    settings.field_cache.clear();  // the loaded scene's own cache, beside its file
    Renderer from_file(loaded, settings);
    for (float t : {0.0f, 0.3f}) {
        from_code.set_time(t);
        from_file.set_time(t);
        const api::VertexColors a = from_code.shade(), b = from_file.shade();
        REQUIRE(a.rgb == b.rgb);
        REQUIRE(from_code.truth().rgb == from_file.truth().rgb);
    }
    // Made again, the code-built scene reads its fields from the folder it was given.
    settings.field_cache = (folder / "built-cache").string();
    const Renderer again(built, settings);
    CHECK(again.setup().fields_loaded == 4);
    CHECK(again.setup().fields_baked == 0);
}

TEST_CASE("a scene built in code without a cache folder bakes in memory and shades", "[api]") {
    Scene scene("tiny");
    scene.add_material({"grey", "lambert", {{"albedo", {0.5f, 0.5f, 0.5f}}}, ""});
    api::Mesh quad{{{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}}, {0, 2, 1, 0, 3, 2}, {}};
    scene.add_part("quad", quad, "grey");
    scene.add_sphere_light({{0, 1, 0}, 0.1f, {10, 10, 10}});
    scene.set_camera({{0, 2, 2}, {0, 0, 0}, {0, 1, 0}, 40, 32, 24});
    scene.set_precompute({8, 4, 2, 1, 3, 0.4f, 6.0f, 4, 8, 2});
    Renderer renderer(scene);
    const api::VertexColors colors = renderer.shade();
    REQUIRE(colors.vertex_count() == 4);
    // A Lambertian floor under a small light: every corner lit, all within
    // 1% (the light's square turns with each vertex's tangent frame, so the
    // RSL sum is not quite symmetric; the truth is), and the corners the
    // mirror x → −x swaps (0 and 1, 2 and 3) alike.
    for (size_t i = 0; i < colors.rgb.size(); ++i) {
        CHECK(colors.rgb[i] > 0);
        CHECK(colors.rgb[i] == Approx(colors.rgb[i % 3]).epsilon(0.01));
        CHECK(colors.rgb[i] == Approx(colors.rgb[((i / 3) ^ 1) * 3 + i % 3]).epsilon(1e-5));
    }
    const api::VertexColors truth = renderer.truth();
    CHECK(api::compare(colors, truth).relative_l2 < 0.02);
    CHECK(test::error_of([&] { scene.add_part("bad", {{{0, 0, 0}}, {0, 0, 1}, {}}, "grey"); }).find("part 'bad'") == 0);
    CHECK(test::error_of([&] { scene.add_part("x", quad, "gold"); }) == "part 'x': no material 'gold' (add_material first)");
    // The OVDF's inner radius: 0 asks for the per-mesh choice; below 0 is refused.
    CHECK_NOTHROW(scene.set_precompute({8, 4, 2, 1, 3, 0.0f, 6.0f, 4, 8, 2}));
    CHECK(test::error_of([&] { scene.set_precompute({8, 4, 2, 1, 3, -0.1f, 6.0f, 4, 8, 2}); }).find("0 ≤ inner < outer") !=
          std::string::npos);
    // Errors of a scene without a file name no file.
    api::RenderSettings overridden;
    overridden.part_materials = {{"nope", "grey"}};
    CHECK(test::error_of([&] { Renderer(scene, overridden); }) == "material override: no part named 'nope'");
}

TEST_CASE("poses from matrices: translation · rotation · scale round-trips, shear and projections are refused", "[api]") {
    std::mt19937 rng(18);
    std::uniform_real_distribution<float> u(-1, 1), positive(0.2f, 3.0f);
    for (int i = 0; i < 200; ++i) {
        Transform t;
        t.translation = 5.0f * test::random_vec3(u, rng);
        t.rotation = glm::normalize(test::random_quat(u, rng));
        t.scale = test::random_vec3(positive, rng);
        const Mat4 m = t.matrix();
        std::array<float, 16> column_major;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) column_major[4 * c + r] = m[c][r];
        const api::Pose pose = api::Pose::from_matrix(column_major);
        Transform back;
        back.translation = Vec3(pose.translation[0], pose.translation[1], pose.translation[2]);
        back.rotation = Quat(pose.rotation[0], pose.rotation[1], pose.rotation[2], pose.rotation[3]);
        back.scale = Vec3(pose.scale[0], pose.scale[1], pose.scale[2]);
        const Mat4 again = back.matrix();
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) REQUIRE(again[c][r] == Approx(m[c][r]).margin(2e-5f * 5));
    }
    std::array<float, 16> shear{1, 0, 0, 0, 0.5f, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    CHECK(test::error_of([&] { api::Pose::from_matrix(shear); }).find("shear") != std::string::npos);
    std::array<float, 16> projection{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -1, 0, 0, 0, 1};
    CHECK(test::error_of([&] { api::Pose::from_matrix(projection); }).find("projection") != std::string::npos);
    std::array<float, 16> mirror{-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    CHECK(test::error_of([&] { api::Pose::from_matrix(mirror); }).find("mirror") != std::string::npos);
}

TEST_CASE("progress reaches the callback: the fit, every bake, the truth, each ending at 1", "[api]") {
    const auto folder = test::scratch_dir("api-progress");
    const auto file = test::write_api_scene(folder, "scene.json");
    std::mutex mutex;
    std::map<std::string, std::vector<double>> heard;
    api::RenderSettings settings;
    settings.field_cache = (folder / "cache").string();
    settings.progress = [&](const std::string& what, double fraction) {
        std::lock_guard<std::mutex> lock(mutex);
        heard[what].push_back(fraction);
    };
    Renderer renderer(Scene::load(file.string()), settings);
    REQUIRE(heard.count("fit") == 1);
    int bakes = 0;
    for (const auto& [what, fractions] : heard) {
        for (double f : fractions) REQUIRE((f >= 0 && f <= 1));
        REQUIRE(fractions.back() == 1.0);
        bakes += what.rfind("SVDF ", 0) == 0 || what.rfind("OVDF ", 0) == 0;
    }
    CHECK(bakes == 4);
    api::TruthSettings truth;
    truth.progress = settings.progress;
    renderer.truth(truth);
    REQUIRE(heard.count("truth") == 1);
    CHECK(heard["truth"].back() == 1.0);

    // `rsl bake` ahead of time: the renderer then only loads.
    const Scene scene = Scene::load(file.string());
    const api::SetupReport baked = api::bake_fields(scene, (folder / "ahead").string());
    CHECK(baked.fields_baked == 4);
    CHECK(baked.fields_loaded == 0);
    CHECK(api::bake_fields(scene, (folder / "ahead").string()).fields_loaded == 4);
    settings.field_cache = (folder / "ahead").string();
    settings.progress = {};
    CHECK(Renderer(scene, settings).setup().fields_baked == 0);
    CHECK(test::error_of([] { api::bake_fields(Scene("nameless")); }).find("give a field_cache folder") !=
          std::string::npos);
}

TEST_CASE("build information names the version, commit and libraries", "[api]") {
    const api::BuildInfo info = api::build_info();
    CHECK(info.version == RSL_VERSION_STRING);
    CHECK(!info.commit.empty());
    CHECK(info.embree.find("3.") == 0);
    CHECK(info.openexr.find("3.") == 0);
    CHECK(info.backends.front() == "cpu");
    const auto [status, text] = test::run_rsl("--version");
    REQUIRE(status == 0);
    CHECK(text.find("rsl " + info.version + "\ncommit: " + info.commit + "\n") == 0);
    CHECK(text.find("Embree: " + info.embree) != std::string::npos);
    CHECK(text.find("OpenEXR: " + info.openexr) != std::string::npos);
}

}  // namespace
}  // namespace rsl
