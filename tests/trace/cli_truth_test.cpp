// End to end through the `rsl` program: a furnace scene file → rsl truth →
// .rslv/.exr/.png, then rsl compare on the results and on mismatched inputs.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <catch2/catch.hpp>

#include "src/formats/image_file.h"
#include "src/formats/vertex_colors.h"
#include "tests/test_support.h"

using namespace rsl;
namespace fs = std::filesystem;

namespace {

using test::run_command;
using test::write_text;

}  // namespace

TEST_CASE("rsl truth and rsl compare end to end on a furnace scene", "[trace][cli]") {
    const fs::path dir = test::scratch_dir("cli_truth");
    write_text(dir / "floor.obj",
               "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvn 0 1 0\nf 1//1 4//1 3//1\nf 1//1 3//1 2//1\n");
    Image white(32, 16, 3);
    std::fill(white.pixels.begin(), white.pixels.end(), 1.0f);
    write_exr(dir / "white.exr", white);
    write_text(dir / "furnace.json", R"({
  "name": "furnace",
  "parts": [ { "name": "floor", "obj": "floor.obj" } ],
  "materials": { "grey": { "model": "lambert", "albedo": [0.5, 0.5, 0.5] } },
  "part_materials": { "*": "grey" },
  "environment": { "file": "white.exr", "resolution": 32 },
  "subdivision": false,
  "camera": { "position": [0, 3, 2], "target": [0, 0, 0], "up": [0, 1, 0], "fov_degrees": 60,
              "width": 40, "height": 30 }
})");
    const std::string rsl = RSL_RSL_EXECUTABLE;
    const fs::path out = dir / "truth.exr";
    auto [status, text] = run_command(rsl + " truth " + (dir / "furnace.json").string() + " -q -o " + out.string());
    INFO(text);
    REQUIRE(status == 0);
    CHECK(text.find("shadow rays") == std::string::npos);  // -q: no summary line
    REQUIRE(fs::exists(dir / "truth.png"));
    const VertexColors colors = read_vertex_colors(dir / "truth.rslv");
    REQUIRE(colors.scene_name == "furnace");
    REQUIRE(colors.vertex_count() == 4);
    // Constant environment 1, albedo 0.5, nothing above the floor: 0.5 everywhere.
    for (const Color& c : colors.parts[0]) REQUIRE(c.g == Approx(0.5f).margin(1e-3));
    const Image image = read_exr(out);
    REQUIRE(image.width == 40);
    REQUIRE(image.channels == 4);

    // `rsl info` reads what `rsl truth` wrote: the per-vertex file and the image.
    auto [info_status, info] = run_command(rsl + " info " + (dir / "truth.rslv").string() + " " + out.string());
    INFO(info);
    CHECK(info_status == 0);
    CHECK(info.find("per-vertex colours") != std::string::npos);
    CHECK(info.find("floor") != std::string::npos);
    CHECK(info.find("HDR image (not an environment map layout)") != std::string::npos);

    auto [same_status, same] = run_command(rsl + " compare " + (dir / "truth.rslv").string() + " " + (dir / "truth.rslv").string());
    INFO(same);
    REQUIRE(same_status == 0);
    REQUIRE(same.rfind("relative L2: 0 ", 0) == 0);
    CHECK(same.find("objects:") == std::string::npos);  // the floor is a receiver: no object to measure
    auto [objects_status, objects] = run_command(rsl + " compare " + (dir / "truth.rslv").string() + " " +
                                                 (dir / "truth.rslv").string() + " --receivers ground,wall");
    INFO(objects);
    REQUIRE(objects_status == 0);
    CHECK(objects.find("objects: relative L2 0 over 4 vertices of 1 parts (all but the receivers ground, wall); "
                       "worst part floor: 0\n") != std::string::npos);
    auto [image_status, images] = run_command(rsl + " compare " + out.string() + " " + out.string() + " --error-image " +
                                      (dir / "err.png").string());
    INFO(images);
    REQUIRE(image_status == 0);
    REQUIRE(images.find("relative H1: 0 ") != std::string::npos);
    REQUIRE(fs::exists(dir / "err.png"));

    // A different scene's vertices are refused, naming both files.
    VertexColors other = colors;
    other.scene_name = "kitchen";
    write_vertex_colors(dir / "other.rslv", other);
    auto [bad_status, bad] = run_command(rsl + " compare " + (dir / "other.rslv").string() + " " + (dir / "truth.rslv").string());
    INFO(bad);
    REQUIRE(bad_status == 1);
    REQUIRE(bad.find("not comparable") != std::string::npos);
}
