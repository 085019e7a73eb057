// The scene file's part animation (docs/SCENE_FORMAT.md, "Animating parts")
// and `part_materials["*"]` over glTF materials.
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "src/core/error.h"
#include "src/core/scene.h"
#include "src/formats/scene_file.h"
#include "tests/formats/gltf_builder.h"
#include "tests/test_support.h"

using namespace rsl;

namespace {

const char* kTetrahedron = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

// A scene of one tetrahedron whose part entry carries `animation`.
std::filesystem::path animated_scene(const std::filesystem::path& dir, const std::string& animation) {
    test::write_text(dir / "tet.obj", kTetrahedron);
    const std::filesystem::path file = dir / "scene.json";
    test::write_text(file, R"({ "subdivision": false, "parts": [ { "name": "tet", "obj": "tet.obj",
        "transform": { "translation": [5, 6, 7], "rotation_axis_angle": [1, 0, 0, 30], "scale": 3 },
        "animation": )" + animation + " } ] }");
    return file;
}

// The brute-force pose: translation, then rotation about y by `degrees`, then scale, applied by hand.
Vec3 posed(const Vec3& v, const Vec3& translation, float degrees, const Vec3& scale) {
    const float c = std::cos(glm::radians(degrees)), s = std::sin(glm::radians(degrees));
    const Vec3 scaled = v * scale;
    const Vec3 turned(c * scaled.x + s * scaled.z, scaled.y, -s * scaled.x + c * scaled.z);  // about +y
    return turned + translation;
}

std::string error_of(const std::filesystem::path& file) {
    try {
        load_scene(file);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace

TEST_CASE("part animation: translation, axis-angle rotation and scale keys, at and between keys",
          "[scene][animation]") {
    const auto dir = test::scratch_dir("part_animation_keys");
    const Scene scene = load_scene(animated_scene(dir, R"({
        "translation": { "times": [0, 2, 4], "values": [[0, 0, 0], [2, 0, -4], [2, 6, -4]] },
        "rotation":    { "times": [1, 3], "values": [[0, 1, 0, 20], [0, 2, 0, 140]] },
        "scale":       { "times": [0, 2], "values": [1, [1, 3, 0.5]], "interpolation": "step" } })"));
    REQUIRE(scene.parts.size() == 1);
    CHECK(scene.animation.start == 0);
    CHECK(scene.animation.end == 4);  // the range covers the part's keys
    // Hand computations: (t, translation, rotation about y in degrees, scale).
    struct Pose {
        float t;
        Vec3 translation;
        float degrees;
        Vec3 scale;
    };
    const Pose poses[] = {
        {-1, {0, 0, 0}, 20, {1, 1, 1}},       // before every key: first values
        {0, {0, 0, 0}, 20, {1, 1, 1}},        // at a key
        {0.5f, {0.5f, 0, -1}, 20, {1, 1, 1}}, // translation a quarter of its first interval; rotation held
        {1.5f, {1.5f, 0, -3}, 50, {1, 1, 1}}, // slerp about one axis: 20 + (140 − 20)·0.25
        {2, {2, 0, -4}, 80, {1, 3, 0.5f}},    // step scale switches at its key
        {2.5f, {2, 1.5f, -4}, 110, {1, 3, 0.5f}},
        {3, {2, 3, -4}, 140, {1, 3, 0.5f}},
        {9, {2, 6, -4}, 140, {1, 3, 0.5f}},   // after every key: last values
    };
    for (const Pose& pose : poses) {
        INFO("t = " << pose.t);
        const Mat4 m = scene.part_transform_at(0, pose.t);
        for (const Vec3& v : scene.parts[0].mesh.positions) {
            const Vec3 got(m * Vec4(v, 1));
            const Vec3 want = posed(v, pose.translation, pose.degrees, pose.scale);
            INFO("vertex " << v.x << " " << v.y << " " << v.z << ": got " << got.x << " " << got.y << " " << got.z
                           << ", want " << want.x << " " << want.y << " " << want.z);
            CHECK(glm::length(got - want) < 1e-5f);
        }
    }
}

TEST_CASE("part animation: a channel it does not key keeps the transform's", "[scene][animation]") {
    const auto dir = test::scratch_dir("part_animation_partial");
    const Scene scene = load_scene(animated_scene(dir, R"({ "scale": { "times": [0, 1], "values": [1, 2] } })"));
    // translation (5, 6, 7) and 30° about x stay; the scale goes 1 → 2 linearly.
    const Mat4 m = scene.part_transform_at(0, 0.25f);
    const Mat4 want = glm::translate(Mat4(1), Vec3(5, 6, 7)) * glm::rotate(Mat4(1), glm::radians(30.0f), Vec3(1, 0, 0)) *
                      glm::scale(Mat4(1), Vec3(1.25f));
    for (int c = 0; c < 4; ++c) CHECK(glm::length(m[c] - want[c]) < 1e-5f);
}

TEST_CASE("part animation: a glTF entry's nodes move with it, their own animation below", "[scene][animation][gltf]") {
    const auto dir = test::scratch_dir("part_animation_gltf");
    test::GltfBuilder gltf;
    const int mesh = gltf.mesh({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2});
    const int node = gltf.node({{"name", "blade"}, {"mesh", mesh}});
    gltf.channel(node, "translation", "LINEAR", {0, 2}, {0, 0, 0, 0, 4, 0});  // the file's own: up by 2 m/s
    gltf.doc()["scenes"] = {{{"nodes", nlohmann::json::array({node})}}};
    gltf.write_gltf(dir / "blade.gltf");
    test::write_text(dir / "scene.json", R"({ "subdivision": false, "parts": [ { "name": "fan", "gltf": "blade.gltf",
        "animation": { "translation": { "times": [0, 2], "values": [[0, 0, 0], [10, 0, 0]] },
                       "rotation": { "times": [0, 2], "values": [[0, 1, 0, 0], [0, 1, 0, 90]] } } } ] })");
    const Scene scene = load_scene(dir / "scene.json");
    REQUIRE(scene.parts.size() == 1);
    CHECK(scene.parts[0].name == "fan");
    for (float t : {0.0f, 0.5f, 1.0f, 2.0f}) {
        INFO("t = " << t);
        const Mat4 m = scene.part_transform_at(0, t);
        for (const Vec3& v : scene.parts[0].mesh.positions) {
            // The glTF node lifts the vertex by 2t; the entry turns it by 45t° about y and moves it 5t along x.
            const Vec3 want = posed(v + Vec3(0, 2 * t, 0), Vec3(5 * t, 0, 0), 45 * t, Vec3(1));
            CHECK(glm::length(Vec3(m * Vec4(v, 1)) - want) < 1e-5f);
        }
    }
}

TEST_CASE("part animation: bad keys are refused naming the file, the key and the key frame",
          "[scene][animation][bad-input]") {
    const auto dir = test::scratch_dir("part_animation_errors");
    const std::string file = (dir / "scene.json").string();
    const std::pair<const char*, const char*> cases[] = {
        {R"({ "translation": { "times": [0, 2, 1], "values": [[0,0,0],[1,0,0],[2,0,0]] } })",
         "parts[0].animation.translation.times[2]: times must increase: 1 follows 2 (times[1])"},
        {R"({ "translation": { "times": [0, 0], "values": [[0,0,0],[1,0,0]] } })",
         "parts[0].animation.translation.times[1]: times must increase"},
        {R"({ "translation": { "times": [0, 1], "values": [[0,0,0]] } })",
         "parts[0].animation.translation.values: expected an array of 2 keys (one per time), got 1 keys"},
        {R"({ "translation": { "times": [0, 1], "values": [[0,0,0],[1,0]] } })",
         "parts[0].animation.translation.values[1]: expected an array of 3 numbers"},
        {R"({ "translation": { "times": [0, 1e39], "values": [[0,0,0],[1,0,0]] } })",
         "parts[0].animation.translation.times[1]: 1e+39 is not a finite number"},
        {R"({ "scale": { "times": [0, 1], "values": [1, 0] } })",
         "parts[0].animation.scale.values[1]: scale must be positive, got 0"},
        {R"({ "scale": { "times": [0, 1], "values": [1, [1, -2, 1]] } })",
         "parts[0].animation.scale.values[1]: scale must be positive"},
        {R"({ "rotation": { "times": [0, 1], "values": [[0,1,0,0],[0,1,0,270]] } })",
         "parts[0].animation.rotation.values[1]: turns 270° from values[0]"},
        {R"({ "rotation": { "times": [0, 1], "values": [[0,1,0,0],[1,0,0,180]] } })",
         "parts[0].animation.rotation.values[1]: turns 180° from values[0]"},
        {R"({ "rotation": { "times": [0, 1], "values": [[0,1,0,0],[0,0,0,10]] } })",
         "parts[0].animation.rotation.values[1]: the axis is zero"},
        {R"({ "rotation": { "times": [0], "values": [[0,1,0]] } })",
         "parts[0].animation.rotation.values[0] ([axis x, y, z, degrees]): expected an array of 4 numbers"},
        {R"({ "translation": { "times": [], "values": [] } })",
         "parts[0].animation.translation.times: expected a non-empty array"},
        {R"({ "translation": { "times": [0], "values": [[0,0,0]], "interpolation": "cubic" } })",
         "parts[0].animation.translation.interpolation: expected \"linear\" or \"step\""},
        {R"({ "translation": { "times": [0] } })", "parts[0].animation.translation: `values` is required"},
        {R"({ "spin": {} })", "parts[0].animation.spin: unknown key"},
        {R"({})", "parts[0].animation: give at least one of"},
        {R"([1, 2])", "parts[0].animation: expected an object"},
    };
    for (const auto& [animation, expected] : cases) {
        const std::string message = error_of(animated_scene(dir, animation));
        INFO(animation << "\n→ " << message);
        CHECK(message.rfind(file + ": ", 0) == 0);
        CHECK(message.find(expected) != std::string::npos);
    }
    // A spin in steps under 180° is fine: 0, 120, 240, 360 about y.
    const Scene spin = load_scene(animated_scene(
        dir, R"({ "rotation": { "times": [0, 1, 2, 3], "values": [[0,1,0,0],[0,1,0,120],[0,1,0,240],[0,1,0,360]] } })"));
    const Vec3 x(spin.part_transform_at(0, 1.5f) * Vec4(1, 0, 0, 0));
    CHECK(glm::length(x / 3.0f - posed(Vec3(1, 0, 0), Vec3(0), 180, Vec3(1))) < 1e-5f);
}

TEST_CASE("part_materials \"*\" overrides every part's material, glTF materials included; rsl info shows it",
          "[scene][gltf]") {
    const auto dir = test::scratch_dir("star_material");
    test::GltfBuilder gltf;
    const int mesh = gltf.mesh({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2});
    gltf.doc()["materials"] = {{{"name", "gold"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0.8, 0.2, 1}},
                                                                             {"metallicFactor", 1},
                                                                             {"roughnessFactor", 0.3}}}}};
    gltf.doc()["meshes"][mesh]["primitives"][0]["material"] = 0;
    const int a = gltf.node({{"name", "a"}, {"mesh", mesh}});
    const int b = gltf.node({{"name", "b"}, {"mesh", mesh}, {"translation", {2, 0, 0}}});
    gltf.doc()["scenes"] = {{{"nodes", {a, b}}}};
    gltf.write_gltf(dir / "two.gltf");
    const std::string materials = R"("materials": { "default": { "model": "lambert", "albedo": [0.7, 0.7, 0.7] },
                                                   "red": { "model": "lambert", "albedo": [1, 0, 0] } })";
    // Without "*": the glTF's material.
    test::write_text(dir / "own.json", R"({ "gltf": "two.gltf", )" + materials + " }");
    const Scene own = load_scene(dir / "own.json");
    for (const Part& part : own.parts) CHECK(own.materials[part.material].name == "gold");
    // With "*": every part, unless named.
    test::write_text(dir / "star.json",
                     R"({ "gltf": "two.gltf", )" + materials + R"(, "part_materials": { "*": "default", "b": "red" } })");
    const Scene star = load_scene(dir / "star.json");
    REQUIRE(star.parts.size() == 2);
    CHECK(star.materials[star.parts[0].material].name == "default");
    CHECK(star.materials[star.parts[1].material].name == "red");
    for (const MaterialDesc& m : star.materials) CHECK(m.model != "gltf_pbr");  // the glTF's is not loaded
    const auto [status, text] = test::run_rsl("info " + (dir / "star.json").string());
    INFO(text);
    CHECK(status == 0);
    CHECK(text.find("material default (lambert)") != std::string::npos);
    CHECK(text.find("material red (lambert)") != std::string::npos);
    CHECK(text.find("gold") == std::string::npos);
}
