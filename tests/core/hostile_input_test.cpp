// Regression tests for what mutation fuzzing found (issue 20): each builds the
// bad file the way the fuzzer did (flipped bits, a corrupted header field,
// an out-of-range number) and checks the refusal names the file and the
// problem, quickly and before large allocations.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstring>
#include <string>

#include "lightfit/decompose.h"
#include "src/core/atomic_file.h"
#include "src/core/envmap.h"
#include "src/core/error.h"
#include "src/core/image.h"
#include "src/core/scene.h"
#include "tests/test_support.h"

using namespace rsl;
namespace fs = std::filesystem;

namespace {

// A flat (not run-length encoded) Radiance file: every pixel mantissa 100,
// exponent 128 (about 0.39), so no scanline starts with the RLE marker 2, 2.
std::string flat_radiance(int width, int height) {
    std::string bytes = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " +
                        std::to_string(width) + "\n";
    for (int k = 0; k < width * height; ++k) bytes += std::string{char(100), char(100), char(100), char(128)};
    return bytes;
}

// Patches one int32 of an EXR header's box2i attribute `name` (index 0..3:
// xMin, yMin, xMax, yMax), as a bit flip in the header would.
void patch_box(std::string& exr, const std::string& name, int index, int32_t value) {
    const std::string key = name + std::string(1, '\0') + "box2i" + std::string(1, '\0');
    const size_t at = exr.find(key);
    REQUIRE(at != std::string::npos);
    std::memcpy(exr.data() + at + key.size() + 4 + 4 * index, &value, 4);  // after the u32 attribute size
}

}  // namespace

TEST_CASE("A flipped exponent (huge but finite radiance) is refused by the reader and the fit", "[bad-input][fuzz]") {
    const fs::path dir = test::scratch_dir("hostile_radiance");
    std::string bytes = flat_radiance(64, 32);
    const size_t pixel = size_t(3) * 64 + 7;  // (x=7, y=3)
    const size_t exponent = bytes.size() - size_t(64 * 32 - pixel) * 4 + 3;
    bytes[exponent] = char(uint8_t(bytes[exponent]) ^ 0x78);  // 128 → 248: about 5e35
    write_file_atomically(dir / "flipped.hdr", bytes);
    CHECK_THROWS_WITH(read_hdr_image(dir / "flipped.hdr"), Catch::Contains("flipped.hdr") &&
                                                               Catch::Contains("implausibly large") &&
                                                               Catch::Contains("x=7, y=3"));
    // Maps built in code reach the fit without a reader: it refuses them too,
    // at once, instead of comparing NaN costs for minutes.
    CubeMap map(16);
    for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = Color(0.5f);
    map.radiance(77) = Color(5e36f, 0.5f, 0.5f);
    const auto start = std::chrono::steady_clock::now();
    CHECK_THROWS_WITH(lightfit::decompose(map, {.lights = 10}), Catch::Contains("texel 77") && Catch::Contains("1e15"));
    CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 5.0);
    map.radiance(77) = Color(std::nanf(""));
    CHECK_THROWS_WITH(lightfit::decompose(map, {.lights = 10}), Catch::Contains("texel 77"));
    fs::remove_all(dir);
}

TEST_CASE("A Radiance header claiming more pixels than the file holds is refused before allocating",
          "[bad-input][fuzz]") {
    const fs::path dir = test::scratch_dir("hostile_hdr_size");
    std::string bytes = flat_radiance(64, 32);
    bytes.replace(bytes.find("-Y 32 +X 64"), 11, "-Y 16000 +X 16000");  // 3 GB of floats, if believed
    write_file_atomically(dir / "huge.hdr", bytes);
    CHECK_THROWS_WITH(read_hdr_image(dir / "huge.hdr"),
                      Catch::Contains("huge.hdr") && Catch::Contains("truncated or corrupt") &&
                          Catch::Contains("16000×16000"));
    fs::remove_all(dir);
}

TEST_CASE("An EXR whose data window was corrupted is refused before reading pixels", "[bad-input][fuzz]") {
    const fs::path dir = test::scratch_dir("hostile_exr_window");
    Image image(64, 32, 3);
    for (size_t k = 0; k < image.pixels.size(); ++k) image.pixels[k] = 0.01f * float(k % 97);
    write_exr(dir / "latlong.exr", image, {.envmap = EnvmapKind::LatLong});
    write_exr(dir / "plain.exr", image, {});
    // Declared lat-long, data window 100001 wide: the fuzzer's 28 s and 3.4 GB.
    std::string latlong = read_file(dir / "latlong.exr");
    patch_box(latlong, "dataWindow", 2, 100000);
    write_file_atomically(dir / "wide.exr", latlong);
    const auto start = std::chrono::steady_clock::now();
    CHECK_THROWS_WITH(read_hdr_image(dir / "wide.exr"), Catch::Contains("wide.exr") &&
                                                            Catch::Contains("latitude-longitude") &&
                                                            Catch::Contains("100001×32"));
    CHECK_THROWS_WITH(load_environment(dir / "wide.exr", 32), Catch::Contains("wide.exr"));
    CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 2.0);
    // No layout declared: the window needs more data than any compression fits in the file.
    std::string plain = read_file(dir / "plain.exr");
    patch_box(plain, "dataWindow", 2, 1000000);  // 1 M wide: 384 MB of floats, if believed
    write_file_atomically(dir / "wide_plain.exr", plain);
    CHECK_THROWS_WITH(read_hdr_image(dir / "wide_plain.exr"),
                      Catch::Contains("wide_plain.exr") && Catch::Contains("needs more data than the file"));
    fs::remove_all(dir);
}

TEST_CASE("An out-of-range JSON number names the file, line, column and key, and is bad input", "[bad-input][fuzz]") {
    const fs::path dir = test::scratch_dir("hostile_json");
    test::write_text(dir / "tet.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
    test::write_text(dir / "good.json", R"({ "parts": [{ "obj": "tet.obj" }] })");
    test::write_text(dir / "overflow.json", "{ \"parts\": [{ \"obj\": \"tet.obj\" }],\n  \"camera\": { \"fov_degrees\": 1e309 } }");
    test::write_text(dir / "array.json", "{ \"parts\": [{ \"obj\": \"tet.obj\" }],\n  \"lights\": [{ \"position\": [1, 2, -1e999] }] }");
    CHECK_THROWS_WITH(load_scene(dir / "overflow.json"),
                      Catch::Contains("overflow.json: line 2, column") &&
                          Catch::Contains("key camera.fov_degrees") && Catch::Contains("1e309"));
    CHECK_THROWS_WITH(load_scene(dir / "array.json"),
                      Catch::Contains("array.json: line 2") && Catch::Contains("key lights[0].position[2]"));
    // The program: status 1 (bad input, not an internal error), and the next file is still reported.
    const auto [status, text] =
        test::run_rsl("info " + (dir / "overflow.json").string() + " " + (dir / "good.json").string());
    INFO(text);
    CHECK(status == 1);
    CHECK(text.find("internal error") == std::string::npos);
    CHECK(text.find("key camera.fov_degrees") != std::string::npos);
    CHECK(text.find("good.json: scene") != std::string::npos);
    fs::remove_all(dir);
}
