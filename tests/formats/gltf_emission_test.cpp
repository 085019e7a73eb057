// glTF emission: emissiveFactor, emissiveTexture (sRGB-encoded, read at the
// material's texture coordinates) and KHR_materials_emissive_strength read
// into MaterialDesc::emissive and emissive_texture; bad values refused naming
// the file and the material; `rsl info` shows the emission.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <regex>

#include <nlohmann/json.hpp>

#include "src/core/scene.h"
#include "src/core/scene_limits.h"
#include "src/formats/image_file.h"
#include "src/formats/scene_file.h"
#include "tests/formats/gltf_builder.h"
#include "tests/test_support.h"
#include "tools/assets/model.h"
#include "tools/assets/pbr_scene.h"
#include "tools/assets/primitives.h"

namespace rsl {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

const MaterialDesc& material_named(const Scene& scene, const std::string& name) {
    for (const MaterialDesc& m : scene.materials)
        if (m.name == name) return m;
    FAIL("no material " << name);
    throw 0;
}

// A screen (emission past 1: factor × strength, and a texture), a lamp
// (factor only) and a plain ground, written by tinygltf's writer as an exporter would.
assets::GeneratedModel emissive_model() {
    assets::GeneratedModel model;
    MaterialDesc screen = assets::gltf_pbr_material("screen", Color(0.2f), 0.0f, 0.5f);
    screen.emissive = Color(3.0f, 1.5f, 0.6f);
    screen.emissive_texture = assets::make_tile_texture(2, 4);
    MaterialDesc lamp = assets::gltf_pbr_material("lamp", Color(0.9f), 0.0f, 0.5f);
    lamp.emissive = Color(0.25f, 0.5f, 1.0f);
    model.scene.materials = {screen, lamp, assets::gltf_pbr_material("ground", Color(0.5f), 0.0f, 0.8f)};
    for (int k = 0; k < 3; ++k) {
        TriangleMesh plane = assets::grid_plane(1.0f, 1.0f, 4, 4);
        for (const Vec3& p : plane.positions) plane.texcoords.emplace_back(p.x + 0.5f, p.z + 0.5f);
        model.add_node(model.scene.materials[size_t(k)].name, -1, Vec3(float(k), 0, 0), plane);
        model.scene.parts.back().material = k;
        validate_and_complete(model.scene.parts.back().mesh, "emissive.glb");
    }
    return model;
}

TEST_CASE("glTF emission: emissiveFactor, emissiveTexture and KHR_materials_emissive_strength", "[gltf][emission]") {
    const fs::path dir = test::scratch_dir("gltf_emission");
    const assets::GeneratedModel model = emissive_model();
    assets::write_glb(dir / "emissive.glb", model);
    test::WarningCapture warnings;
    const Scene scene = load_scene(dir / "emissive.glb");
    for (const std::string& w : warnings.messages()) {
        INFO(w);
        CHECK(w.find("emissi") == std::string::npos);  // nothing about emission is ignored any more
    }

    // The screen: factor (1, 0.5, 0.2) × strength 3, within float rounding.
    const MaterialDesc& screen = material_named(scene, "screen");
    for (int c = 0; c < 3; ++c) CHECK(screen.emissive[c] == Approx(Color(3.0f, 1.5f, 0.6f)[c]).epsilon(1e-6));
    REQUIRE(screen.emissive_texture);
    const Image& written = model.scene.materials[0].emissive_texture->image;
    const Image& read = screen.emissive_texture->image;
    REQUIRE(read.width == written.width);
    REQUIRE(read.height == written.height);
    REQUIRE(read.channels == 3);
    // sRGB-decoded: each texel the 8-bit sRGB value the PNG holds, back in linear RGB.
    for (size_t i = 0; i < read.pixels.size(); ++i)
        REQUIRE(read.pixels[i] == Approx(srgb_to_linear(float(linear_to_srgb8(written.pixels[i])) / 255.0f)).margin(1e-6));
    // The part reads texture coordinates for it (no base colour texture on this material).
    const Part& screen_part = scene.parts[0];
    REQUIRE(scene.materials[size_t(screen_part.material)].name == "screen");
    CHECK(screen_part.mesh.texcoords.size() == screen_part.mesh.vertex_count());

    // The lamp: the factor alone, no texture; the ground emits nothing.
    const MaterialDesc& lamp = material_named(scene, "lamp");
    CHECK(lamp.emissive == Color(0.25f, 0.5f, 1.0f));
    CHECK(!lamp.emissive_texture);
    CHECK(material_named(scene, "ground").emissive == Color(0.0f));

    // `rsl info` shows the emission of each emitting material.
    const auto [status, output] = test::run_rsl("info " + (dir / "emissive.glb").string());
    INFO(output);
    CHECK(status == 0);
    CHECK(output.find("emissive=3,1.5,0.6 × texture 'tiles.png'") != std::string::npos);
    CHECK(output.find("emissive=0.25,0.5,1") != std::string::npos);
    CHECK(std::regex_search(output, std::regex("KHR_materials_emissive_strength +honoured")));
}

// A square with TEXCOORD_0 and TEXCOORD_1, its material `material`.
test::GltfBuilder square_with(const Json& material) {
    test::GltfBuilder b;
    const int mesh = b.mesh({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 1, 2, 0, 2, 3});
    const std::vector<float> uv{0, 0, 1, 0, 1, 1, 0, 1};
    b.doc()["meshes"][mesh]["primitives"][0]["attributes"]["TEXCOORD_0"] = b.floats(uv, "VEC2");
    b.doc()["meshes"][mesh]["primitives"][0]["attributes"]["TEXCOORD_1"] = b.floats(uv, "VEC2");
    b.doc()["meshes"][mesh]["primitives"][0]["material"] = 0;
    b.doc()["materials"] = Json::array({material});
    b.node({{"name", "square"}, {"mesh", mesh}});
    return b;
}

TEST_CASE("glTF emission: bad values are refused, naming the file and the material", "[gltf][emission][bad-input]") {
    const fs::path dir = test::scratch_dir("gltf_emission_bad");
    const auto strength = [](const Json& value) {
        return Json{{"KHR_materials_emissive_strength", {{"emissiveStrength", value}}}};
    };
    struct Case {
        const char* name;
        Json material;
        const char* expected;
    };
    const Case cases[] = {
        {"negative factor", {{"emissiveFactor", {-0.5, 0, 0}}}, "emissiveFactor must be in [0, 1] (got -0.5)"},
        {"factor past 1", {{"emissiveFactor", {0, 1.5, 0}}}, "emissiveFactor must be in [0, 1] (got 1.5)"},
        {"negative strength", {{"emissiveFactor", {1, 1, 1}}, {"extensions", strength(-2.0)}},
         "emissiveStrength -2 is not in [0, 1e+13]"},
        {"huge strength", {{"emissiveFactor", {1, 1, 1}}, {"extensions", strength(1e30)}},
         "emissiveStrength 1e+30 is not in [0, 1e+13]"},
        {"strength not a number", {{"emissiveFactor", {1, 1, 1}}, {"extensions", strength("bright")}},
         "emissiveStrength is not a number"},
        {"texture out of range", {{"emissiveFactor", {1, 1, 1}}, {"emissiveTexture", {{"index", 4}}}},
         "emissive texture index 4 is out of range (0 textures)"},
        {"two texture coordinate sets",
         {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", 0}}}}},
          {"emissiveFactor", {1, 1, 1}}, {"emissiveTexture", {{"index", 0}, {"texCoord", 1}}}},
         "baseColorTexture reads TEXCOORD_0 and emissiveTexture TEXCOORD_1"},
    };
    for (const Case& c : cases) {
        Json material = c.material;
        material["name"] = "glow";
        const fs::path path = dir / (std::string(c.name) + ".gltf");
        square_with(material).write_gltf(path);
        const std::string error = test::error_of([&] { load_scene(path); });
        INFO(c.name << ": " << error);
        CHECK(error.find(path.string() + ": ") == 0);
        CHECK(error.find("material 'glow'") != std::string::npos);
        CHECK(error.find(c.expected) != std::string::npos);
    }
    // At the limit itself: accepted.
    Json at_limit{{"name", "glow"}, {"emissiveFactor", {1, 0, 0}}, {"extensions", strength(double(kMaxEmission))}};
    square_with(at_limit).write_gltf(dir / "at_limit.gltf");
    CHECK(load_scene(dir / "at_limit.gltf").materials.back().emissive == Color(kMaxEmission, 0, 0));
}

TEST_CASE("Scene-file materials take an `emissive` colour; bad ones are refused naming the key", "[scene][emission]") {
    const fs::path dir = test::scratch_dir("scene_emissive");
    std::ofstream(dir / "plane.obj") << test::grid_obj(2, 1.0);
    const auto scene_with = [&](const std::string& emissive) {
        const fs::path path = dir / "scene.json";
        std::ofstream(path) << R"({"name": "glow", "parts": [{"name": "panel", "obj": "plane.obj", "material": "panel"}],
  "materials": {"panel": {"model": "lambert", "albedo": 0.5, "emissive": )" << emissive << R"(}}})";
        return path;
    };
    const Scene scene = load_scene(scene_with("[2, 1, 0.5]"));
    CHECK(material_named(scene, "panel").emissive == Color(2.0f, 1.0f, 0.5f));
    CHECK(material_named(scene, "panel").params.count("emissive") == 0);  // not the BRDF's
    CHECK(material_named(load_scene(scene_with("0.25")), "panel").emissive == Color(0.25f));
    for (const char* bad : {"[-1, 0, 0]", "[1, 2]", "1e30"}) {
        const fs::path path = scene_with(bad);
        const std::string error = test::error_of([&] { load_scene(path); });
        INFO(bad << ": " << error);
        CHECK(error.find(path.string()) == 0);
        CHECK(error.find("materials.panel.emissive") != std::string::npos);
    }
}

}  // namespace
}  // namespace rsl
