// RslSet: rotation and its JSON file (round trip, refusal of bad files).
#include <filesystem>
#include <fstream>
#include <random>

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "src/lightfit/square_light.h"
#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "tests/test_support.h"
#include "tests/random_cases.h"

using namespace rsl;
namespace fs = std::filesystem;

namespace {

RslSet random_set(unsigned seed, int count, int resolution) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> g;
    std::uniform_real_distribution<float> u(0.01f, 0.5f);
    RslSet set;
    set.resolution = resolution;
    for (int i = 0; i < count; ++i)
        set.lights.push_back({glm::normalize(test::random_vec3(g, rng)), u(rng),
                              Color(test::random_vec3(u, rng) * Vec3(10, 1, 3)), int(u(rng) * 100), u(rng) * 1e-3f});
    std::uniform_int_distribution<int> label(0, count - 1);
    for (int t = 0; t < 6 * resolution * resolution; ++t) set.region_of_texel.push_back(label(rng));
    return set;
}

fs::path temp_dir() { return test::scratch_dir("lightfit_rsl"); }

using test::write_text;

}  // namespace

TEST_CASE("rotating an RSL set rotates its centers and keeps its energy", "[lightfit][rsl]") {
    RslSet set = random_set(1, 20, 4);
    const RslSet original = set;
    const Mat3 rotation = Mat3(glm::rotate(glm::mat4(1.0f), 1.1f, glm::normalize(Vec3(0.3f, -1.0f, 0.4f))));
    set.rotate(rotation);
    for (size_t i = 0; i < set.lights.size(); ++i) {
        CHECK(glm::length(set.lights[i].center - rotation * original.lights[i].center) < 1e-6f);
        CHECK(set.lights[i].half_diagonal == original.lights[i].half_diagonal);
        CHECK(set.lights[i].radiance == original.lights[i].radiance);
    }
    CHECK(glm::length(set.total_energy() - original.total_energy()) == 0.0);
    CHECK(set.region_of_texel.empty());  // labels described the unrotated map
    // Rotating back restores the centers.
    set.rotate(glm::transpose(rotation));
    for (size_t i = 0; i < set.lights.size(); ++i)
        CHECK(glm::length(set.lights[i].center - original.lights[i].center) < 1e-6f);
}

TEST_CASE("an RSL set survives a JSON round trip", "[lightfit][rsl]") {
    const RslSet set = random_set(2, 37, 8);
    const fs::path path = temp_dir() / "round_trip.json";
    save_rsl_set(path, set);
    const RslSet back = load_rsl_set(path);
    REQUIRE(back.lights.size() == set.lights.size());
    CHECK(back.resolution == set.resolution);
    CHECK(back.region_of_texel == set.region_of_texel);
    for (size_t i = 0; i < set.lights.size(); ++i) {
        const auto &a = set.lights[i], &b = back.lights[i];
        CHECK(glm::length(a.center - b.center) < 1e-6f);
        CHECK(a.half_diagonal == b.half_diagonal);  // floats print round-trip exact
        CHECK(a.radiance == b.radiance);
        CHECK(a.texel_count == b.texel_count);
        CHECK(a.fit_error == b.fit_error);
    }
    // Without labels the file is still valid.
    RslSet unlabeled = set;
    unlabeled.region_of_texel.clear();
    save_rsl_set(path, unlabeled);
    CHECK(load_rsl_set(path).region_of_texel.empty());
}

TEST_CASE("a bad RSL file is refused with its name and the problem", "[lightfit][rsl]") {
    const fs::path dir = temp_dir();
    const fs::path good = dir / "good.json";
    save_rsl_set(good, random_set(3, 3, 2));
    const std::string text = rsl::read_file(good);

    struct Case {
        std::string name, from, to, message;
    };
    const std::vector<Case> cases = {
        {"truncated", "", "", "invalid JSON"},
        {"wrong_format", "\"rsl-lights\"", "\"something-else\"", "format"},
        {"wrong_version", "\"version\": 1", "\"version\": 7", "version 7"},
        {"negative_radius", "\"half_diagonal\": ", "\"half_diagonal\": -", "lights[0].half_diagonal"},
        {"no_lights", "\"lights\"", "\"lamps\"", "'lights'"},
        {"bad_resolution", "\"resolution\": 2", "\"resolution\": 3", "region_of_texel has 24 entries"},
    };
    for (const auto& c : cases) {
        const fs::path bad = dir / (c.name + ".json");
        std::string contents = text;
        if (c.name == "truncated") {
            contents = text.substr(0, text.size() / 2);
        } else {
            const auto at = contents.find(c.from);
            REQUIRE(at != std::string::npos);
            contents.replace(at, c.from.size(), c.to);
        }
        write_text(bad, contents);
        INFO(c.name);
        try {
            load_rsl_set(bad);
            FAIL("accepted a bad file: " << c.name);
        } catch (const rsl::Error& e) {
            const std::string what = e.what();
            CHECK_THAT(what, Catch::Contains(bad.string()));
            CHECK_THAT(what, Catch::Contains(c.message));
        }
    }
    // A center that is not a unit vector.
    {
        RslSet set = random_set(4, 2, 2);
        set.lights[1].center = Vec3(0.5f, 0.0f, 0.0f);
        const fs::path bad = dir / "not_unit.json";
        save_rsl_set(bad, set);
        CHECK_THROWS_WITH(load_rsl_set(bad), Catch::Contains(bad.string()) && Catch::Contains("lights[1].center"));
    }
    CHECK_THROWS_WITH(load_rsl_set(dir / "missing.json"), Catch::Contains("missing.json"));
}
