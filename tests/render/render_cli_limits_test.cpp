// Issue 43, "nothing hangs, nothing lies": `rsl render` and `rsl truth`
// refuse non-finite and out-of-range times, frames, sizes, samples and
// exposures before loading anything (each at once, with the limit), a FIFO
// as the scene file, and -q prints no per-frame line.
#include <catch2/catch.hpp>

#include <chrono>

#include "tests/special_files.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

namespace {

// A box on a ground with the lightest precomputation: renders in about a second.
fs::path tiny_scene(const fs::path& dir) {
    write_text(dir / "ground.obj",
               "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nv 0 0 0\nf 1 5 2\nf 2 5 3\nf 3 5 4\nf 4 5 1\n");
    write_text(dir / "box.obj", kUnitBoxObj);
    write_text(dir / "tiny.json", R"({
  "parts": [ { "name": "ground", "obj": "ground.obj" }, { "name": "box", "obj": "box.obj" } ],
  "camera": { "width": 16, "height": 12 },
  "precompute": { "svdf": { "resolution": 8, "clusters": 4, "vectors": 2, "supersampling": 1 },
                  "ovdf": { "shells": 2, "cube_resolution": 4, "vdt_resolution": 8, "vectors": 2 } }
})");
    return dir / "tiny.json";
}

// `rsl ARGS` under a 20 s timeout (status 124 past it), in seconds too.
struct Run {
    int status;
    std::string output;
    double seconds;
};
Run run_limited(const std::string& arguments) {
    const auto start = std::chrono::steady_clock::now();
    auto [status, output] = run_command(std::string("timeout 20 ") + RSL_RSL_EXECUTABLE + " " + arguments);
    return {status, output, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

}  // namespace

TEST_CASE("rsl render refuses non-finite and out-of-range numbers before loading the scene", "[render][cli][bad-input]") {
    const fs::path dir = scratch_dir("render_cli_limits");
    const std::string scene = tiny_scene(dir).string();
    const std::string out = " -q -o " + (dir / "out.exr").string();
    const std::pair<const char*, const char*> cases[] = {
        {"--frames nan:1:0.5", "--frames 'nan:1:0.5': expected START:END:STEP"},
        {"--frames 0:inf:1", "--frames END inf: expected a time from -1e+06 to 1e+06 seconds"},
        {"--frames 0:1:1e-30", "frames, at most 100000 in one run"},
        {"--time nan", "--time nan: expected a time from -1e+06 to 1e+06 seconds"},
        {"--time inf", "--time inf: expected a time from"},
        {"--time 1e39", "--time inf: expected a time from"},
        {"--exposure nan", "--exposure nan: expected -64 to 64 stops"},
        {"--width 20000 --height 20000", "--width 20000: expected 1 to 16384 pixels"},
        {"--width 0", "--width 0: expected 1 to 16384 pixels (leave it out for the scene camera's width)"},
        {"--height -3", "--height -3: expected 1 to 16384 pixels"},
        {"--samples 1000", "--samples 1000: expected 1 to 16"},
        {"--gpu-rays 17", "--gpu-rays 17: expected S of 1..16"},
        {"--backend rays --ray-samples 17", "--ray-samples 17: expected S of 1..16"},
        {"--ray-samples 2", "--ray-samples: the cpu backend traces no rays (add --backend rays)"},
        {"--backend rays --no-occluders", "--no-occluders: the rays backend shades with no fields"},
        {"--material box", "--material 'box': expected PART=MATERIAL"},
#ifdef RSL_HAVE_GL
        {"--gpu-rays 2", "--gpu-rays: GPU ray-traced visibility is a GPU baseline (add --backend gl)"},
        {"--gpu-rays 2 --backend gl --shadow-maps 256", "--gpu-rays and --shadow-maps: pick one"},
#else
        {"--gpu-rays 2", "--gpu-rays: GPU ray-traced visibility is a GPU baseline (add a backend this rsl was built without)"},
#endif
    };
    for (const auto& [arguments, message] : cases) {
        const Run run = run_limited("render " + scene + " " + arguments + out);
        INFO(arguments << " -> " << run.status << ": " << run.output);
        CHECK(run.status == 1);
        CHECK(run.output.find(message) != std::string::npos);
        CHECK(run.seconds < 5);  // before the fix: minutes, gigabytes, or an endless allocation
    }
    CHECK_FALSE(fs::exists(dir / "out.exr"));
    // rsl truth takes the same flags by the same rules.
    const Run truth = run_limited("truth " + scene + " --time nan" + out);
    CHECK(truth.status == 1);
    CHECK(truth.output.find("--time nan: expected a time from") != std::string::npos);
}

TEST_CASE("rsl render refuses a FIFO as the scene file at once, and -q prints no per-frame line", "[render][cli][bad-input]") {
    const fs::path dir = scratch_dir("render_cli_fifo");
    const fs::path fifo = make_fifo(dir / "ff.json");
    const FifoRelease release(fifo);
    const Run refused = run_limited("render " + fifo.string() + " -q -o " + (dir / "out.exr").string());
    INFO(refused.output);
    CHECK(refused.status == 1);
    CHECK(refused.output.find(fifo.string() + ": is a FIFO (named pipe), not a regular file") != std::string::npos);
    CHECK(refused.seconds < 3);

    const std::string scene = tiny_scene(dir).string();
    const Run quiet = run_limited("render " + scene + " -q -k 2 --frames 0:0.5:0.5 -o " + (dir / "q.exr").string());
    INFO(quiet.output);
    CHECK(quiet.status == 0);
    CHECK(quiet.output.find("t=") == std::string::npos);
    CHECK(fs::exists(dir / "q.0001.exr"));
    const Run loud = run_limited("render " + scene + " -k 2 -o " + (dir / "loud.exr").string());
    CHECK(loud.output.find("t=0.000: ") != std::string::npos);
}

#ifdef RSL_HAVE_GL
TEST_CASE("rsl render refuses a shadow-map resolution out of range, and shadow maps on the CPU, before any work",
          "[render][cli][bad-input]") {
    const std::string render = "render " + std::string(RSL_SOURCE_DIR) + "/assets/scenes/default.json ";
    const auto [low, low_output] = run_rsl(render + "--backend gl --shadow-maps 8 -o x.exr");
    CHECK(low != 0);
    CHECK_THAT(low_output, Catch::Contains("--shadow-maps 8: expected a resolution of 16..8192"));
    const auto [cpu, cpu_output] = run_rsl(render + "--shadow-maps 256 -o x.exr");
    CHECK(cpu != 0);
    CHECK_THAT(cpu_output, Catch::Contains("add --backend gl"));
    const auto [filter, filter_output] = run_rsl(render + "--shadow-filter pcf -o x.exr");
    CHECK(filter != 0);
    CHECK_THAT(filter_output, Catch::Contains("--shadow-maps"));
}
#endif
