// `rsl fit` end to end: an EXR in, an RSL set and a preview out.
#include <cstdlib>
#include <filesystem>

#include <unistd.h>

#include <fmt/core.h>

#include <catch2/catch.hpp>

#include "src/formats/environment_file.h"
#include "src/lightfit/square_light.h"
#include "src/core/envmap.h"
#include "src/formats/image_file.h"
#include "tests/test_support.h"

using namespace rsl;
namespace fs = std::filesystem;

namespace {

int run(const std::string& arguments) { return test::run_rsl(arguments).first; }

}  // namespace

TEST_CASE("rsl fit writes K lights that keep the environment's energy, and a preview", "[lightfit][cli]") {
    const fs::path dir = test::scratch_dir("fit_cli");
    // A dim lat-long sky with one bright spot.
    Image latlong(64, 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) latlong.set_rgb(x, y, Color(0.2f + 0.01f * y, 0.3f, 0.4f));
    latlong.set_rgb(20, 8, Color(300.0f, 280.0f, 250.0f));
    const fs::path env = dir / "sky.exr";
    write_exr(env, latlong);

    const fs::path lights = dir / "lights.json", preview = dir / "fit.png";
    REQUIRE(run(fmt::format("fit {} --lights 12 --resolution 8 -o {} --preview {} --preview-width 64", env.string(),
                            lights.string(), preview.string())) == 0);
    const RslSet set = load_rsl_set(lights);
    CHECK(set.lights.size() == 12);
    CHECK(set.resolution == 8);
    const DVec3 expected = load_environment(env, 8).energy(), got = set.total_energy();
    for (int ch = 0; ch < 3; ++ch) CHECK(got[ch] == Approx(expected[ch]).epsilon(1e-5));
    CHECK(fs::file_size(preview) > 100);
    // `rsl info` tells the light set from a scene file and describes it.
    const auto [info_status, info] = test::run_rsl("info " + lights.string());
    INFO(info);
    CHECK(info_status == 0);
    CHECK(info.find("rotatable square lights") != std::string::npos);
    CHECK(info.find("lights:            12") != std::string::npos);

    // Same-face with fewer lights than faces is refused, as is a missing file.
    CHECK(run(fmt::format("fit {} --lights 3 --same-face -o {}", env.string(), lights.string())) != 0);
    CHECK(run(fmt::format("fit {} --lights 3 -o {}", (dir / "missing.exr").string(), lights.string())) != 0);

    // A preview path that is no .png (a PNG was written into scene.json) is refused before any work.
    const fs::path scene = dir / "scene.json";
    test::write_text(scene, "{}\n");
    const auto [status, text] = test::run_rsl(fmt::format("fit {} --lights 12 --resolution 8 -o {} --preview {}",
                                                          env.string(), (dir / "other.json").string(), scene.string()));
    INFO(text);
    CHECK(status == 1);
    CHECK(text.find("rsl: error: --preview " + scene.string() + ": expected a .png path") != std::string::npos);
    CHECK(test::read_bytes(scene) == "{}\n");
    CHECK_FALSE(fs::exists(dir / "other.json"));
    fs::remove_all(dir);
}
