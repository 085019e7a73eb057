// Fault test of `rsl render` (issue 20): killed (SIGKILL) at several moments
// — while it bakes the scene's missing fields into the cache, shades, forms
// the image or writes it — it leaves no partial field, image, preview or
// vertex file under a final name; the rerun completes, reuses the fields
// the killed runs finished, and sweeps every temporary they left.
#include <map>

#include <catch2/catch.hpp>

#include "src/fields/field_file.h"
#include "src/formats/image_file.h"
#include "src/formats/vertex_colors.h"
#include "tests/interrupted_run.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

namespace {

std::map<fs::path, std::string> field_files(const fs::path& cache) {
    std::map<fs::path, std::string> files;
    if (fs::exists(cache))
        for (const auto& e : fs::directory_iterator(cache))
            if (e.path().extension() == ".rslf" && e.path().filename().string()[0] != '.')
                files[e.path()] = read_bytes(e.path());
    return files;
}

}  // namespace

TEST_CASE("rsl render killed at any moment: no partial output or field, and the rerun reuses and sweeps",
          "[render][cli][fault]") {
    const fs::path dir = scratch_dir("render_killed");
    // Light precomputation: a bake of a few tenths of a second.
    write_killable_scene(dir, 30, R"({ "svdf": { "resolution": 16, "clusters": 4, "vectors": 2, "supersampling": 2 },
                  "ovdf": { "shells": 6, "cube_resolution": 12, "vdt_resolution": 16, "vectors": 4 } })");
    const fs::path cache = dir / ".rsl-cache";
    const fs::path exr = dir / "out.exr", png = dir / "out.png", rslv = dir / "out.rslv";
    const std::string command = fmt::format("{} render {} -q --lights 8 -o {} --vertex-out {}", RSL_RSL_EXECUTABLE,
                                            (dir / "scene.json").string(), exr.string(), rslv.string());
    const auto check_whole = [&](const fs::path& path) {
        if (path == exr) CHECK(read_exr(path).width == 1600);
        if (path == png) CHECK(is_whole_png(read_bytes(path)));
        if (path == rslv) CHECK(read_vertex_colors(path).vertex_count() == 31 * 31 + 8);
    };
    const auto kills = [&](double seconds, std::initializer_list<double> fractions) {
        KilledRuns runs;
        for (const double fraction : fractions) {  // the cache is kept: later runs reuse what earlier ones finished
            const KilledRuns run = run_killed(command, {fraction * seconds}, {exr, png, rslv}, check_whole);
            runs.killed += run.killed;
            for (const auto& [path, bytes] : field_files(cache)) CHECK_NOTHROW(read_field_header(path));
        }
        return runs;
    };
    // Kills while the fields are baked: at fractions of a run from an empty cache.
    const double first = timed_run(command);
    REQUIRE(field_files(cache).size() == 4);  // SVDF and OVDF of both parts
    fs::remove_all(cache);
    const KilledRuns baking = kills(first, {0.05, 0.15, 0.3, 0.45});

    // The rerun completes and reuses, byte for byte and untouched, what the killed runs finished.
    const auto finished = field_files(cache);
    std::map<fs::path, fs::file_time_type> written;
    for (const auto& [path, bytes] : finished) written[path] = fs::last_write_time(path);
    const double cached = timed_run(command);
    for (const fs::path& f : {exr, png, rslv}) check_whole(f);
    CHECK(field_files(cache).size() == 4);
    for (const auto& [path, bytes] : finished) {
        CHECK(read_bytes(path) == bytes);
        CHECK(fs::last_write_time(path) == written[path]);  // not baked again
    }

    // Kills while the image is formed and written: at fractions of a run from the full cache.
    const KilledRuns writing = kills(cached, {0.3, 0.45, 0.55, 0.65, 0.75, 0.85, 0.95});
    CHECK(baking.killed + writing.killed > 0);  // else nothing was cut, and the test proved nothing
    // And one kill certain to land inside a write (the timed ones may miss it on a slow or loaded machine).
    int tries = 0;
    while (tries < 5 && !killed_inside_a_write(command, dir)) ++tries;
    CHECK(tries < 5);
    for (const fs::path& f : {exr, png, rslv})
        if (fs::exists(f)) check_whole(f);
    for (const fs::path& f : {exr, png, rslv}) plant_stale_temporary(f);
    const auto [status, text] = run_command(command);
    INFO(text);
    REQUIRE(status == 0);
    for (const fs::path& f : {exr, png, rslv}) check_whole(f);
    for (const auto& left : temporaries_in(dir)) FAIL_CHECK("left behind: " << left.filename().string());
    CHECK(temporaries_in(cache).empty());
    fs::remove_all(dir);
}
