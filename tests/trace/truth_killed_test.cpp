// Fault test of `rsl truth` (issue 20): killed (SIGKILL) at several moments
// of a run, it leaves no partial image, preview or vertex file under a final
// name; the rerun completes and sweeps every temporary a dead run left.
#include <catch2/catch.hpp>

#include "src/formats/image_file.h"
#include "src/formats/vertex_colors.h"
#include "tests/interrupted_run.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

TEST_CASE("rsl truth killed at any moment: no partial output, and the rerun completes and sweeps", "[trace][cli][fault]") {
    const fs::path dir = scratch_dir("truth_killed");
    write_killable_scene(dir, 40);  // shading, image and files each a noticeable part of a run (about 1 s)
    const fs::path exr = dir / "out.exr", png = dir / "out.png", rslv = dir / "out.rslv";
    const std::string command = fmt::format("{} truth {} -q -o {}", RSL_RSL_EXECUTABLE, (dir / "scene.json").string(),
                                            exr.string());
    // Kills spread over one uninterrupted run's duration, most in its second
    // third, where the EXR is written (the PNG and .rslv take milliseconds).
    const double seconds = timed_run(command);
    const size_t vertices = read_vertex_colors(rslv).vertex_count();
    CHECK(vertices == 41 * 41 + 8);
    const auto check_whole = [&](const fs::path& path) {
        if (path == exr) CHECK(read_exr(path).width == 1600);
        if (path == png) CHECK(is_whole_png(read_bytes(path)));
        if (path == rslv) CHECK(read_vertex_colors(path).vertex_count() == vertices);
    };
    for (const fs::path& f : {exr, png}) check_whole(f);
    std::vector<double> delays;
    for (const double fraction : {0.1, 0.3, 0.4, 0.5, 0.6, 0.7, 0.85, 0.95}) delays.push_back(fraction * seconds);
    const KilledRuns runs = run_killed(command, delays, {exr, png, rslv}, check_whole);
    CHECK(runs.killed > 0);  // else nothing was cut, and the test proved nothing
    // And one kill certain to land inside a write (the timed ones may miss it on a slow or loaded machine).
    int tries = 0;
    while (tries < 5 && !killed_inside_a_write(command, dir)) ++tries;
    CHECK(tries < 5);
    for (const fs::path& f : {exr, png, rslv})
        if (fs::exists(f)) check_whole(f);
    // The sweep is tested whatever the kills left: a dead writer's temporary of each output.
    for (const fs::path& f : {exr, png, rslv}) plant_stale_temporary(f);
    REQUIRE(temporaries_in(dir).size() >= 3);

    const auto [status, text] = run_command(command);
    INFO(text);
    REQUIRE(status == 0);
    for (const fs::path& f : {exr, png, rslv}) check_whole(f);
    for (const auto& left : temporaries_in(dir)) FAIL_CHECK("left behind: " << left.filename().string());
    fs::remove_all(dir);
}
