// Issue 56, "nothing destroyed, nothing silently wrong": every command
// refuses an output that is one of its inputs before any work (the input
// untouched, exit status 1, both paths named); a write never sweeps a user's
// file; a 240-byte file name writes; lights too bright for an image file,
// roughness too small for a float and a NaN background are refused or
// raised, never written as NaN.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>

#include "src/formats/image_file.h"
#include "src/formats/vertex_colors.h"
#include "tests/formats/gltf_builder.h"
#include "tests/hostile_inputs.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

// A box on a ground under a small white map, with the lightest
// precomputation: renders in about a second. `extra` goes into the scene
// file's top level (materials, lights).
fs::path small_scene(const fs::path& dir, const std::string& name = "scene.json", const std::string& extra = "") {
    write_text(dir / "ground.obj",
               "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nv 0 0 0\nf 1 5 2\nf 2 5 3\nf 3 5 4\nf 4 5 1\n");
    write_text(dir / "box.obj", kUnitBoxObj);
    Image white(16, 8, 3);
    std::fill(white.pixels.begin(), white.pixels.end(), 1.0f);
    write_exr(dir / "env.exr", white);
    write_text(dir / name, std::string(R"({
  "parts": [ { "name": "ground", "obj": "ground.obj" }, { "name": "box", "obj": "box.obj", "material": "box" } ],
  "environment": { "file": "env.exr", "resolution": 4 },
  "subdivision": false,
  "camera": { "position": [0, 3, 4], "target": [0, 0, 0], "up": [0, 1, 0], "width": 16, "height": 12 },
  "precompute": { "svdf": { "resolution": 8, "clusters": 4, "vectors": 2, "supersampling": 1 },
                  "ovdf": { "shells": 2, "cube_resolution": 4, "vdt_resolution": 8, "vectors": 2 } })") +
                                (contains(extra, "\"materials\"") ? "" : R"(,
  "materials": { "box": { "model": "lambert", "albedo": 0.5 } })") +
                                (extra.empty() ? "" : ",\n  " + extra) + "\n}\n");
    return dir / name;
}

// Runs `rsl ARGS`, which must fail naming `output` and `input` and leave every file in `kept` as it was.
void require_refused(const std::string& arguments, const fs::path& output, const fs::path& input,
                     const std::vector<fs::path>& kept) {
    std::vector<std::string> before;
    for (const fs::path& file : kept) before.push_back(read_bytes(file));
    const auto [status, text] = run_rsl(arguments);
    INFO("rsl " << arguments << "\n" << text);
    CHECK(status == 1);
    CHECK(contains(text, "rsl: error: " + output.string() + ": this output is the input " + input.string()));
    for (size_t k = 0; k < kept.size(); ++k) CHECK(read_bytes(kept[k]) == before[k]);
}

}  // namespace

TEST_CASE("an output that is an input is refused before any work, the input kept", "[cli][issue-56]") {
    const fs::path dir = scratch_dir("nothing_destroyed_inputs");
    const fs::path scene = small_scene(dir);
    const fs::path env = dir / "env.exr", box = dir / "box.obj";
    const std::vector<fs::path> inputs = {scene, env, box, dir / "ground.obj"};
    require_refused("fit " + env.string() + " -k 2 -n 4 -o " + env.string(), env, env, inputs);
    fs::create_symlink(env, dir / "env_link.png");  // a preview must end in .png: the map by a link
    require_refused("fit " + env.string() + " -k 2 -n 4 -o " + (dir / "l.json").string() + " --preview " +
                        (dir / "env_link.png").string(), dir / "env_link.png", env, inputs);
    require_refused("render " + scene.string() + " -q -k 2 -o " + env.string(), env, env, inputs);
    require_refused("render " + scene.string() + " -q -k 2 -o " + (dir / "out.exr").string() + " --vertex-out " +
                        scene.string(), scene, scene, inputs);
    require_refused("render " + scene.string() + " -q -k 2 --frames 0:0:1 -o " + env.string(), env, env, inputs);
    require_refused("truth " + scene.string() + " -q -o " + (dir / "t.exr").string() + " --vertex-out " +
                        box.string(), box, box, inputs);
    // Another spelling of the same file, a folder that does not exist yet, and a symbolic link.
    const fs::path around = dir / "new" / ".." / "env.exr";
    require_refused("truth " + scene.string() + " -q -o " + around.string(), around, env, inputs);
    CHECK_FALSE(fs::exists(dir / "new"));
    fs::create_symlink(env, dir / "link.exr");
    require_refused("render " + scene.string() + " -q -k 2 -o " + (dir / "link.exr").string(), dir / "link.exr", env,
                    inputs);

    // compare's A and B, and the scene it draws a vertex error image on.
    REQUIRE(run_rsl("truth " + scene.string() + " -q -o " + (dir / "a.exr").string()).first == 0);
    REQUIRE(run_rsl("truth " + scene.string() + " -q --subdivision 2 -o " + (dir / "b.exr").string()).first == 0);
    const std::vector<fs::path> results = {dir / "a.exr", dir / "b.exr", dir / "a.rslv", dir / "b.rslv"};
    require_refused("compare " + (dir / "a.exr").string() + " " + (dir / "b.exr").string() + " --error-image " +
                        (dir / "a.exr").string(), dir / "a.exr", dir / "a.exr", results);
    require_refused("compare " + (dir / "a.rslv").string() + " " + (dir / "b.rslv").string() + " --scene " +
                        scene.string() + " --error-image " + box.string(), box, box, inputs);

    // Two outputs that are one file.
    const auto [status, text] = run_rsl("render " + scene.string() + " -q -k 2 -o " + (dir / "same.exr").string() +
                                        " --vertex-out " + (dir / "same.exr").string());
    INFO(text);
    CHECK(status == 1);
    CHECK(contains(text, "two outputs are this one file"));
    CHECK_FALSE(fs::exists(dir / "same.exr"));
}

TEST_CASE("a glTF file's external buffer is an input no output may replace", "[cli][issue-56][gltf]") {
    const fs::path dir = scratch_dir("nothing_destroyed_gltf");
    const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    write_text(dir / "tri.bin", std::string(reinterpret_cast<const char*>(triangle), sizeof(triangle)));
    write_text(dir / "tri.gltf", hostile::gltf_triangle("3", "tri.bin"));
    require_refused("truth " + (dir / "tri.gltf").string() + " -q --width 8 --height 8 -o " +
                        (dir / "t.exr").string() + " --vertex-out " + (dir / "tri.bin").string(),
                    dir / "tri.bin", dir / "tri.bin", {dir / "tri.bin", dir / "tri.gltf"});
    // The same run with an output of its own writes.
    const auto [status, text] = run_rsl("truth " + (dir / "tri.gltf").string() + " -q --width 8 --height 8 -o " +
                                        (dir / "t.exr").string());
    INFO(text);
    CHECK(status == 0);
    CHECK(fs::exists(dir / "t.rslv"));
}

TEST_CASE("a write keeps a user's old '.notes.tmp-…' file and sweeps rsl's own orphan", "[cli][issue-56][sweep]") {
    const fs::path dir = scratch_dir("nothing_destroyed_sweep");
    const fs::path scene = small_scene(dir);
    const auto plant = [&](const std::string& name) {
        write_text(dir / name, "planted");
        fs::last_write_time(dir / name, fs::file_time_type::clock::now() - std::chrono::hours(72));
        return dir / name;
    };
    const fs::path notes = plant(".notes.tmp-2024-06.txt");
    const fs::path orphan = plant(".lights.rsl-tmp-0123456789abcdef-4343-fedcba9876543210.json");
    const auto [status, text] = run_rsl("fit " + (dir / "env.exr").string() + " -k 2 -n 4 -o " +
                                        (dir / "lights.json").string());
    INFO(text);
    CHECK(status == 0);
    CHECK(read_bytes(notes) == "planted");
    CHECK_FALSE(fs::exists(orphan));
}

TEST_CASE("an output named with 240 bytes writes: its temporary stays within NAME_MAX", "[cli][issue-56]") {
    const fs::path dir = scratch_dir("nothing_destroyed_long_name");
    small_scene(dir);
    const fs::path output = dir / (std::string(235, 'a') + ".json");
    const auto [status, text] = run_rsl("fit " + (dir / "env.exr").string() + " -k 2 -n 4 -o " + output.string());
    INFO(text);
    CHECK(status == 0);
    CHECK(fs::exists(output));
}

TEST_CASE("lights too bright for an image file are refused at load, naming the key and the limit",
          "[cli][issue-56][lights]") {
    const fs::path dir = scratch_dir("nothing_destroyed_lights");
    const std::pair<const char*, const char*> cases[] = {
        {R"("lights": [ { "position": [1, 2, 1], "power": [3e38, 3e38, 3e38] } ])",
         "lights[0].power: 3e+38 W is past the limit; expected 0 to 1e+12 W per channel"},
        {R"("lights": [ { "position": [1, 2, 1], "power": [1, 1e20, 1] } ])", "lights[0].power: 1e+20 W"},
        {R"("lights": [ { "position": [1, 2, 1], "radius": 1e-9, "power": [100, 100, 100] } ])",
         "lights[0]: radiance power / (4π² radius²) = 2.5"},
    };
    for (const auto& [lights, message] : cases) {
        const fs::path scene = small_scene(dir, "bright.json", lights);
        for (const char* command : {"truth", "render"}) {
            const auto [status, text] =
                run_rsl(std::string(command) + " " + scene.string() + " -q -o " + (dir / "out.exr").string());
            INFO(command << " " << lights << "\n" << text);
            CHECK(status == 1);
            CHECK(contains(text, "rsl: error: " + scene.string() + ": " + message));
            CHECK_FALSE(fs::exists(dir / "out.exr"));
        }
    }
    // The brightest allowed light renders finite values that rsl reads back.
    const fs::path scene = small_scene(dir, "bright.json", R"("lights": [ { "position": [1, 2, 1], "radius": 0.5, "power": [1e12, 1e12, 1e12] } ])");
    const auto [status, text] = run_rsl("truth " + scene.string() + " -q -o " + (dir / "brightest.exr").string());
    INFO(text);
    REQUIRE(status == 0);
    CHECK(read_exr(dir / "brightest.exr").width == 16);
    CHECK(read_vertex_colors(dir / "brightest.rslv").vertex_count() > 0);
}

TEST_CASE("roughness below the tables' smallest is raised with a warning: no NaN pixel or vertex",
          "[cli][issue-56][brdf]") {
    const fs::path dir = scratch_dir("nothing_destroyed_roughness");
    const std::pair<const char*, const char*> materials[] = {
        {R"("ward", "kd": 0.3, "ks": 0.5, "alpha": 1e-20)", "parameter 'alpha' 1e-20 is below 0.001"},
        {R"("cook_torrance_beckmann", "f0": 0.5, "kd": 0.3, "roughness": 1e-38)", "parameter 'roughness' 1e-38 is below 0.001"},
        {R"("ward_anisotropic", "kd": 0.3, "ks": 0.5, "alpha_x": 1e-38, "alpha_y": 0.2)", "parameter 'alpha_x' 1e-38 is below 0.001"},
    };
    for (const auto& [material, warning] : materials) {
        const fs::path scene = small_scene(dir, "rough.json", std::string(R"("materials": { "box": { "model": )") + material + " } }");
        for (const char* command : {"render", "truth"}) {
            const auto [status, text] = run_rsl(std::string(command) + " " + scene.string() + " -q -o " +
                                                (dir / "out.exr").string() + " --vertex-out " + (dir / "out.rslv").string());
            INFO(command << " " << material << "\n" << text);
            REQUIRE(status == 0);
            if (std::string(command) == "render") CHECK((contains(text, "rsl: warning: material 'box'") && contains(text, warning)));
            // The readers refuse NaN: both files read back, and hold no NaN.
            const Image image = read_exr(dir / "out.exr");
            for (float v : image.pixels) REQUIRE(std::isfinite(v));
            CHECK(read_vertex_colors(dir / "out.rslv").vertex_count() > 0);
        }
    }
}

TEST_CASE("rsl truth refuses a NaN, infinite or negative background", "[cli][issue-56]") {
    const fs::path dir = scratch_dir("nothing_destroyed_background");
    const fs::path scene = small_scene(dir);
    for (const char* background : {"nan 0 0", "0 inf 0", "0 0 -1"}) {
        const auto [status, text] =
            run_rsl("truth " + scene.string() + " -q -o " + (dir / "bg.exr").string() + " --background " + background);
        INFO(background << "\n" << text);
        CHECK(status == 1);
        CHECK(contains(text, std::string("--background ") + background + ": expected radiances from 0 to 1e+15"));
        CHECK_FALSE(fs::exists(dir / "bg.exr"));
    }
}

TEST_CASE("a part whose transform is singular is refused at load, naming the file and the part, before the bake",
          "[cli][issue-56]") {
    const fs::path dir = scratch_dir("nothing_destroyed_singular");
    // A zero scale has determinant 0; 1e20 one of Inf in float.
    for (const char* scale : {"[0, 1, 1]", "[1e20, 1e20, 1e20]"}) {
        std::string gltf = hostile::gltf_triangle();
        const std::string node = R"("nodes": [{"mesh": 0}])";
        gltf.replace(gltf.find(node), node.size(), std::string(R"("nodes": [{"mesh": 0, "name": "flat", "scale": )") +
                                                       scale + "}]");
        write_text(dir / "flat.gltf", gltf);
        for (const char* command : {"render", "truth"}) {
            const auto [status, text] =
                run_rsl(std::string(command) + " " + (dir / "flat.gltf").string() + " -q -o " + (dir / "out.exr").string());
            INFO(command << " " << scale << "\n" << text);
            CHECK(status == 1);
            CHECK(contains(text, "rsl: error: " + (dir / "flat.gltf").string() +
                                     ": part 'flat': its transform at the scene's start (t = 0 s) is singular"));
        }
    }
    // A scene file's part transform, as its glTF node's.
    const fs::path huge = small_scene(dir, "huge.json");
    std::string text = read_bytes(huge);
    const std::string box = R"("material": "box" })";
    text.replace(text.find(box), box.size(), R"("material": "box", "transform": { "scale": 1e20 } })");
    write_text(huge, text);
    const auto [status, out] = run_rsl("render " + huge.string() + " -q -o " + (dir / "out.exr").string());
    INFO(out);
    CHECK(status == 1);
    CHECK(contains(out, "rsl: error: " + huge.string() + ": part 'box': its transform at the scene's start (t = 0 s) "
                        "is singular (determinant inf"));
    CHECK_FALSE(fs::exists(dir / ".rsl-cache"));  // nothing was baked
    CHECK_FALSE(fs::exists(dir / "out.exr"));
}

TEST_CASE("a frame where an animated scale reaches 0 is refused naming the file, the part and the time",
          "[cli][issue-56]") {
    const fs::path dir = scratch_dir("nothing_destroyed_singular_frame");
    GltfBuilder gltf;
    gltf.mesh({0, 0, 0, 0.5f, 0, 0, 0, 0.5f, 0, 0, 0, 0.5f}, {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3});
    const int node = gltf.node({{"mesh", 0}, {"name", "shrinking"}, {"translation", {0, 1, 0}}});
    gltf.channel(node, "scale", "LINEAR", {0, 1}, {1, 1, 1, 0, 0, 0});
    gltf.write_gltf(dir / "shrink.gltf");
    const fs::path scene = small_scene(dir, "anim.json", R"("gltf": "shrink.gltf")");
    const std::string singular = "rsl: error: " + scene.string() + ": part 'shrinking': its transform at t = 1 s is singular";
    {
        const auto [status, text] =
            run_rsl("render " + scene.string() + " -q --frames 0:1:0.5 -o " + (dir / "frame.exr").string());
        INFO(text);
        CHECK(status == 1);
        CHECK(contains(text, singular));
        CHECK(fs::exists(dir / "frame.0000.exr"));  // the frames before it are whole
    }
    {
        const auto [status, text] = run_rsl("truth " + scene.string() + " -q --time 1 -o " + (dir / "t.exr").string());
        INFO(text);
        CHECK(status == 1);
        CHECK(contains(text, singular));
        CHECK_FALSE(fs::exists(dir / "t.exr"));
    }
}

TEST_CASE("errors never echo a data: URI's payload, and cut any quoted value to 80 bytes", "[cli][issue-56][gltf]") {
    const fs::path dir = scratch_dir("nothing_destroyed_echo");
    std::string payload;
    for (int k = 0; k < 400; ++k) payload += "QUFB";
    write_text(dir / "data.gltf", hostile::gltf_triangle("3", "data:application/octet-stream;base64," + payload + "!!"));
    write_text(dir / "long.gltf", hostile::gltf_triangle("3", "missing_" + std::string(300, 'x') + ".bin"));
    write_text(dir / "long.json", R"({ "parts": [ { "obj": ")" + std::string(300, 'y') + R"(.obj" } ] })");
    for (const char* name : {"data.gltf", "long.gltf", "long.json"}) {
        const auto [status, text] = run_rsl("info " + (dir / name).string());
        INFO(text);
        CHECK(status == 1);
        CHECK_FALSE(contains(text, "QUFBQUFB"));
        CHECK_FALSE(contains(text, std::string(80, 'x')));
        CHECK_FALSE(contains(text, std::string(80, 'y')));
        CHECK((contains(text, "a data: URI of 1639 bytes") || contains(text, "… (")));
    }
}

TEST_CASE("cube maps past 512 texels a side are refused at once by every command, as by rsl fit",
          "[cli][issue-56]") {
    const fs::path dir = scratch_dir("nothing_destroyed_cube_size");
    const fs::path scene = small_scene(dir);
    for (const std::string command : {"truth", "baselines"}) {
        const auto start = std::chrono::steady_clock::now();
        const auto [status, text] = run_rsl(command + " " + scene.string() + " -q --resolution 4096 -o " +
                                            (dir / (command == "truth" ? "t.exr" : "out")).string());
        INFO(text);
        CHECK(status == 1);
        CHECK(contains(text, "--resolution 4096: expected 1 to 512 texels per cube-face edge"));
        CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 5);
    }
}
