// .rslv files: exact round trip, and refusal of foreign, truncated, corrupt,
// other-version and mismatched files with a message naming the file.
#include <cstring>
#include <filesystem>
#include <random>

#include <catch2/catch.hpp>

#include "src/core/atomic_file.h"
#include "src/formats/binary_io.h"
#include "src/core/texture.h"
#include "src/core/error.h"
#include "src/formats/vertex_colors.h"
#include "tests/test_support.h"
#include "tests/random_cases.h"

using namespace rsl;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir() { return test::scratch_dir("vertex_colors"); }
using test::error_of;

VertexColors random_colors(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uni(0, 5);
    VertexColors c;
    c.scene_name = "robot";
    c.producer = "truth";
    c.time = 1.25f;
    c.add_part("torso", 37);
    c.add_part("arm.left", 0);  // empty parts are allowed
    c.add_part("head", 101);
    for (auto& part : c.parts)
        for (Color& v : part) v = test::random_vec3(uni, rng);
    return c;
}

}  // namespace

TEST_CASE("Vertex colours round-trip exactly", "[trace][vertex_colors]") {
    const fs::path path = temp_dir() / "roundtrip.rslv";
    const VertexColors original = random_colors(1);
    write_vertex_colors(path, original);
    const VertexColors back = read_vertex_colors(path);
    REQUIRE(back.scene_name == original.scene_name);
    REQUIRE(back.producer == original.producer);
    REQUIRE(back.time == original.time);
    REQUIRE(back.part_names == original.part_names);
    REQUIRE(back.vertex_count() == 138);
    for (size_t p = 0; p < original.parts.size(); ++p)
        for (size_t v = 0; v < original.parts[p].size(); ++v) REQUIRE(back.parts[p][v] == original.parts[p][v]);
    REQUIRE_NOTHROW(check_same_vertices(back, path, original, "b.rslv"));
}

TEST_CASE("Corrupt, truncated, foreign and other-version files are refused", "[trace][vertex_colors]") {
    const fs::path path = temp_dir() / "good.rslv";
    write_vertex_colors(path, random_colors(2));
    const std::string good = read_file(path);
    const fs::path bad = temp_dir() / "bad.rslv";

    SECTION("every single flipped byte is caught") {
        // Any byte: header fields, names, data or the checksum itself.
        for (size_t at = 0; at < good.size(); at += 7) {
            std::string bytes = good;
            bytes[at] = char(bytes[at] ^ 0x10);
            write_file_atomically(bad, bytes);
            const std::string message = error_of([&] { read_vertex_colors(bad); });
            INFO("byte " << at << ": " << message);
            REQUIRE(message.find(bad.string()) == 0);
        }
    }
    SECTION("truncation") {
        for (size_t size : {size_t(0), size_t(5), size_t(20), good.size() / 2, good.size() - 1}) {
            write_file_atomically(bad, good.substr(0, size));
            const std::string message = error_of([&] { read_vertex_colors(bad); });
            INFO(message);
            REQUIRE(message.find(bad.string()) == 0);
        }
    }
    SECTION("foreign file") {
        write_file_atomically(bad, "P6\n2 2\n255\n............");
        REQUIRE_THAT(error_of([&] { read_vertex_colors(bad); }), Catch::Contains("wrong magic"));
    }
    SECTION("other version") {
        std::string bytes = good;
        bytes[8] = 3;  // the u32 after the 8-byte magic
        write_file_atomically(bad, bytes);
        REQUIRE_THAT(error_of([&] { read_vertex_colors(bad); }), Catch::Contains("version 3"));
    }
    SECTION("missing file") {
        REQUIRE_THROWS_AS(read_vertex_colors(temp_dir() / "absent.rslv"), Error);
    }
}

TEST_CASE("Files of different geometry are not comparable", "[trace][vertex_colors]") {
    const VertexColors a = random_colors(3);
    auto expect_mismatch = [&](VertexColors b, const char* fragment) {
        REQUIRE_THAT(error_of([&] { check_same_vertices(a, "a.rslv", b, "b.rslv"); }),
                     Catch::Contains("a.rslv and b.rslv") && Catch::Contains(fragment));
    };
    VertexColors b = a;
    b.scene_name = "kitchen";
    expect_mismatch(b, "scenes");
    b = a;
    b.parts[2].pop_back();
    expect_mismatch(b, "vertices");
    b = a;
    b.add_part("extra", 3);
    expect_mismatch(b, "parts");
    b = a;
    b.part_names[0] = "legs";
    expect_mismatch(b, "legs");
    b = a;
    b.time = 2.0f;
    expect_mismatch(b, "times");
}

TEST_CASE("layered (textured) parts round-trip as version 2; files without them stay version 1",
          "[frame][vertex_colors]") {
    VertexColors colors;
    colors.scene_name = "layers";
    colors.producer = "test";
    colors.add_part("plain", 3);
    colors.add_part("textured", 2, std::make_shared<Texture>());
    colors.parts[0] = {Color(1, 2, 3), Color(4, 5, 6), Color(7, 8, 9)};
    colors.parts[1] = {Color(0.5f), Color(0.25f)};
    colors.specular[1] = {Color(0.1f, 0.2f, 0.3f), Color(0.4f)};
    const auto path = temp_dir() / "layers.rslv";
    write_vertex_colors(path, colors);
    const std::string bytes = read_file(path);
    CHECK(bytes[8] == 2);
    const VertexColors back = read_vertex_colors(path);
    CHECK(!back.layered(0));
    REQUIRE(back.layered(1));
    CHECK(back.parts == colors.parts);
    CHECK(back.specular[1] == colors.specular[1]);
    // At unit texture a layered part is diffuse + specular, and compares so.
    const VertexColors folded = back.at_unit_texture();
    CHECK(!folded.layered(1));
    CHECK(folded.parts[1][0] == Color(0.6f, 0.7f, 0.8f));
    write_vertex_colors(path, folded);
    CHECK(read_file(path)[8] == 1);
    // A layered file against an unlayered one of the same vertices is not comparable.
    CHECK_THROWS_WITH(check_same_vertices(back, "a.rslv", folded, "b.rslv"), Catch::Contains("layered"));
}

TEST_CASE("A layered part's vertex count that overflows when doubled is refused", "[frame][vertex_colors][bad-input]") {
    // fuzz_vertex_colors (10-minute run): 2^63 + 2 vertices in two layers
    // wrapped to 4, which the data matched; allocating them threw
    // std::length_error instead of an error naming the file.
    VertexColors colors;
    colors.scene_name = "overflow";
    colors.producer = "test";
    colors.add_part("textured_part", 2, std::make_shared<Texture>());
    const auto path = temp_dir() / "overflow.rslv";
    write_vertex_colors(path, colors);
    std::string bytes = read_file(path);
    const size_t name = bytes.find("textured_part");
    REQUIRE(name != std::string::npos);
    const uint64_t wrapping = (uint64_t(1) << 63) + 2;
    std::memcpy(bytes.data() + name + std::strlen("textured_part"), &wrapping, sizeof wrapping);
    const uint64_t checksum = fnv1a64(bytes.data(), bytes.size() - 8);
    std::memcpy(bytes.data() + bytes.size() - 8, &checksum, 8);
    write_file_atomically(path, bytes);
    const std::string message = error_of([&] { read_vertex_colors(path); });
    CHECK(message.find(path.string()) == 0);
    CHECK_THAT(message, Catch::Contains("do not fit in the file"));
}
