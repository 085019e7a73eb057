// glTF files as exporters write them: the default scene only, cameras,
// KHR_lights_punctual, skins (segments on their joints) and morph targets (base shape, one warning),
// sparse accessors, required extensions. Expected values are computed by
// hand from the node transforms the files are written with.
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "src/core/error.h"
#include "src/core/scene.h"
#include "src/core/sphere_light.h"
#include "tests/formats/gltf_builder.h"
#include "tests/test_support.h"
#include "src/formats/gltf_file.h"
#include "src/formats/scene_file.h"
#include "src/shading/squares.h"

using namespace rsl;
using test::GltfBuilder;
using Json = nlohmann::json;

namespace {

const std::vector<float> kSquare{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::vector<uint32_t> kSquareIndices{0, 1, 2, 0, 2, 3};

std::filesystem::path temp_dir(const std::string& name) { return test::scratch_dir("gltf_scene_" + name); }

void check_near(Vec3 a, Vec3 b, float tolerance = 1e-5f) {
    INFO("(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y << ", " << b.z << ")");
    CHECK(glm::length(a - b) < tolerance);
}

std::vector<std::string> part_names(const Scene& scene) {
    std::vector<std::string> names;
    for (const Part& p : scene.parts) names.push_back(p.name);
    return names;
}

// glTF (x, y, z, w) of a rotation by `degrees` about a unit axis.
std::vector<float> rotation_xyzw(Vec3 axis, float degrees) {
    const Quat q = glm::angleAxis(glm::radians(degrees), axis);
    return {q.x, q.y, q.z, q.w};
}

void require_error(const std::filesystem::path& path, const std::vector<std::string>& fragments) {
    const std::string message = test::error_of([&] { load_scene(path); });
    INFO(message);
    REQUIRE(!message.empty());
    CHECK(message.find(path.string()) != std::string::npos);
    for (const std::string& f : fragments) CHECK(message.find(f) != std::string::npos);
}

// Two scenes: scene 0 holds "first"; scene 1 holds "base" (translated
// (0, 0, 2)) with its child "top", and an animated node of scene 0.
GltfBuilder two_scenes() {
    GltfBuilder b;
    const int square = b.mesh(kSquare, kSquareIndices);
    const int first = b.node({{"name", "first"}, {"mesh", square}});
    const int top = b.node({{"name", "top"}, {"mesh", square}, {"translation", {0, 1, 0}}});
    const int base = b.node({{"name", "base"}, {"mesh", square}, {"translation", {0, 0, 2}}, {"children", {top}}});
    b.channel(first, "translation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0});
    b.doc()["scenes"] = {{{"nodes", {first}}}, {{"nodes", {base}}}};
    return b;
}

}  // namespace

TEST_CASE("glTF: only the default scene's nodes load (`scene`, else scene 0; no scenes: every root)", "[gltf]") {
    const auto dir = temp_dir("default");
    GltfBuilder b = two_scenes();
    b.write_gltf(dir / "implicit.gltf");  // no `scene`: scene 0
    b.doc()["scene"] = 1;
    b.write_gltf(dir / "second.gltf");
    b.doc()["scene"] = 2;
    b.write_gltf(dir / "out_of_range.gltf");
    b.doc().erase("scene");
    b.doc().erase("scenes");
    b.write_gltf(dir / "no_scenes.gltf");

    const Scene implicit = load_scene(dir / "implicit.gltf");
    CHECK(part_names(implicit) == std::vector<std::string>{"first"});
    CHECK(implicit.nodes.size() == 1);
    CHECK(implicit.animation.end == 1.0f);  // its animation loads with it

    const Scene second = load_scene(dir / "second.gltf");
    REQUIRE(part_names(second) == std::vector<std::string>{"top", "base"});
    CHECK(second.nodes.size() == 2);
    CHECK(second.nodes[second.parts[0].node].parent == second.parts[1].node);
    check_near(Vec3(second.part_transform_at(0, 0)[3]), {0, 1, 2});
    CHECK(second.animation.end == 0.0f);  // the channel of a node outside the scene is dropped

    CHECK(part_names(load_scene(dir / "no_scenes.gltf")) == std::vector<std::string>{"first", "top", "base"});
    require_error(dir / "out_of_range.gltf", {"scene 2", "out of range (2 scenes)"});
}

TEST_CASE("glTF camera: the first perspective camera node of the default scene, when the scene file has none",
          "[gltf]") {
    const auto dir = temp_dir("camera");
    GltfBuilder b;
    const int square = b.mesh(kSquare, kSquareIndices);
    b.doc()["cameras"] = {{{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}},
                          {{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}, {"aspectRatio", 1.5}}}}};
    // rig: translated (0, 1, 5), turned 90° about +y; its child camera at
    // (0, 0, 1) in the rig, tilted 30° down about its x axis.
    const int ortho = b.node({{"name", "ortho"}, {"camera", 0}});
    const int camera = b.node({{"name", "lens"}, {"camera", 1}, {"translation", {0, 0, 1}},
                               {"rotation", rotation_xyzw({1, 0, 0}, -30)}});
    const int rig = b.node({{"name", "rig"}, {"translation", {0, 1, 5}}, {"rotation", rotation_xyzw({0, 1, 0}, 90)},
                            {"children", {camera}}});
    const int ground = b.node({{"name", "ground"}, {"mesh", square}});
    b.doc()["scenes"] = {{{"nodes", {ortho, rig, ground}}}};
    b.write_gltf(dir / "camera.gltf");

    const Mat3 turn = Mat3(glm::rotate(Mat4(1), glm::radians(90.0f), Vec3(0, 1, 0)));
    const Mat3 tilt = Mat3(glm::rotate(Mat4(1), glm::radians(-30.0f), Vec3(1, 0, 0)));
    const Vec3 position = Vec3(0, 1, 5) + turn * Vec3(0, 0, 1);
    const Vec3 forward = turn * tilt * Vec3(0, 0, -1), up = turn * tilt * Vec3(0, 1, 0);

    SECTION("a bare glTF") {
        test::WarningCapture warnings;
        const Scene scene = load_scene(dir / "camera.gltf");
        REQUIRE(scene.gltf_camera);
        CHECK(scene.gltf_camera->name == "lens");
        CHECK(scene.gltf_camera->used);
        check_near(scene.camera.position, position);
        check_near(glm::normalize(scene.camera.target - scene.camera.position), forward);
        check_near(scene.camera.up, up);
        CHECK(scene.camera.fov_y_degrees == Approx(0.6 * 180 / kPi));
        CHECK(scene.camera.width == 640);  // the size is not the glTF's aspect ratio: defaults
        CHECK(scene.camera.height == 480);
        REQUIRE(warnings.messages().size() == 1);
        CHECK(warnings.messages()[0].find("camera node 'ortho' (orthographic) not used") != std::string::npos);
    }
    SECTION("a scene file with only a size keeps the glTF pose; one with a pose uses its own") {
        test::write_text(dir / "sized.json", R"({ "gltf": "camera.gltf", "camera": { "width": 200, "height": 100 } })");
        const Scene sized = load_scene(dir / "sized.json");
        check_near(sized.camera.position, position);
        CHECK(sized.camera.width == 200);
        CHECK(sized.camera.height == 100);
        test::write_text(dir / "posed.json", R"({ "gltf": "camera.gltf", "camera": { "position": [0, 0, 9] } })");
        const Scene posed = load_scene(dir / "posed.json");
        check_near(posed.camera.position, {0, 0, 9});
        CHECK_FALSE(posed.gltf_camera->used);
    }
    SECTION("an animated camera node gives keyed paths") {
        b.channel(rig, "translation", "LINEAR", {0, 2}, {0, 1, 5, 4, 1, 5});
        b.write_gltf(dir / "moving.gltf");
        const Scene scene = load_scene(dir / "moving.gltf");
        REQUIRE(scene.camera.position_path);
        REQUIRE(scene.camera.target_path);
        for (float t : {0.0f, 0.5f, 1.3f, 2.0f}) {
            check_near(scene.camera.position_at(t), position + Vec3(2 * t, 0, 0), 1e-4f);
            check_near(glm::normalize(scene.camera.target_at(t) - scene.camera.position_at(t)), forward, 1e-4f);
        }
    }
    SECTION("yfov out of range is refused") {
        b.doc()["cameras"][1]["perspective"]["yfov"] = 3.5;
        b.write_gltf(dir / "wide.gltf");
        require_error(dir / "wide.gltf", {"camera 1 on node 'lens'", "yfov 3.5"});
    }
}

namespace {

// A lamp (point, under a translated parent), a spot turned to point down,
// a directional sun and an animated point light.
GltfBuilder lights_file() {
    GltfBuilder b;
    const int square = b.mesh(kSquare, kSquareIndices);
    b.doc()["extensionsUsed"] = {"KHR_lights_punctual"};
    b.doc()["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"name", "bulb"}, {"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 3.0}},
        {{"name", "cone"}, {"type", "spot"}, {"intensity", 2.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}},
        {{"name", "sun"}, {"type", "directional"}, {"intensity", 5.0}},
        {{"name", "ranged"}, {"type", "point"}, {"range", 4.0}}};
    const auto light = [](int index) { return Json{{"KHR_lights_punctual", {{"light", index}}}}; };
    const int lamp = b.node({{"name", "lamp"}, {"translation", {0, 1, 0}}, {"extensions", light(0)}});
    const int shelf = b.node({{"name", "shelf"}, {"translation", {1, 0, 0}}, {"children", {lamp}}});
    const int spot = b.node({{"name", "spot"}, {"translation", {0, 2, 0}}, {"rotation", rotation_xyzw({1, 0, 0}, -90)},
                             {"extensions", light(1)}});
    const int sun = b.node({{"name", "sun"}, {"rotation", rotation_xyzw({1, 0, 0}, -60)}, {"extensions", light(2)}});
    const int mover = b.node({{"name", "mover"}, {"extensions", light(3)}});
    const int ground = b.node({{"name", "ground"}, {"mesh", square}});
    b.channel(mover, "translation", "LINEAR", {0, 1}, {0, 0, 0, 0, 2, 0});
    b.doc()["scenes"] = {{{"nodes", {shelf, spot, sun, mover, ground}}}};
    return b;
}

}  // namespace

TEST_CASE("KHR_lights_punctual: point and spot lights become sphere lights on their nodes, directional ones suns",
          "[gltf]") {
    const auto dir = temp_dir("lights");
    GltfBuilder b = lights_file();
    b.write_gltf(dir / "lights.gltf");
    test::WarningCapture warnings;
    const Scene scene = load_scene(dir / "lights.gltf");
    REQUIRE(scene.lights.size() == 3);  // the directional light is a sun of the environment
    REQUIRE(scene.environment.suns.size() == 1);
    const SunLight& sun = scene.environment.suns[0];
    CHECK(sun.name == "sun");
    check_near(sun.irradiance, Color(5.0f));  // lux read as irradiance, white by default
    // Against its node's −Z, turned −60° about x: up and towards +Z.
    check_near(sun.direction_at(scene, 0.0f), {0.0f, std::sin(kPi / 3.0f), std::cos(kPi / 3.0f)});
    // A bare glTF has no map: a uniform white sky lights it with its suns.
    CHECK(scene.environment.uniform == Color(1.0f));
    CHECK(scene.environment.present());
    const LocalLight& lamp = scene.lights[0];
    CHECK(lamp.name == "lamp");
    CHECK(lamp.radius == kGltfLightRadius);
    CHECK_FALSE(lamp.spot);
    check_near(lamp.position_at(scene, 0), {1, 1, 0});
    // Φ = 4π·I·colour: on its axis the sphere has intensity L·πa² = I.
    check_near(lamp.power, 4 * kPi * 3.0f * Vec3(1.0f, 0.5f, 0.25f), 1e-4f);
    CHECK(luminance(sphere_light_radiance(lamp)) * kPi * lamp.radius * lamp.radius ==
          Approx(3.0f * luminance(Color(1.0f, 0.5f, 0.25f))));
    CHECK(spot_cone_scale_offset(lamp) == Vec2(0, 1));

    const LocalLight& spot = scene.lights[1];
    CHECK(spot.spot);
    CHECK(spot.inner_cone_radians == Approx(0.2f));
    CHECK(spot.outer_cone_radians == Approx(0.5f));
    check_near(spot.position_at(scene, 0), {0, 2, 0});
    check_near(spot.axis_at(scene, 0), {0, -1, 0});
    check_near(spot.axis, {0, -1, 0});  // its pose at the start, for what edits lights

    const LocalLight& mover = scene.lights[2];
    check_near(mover.position_at(scene, 0.5f), {0, 1, 0});
    check_near(mover.power, Color(4 * kPi), 1e-5f);  // defaults: white, intensity 1

    REQUIRE(warnings.messages().size() == 1);
    CHECK(warnings.messages()[0].find("the range of light 'mover' is ignored") != std::string::npos);
    for (const std::string& m : warnings.messages()) CHECK(m.find((dir / "lights.gltf").string()) == 0);

    SECTION("the scene file sets radii by node name, \"*\" for the rest") {
        test::write_text(dir / "radii.json", R"({ "gltf": "lights.gltf", "light_radii": { "*": 0.2, "spot": 0.01 },
            "lights": [ { "radius": 0.3, "position": [0, 5, 0] } ] })");
        const Scene s = load_scene(dir / "radii.json");
        REQUIRE(s.lights.size() == 4);
        CHECK(s.environment.suns.size() == 1);       // the glTF's sun comes along
        CHECK(s.environment.uniform == Color(0.0f));  // a scene file says what lights it
        CHECK(s.lights[0].radius == 0.2f);
        CHECK(s.lights[1].radius == 0.01f);
        CHECK(s.lights[2].radius == 0.2f);
        CHECK(s.lights[3].radius == 0.3f);  // a scene-file light keeps its own
        test::write_text(dir / "typo.json", R"({ "gltf": "lights.gltf", "light_radii": { "lmap": 0.2 } })");
        require_error(dir / "typo.json", {"light_radii.lmap", "no glTF light"});
    }
    SECTION("bad lights are refused, naming the file and the light") {
        b.doc()["extensions"]["KHR_lights_punctual"]["lights"][1]["spot"]["innerConeAngle"] = 0.6;
        b.write_gltf(dir / "cone.gltf");
        require_error(dir / "cone.gltf", {"light 1 ('cone') on node 'spot'", "cone angles 0.6 .. 0.5"});
        b = lights_file();
        b.doc()["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 7;
        b.write_gltf(dir / "index.gltf");
        require_error(dir / "index.gltf", {"node 'lamp'", "light index 7 is out of range (4 lights)"});
        b = lights_file();
        b.doc()["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = -1.0;
        b.write_gltf(dir / "negative.gltf");
        require_error(dir / "negative.gltf", {"light 0 ('bulb')", "intensity -1"});
    }
}

TEST_CASE("glTF's spot cone falloff: 1 inside the inner cone, 0 outside the outer, glTF's formula between",
          "[gltf][shading]") {
    LocalLight light;
    light.spot = true;
    light.inner_cone_radians = 0.3f;
    light.outer_cone_radians = 0.7f;
    const Vec2 cone = spot_cone_scale_offset(light);
    const Vec3 axis(0, -1, 0);
    for (int k = 0; k <= 100; ++k) {
        const float angle = 1.2f * float(k) / 100.0f;
        const Vec3 w(std::sin(angle), -std::cos(angle), 0);
        // KHR_lights_punctual's reference: ((cos θ − cos θo) / (cos θi − cos θo)) clamped, squared.
        const float t = std::clamp((std::cos(angle) - std::cos(0.7f)) / (std::cos(0.3f) - std::cos(0.7f)), 0.0f, 1.0f);
        INFO("angle " << angle);
        CHECK(shading::spot_cone_factor(axis, w, cone.x, cone.y) == Approx(t * t).margin(1e-5));
        CHECK(spot_cone_factor_at(Vec3(2, 3, 0) + 1.5f * w, Vec3(2, 3, 0), axis, cone) ==
              Approx(t * t).margin(1e-5));
        if (angle <= 0.3f) CHECK(shading::spot_cone_factor(axis, w, cone.x, cone.y) == Approx(1.0f));
        if (angle >= 0.7f) CHECK(shading::spot_cone_factor(axis, w, cone.x, cone.y) == 0.0f);
    }
    light.spot = false;
    CHECK(shading::spot_cone_factor(axis, Vec3(0, 1, 0), spot_cone_scale_offset(light).x,
                                    spot_cone_scale_offset(light).y) == 1.0f);
}

TEST_CASE("glTF skins move with their joints; morph targets render in the base shape, with one warning naming them",
          "[gltf]") {
    const auto dir = temp_dir("skin");
    GltfBuilder b;
    const int body = b.mesh(kSquare, kSquareIndices);
    const int face = b.mesh({0, 0, 0, 1, 0, 0, 0, 1, 0}, {});
    b.doc()["meshes"][body]["name"] = "body";
    b.doc()["meshes"][face]["name"] = "face";
    // body: JOINTS_0/WEIGHTS_0 and a skin of one joint; face: one morph target.
    const std::vector<float> joints(4 * 4, 0.0f), weights{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    b.doc()["meshes"][body]["primitives"][0]["attributes"]["JOINTS_0"] = b.floats(joints, "VEC4");
    b.doc()["meshes"][body]["primitives"][0]["attributes"]["WEIGHTS_0"] = b.floats(weights, "VEC4");
    b.doc()["meshes"][face]["primitives"][0]["targets"] = {{{"POSITION", b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3")}}};
    b.doc()["meshes"][face]["weights"] = {1.0};
    const std::vector<float> identity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const int bone = b.node({{"name", "bone"}, {"rotation", rotation_xyzw({0, 0, 1}, 45)}});
    const int skinned = b.node({{"name", "skinned"}, {"mesh", body}, {"skin", 0}});
    const int morphed = b.node({{"name", "morphed"}, {"mesh", face}});
    b.doc()["skins"] = {{{"joints", {bone}}, {"inverseBindMatrices", b.floats(identity, "MAT4")}}};
    b.doc()["scenes"] = {{{"nodes", {bone, skinned, morphed}}}};
    b.write_glb(dir / "skin.glb");
    test::WarningCapture warnings;
    const Scene scene = load_scene(dir / "skin.glb");
    REQUIRE(scene.parts.size() == 2);
    // The skinned mesh: one segment on the bone (identity bind matrix), turned with it.
    CHECK(scene.parts[0].name == "skinned/bone");
    REQUIRE(scene.parts[0].skin);
    CHECK(scene.nodes[size_t(scene.parts[0].node)].name == "bone");
    const Mat4 bone_world = scene.part_transform_at(0, 0.0f);
    for (size_t v = 0; v < 4; ++v) {
        const Vec3 p(kSquare[3 * v], kSquare[3 * v + 1], kSquare[3 * v + 2]);
        check_near(scene.parts[0].mesh.positions[v], p);
        check_near(Vec3(bone_world * Vec4(scene.parts[0].mesh.positions[v], 1.0f)),
                   Vec3(glm::angleAxis(glm::radians(45.0f), Vec3(0, 0, 1)) * p));
    }
    check_near(scene.parts[1].mesh.positions[0], {0, 0, 0});  // not the morph target's z = 1
    REQUIRE(warnings.messages().size() == 1);
    const std::string& w = warnings.messages()[0];
    INFO(w);
    CHECK(w.find((dir / "skin.glb").string()) == 0);
    CHECK(w.find("body") == std::string::npos);
    CHECK(w.find("mesh 'face' of node 'morphed' (morph targets) renders without its morph targets") != std::string::npos);
}

TEST_CASE("glTF skins: a second joint set needs both halves, and a third is refused, naming the file", "[gltf]") {
    const auto dir = temp_dir("skin_sets");
    const std::vector<float> zeros(4 * 4, 0.0f), weights{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    const std::vector<float> identity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const auto skinned_square = [&](const std::vector<std::string>& extra, const std::string& name) {
        GltfBuilder b;
        const int body = b.mesh(kSquare, kSquareIndices);
        Json& attributes = b.doc()["meshes"][body]["primitives"][0]["attributes"];
        attributes["JOINTS_0"] = b.floats(zeros, "VEC4");
        attributes["WEIGHTS_0"] = b.floats(weights, "VEC4");
        for (const std::string& a : extra) attributes[a] = b.floats(zeros, "VEC4");
        const int bone = b.node({{"name", "bone"}});
        const int skinned = b.node({{"name", "skinned"}, {"mesh", body}, {"skin", 0}});
        b.doc()["skins"] = {{{"joints", {bone}}, {"inverseBindMatrices", b.floats(identity, "MAT4")}}};
        b.doc()["scenes"] = {{{"nodes", {bone, skinned}}}};
        b.write_glb(dir / name);
        return dir / name;
    };
    // Both halves of set 1 (zero weights): it loads, the square on its one joint.
    const Scene scene = load_scene(skinned_square({"JOINTS_1", "WEIGHTS_1"}, "two_sets.glb"));
    REQUIRE(scene.parts.size() == 1);
    REQUIRE(scene.parts[0].skin);
    CHECK(scene.parts[0].skin->weights[0][0] == 1.0f);
    CHECK_THROWS_WITH(load_scene(skinned_square({"JOINTS_1"}, "half_set.glb")),
                      Catch::Contains("half_set.glb") && Catch::Contains("it has JOINTS_1 but the primitive has no WEIGHTS_1"));
    CHECK_THROWS_WITH(load_scene(skinned_square({"JOINTS_1", "WEIGHTS_1", "JOINTS_2", "WEIGHTS_2"}, "three_sets.glb")),
                      Catch::Contains("three_sets.glb") && Catch::Contains("JOINTS_2/WEIGHTS_2") &&
                          Catch::Contains("at most eight"));
}

TEST_CASE("glTF sparse accessors: base values (or zeros) with the sparse values at their indices", "[gltf]") {
    const auto dir = temp_dir("sparse");
    // Base: the unit square; sparse: vertex 2 moves to (2, 2, 0), vertex 0 to (0, 0, 1).
    const std::vector<uint16_t> indices{0, 2};
    const std::vector<float> values{0, 0, 1, 2, 2, 0};
    const auto square_with = [&](int positions, GltfBuilder& b) {
        Json primitive = {{"attributes", {{"POSITION", positions}}}, {"indices", b.indices(kSquareIndices)}};
        b.doc()["meshes"].push_back({{"primitives", Json::array({primitive})}});
        b.node({{"name", "square"}, {"mesh", 0}});
    };
    SECTION("over a base") {
        GltfBuilder b;
        square_with(b.sparse_floats(kSquare, 4, "VEC3", indices, values), b);
        b.write_glb(dir / "based.glb");
        const Scene scene = load_scene(dir / "based.glb");
        const std::vector<Vec3>& p = scene.parts[0].mesh.positions;
        REQUIRE(p.size() == 4);
        check_near(p[0], {0, 0, 1});
        check_near(p[1], {1, 0, 0});
        check_near(p[2], {2, 2, 0});
        check_near(p[3], {0, 1, 0});
    }
    SECTION("over zeros (no buffer view)") {
        GltfBuilder b;
        square_with(b.sparse_floats({}, 4, "VEC3", {1, 2, 3}, {1, 0, 0, 1, 1, 0, 0, 1, 0}), b);
        b.write_gltf(dir / "zeros.gltf");
        const Scene scene = load_scene(dir / "zeros.gltf");
        const std::vector<Vec3>& p = scene.parts[0].mesh.positions;
        REQUIRE(p.size() == 4);
        for (size_t v = 0; v < 4; ++v) check_near(p[v], {kSquare[3 * v], kSquare[3 * v + 1], kSquare[3 * v + 2]});
    }
    SECTION("corrupt sparse data is refused, naming the file and the accessor") {
        GltfBuilder b;
        const int a = b.sparse_floats(kSquare, 4, "VEC3", indices, values);
        square_with(a, b);
        Json good = b.doc();
        b.doc()["bufferViews"][b.doc()["accessors"][a]["sparse"]["indices"]["bufferView"].get<int>()]["byteLength"] = 2;
        b.write_gltf(dir / "short_indices.gltf");
        require_error(dir / "short_indices.gltf", {"accessor 0 (sparse) indices", "2 elements", "overrun"});
        b.doc() = good;
        b.doc()["accessors"][a]["sparse"]["count"] = 5;
        b.write_gltf(dir / "count.gltf");
        require_error(dir / "count.gltf", {"accessor 0 (sparse)", "5 sparse elements for an accessor of 4"});
        b.doc() = good;
        b.doc()["accessors"][a]["sparse"]["values"]["byteOffset"] = 8;
        b.write_gltf(dir / "values.gltf");
        require_error(dir / "values.gltf", {"accessor 0 (sparse) values", "overrun"});
        b.doc() = good;
        b.doc()["accessors"][a]["sparse"]["indices"]["componentType"] = 5126;
        b.write_gltf(dir / "float_indices.gltf");
        require_error(dir / "float_indices.gltf", {"accessor 0 (sparse)", "not an unsigned integer"});
        // An index past the accessor's count.
        GltfBuilder c;
        square_with(c.sparse_floats(kSquare, 4, "VEC3", {0, 9}, values), c);
        c.write_gltf(dir / "index.gltf");
        require_error(dir / "index.gltf", {"accessor 0 (sparse)", "index 1 is 9, out of range for 4 elements"});
        // Zero-filled elements beyond what any mesh holds.
        GltfBuilder d;
        square_with(d.sparse_floats({}, size_t(1) << 40, "VEC3", indices, values), d);
        d.write_gltf(dir / "huge.gltf");
        require_error(dir / "huge.gltf", {"accessor 0", "zero-filled elements"});
    }
}

TEST_CASE("glTF extensions: a required one rsl does not support is refused by name; used ones are listed",
          "[gltf]") {
    const auto dir = temp_dir("extensions");
    GltfBuilder b;
    b.node({{"name", "square"}, {"mesh", b.mesh(kSquare, kSquareIndices)}});
    b.doc()["extensionsUsed"] = {"KHR_lights_punctual", "KHR_draco_mesh_compression", "KHR_materials_clearcoat"};
    b.doc()["extensionsRequired"] = {"KHR_lights_punctual"};
    b.write_gltf(dir / "used.gltf");
    const Scene scene = load_scene(dir / "used.gltf");  // honoured when required; others only used
    REQUIRE(scene.gltf_files.size() == 1);
    CHECK(scene.gltf_files[0].extensions_used.size() == 3);
    CHECK(gltf_extension_honoured("KHR_lights_punctual"));
    CHECK(gltf_extension_support("KHR_lights_punctual").rfind("honoured", 0) == 0);
    CHECK(gltf_extension_support("KHR_draco_mesh_compression").rfind("not supported", 0) == 0);
    CHECK(gltf_extension_support("EXT_unheard_of") == "not supported: unknown to rsl");

    b.doc()["extensionsRequired"] = {"KHR_lights_punctual", "KHR_draco_mesh_compression"};
    b.write_gltf(dir / "draco.gltf");
    require_error(dir / "draco.gltf", {"requires the glTF extension KHR_draco_mesh_compression"});
    test::write_text(dir / "draco.json", R"({ "gltf": "draco.gltf" })");
    require_error(dir / "draco.json", {"draco.gltf", "KHR_draco_mesh_compression"});
}
