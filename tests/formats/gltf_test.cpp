// glTF loading: hierarchy and animation round trip against hand-computed
// transforms, computed normals, corrupt files; the documented scene-file
// example (which references a .glb).
#include <catch2/catch.hpp>

#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>

#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "src/core/error.h"
#include "src/formats/image_file.h"
#include "src/core/scene.h"
#include "src/formats/scene_file.h"
#include "tests/formats/gltf_builder.h"
#include "tests/test_support.h"

using namespace rsl;
using Json = nlohmann::json;
using test::GltfBuilder;

namespace {

std::filesystem::path temp_dir(const std::string& name) { return test::scratch_dir("gltf_" + name); }

// A unit square in the xy-plane (two triangles), no normals.
const std::vector<float> kSquare{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::vector<uint32_t> kSquareIndices{0, 1, 2, 0, 2, 3};

// Base (translation: linear (0,0,0)→(2,0,0) over [0, 2]) with child arm (rest
// translation (0,1,0); rotation slerp identity → 90° about z over [0, 1];
// scale step 1 → 2 at t = 1).
GltfBuilder robot_arm() {
    GltfBuilder b;
    const int square = b.mesh(kSquare, kSquareIndices);
    const int triangle = b.mesh({0, 0, 0, 1, 0, 0, 0, 0, 1}, {}, {0, 1, 0, 0, 1, 0, 0, 1, 0});
    const int arm = b.node({{"name", "arm"}, {"mesh", triangle}, {"translation", {0, 1, 0}}});
    b.node({{"name", "base"}, {"mesh", square}, {"children", {arm}}});
    b.node({{"name", "empty"}});
    const float s = std::sqrt(0.5f);
    b.channel(1, "translation", "LINEAR", {0, 2}, {0, 0, 0, 2, 0, 0});
    b.channel(arm, "rotation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0, s, s});  // glTF (x, y, z, w)
    b.channel(arm, "scale", "STEP", {0, 1}, {1, 1, 1, 2, 2, 2});
    return b;
}

const Part& part_named(const Scene& scene, const std::string& name) {
    for (const Part& p : scene.parts)
        if (p.name == name) return p;
    FAIL("no part " << name);
    throw;
}

Vec3 world_point(const Scene& scene, const Part& part, float t, Vec3 p) {
    return Vec3(scene.node_world_at(part.node, t) * Vec4(p, 1.0f));
}

void check_near(Vec3 a, Vec3 b) {
    INFO("(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y << ", " << b.z << ")");
    CHECK(glm::length(a - b) < 1e-5f);
}

void check_robot_arm(const Scene& scene) {
    REQUIRE(scene.parts.size() == 2);
    REQUIRE(scene.nodes.size() == 3);
    const Part& base = part_named(scene, "base");
    const Part& arm = part_named(scene, "arm");
    CHECK(scene.nodes[arm.node].parent == base.node);
    CHECK(base.mesh.triangle_count() == 2);
    CHECK(arm.mesh.triangle_count() == 1);

    // Base: translation only.
    check_near(world_point(scene, base, 0.5f, {1, 1, 0}), {1.5f, 1, 0});
    check_near(world_point(scene, base, 3.0f, {0, 0, 0}), {2, 0, 0});  // clamped after the last key
    // Arm point (1, 0, 0): scale, rotate about z, + (0, 1, 0), + base translation.
    check_near(world_point(scene, arm, 0.0f, {1, 0, 0}), {1, 1, 0});
    const float c45 = std::sqrt(0.5f);
    check_near(world_point(scene, arm, 0.5f, {1, 0, 0}), {0.5f + c45, 1 + c45, 0});
    const float c22 = std::cos(kPi / 8), s22 = std::sin(kPi / 8);  // slerp at 1/4: 22.5°
    check_near(world_point(scene, arm, 0.25f, {1, 0, 0}), {0.25f + c22, 1 + s22, 0});
    check_near(world_point(scene, arm, 0.99f, {0, 0, 1}), {0.99f, 1, 1});       // scale still 1 (step)
    check_near(world_point(scene, arm, 1.5f, {1, 0, 0}), {1.5f, 3, 0});         // scale 2, 90°
    check_near(world_point(scene, arm, 1.5f, {0, 0, 1}), {1.5f, 1, 2});
}

template <typename F>
void require_error_naming(const std::filesystem::path& path, F&& load, const std::string& fragment) {
    try {
        load();
        FAIL("no error for " << path);
    } catch (const Error& e) {
        const std::string message = e.what();
        INFO(message);
        CHECK(message.find(path.string()) != std::string::npos);
        CHECK(message.find(fragment) != std::string::npos);
    }
}

}  // namespace

TEST_CASE("glTF hierarchy and animation round trip (.gltf and .glb)", "[gltf]") {
    const auto dir = temp_dir("round_trip");
    GltfBuilder b = robot_arm();
    b.write_gltf(dir / "arm.gltf");
    b.write_glb(dir / "arm.glb");
    for (const char* name : {"arm.gltf", "arm.glb"}) {
        INFO(name);
        const Scene scene = load_scene(dir / name);
        check_robot_arm(scene);
        CHECK(scene.animation.start == 0.0f);
        CHECK(scene.animation.end == 2.0f);
        // Bare mesh file: a Lambert default material and a camera that sees the scene.
        REQUIRE(scene.materials.size() == 1);
        CHECK(scene.materials[0].model == "lambert");
        CHECK(glm::length(scene.camera.position - scene.camera.target) > 1.0f);
    }
}

TEST_CASE("glTF animations on different nodes play together; on the same node the first plays, with a warning",
          "[gltf]") {
    const auto dir = temp_dir("several_animations");
    GltfBuilder b = robot_arm();  // animation 0 moves the base to (2, 0, 0) at t = 2
    b.doc()["animations"][0]["name"] = "First";
    const int times = b.floats({0, 2}, "SCALAR");
    const auto animation = [&](const char* name, int node, std::vector<float> values) {
        b.doc()["animations"].push_back(
            {{"name", name},
             {"samplers", {{{"input", times}, {"output", b.floats(values, "VEC3")}, {"interpolation", "LINEAR"}}}},
             {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", "translation"}}}}}}});
    };
    animation("Second", 1, {0, 0, 0, 5, 0, 0});  // the base again: left out
    animation("Third", 2, {0, 0, 0, 0, 0, 3});   // the empty node: plays
    b.write_glb(dir / "several.glb");
    test::WarningCapture warnings;
    const Scene scene = load_scene(dir / "several.glb");
    check_near(world_point(scene, part_named(scene, "base"), 2.0f, Vec3(0.0f)), {2, 0, 0});
    const auto empty = std::find_if(scene.nodes.begin(), scene.nodes.end(), [](const SceneNode& n) { return n.name == "empty"; });
    REQUIRE(empty != scene.nodes.end());
    check_near(empty->local_at(2.0f).translation, {0, 0, 3});
    REQUIRE(warnings.messages().size() == 1);
    INFO(warnings.messages()[0]);
    CHECK_THAT(warnings.messages()[0], Catch::Contains("several.glb") && Catch::Contains("animation 'Second' keys") &&
                                           Catch::Contains("'First' first") && !Catch::Contains("Third"));
}

TEST_CASE("A scene file's gltf_animations chooses the glTF's animations that play", "[gltf]") {
    const auto dir = temp_dir("chosen_animations");
    GltfBuilder b = robot_arm();  // animation 0 moves the base to (2, 0, 0) at t = 2
    b.doc()["animations"][0]["name"] = "First";
    const int times = b.floats({0, 2}, "SCALAR");
    b.doc()["animations"].push_back(
        {{"name", "Second"},
         {"samplers", {{{"input", times}, {"output", b.floats({0, 0, 0, 5, 0, 0}, "VEC3")}, {"interpolation", "LINEAR"}}}},
         {"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}}}}});
    b.write_glb(dir / "clips.glb");
    const auto base_at_2 = [&](const std::string& keys) {
        test::write_text(dir / "scene.json", R"({ "gltf": "clips.glb", )" + keys + " }");
        const Scene scene = load_scene(dir / "scene.json");
        return world_point(scene, part_named(scene, "base"), 2.0f, Vec3(0.0f));
    };
    check_near(base_at_2(R"("gltf_animations": "Second")"), {5, 0, 0});  // the later clip, no warning needed
    check_near(base_at_2(R"("gltf_animations": ["First"])"), {2, 0, 0});
    check_near(base_at_2(R"("gltf_animations": ["#1"])"), {5, 0, 0});
    // A part entry's glTF too.
    test::write_text(dir / "entry.json", R"({ "parts": [ { "gltf": "clips.glb", "gltf_animations": "Second" } ] })");
    const Scene entry = load_scene(dir / "entry.json");
    check_near(world_point(entry, part_named(entry, "base"), 2.0f, Vec3(0.0f)), {5, 0, 0});
    // A name the file lacks is an error naming the file and what it has.
    CHECK_THROWS_WITH(base_at_2(R"("gltf_animations": "Walk")"),
                      Catch::Contains("clips.glb") && Catch::Contains("no animation 'Walk'") &&
                          Catch::Contains("'First', 'Second'"));
    CHECK_THROWS_WITH(base_at_2(R"("gltf_animations": [])"), Catch::Contains("gltf_animations"));
    test::write_text(dir / "none.json", R"({ "gltf_animations": "First", "parts": [ { "gltf": "clips.glb" } ] })");
    CHECK_THROWS_WITH(load_scene(dir / "none.json"), Catch::Contains("gltf_animations"));
}

TEST_CASE("glTF meshes without normals get computed normals and tangents", "[gltf]") {
    const auto dir = temp_dir("normals");
    robot_arm().write_glb(dir / "arm.glb");
    const Scene scene = load_scene(dir / "arm.glb");
    const Part& base = part_named(scene, "base");  // the square has no NORMAL attribute
    REQUIRE(base.mesh.normals.size() == 4);
    for (const Vec3& n : base.mesh.normals) check_near(n, {0, 0, 1});
    for (const Vec4& t : base.mesh.tangents) check_near(Vec3(t), {1, 0, 0});
    const Part& arm = part_named(scene, "arm");  // given normals are kept
    for (const Vec3& n : arm.mesh.normals) check_near(n, {0, 1, 0});
}

TEST_CASE("glTF degenerate triangles: one warning per file, each mesh counted once", "[gltf]") {
    const auto dir = temp_dir("degenerate");
    GltfBuilder b;
    // The square plus two degenerate triangles (repeated index; collinear),
    // used by two nodes; a clean triangle mesh on a third node.
    std::vector<float> positions = kSquare;
    positions.insert(positions.end(), {2, 2, 0});  // vertex 4: on the diagonal 0-2
    const int square = b.mesh(positions, {0, 1, 2, 0, 2, 3, 1, 1, 2, 0, 2, 4});
    const int clean = b.mesh({0, 0, 0, 1, 0, 0, 0, 0, 1}, {});
    b.node({{"name", "a"}, {"mesh", square}});
    b.node({{"name", "b"}, {"mesh", square}});
    b.node({{"name", "c"}, {"mesh", clean}});
    b.write_glb(dir / "degenerate.glb");
    test::WarningCapture warnings;
    const Scene scene = load_scene(dir / "degenerate.glb");
    REQUIRE(scene.parts.size() == 3);
    CHECK(part_named(scene, "a").mesh.triangle_count() == 2);
    REQUIRE(warnings.messages().size() == 1);
    CHECK(warnings.messages()[0] == (dir / "degenerate.glb").string() + ": 2 degenerate triangles dropped");
}

TEST_CASE("Cubic-spline glTF channels and node matrices", "[gltf]") {
    const auto dir = temp_dir("cubic");
    GltfBuilder b;
    const int square = b.mesh(kSquare, kSquareIndices);
    // Matrix: translate (1, 2, 3) · rotate 90° about y · scale 2 (column-major).
    const Mat4 m = glm::scale(glm::rotate(glm::translate(Mat4(1), Vec3(1, 2, 3)), kPi / 2, Vec3(0, 1, 0)), Vec3(2));
    std::vector<float> matrix(&m[0][0], &m[0][0] + 16);
    b.node({{"name", "fixed"}, {"mesh", square}, {"matrix", matrix}});
    const int moving = b.node({{"name", "moving"}, {"mesh", square}});
    // Keys (in, value, out): value 0 → 1 along x, tangents 0: smoothstep.
    b.channel(moving, "translation", "CUBICSPLINE", {0, 1}, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0});
    b.write_glb(dir / "cubic.glb");
    const Scene scene = load_scene(dir / "cubic.glb");
    check_near(world_point(scene, part_named(scene, "fixed"), 0, {1, 0, 0}), Vec3(m * Vec4(1, 0, 0, 1)));
    check_near(world_point(scene, part_named(scene, "fixed"), 0, {1, 0, 0}), {1, 2, 1});
    check_near(world_point(scene, part_named(scene, "moving"), 0.25f, {0, 0, 0}), {3 * 0.0625f - 2 * 0.015625f, 0, 0});
}

TEST_CASE("Corrupt glTF files are refused with the file name", "[gltf][bad-input]") {
    const auto dir = temp_dir("corrupt");
    GltfBuilder good = robot_arm();
    good.write_glb(dir / "good.glb");

    SECTION("truncated .glb") {
        std::ifstream in(dir / "good.glb", std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), {});
        for (size_t keep : {size_t(8), size_t(30), bytes.size() / 2, bytes.size() - 5}) {
            const auto path = dir / fmt::format("truncated{}.glb", keep);
            std::ofstream(path, std::ios::binary).write(bytes.data(), keep);
            require_error_naming(path, [&] { load_scene(path); }, "");
        }
    }
    SECTION("mislabeled") {
        good.write_gltf(dir / "text.gltf");
        std::filesystem::copy_file(dir / "text.gltf", dir / "text_named.glb", std::filesystem::copy_options::overwrite_existing);
        require_error_naming(dir / "text_named.glb", [&] { load_scene(dir / "text_named.glb"); }, "mislabeled");
        std::filesystem::copy_file(dir / "good.glb", dir / "binary_named.gltf", std::filesystem::copy_options::overwrite_existing);
        require_error_naming(dir / "binary_named.gltf", [&] { load_scene(dir / "binary_named.gltf"); }, "mislabeled");
    }
    SECTION("out-of-range vertex index") {
        GltfBuilder b;
        b.node({{"name", "bad"}, {"mesh", b.mesh(kSquare, {0, 1, 7})}});
        b.write_glb(dir / "bad_index.glb");
        require_error_naming(dir / "bad_index.glb", [&] { load_scene(dir / "bad_index.glb"); }, "is 7, out of range for 4 vertices");
    }
    SECTION("out-of-range accessor, buffer view and byte range") {
        GltfBuilder b = robot_arm();
        b.doc()["meshes"][0]["primitives"][0]["indices"] = 99;
        b.write_gltf(dir / "bad_accessor.gltf");
        require_error_naming(dir / "bad_accessor.gltf", [&] { load_scene(dir / "bad_accessor.gltf"); }, "");

        GltfBuilder c = robot_arm();
        c.doc()["accessors"][0]["count"] = 1000;  // overruns its buffer view
        c.write_glb(dir / "overrun.glb");
        require_error_naming(dir / "overrun.glb", [&] { load_scene(dir / "overrun.glb"); }, "");

        GltfBuilder d = robot_arm();
        d.doc()["nodes"][1]["children"] = {5};
        d.write_glb(dir / "bad_child.glb");
        require_error_naming(dir / "bad_child.glb", [&] { load_scene(dir / "bad_child.glb"); }, "");
    }
    SECTION("missing external buffer") {
        good.write_gltf(dir / "lonely.gltf");
        std::filesystem::remove(dir / "lonely.bin");
        require_error_naming(dir / "lonely.gltf", [&] { load_scene(dir / "lonely.gltf"); }, "");
    }
    SECTION("bad animation") {
        GltfBuilder b = robot_arm();
        b.doc()["animations"][0]["channels"][0]["target"]["node"] = 42;
        b.write_glb(dir / "bad_target.glb");
        require_error_naming(dir / "bad_target.glb", [&] { load_scene(dir / "bad_target.glb"); }, "target node 42 is out of range");
    }
    SECTION("NaN positions") {
        GltfBuilder b;
        std::vector<float> square = kSquare;
        square[4] = std::numeric_limits<float>::quiet_NaN();
        b.node({{"name", "nan"}, {"mesh", b.mesh(square, kSquareIndices)}});
        b.write_glb(dir / "nan.glb");
        require_error_naming(dir / "nan.glb", [&] { load_scene(dir / "nan.glb"); }, "non-finite position");
    }
}

TEST_CASE("The scene-file example of docs/SCENE_FORMAT.md loads", "[scene][gltf]") {
    // Extract the JSON example from the document, and give it the files it names.
    std::ifstream doc(std::filesystem::path(RSL_SOURCE_DIR) / "docs/SCENE_FORMAT.md");
    REQUIRE(doc);
    const std::string text((std::istreambuf_iterator<char>(doc)), {});
    const size_t begin = text.find("```json\n");
    REQUIRE(begin != std::string::npos);
    const size_t end = text.find("```", begin + 8);
    const std::string example = text.substr(begin + 8, end - begin - 8);

    const auto root = temp_dir("doc_example");
    const auto scenes = root / "scenes", generated = root / "generated";
    std::filesystem::create_directories(scenes);
    std::filesystem::create_directories(generated);
    std::ofstream(scenes / "robot.json") << example;
    GltfBuilder robot;
    const int square = robot.mesh(kSquare, kSquareIndices);
    const int head = robot.node({{"name", "head"}, {"mesh", square}, {"translation", {0, 1, 0}}});
    robot.node({{"name", "torso"}, {"mesh", square}, {"children", {head}}});
    const float s45 = std::sin(kPi / 4);
    robot.channel(head, "rotation", "LINEAR", {0, 4}, {0, 0, 0, 1, 0, s45, 0, s45});  // 0 → 90° about y
    robot.write_glb(generated / "robot.glb");
    std::ofstream(generated / "ground.obj") << "v -5 0 -5\nv 5 0 -5\nv 5 0 5\nv -5 0 5\nf 1 4 3 2\n";
    write_exr(generated / "sunsky.exr", Image(8, 4));
    write_exr(generated / "overcast.exr", Image(8, 4));

    const Scene scene = load_scene(scenes / "robot.json");
    CHECK(scene.name == "robot");
    REQUIRE(scene.parts.size() == 3);
    auto material_of = [&](const std::string& part) { return scene.materials.at(part_named(scene, part).material); };
    CHECK(material_of("torso").name == "steel");
    CHECK(material_of("torso").model == "phong");
    CHECK(material_of("torso").params.at("exponent") == std::vector<float>{60});
    CHECK(material_of("torso").params.at("ks") == std::vector<float>{0.6f, 0.6f, 0.6f});
    CHECK(material_of("head").name == "default");
    CHECK(material_of("ground").name == "floor");
    CHECK(part_named(scene, "ground").mesh.triangle_count() == 2);
    // Head: slerp from identity to 90° about y over [0, 4] → 45° at t = 2, then + (0, 1, 0).
    check_near(world_point(scene, part_named(scene, "head"), 2, {1, 0, 0}), {s45, 1, -s45});

    CHECK(scene.environment.file == scenes / "../generated/sunsky.exr");
    CHECK(scene.environment.second_file == scenes / "../generated/overcast.exr");
    CHECK(scene.environment.resolution == 32);
    CHECK(scene.environment.rotation_degrees_per_second == 20);
    CHECK(scene.environment.blend_period_seconds == 8);
    const Mat3 r = scene.environment.rotation_at(4.5f);  // 90° about +y: x → −z
    check_near(r * Vec3(1, 0, 0), {0, 0, -1});

    REQUIRE(scene.lights.size() == 1);
    CHECK(scene.lights[0].radius == Approx(0.05f));
    check_near(scene.lights[0].power, {20, 18, 15});
    check_near(scene.lights[0].position_at(scene, 1), {0, 2, 1});
    check_near(scene.camera.position_at(2), {1.5f, 1.5f, 4.5f});
    check_near(scene.camera.target_at(2), {0, 1, 0});
    CHECK(scene.camera.fov_y_degrees == 40);
    CHECK(scene.camera.width == 640);
    CHECK(scene.animation.end == 4);
    CHECK(scene.animation.fps == 24);
    CHECK(scene.precompute.svdf_clusters == 256);
    CHECK(scene.precompute.ovdf_outer_radius == Approx(6.0f));
    CHECK(scene.precompute.ovdf_inner_radius == 0.0f);  // "auto": per mesh

    // glTF parts entry with a transform: its nodes hang below the entry's node.
    const std::string with_gltf_part = std::regex_replace(
        example, std::regex(R"("obj": "../generated/ground.obj")"), R"("gltf": "../generated/robot.glb")");
    std::ofstream(scenes / "two_robots.json") << with_gltf_part;
    const Scene two = load_scene(scenes / "two_robots.json");
    REQUIRE(two.parts.size() == 4);
    CHECK(part_named(two, "ground/torso").material == part_named(two, "ground/head").material);
    CHECK(two.materials.at(part_named(two, "ground/torso").material).name == "floor");
}
