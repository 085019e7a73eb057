// `rsl baselines` end to end on the bunny at a 6×2² cube (24 texels, so every
// method can keep every term): the rows with every term are the truth, the
// objects' error and worst part are the bunny's own, and --no-ground refuses
// a scene without a ground. Seconds, not minutes: no RSL bake (--no-rsl).
#include <filesystem>
#include <fstream>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "tests/test_support.h"

namespace rsl {
namespace {

const std::filesystem::path kBunny = std::filesystem::path(RSL_SOURCE_DIR) / "assets/external/bunny.json";

nlohmann::json row(const nlohmann::json& results, const std::string& method, int terms) {
    for (const auto& r : results["methods"])
        if (r["method"] == method && r["terms"] == terms) return r;
    FAIL("no row " << method << " " << terms);
    return {};
}

// With all 24 texels kept, Haar, eigentransport and the exact triple product
// are the transport sum, which is the truth: in vertices and in the image.
void check_every_term_is_truth(const nlohmann::json& results) {
    for (const auto& [method, terms] : {std::pair{"haar", 24}, std::pair{"eigen", 24}}) {
        const nlohmann::json r = row(results, method, terms);
        INFO(method << " " << terms);
        CHECK(double(r["vertex_error"]) < 1e-5);
        CHECK(double(r["image_error"]) < 1e-5);
    }
    CHECK(double(results["triple_exact_vertex_error"]["24"]) < 1e-5);
}

TEST_CASE("rsl baselines: eigentransport and the triple product with every term are the truth", "[baselines][cli]") {
    if (!std::filesystem::exists(std::filesystem::path(RSL_SHARED_ASSETS) / "probes/grace.hdr")) {
        WARN("SKIPPED: bunny.json needs " << RSL_SHARED_ASSETS);
        return;
    }
    for (bool no_ground : {false, true}) {
        INFO("--no-ground " << no_ground);
        const std::string dir = std::string(RSL_BINARY_DIR) + "/baselines_cli_" + (no_ground ? "no_ground" : "ground");
        std::filesystem::remove_all(dir);
        const auto [status, output] = test::run_rsl(
            "baselines " + kBunny.string() + " --resolution 2 --no-rsl --sh-orders 2 --haar-terms 24 --haar-drop 0 "
            "--eigen-terms 4,24 --triple-terms 24 --width 64 --height 48 --repeats 1 -q -o " + dir +
            (no_ground ? " --no-ground" : ""));
        INFO(output);
        REQUIRE(status == 0);
        std::ifstream file(dir + "/results.json");
        const nlohmann::json results = nlohmann::json::parse(file);
        CHECK(results["no_ground"] == no_ground);
        CHECK(results["vertices"] == (no_ground ? 34834 : 60755));
        check_every_term_is_truth(results);
        // Four eigentransports are an approximation the check can see.
        CHECK(double(row(results, "eigen", 4)["vertex_error"]) > 1e-2);
        CHECK(double(results["eigen"]["captured_variance"]["24"]) == Approx(1.0).epsilon(1e-5));
        // The bunny is the one object: its error is the objects' error and the worst part's.
        const nlohmann::json triple = row(results, "triple", 24);
        CHECK(triple["worst_part"] == "bunny");
        CHECK(double(triple["worst_part_error"]) == Approx(double(triple["objects_error"])).epsilon(1e-6));
        if (no_ground)
            CHECK(double(triple["objects_error"]) == Approx(double(triple["vertex_error"])).epsilon(1e-6));
        else
            CHECK(double(triple["objects_error"]) != Approx(double(triple["vertex_error"])).epsilon(1e-3));
        for (const char* file_name : {"table.md", "sheet.png", "error_plot.png", "eigen_24.png", "triple_24.png"})
            CHECK(std::filesystem::exists(dir + "/" + file_name));
    }
}

// pbr.json's textured parts: the PRT rows integrate the whole material at unit
// texture (both lobes), and so must the truth they are compared with, in
// vertices and in the image (which then carries no texture).
TEST_CASE("rsl baselines compares textured parts at unit texture, both lobes", "[baselines][cli]") {
    const std::string dir = std::string(RSL_BINARY_DIR) + "/baselines_cli_textured";
    std::filesystem::remove_all(dir);
    const auto [status, output] = test::run_rsl(
        "baselines " + std::string(RSL_SOURCE_DIR) + "/assets/scenes/pbr.json --resolution 2 --no-rsl --sh-orders 2 "
        "--haar-terms 24 --haar-drop 0 --eigen-terms 24 --triple-terms 24 --width 64 --height 48 --repeats 1 -q -o " + dir);
    INFO(output);
    REQUIRE(status == 0);
    std::ifstream file(dir + "/results.json");
    const nlohmann::json results = nlohmann::json::parse(file);
    CHECK(double(results["transport_vs_truth_error"]) < 1e-5);
    check_every_term_is_truth(results);
}

TEST_CASE("rsl baselines --no-ground refuses a scene without a ground, naming it and its parts", "[baselines][cli]") {
    const std::string scene = std::string(RSL_SOURCE_DIR) + "/assets/generated/orb.obj";  // one part, no ground
    const std::string dir = std::string(RSL_BINARY_DIR) + "/baselines_cli_refused";
    std::filesystem::remove_all(dir);
    const auto [status, output] = test::run_rsl("baselines " + scene + " --no-ground --no-rsl -q -o " + dir);
    INFO(output);
    CHECK(status != 0);
    CHECK(output.find("orb.obj") != std::string::npos);
    CHECK(output.find("--no-ground: no part is named ground or floor") != std::string::npos);
    CHECK(!std::filesystem::exists(dir + "/results.json"));
}

// An input kept in the output folder under a name the run writes (a map
// called truth.exr) is refused before any work, and stays as it was.
TEST_CASE("rsl baselines refuses an output folder where it would replace an input", "[baselines][cli][issue-56]") {
    const std::filesystem::path dir = test::scratch_dir("baselines_cli_inputs");
    const std::filesystem::path generated = std::filesystem::path(RSL_SOURCE_DIR) / "assets/generated";
    std::filesystem::copy_file(generated / "sunsky.exr", dir / "truth.exr", std::filesystem::copy_options::overwrite_existing);
    const auto size = std::filesystem::file_size(dir / "truth.exr");
    test::write_text(dir / "scene.json", R"({"parts": [{"name": "orb", "obj": ")" + (generated / "orb.obj").string() +
                                             R"("}], "environment": {"file": "truth.exr"}})");
    for (const std::string mode : {" --no-rsl", " --many-light"}) {
        INFO("mode '" << mode << "'");
        const auto [status, output] =
            test::run_rsl("baselines " + (dir / "scene.json").string() + mode + " -q -o " + dir.string());
        INFO(output);
        CHECK(status != 0);
        CHECK(output.find("truth.exr") != std::string::npos);
        CHECK(output.find("this output is the input") != std::string::npos);
        CHECK(std::filesystem::file_size(dir / "truth.exr") == size);
        CHECK(!std::filesystem::exists(dir / "results.json"));
    }
}

}  // namespace
}  // namespace rsl
