// Scenes: keyframe tracks, transforms and hierarchy, scene-file errors, `rsl info`.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <random>

#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>

#include "src/core/error.h"
#include "src/core/scene.h"
#include "src/formats/scene_file.h"
#include "tests/test_support.h"
#include "tests/random_cases.h"

using namespace rsl;

namespace {

std::filesystem::path temp_dir(const std::string& name) { return test::scratch_dir("scene_" + name); }
using test::write_text;

const char* kTetrahedron = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

bool near(const Vec3& a, const Vec3& b, float tolerance = 1e-5f) { return glm::length(a - b) < tolerance; }

Quat axis_angle(Vec3 axis, float degrees) { return glm::angleAxis(glm::radians(degrees), glm::normalize(axis)); }

// Rotation angle between two unit quaternions (q and −q are the same rotation).
float angle_between(const Quat& a, const Quat& b) { return 2 * std::acos(std::min(1.0f, std::abs(glm::dot(a, b)))); }

}  // namespace

TEST_CASE("Vec3 tracks: step, linear, cubic spline, clamping", "[scene][animation]") {
    Vec3Track track;
    track.times = {1, 2, 4};
    track.values = {{0, 0, 0}, {2, 0, 0}, {2, 4, 0}};
    CHECK(track.sample(0) == Vec3(0, 0, 0));  // before the first key
    CHECK(near(track.sample(1.5f), {1, 0, 0}));
    CHECK(near(track.sample(3.0f), {2, 2, 0}));
    CHECK(track.sample(9) == Vec3(2, 4, 0));  // after the last key
    track.interpolation = Interpolation::Step;
    CHECK(track.sample(1.99f) == Vec3(0, 0, 0));
    CHECK(track.sample(2.0f) == Vec3(2, 0, 0));
    CHECK(track.sample(3.9f) == Vec3(2, 0, 0));

    // Cubic Hermite with tangents: p(s) = h00 v0 + h10 Δt m0 + h01 v1 + h11 Δt m1.
    Vec3Track cubic;
    cubic.interpolation = Interpolation::CubicSpline;
    cubic.times = {0, 2};
    cubic.values = {{9, 9, 9}, {0, 0, 0}, {1, 0, 0},    // key 0: in, value, out
                    {0, 3, 0}, {1, 1, 1}, {9, 9, 9}};   // key 1: in, value, out
    const float s = 0.25f, dt = 2;
    const float h00 = 2 * s * s * s - 3 * s * s + 1, h10 = s * s * s - 2 * s * s + s, h01 = -2 * s * s * s + 3 * s * s,
                h11 = s * s * s - s * s;
    const Vec3 expected = h00 * Vec3(0) + h10 * dt * Vec3(1, 0, 0) + h01 * Vec3(1) + h11 * dt * Vec3(0, 3, 0);
    CHECK(near(cubic.sample(0.5f), expected));
    CHECK(cubic.sample(2) == Vec3(1, 1, 1));
    CHECK(cubic.sample(0) == Vec3(0, 0, 0));
}

TEST_CASE("Quaternion tracks: slerp at constant speed along the short arc", "[scene][animation]") {
    QuatTrack track;
    track.times = {0, 1};
    track.values = {axis_angle({0, 0, 1}, 0), axis_angle({0, 0, 1}, 120)};
    for (float t : {0.1f, 0.25f, 0.5f, 0.8f}) {
        INFO(t);
        CHECK(angle_between(track.sample(t), axis_angle({0, 0, 1}, 120 * t)) < 1e-5f);
    }
    // −q is the same rotation: slerp must not take the long way round.
    track.values[1] = -track.values[1];
    CHECK(angle_between(track.sample(0.5f), axis_angle({0, 0, 1}, 60)) < 1e-5f);
    // Property: on random pairs, the angle to either end grows linearly in t.
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1, 1);
    for (int i = 0; i < 200; ++i) {
        const Quat a = glm::normalize(test::random_quat(u, rng));
        const Quat b = glm::normalize(test::random_quat(u, rng));
        track.values = {a, b};
        const float t = 0.5f * (u(rng) + 1), total = angle_between(a, b);
        const Quat q = track.sample(t);
        REQUIRE(std::abs(glm::length(q) - 1) < 1e-5f);
        REQUIRE(angle_between(a, q) == Approx(t * total).margin(2e-3));
        REQUIRE(angle_between(q, b) == Approx((1 - t) * total).margin(2e-3));
    }
    track.interpolation = Interpolation::Step;
    track.values = {axis_angle({1, 0, 0}, 30), axis_angle({1, 0, 0}, 60)};
    CHECK(angle_between(track.sample(0.99f), axis_angle({1, 0, 0}, 30)) < 1e-5f);
}

TEST_CASE("Transforms compose as T·R·S and ancestors multiply", "[scene]") {
    Transform t;
    t.translation = {1, 2, 3};
    t.rotation = axis_angle({0, 1, 0}, 90);
    t.scale = {2, 3, 4};
    const Mat4 reference =
        glm::scale(glm::translate(Mat4(1), t.translation) * glm::mat4_cast(t.rotation), t.scale);
    for (int c = 0; c < 4; ++c) CHECK(near(Vec3(t.matrix()[c]), Vec3(reference[c])));
    CHECK(near(Vec3(t.matrix() * Vec4(1, 1, 1, 1)), {1 + 4, 2 + 3, 3 - 2}));  // (2,3,4) → R_y(90°) → (4,3,−2)

    // Three-level chain: grandparent rotates about y over time, parent offsets, child scales.
    Scene scene;
    SceneNode root, middle, leaf;
    root.rotation = QuatTrack{Interpolation::Linear, {0, 2}, {axis_angle({0, 1, 0}, 0), axis_angle({0, 1, 0}, 120)}};
    middle.parent = 0;
    middle.rest.translation = {1, 0, 0};
    leaf.parent = 1;
    leaf.scale = Vec3Track{Interpolation::Linear, {0, 2}, {{1, 1, 1}, {3, 3, 3}}};
    scene.nodes = {root, middle, leaf};
    // t = 1.5: root 90° about y, leaf scale 2.5. Leaf point (1, 0, 0) → (2.5, 0, 0) → (3.5, 0, 0) → (0, 0, −3.5).
    CHECK(near(Vec3(scene.node_world_at(2, 1.5f) * Vec4(1, 0, 0, 1)), {0, 0, -3.5f}));
    CHECK(near(Vec3(scene.node_world_at(1, 1.5f) * Vec4(0, 0, 0, 1)), {0, 0, -1}));
    CHECK(near(Vec3(scene.node_world_at(2, 0) * Vec4(1, 0, 0, 1)), {2, 0, 0}));
    CHECK(scene.node_world_at(-1, 0) == Mat4(1));
}

TEST_CASE("Environment rotation over time", "[scene]") {
    EnvironmentDesc env;
    env.rotation_axis = {0, 1, 0};
    env.rotation_degrees = 30;
    env.rotation_degrees_per_second = 20;
    const Mat3 r = env.rotation_at(3);  // 90° about y
    CHECK(near(r * Vec3(1, 0, 0), {0, 0, -1}));
    CHECK(near(r * Vec3(0, 1, 0), {0, 1, 0}));
    CHECK(env.rotation_at(-1.5f) == Mat3(1));  // 30 − 30 = 0
}

TEST_CASE("Scene files: OBJ parts, transforms, defaults and every kind of error", "[scene][bad-input]") {
    const auto dir = temp_dir("json");
    write_text(dir / "tet.obj", kTetrahedron);
    write_text(dir / "scene.json", R"({
      "parts": [ { "obj": "tet.obj", "transform": { "translation": [0, 1, 0], "rotation_axis_angle": [0, 0, 1, 90], "scale": 2 } },
                 { "name": "second", "obj": "tet.obj", "material": "red" } ],
      "materials": { "red": { "model": "ward", "albedo": [1, 0, 0], "alpha": 0.2 } },
      "subdivision": false
    })");
    const Scene scene = load_scene(dir / "scene.json");
    CHECK(scene.name == "scene");
    REQUIRE(scene.parts.size() == 2);
    CHECK(scene.parts[0].name == "tet");
    CHECK(scene.parts[0].mesh.vertex_count() == 4);
    CHECK(scene.materials[scene.parts[0].material].name == "default");  // built in: no "default", no "*"
    CHECK(scene.materials[scene.parts[1].material].params.at("alpha") == std::vector<float>{0.2f});
    // (1, 0, 0) → scale 2 → rotate 90° about z → (0, 2, 0) → + (0, 1, 0).
    CHECK(near(Vec3(scene.part_transform_at(0, 0) * Vec4(1, 0, 0, 1)), {0, 3, 0}));
    CHECK(scene.environment.file.empty());
    CHECK(scene.vertex_count() == 8);
    // The default camera sees every vertex.
    const Vec3 view = glm::normalize(scene.camera.target - scene.camera.position);
    for (const Vec3& p : scene.parts[0].mesh.positions) {
        const Vec3 w(scene.part_transform_at(0, 0) * Vec4(p, 1));
        CHECK(glm::dot(glm::normalize(w - scene.camera.position), view) > std::cos(glm::radians(20.0f)));
    }

    auto require_error = [&](const std::string& json, const std::string& fragment) {
        write_text(dir / "bad.json", json);
        try {
            load_scene(dir / "bad.json");
            FAIL("no error for " << json);
        } catch (const Error& e) {
            const std::string message = e.what();
            INFO(message);
            CHECK(message.find((dir / "bad.json").string()) != std::string::npos);
            CHECK(message.find(fragment) != std::string::npos);
        }
    };
    const std::string part = R"("parts": [{ "obj": "tet.obj" }])";
    require_error("{" + part + R"(, "lihgts": []})", "lihgts: unknown key");
    require_error("{" + part + R"(, "camera": { "fov": 40 }})", "camera.fov: unknown key");
    require_error(R"({"parts": [{ "obj": "tet.obj", "transfrom": {} }]})", "parts[0].transfrom: unknown key");
    require_error("{" + part + ",\n\n  \"name\": oops }", "line 3, column");
    require_error("{" + part + R"(, "camera": { "fov_degrees": "wide" }})", "camera.fov_degrees: expected a number, got string");
    require_error("{" + part + R"(, "camera": { "width": 64.5 }})", "camera.width: expected an integer");
    require_error("{" + part + R"(, "lights": [{ "position": [1, 2] }]})", "lights[0].position: expected 3 numbers, got 2");
    require_error("{" + part + R"(, "lights": [{ "radius": -1 }]})", "lights[0].radius: must be positive");
    require_error("{" + part + R"(, "lights": [{ "path": { "times": [0, 1], "positions": [[0, 0, 0]] } }]})",
                  "lights[0].path.positions: expected an array of 2 points");
    require_error("{" + part + R"(, "environment": { "file": "missing.exr" }})", "environment.file: file");
    require_error(R"({"parts": [{ "obj": "missing.obj" }]})", "parts[0].obj: file");
    require_error(R"({"parts": [{ "obj": "tet.obj", "material": "gold" }]})", "no material named 'gold'");
    require_error("{" + part + R"(, "part_materials": { "tett": "default" }})", "part_materials.tett: no part has this name");
    require_error("{" + part + R"(, "precompute": { "svdf": { "clusters": 0 } }})",
                  "precompute.svdf.clusters: must be an integer from 1 to 65536, got 0");
    // Sizes of what rsl allocates are bounded (docs/SCENE_FORMAT.md): a camera of 16777216² pixels was accepted.
    require_error("{" + part + R"(, "camera": { "width": 16777216 }})", "camera.width: must be an integer from 1 to 16384");
    require_error("{" + part + R"(, "precompute": { "ovdf": { "shells": 18446744073709551615 } }})",
                  "precompute.ovdf.shells: must be an integer from 2 to 256, got 18446744073709551615");
    require_error("{" + part + R"(, "environment": { "file": "tet.obj", "resolution": 8192 }})",
                  "environment.resolution: must be an integer from 1 to 512");
    // The light fit holds about 700 bytes a texel: 4096 (6 × 4096² texels) needed about 70 GB.
    require_error("{" + part + R"(, "environment": { "file": "tet.obj", "resolution": 4096 }})",
                  "environment.resolution: must be an integer from 1 to 512, got 4096");
    // Settings that `rsl bake` took to an internal error (a check in the fields' code).
    require_error("{" + part + R"(, "precompute": { "ovdf": { "shells": 1 } }})",
                  "precompute.ovdf.shells: must be an integer from 2 to 256, got 1");
    require_error("{" + part + R"(, "precompute": { "ovdf": { "cube_resolution": 5 } }})",
                  "precompute.ovdf.cube_resolution: must be even");
    require_error("{" + part + R"(, "precompute": { "ovdf": { "vdt_resolution": 1 } }})",
                  "precompute.ovdf.vdt_resolution: must be an integer from 2 to 256");
    require_error("{" + part + R"(, "precompute": { "ovdf": { "inner_radius": "small" } }})",
                  "precompute.ovdf.inner_radius: must be a positive number or \"auto\"");
    require_error("{" + part + R"(, "precompute": { "ovdf": { "inner_radius": 0 } }})",
                  "precompute.ovdf.inner_radius: must be positive, got 0");
    require_error("{" + part + R"(, "precompute": { "svdf": { "resolution": 1 } }})",
                  "precompute.svdf.resolution: must be an integer from 2 to 256");
    // A light path without positions was an internal error (nlohmann's out_of_range, status 2).
    require_error("{" + part + R"(, "lights": [{ "path": { "times": [0] } }]})", "lights[0].path.positions: required with `times`");
    require_error("{" + part + R"(, "animation": { "start": 2, "end": 1 }})", "animation.end");
    require_error("{}", "no parts");
    require_error("[1, 2]", "top level must be a JSON object");
    write_text(dir / "broken.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    require_error(R"({"parts": [{ "obj": "broken.obj" }]})", "");  // the OBJ's error names the OBJ
    CHECK_THROWS_WITH(load_scene(dir / "bad.json"), Catch::Contains("broken.obj: line 4"));
    CHECK_THROWS_WITH(load_scene(dir / "scene.txt"), Catch::Contains("scene.txt"));
}

TEST_CASE("rsl info describes meshes and scenes and fails on bad files", "[scene][cli]") {
    const auto dir = temp_dir("info");
    write_text(dir / "tet.obj", kTetrahedron);
    write_text(dir / "scene.json", R"({ "parts": [{ "obj": "tet.obj" }] })");
    write_text(dir / "corrupt.obj", "v 0 0 0\nv 1 zero 0\n");
    const std::string rsl = RSL_RSL_EXECUTABLE;
    const std::string out = (dir / "out.txt").string();
    REQUIRE(std::system((rsl + " info " + (dir / "tet.obj").string() + " " + (dir / "scene.json").string() + " > " + out).c_str()) == 0);
    std::ifstream in(out);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    INFO(text);
    CHECK(text.find("4 vertices") != std::string::npos);
    CHECK(text.find("parts:             1") != std::string::npos);

    const std::string err = (dir / "err.txt").string();
    CHECK(std::system((rsl + " info " + (dir / "corrupt.obj").string() + " > /dev/null 2> " + err).c_str()) != 0);
    std::ifstream err_in(err);
    const std::string message((std::istreambuf_iterator<char>(err_in)), {});
    CHECK(message.find("corrupt.obj: line 2") != std::string::npos);
    CHECK(std::system((rsl + " info " + (dir / "nothing.obj").string() + " > /dev/null 2>&1").c_str()) != 0);
    // A material with a bad parameter is caught by `rsl info`, naming the scene and the parameter.
    write_text(dir / "bad_material.json", R"({ "parts": [{ "obj": "tet.obj" }],
        "materials": { "shiny": { "model": "phong", "ks": [0.5, 0.5, 0.5] } }, "part_materials": { "*": "shiny" } })");
    const auto [material_status, material_text] = test::run_rsl("info " + (dir / "bad_material.json").string());
    INFO(material_text);
    CHECK(material_status != 0);
    CHECK(material_text.find((dir / "bad_material.json").string() + ": material 'shiny' (phong): parameter 'exponent'") !=
          std::string::npos);

    const std::filesystem::path meshes = std::filesystem::path(RSL_SHARED_ASSETS) / "meshes";
    if (!std::filesystem::exists(meshes)) {
        WARN("SKIPPED: " << meshes << " is absent");
        return;
    }
    for (const auto& entry : std::filesystem::directory_iterator(meshes)) {
        if (entry.path().extension() != ".obj") continue;
        INFO(entry.path());
        CHECK(std::system((rsl + " info " + entry.path().string() + " > /dev/null").c_str()) == 0);
    }
}
