// The renderer's memory estimate (src/render/memory_estimate.h): a scene of
// many instanced parts is refused before its fields are baked, naming the
// file and the way out, and an accepted scene's measured peak stays within
// 1.5× of the estimate.
#include <catch2/catch.hpp>

#include <chrono>
#include <fstream>
#include <regex>

#include <sys/resource.h>

#include "tests/test_support.h"

using namespace rsl;

// AddressSanitizer's shadow memory and quarantine multiply a program's
// resident memory, so the sanitizer build (scripts/sanitize.sh) cannot
// measure the plain program's peak.
#if defined(__SANITIZE_ADDRESS__)
#define RSL_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RSL_TEST_UNDER_ASAN 1
#endif
#endif

namespace {

// A glTF of `nodes` nodes, each instancing one unit triangle, and a scene
// file that subdivides them (289 vertices a part) under the generated sky.
std::filesystem::path instanced_triangles(const std::filesystem::path& dir, int nodes) {
    // The triangle (0,0,0) (1,0,0) (0,1,0) as 9 little-endian floats, base64.
    const std::string buffer = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
    std::string node_list, scene_nodes;
    for (int i = 0; i < nodes; ++i) {
        node_list += fmt::format("{}{{\"mesh\":0,\"translation\":[{},0,{}]}}", i ? "," : "", 1.5 * (i % 100),
                                 1.5 * (i / 100));
        scene_nodes += fmt::format("{}{}", i ? "," : "", i);
    }
    test::write_text(dir / "many.gltf",
                     fmt::format(R"({{"asset":{{"version":"2.0"}},
"buffers":[{{"byteLength":36,"uri":"data:application/octet-stream;base64,{}"}}],
"bufferViews":[{{"buffer":0,"byteLength":36}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
"nodes":[{}],"scenes":[{{"nodes":[{}]}}],"scene":0}})",
                                 buffer, node_list, scene_nodes));
    test::write_text(dir / "scene.json", fmt::format(R"({{"gltf": "many.gltf",
"environment": {{"file": "{}/assets/generated/sunsky.exr", "resolution": 16}},
"precompute": {{"svdf": {{"resolution": 8, "clusters": 16, "vectors": 4}},
               "ovdf": {{"shells": 4, "cube_resolution": 8, "vdt_resolution": 8, "vectors": 4}}}}}})",
                                                     RSL_SOURCE_DIR));
    return dir / "scene.json";
}

uint64_t estimate_of(const std::string& info_output) {
    std::smatch m;
    REQUIRE(std::regex_search(info_output, m, std::regex(R"(memory: +about ([0-9.]+) (GB|MB|kB) to render)")));
    const double unit = m[2] == "GB" ? 1e9 : m[2] == "MB" ? 1e6 : 1e3;
    return uint64_t(std::stod(m[1]) * unit);
}

}  // namespace

TEST_CASE("a scene whose render passes the memory limit is refused before its fields are baked", "[render][memory]") {
    const auto dir = test::scratch_dir("memory_refused");
    const auto scene = instanced_triangles(dir, 3000);
    const auto [info_status, info] = test::run_rsl("info " + scene.string() + " --memory-limit 300M");
    INFO(info);
    REQUIRE(info_status == 0);  // the meshes alone (about 83 MB) fit
    CHECK(estimate_of(info) > (300ull << 20));

    const auto [status, output] = test::run_rsl("render " + scene.string() + " -o " + (dir / "out.exr").string() +
                                                " --memory-limit 300M");
    INFO(output);
    CHECK(status == 1);
    CHECK_THAT(output, Catch::Contains("scene.json") && Catch::Contains("867000 vertices in 3000 parts") &&
                           Catch::Contains("over rsl's limit of 315 MB") && Catch::Contains("--memory-limit"));
    CHECK_FALSE(std::filesystem::exists(dir / ".rsl-cache"));  // nothing baked
    CHECK_FALSE(std::filesystem::exists(dir / "out.exr"));

    const auto [bad_status, bad] = test::run_rsl("--memory-limit lots info " + scene.string());
    CHECK(bad_status != 0);
    CHECK_THAT(bad, Catch::Contains("--memory-limit 'lots': not a memory size"));
}

TEST_CASE("an accepted render's peak memory is within 1.5x of its estimate", "[render][memory]") {
#ifdef RSL_TEST_UNDER_ASAN
    WARN("SKIPPED: a sanitizer build's peak memory is not the program's");
    return;
#endif
    const auto dir = test::scratch_dir("memory_peak");
    const auto scene = instanced_triangles(dir, 600);
    const auto [info_status, info] = test::run_rsl("info " + scene.string());
    INFO(info);
    REQUIRE(info_status == 0);
    const uint64_t estimate = estimate_of(info);
    const auto [status, output] = test::run_rsl("render " + scene.string() + " -q --width 64 --height 48 -o " +
                                                (dir / "out.exr").string());
    INFO(output);
    REQUIRE(status == 0);
    rusage usage{};
    REQUIRE(getrusage(RUSAGE_CHILDREN, &usage) == 0);
    const uint64_t peak = uint64_t(usage.ru_maxrss) * 1024;  // the largest child's resident peak, in kB
    INFO("peak " << peak / 1e6 << " MB, estimate " << estimate / 1e6 << " MB");
    CHECK(peak <= estimate * 3 / 2);
    CHECK(peak >= estimate / 4);  // an estimate that still measures something
}

TEST_CASE("an image too large for the memory limit is refused before any work, naming its size", "[render][memory]") {
    const auto dir = test::scratch_dir("memory_image");
    const auto scene = instanced_triangles(dir, 1);
    for (const std::string command : {"render", "truth"}) {
        const auto start = std::chrono::steady_clock::now();
        const auto [status, output] = test::run_rsl(command + " " + scene.string() + " -q --width 16384 --height 16384 " +
                                                    "--memory-limit 300M -o " + (dir / "big.exr").string());
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        INFO(command << " (" << seconds << " s)\n" << output);
        CHECK(status == 1);
        // 16384² × 32 bytes: 8.6 GB, whatever else the run needs.
        CHECK_THAT(output, Catch::Contains(scene.string() + ": needs about 8.") && Catch::Contains("16384×16384 image") &&
                               Catch::Contains("a smaller image") && Catch::Contains("over rsl's limit of 315 MB"));
        CHECK(seconds < 20);  // before the fit, the bake and the image (minutes and 4 GB and more)
        CHECK_FALSE(std::filesystem::exists(dir / "big.exr"));
        CHECK_FALSE(std::filesystem::exists(dir / ".rsl-cache"));
    }
    for (const std::string command : {"render", "truth"}) {  // a small image of the same scene fits the same limit
        const auto [small_status, small] = test::run_rsl(command + " " + scene.string() + " -q --width 64 --height 48 " +
                                                         "--memory-limit 300M -o " + (dir / "small.exr").string());
        INFO(small);
        CHECK(small_status == 0);
    }
}

TEST_CASE("a skinned character's estimate counts its posed vertices, and its render's peak stays within 1.5x",
          "[render][memory][skin]") {
    const auto dir = test::scratch_dir("memory_skinned");
    test::write_text(dir / "scene.json", fmt::format(R"({{"gltf": "{0}/assets/generated/tube.glb",
"environment": {{"file": "{0}/assets/generated/sunsky.exr", "resolution": 16}},
"precompute": {{"svdf": {{"resolution": 8, "clusters": 16, "vectors": 4}},
               "ovdf": {{"shells": 4, "cube_resolution": 8, "vdt_resolution": 8, "vectors": 4}}}}}})",
                                                     RSL_SOURCE_DIR));
    const std::string scene = (dir / "scene.json").string();
    // The refusal's account names the skinned vertices.
    const auto [refused_status, refused] = test::run_rsl("render " + scene + " -o " + (dir / "x.exr").string() +
                                                         " --memory-limit 1M");
    INFO(refused);
    CHECK(refused_status == 1);
    CHECK_THAT(refused, Catch::Matches(R"((.|\n)*[0-9]+ vertices \([0-9]+ skinned\) in [0-9]+ parts(.|\n)*)"));
#ifdef RSL_TEST_UNDER_ASAN
    WARN("SKIPPED: a sanitizer build's peak memory is not the program's");
    return;
#endif
    const auto [info_status, info] = test::run_rsl("info " + scene);
    INFO(info);
    REQUIRE(info_status == 0);
    const uint64_t estimate = estimate_of(info);
    const auto [status, output] = test::run_rsl("render " + scene + " -q --frames 0:1:0.5 --width 64 --height 48 -o " +
                                                (dir / "out.exr").string());
    INFO(output);
    REQUIRE(status == 0);
    rusage usage{};
    REQUIRE(getrusage(RUSAGE_CHILDREN, &usage) == 0);
    const uint64_t peak = uint64_t(usage.ru_maxrss) * 1024;
    INFO("peak " << peak / 1e6 << " MB, estimate " << estimate / 1e6 << " MB");
    CHECK(peak <= estimate * 3 / 2);
}
