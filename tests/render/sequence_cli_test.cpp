// Sequences and images end to end through the `rsl` program: render and
// truth --frames with one exposure for every frame and an animated PNG,
// compare --sequence against the single-pair compares, -o NAME.png, and
// --background as a colour and as the environment.
#include <catch2/catch.hpp>

#include <fstream>
#include <regex>

#include <nlohmann/json.hpp>

#include "src/formats/image_file.h"
#include "tests/png_test_support.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

namespace {

// A box on a ground under a white sky that cross-fades to a dim one (4 s
// period): the frames at t = 0, 0.5, 1 differ in brightness by a factor of
// about 2, so per-frame automatic exposure would show.
fs::path write_fading_scene(const fs::path& dir) {
    write_text(dir / "ground.obj", grid_obj(4, 3.0));
    write_text(dir / "box.obj", kUnitBoxObj);
    Image white(16, 8, 3), dim(16, 8, 3);
    std::fill(white.pixels.begin(), white.pixels.end(), 1.0f);
    std::fill(dim.pixels.begin(), dim.pixels.end(), 0.1f);
    write_exr(dir / "white.exr", white);
    write_exr(dir / "dim.exr", dim);
    write_text(dir / "fade.json", R"({
  "name": "fade",
  "parts": [ { "name": "ground", "obj": "ground.obj" }, { "name": "box", "obj": "box.obj" } ],
  "environment": { "file": "white.exr", "second_file": "dim.exr", "blend_period_seconds": 4, "resolution": 8 },
  "subdivision": false,
  "camera": { "position": [0, 1.2, 4], "target": [0, 0.8, 0], "up": [0, 1, 0], "fov_degrees": 50,
              "width": 24, "height": 18 },
  "precompute": { "svdf": { "resolution": 8, "clusters": 4, "vectors": 2, "supersampling": 1 },
                  "ovdf": { "shells": 2, "cube_resolution": 4, "vdt_resolution": 8, "vectors": 2 } }
})");
    return dir / "fade.json";
}

// The 8-bit pixels of a PNG file, as `channels` channels.
std::vector<unsigned char> png_pixels(const fs::path& path, int channels) {
    int width = 0, height = 0;
    return decode(read_bytes(path), channels, width, height);
}

double relative_l2_of(const std::string& compare_output) {
    std::smatch match;
    REQUIRE(std::regex_search(compare_output, match, std::regex("relative L2: ([0-9.e+-]+)")));
    return std::stod(match[1]);
}

bool contains(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

}  // namespace

TEST_CASE("render and truth sequences: one exposure, an animated PNG, and a per-frame comparison", "[cli][sequence]") {
    const fs::path dir = scratch_dir("sequence_cli");
    const fs::path scene = write_fading_scene(dir);
    const std::string frames = " --frames 0:1:0.5 ";
    auto [render_status, render] = run_rsl("render " + scene.string() + frames + "--lights 4 -o " +
                                           (dir / "r.exr").string() + " --vertex-out " + (dir / "r.rslv").string() +
                                           " --animation " + (dir / "r_anim.png").string());
    INFO(render);
    REQUIRE(render_status == 0);
    CHECK(contains(render, "stops for every frame (the first frame's"));
    auto [truth_status, truth] = run_rsl("truth " + scene.string() + frames + "-q -o " + (dir / "t.exr").string());
    INFO(truth);
    REQUIRE(truth_status == 0);
    for (int f = 0; f < 3; ++f)
        for (const char* name : {"r.{:04d}.exr", "r.{:04d}.png", "r.{:04d}.rslv", "t.{:04d}.exr", "t.{:04d}.png", "t.{:04d}.rslv"})
            CHECK(fs::exists(dir / fmt::format(fmt::runtime(name), f)));
    CHECK_FALSE(fs::exists(dir / "r.0003.exr"));

    // Every frame's PNG is tone-mapped with the first frame's automatic
    // exposure, which differs from the later frames' own by far more than a rounding.
    for (const char* run : {"r", "t"}) {
        INFO(run);
        std::vector<Image> images;
        for (int f = 0; f < 3; ++f) images.push_back(read_exr(dir / fmt::format("{}.{:04d}.exr", run, f)));
        const float stops = auto_exposure_stops(images[0]);
        CHECK(std::abs(auto_exposure_stops(images[2]) - stops) > 0.5f);
        for (int f = 0; f < 3; ++f)
            CHECK(png_pixels(dir / fmt::format("{}.{:04d}.png", run, f), 4) ==
                  tone_mapped_pixels(images[f], ToneMap{stops, false}));
    }
    // The animated PNG holds the three frames, each decoding to its frame's PNG.
    const std::vector<std::string> stills = apng_frames(read_bytes(dir / "r_anim.png"));
    REQUIRE(stills.size() == 3);
    for (int f = 0; f < 3; ++f) {
        int width = 0, height = 0;
        CHECK(decode(stills[f], 4, width, height) == png_pixels(dir / fmt::format("r.{:04d}.png", f), 4));
    }

    // The sequence's table against the three single compares; the worst frame is the largest.
    std::vector<double> single;
    for (int f = 0; f < 3; ++f) {
        auto [status, text] = run_rsl(fmt::format("compare {} {}", (dir / fmt::format("r.{:04d}.exr", f)).string(),
                                                  (dir / fmt::format("t.{:04d}.exr", f)).string()));
        REQUIRE(status == 0);
        single.push_back(relative_l2_of(text));
    }
    const size_t worst = size_t(std::max_element(single.begin(), single.end()) - single.begin());
    auto [sequence_status, sequence] = run_rsl("compare " + (dir / "r.exr").string() + " " + (dir / "t.exr").string() +
                                               " --sequence --table " + (dir / "table.json").string());
    INFO(sequence);
    REQUIRE(sequence_status == 0);
    CHECK(contains(sequence, fmt::format("worst frame: {} (", worst)));
    std::ifstream table_file(dir / "table.json");
    const nlohmann::json table = nlohmann::json::parse(table_file);
    REQUIRE(table.size() == 3);
    for (int f = 0; f < 3; ++f) {
        CHECK(table[f]["frame"] == f);
        CHECK(table[f]["relative_l2"].get<double>() == Approx(single[f]).epsilon(1e-5));
        CHECK(table[f].contains("relative_h1"));
    }
    // Per-vertex files compare the same way, into CSV.
    auto [vertex_status, vertices] = run_rsl("compare " + (dir / "r.rslv").string() + " " + (dir / "t.rslv").string() +
                                             " --sequence --table " + (dir / "table.csv").string());
    INFO(vertices);
    REQUIRE(vertex_status == 0);
    const std::string csv = read_bytes(dir / "table.csv");
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 4);  // header and three frames
    CHECK(contains(csv, "frame,a,b,relative_l2"));

    // A sequence's -o path without --sequence is pointed to it; sequences of different lengths are refused.
    auto [plain_status, plain] = run_rsl("compare " + (dir / "r.exr").string() + " " + (dir / "t.exr").string());
    CHECK(plain_status == 1);
    CHECK(contains(plain, "add --sequence"));
    fs::remove(dir / "t.0002.exr");
    auto [short_status, short_text] =
        run_rsl("compare " + (dir / "r.exr").string() + " " + (dir / "t.exr").string() + " --sequence");
    CHECK(short_status == 1);
    CHECK(contains(short_text, "has 3 frames and"));
}

TEST_CASE("render writes a PNG alone, and draws a colour or the environment behind the scene", "[cli][sequence]") {
    const fs::path dir = scratch_dir("render_png_background");
    const fs::path scene = write_fading_scene(dir);
    const std::string render = "render " + scene.string() + " -q --lights 4 ";
    REQUIRE(run_rsl(render + "-o " + (dir / "plain.png").string()).first == 0);
    CHECK(fs::exists(dir / "plain.png"));
    CHECK_FALSE(fs::exists(dir / "plain.exr"));
    // The top rows see the sky: uncovered without a background.
    REQUIRE(run_rsl(render + "-o " + (dir / "plain.exr").string()).first == 0);
    const Image plain = read_exr(dir / "plain.exr");
    REQUIRE(plain.channels == 4);
    REQUIRE(plain.at(0, 0)[3] == 0.0f);

    REQUIRE(run_rsl(render + "-o " + (dir / "colour.exr").string() + " --background 0.5,0.25,1").first == 0);
    const Image colour = read_exr(dir / "colour.exr");
    CHECK(colour.rgb(0, 0).r == Approx(0.5f));
    CHECK(colour.rgb(0, 0).g == Approx(0.25f));
    CHECK(colour.rgb(0, 0).b == Approx(1.0f));
    CHECK(colour.at(0, 0)[3] == 1.0f);
    // At t = 0 the sky is the white map alone: radiance 1 behind the scene.
    REQUIRE(run_rsl(render + "-o " + (dir / "sky.exr").string() + " --background environment").first == 0);
    const Image sky = read_exr(dir / "sky.exr");
    for (int k = 0; k < 3; ++k) CHECK(sky.at(0, 0)[k] == Approx(1.0f).margin(0.02));
    CHECK(sky.at(0, 0)[3] == 1.0f);
    // Covered pixels keep their colour.
    for (int y = 0; y < plain.height; ++y)
        for (int x = 0; x < plain.width; ++x)
            if (plain.at(x, y)[3] == 1.0f) CHECK(sky.rgb(x, y).g == Approx(plain.rgb(x, y).g).margin(1e-6));

    for (const char* bad : {"1,2", "red", "0,nan,0", "1,1,1,1"}) {
        auto [status, text] = run_rsl(render + "-o " + (dir / "bad.exr").string() + " --background " + bad);
        INFO(bad << "\n" << text);
        CHECK(status == 1);
        CHECK(contains(text, std::string("--background ") + bad));
        CHECK_FALSE(fs::exists(dir / "bad.exr"));
    }
    auto [jpg_status, jpg] = run_rsl(render + "-o " + (dir / "x.jpg").string());
    CHECK(jpg_status == 1);
    CHECK(contains(jpg, "expected an .exr path"));
}
