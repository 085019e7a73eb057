#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>

#include "src/fields/field_file.h"
#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "tests/hostile_inputs.h"
#include "tests/test_support.h"

using namespace rsl;
namespace fs = std::filesystem;

namespace {

// A small SVDF with random-ish content (the file format does not care).
Svdf small_svdf() {
    Svdf svdf;
    svdf.params.resolution = 4;
    svdf.params.vectors = 2;
    CpcaModel& m = svdf.model;
    m.dims = 16;
    m.vectors = 2;
    m.clusters = 2;
    for (int i = 0; i < 2 * 16 * 3; ++i) m.tables.push_back(round_to_half(0.01f * float(i % 37) - 0.1f));
    for (int s = 0; s < 5; ++s) {
        m.assignment.push_back(s % 2);
        m.coefficients.push_back(0.5f * s);
        m.coefficients.push_back(-0.25f * s);
    }
    return svdf;
}

fs::path temp_path(const std::string& name) { return test::scratch_dir("field_file") / name; }
using test::error_of;

}  // namespace

TEST_CASE("field files round-trip exactly", "[field_file]") {
    const Svdf svdf = small_svdf();
    const fs::path path = temp_path("roundtrip.rslf");
    write_svdf(path, svdf, 1234);
    const Svdf back = read_svdf(path, {1234ull, params_json(svdf.params)});
    CHECK(back.model.tables == svdf.model.tables);  // values were already half-representable
    CHECK(back.model.assignment == svdf.model.assignment);
    CHECK(back.model.coefficients == svdf.model.coefficients);
    CHECK(back.params.resolution == 4);
    const FieldHeader h = read_field_header(path);
    CHECK(h.kind == FieldKind::Svdf);
    CHECK(h.samples == 5);
    CHECK(h.mesh_hash == 1234);
}

TEST_CASE("corrupt, truncated, foreign and stale field files are refused by name", "[field_file]") {
    const Svdf svdf = small_svdf();
    const fs::path good = temp_path("good.rslf");
    write_svdf(good, svdf, 99);
    const std::string bytes = read_file(good);

    const fs::path bad = temp_path("bad.rslf");
    auto refused = [&](const std::string& contents, const FieldExpectation& expect = {}) {
        write_file_atomically(bad, contents);
        const std::string message = error_of([&] { read_svdf(bad, expect); });
        INFO(message);
        CHECK(message.find(bad.string()) != std::string::npos);  // names the file
        return message;
    };
    // One flipped bit anywhere in the payload.
    for (size_t at : {size_t(20), bytes.size() / 2, bytes.size() - 12}) {
        std::string corrupt = bytes;
        corrupt[at] ^= 0x10;
        CHECK(refused(corrupt).find("checksum") != std::string::npos);
    }
    // Truncated at several points (including inside the header).
    for (size_t keep : {size_t(4), size_t(30), bytes.size() / 2, bytes.size() - 1})
        CHECK(!refused(bytes.substr(0, keep)).empty());
    // Foreign.
    CHECK(refused("P6\n1 1\n255\nabc" + std::string(64, 'x')).find("not an rsl field file") != std::string::npos);
    // Stale: another mesh, other parameters, another kind.
    CHECK(refused(bytes, {uint64_t(100), std::nullopt}).find("different mesh") != std::string::npos);
    SvdfParams other = svdf.params;
    other.clusters = 17;
    CHECK(refused(bytes, {std::nullopt, params_json(other)}).find("stale") != std::string::npos);
    write_file_atomically(bad, bytes);
    CHECK(error_of([&] { read_ovdf(bad); }).find("SVDF") != std::string::npos);
    // A future format version (checksum recomputed, so only the version differs).
    std::string future = bytes.substr(0, bytes.size() - 8);
    future[8] = char(kFieldFormatVersion + 1);
    const uint64_t sum = fnv1a64(future.data(), future.size());
    future.append(reinterpret_cast<const char*>(&sum), 8);
    CHECK(refused(future).find("format version") != std::string::npos);
}

TEST_CASE("A field file with a right checksum but NaN or infinite numbers is refused", "[field_file][bad-input][fuzz]") {
    // Found by fuzz_rslf (docs/design/FUZZING.md): the reader checked the bytes, not
    // the numbers, and NaN tables made every lookup NaN.
    const fs::path dir = test::scratch_dir("field_file_nan");
    for (size_t at : {size_t(0), size_t(5)}) {
        write_file_atomically(dir / "nan.rslf", test::hostile::svdf_with_nan(dir, at));
        const std::string message = error_of([&] { read_svdf(dir / "nan.rslf"); });
        INFO(message);
        CHECK(message.find("nan.rslf") != std::string::npos);
        CHECK(message.find(fmt::format("non-finite table value nan at index {}", at)) != std::string::npos);
        CHECK(error_of([&] { read_field_header(dir / "nan.rslf"); }) == message);
    }
    // Coefficients: one made infinite, the checksum made right again.
    std::string bytes = test::hostile::svdf_with_nan(dir, 0);
    const float one = 0.25f, nan = std::nanf(""), inf = INFINITY;
    bytes.replace(bytes.find(std::string(reinterpret_cast<const char*>(&nan), 4)), 4,
                  std::string(reinterpret_cast<const char*>(&one), 4));  // the tables are finite again
    const float last = 1.0f;  // the last coefficient, just before the checksum
    const size_t at = bytes.size() - 8 - 4;
    REQUIRE(std::memcmp(bytes.data() + at, &last, 4) == 0);
    std::memcpy(bytes.data() + at, &inf, 4);
    const uint64_t sum = fnv1a64(bytes.data(), bytes.size() - 8);
    std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
    write_file_atomically(dir / "inf.rslf", bytes);
    CHECK(error_of([&] { read_svdf(dir / "inf.rslf"); }).find("non-finite PCA coefficient inf at index 2") !=
          std::string::npos);
    // Finite but overflowing (found by fuzz_rslf: a lookup gave -inf): 1e30 ×
    // 0.25 is finite, and so is the sum here, but 1e38 would not be; any
    // reconstruction past 1e6 plane units is refused, a baked one passes.
    for (const float huge : {1e30f, 3e38f, 8e6f}) {
        std::memcpy(bytes.data() + at, &huge, 4);
        const uint64_t fixed = fnv1a64(bytes.data(), bytes.size() - 8);
        std::memcpy(bytes.data() + bytes.size() - 8, &fixed, 8);
        write_file_atomically(dir / "huge.rslf", bytes);
        const std::string message = error_of([&] { read_svdf(dir / "huge.rslf"); });
        INFO(message);
        CHECK(message.find("huge.rslf") != std::string::npos);
        CHECK(message.find("implausible field: cluster 0 reconstructs distances up to") != std::string::npos);
    }
    const float plausible = 1e5f;  // 0.25 + 0.25·1e5: within the limit
    std::memcpy(bytes.data() + at, &plausible, 4);
    const uint64_t fixed = fnv1a64(bytes.data(), bytes.size() - 8);
    std::memcpy(bytes.data() + bytes.size() - 8, &fixed, 8);
    write_file_atomically(dir / "huge.rslf", bytes);
    CHECK(error_of([&] { read_svdf(dir / "huge.rslf"); }).empty());
}

TEST_CASE("Field files with parameters or a bounding sphere the lookups cannot use are refused", "[field_file][bad-input][fuzz]") {
    // fuzz_rslf found a NaN center (a NaN shell coordinate converted to int
    // in the lookup); the parameters below reached prepare()'s checks
    // (status 2), a division by zero, or lookups one tap outside a table.
    using namespace test::hostile;
    const fs::path dir = test::scratch_dir("field_file_params");
    const std::string good = ovdf_bytes(dir);
    write_file_atomically(dir / "good.rslf", good);
    const Ovdf ovdf = read_ovdf(dir / "good.rslf");
    CHECK(std::isfinite(ovdf.visible_fraction(ovdf.center + Vec3(2 * ovdf.radius, 0, 0), Vec3(-1, 0, 0), 0.1f)));
    const auto refused = [&](const std::string& bytes, const std::string& message) {
        write_file_atomically(dir / "bad.rslf", bytes);
        const std::string error = error_of([&] { read_ovdf(dir / "bad.rslf"); });
        INFO(error);
        CHECK(error.find("bad.rslf: ") != std::string::npos);
        CHECK(error.find(message) != std::string::npos);
    };
    refused(ovdf_nan_center(dir), "implausible OVDF bounding sphere (center nan");
    refused(with_field_parameter(good, "shells", "1"), "bad parameter block: shells: 1 is not an integer from 2 to 256");
    refused(with_field_parameter(good, "segments_per_side", "0"), "segments_per_side: 0 is not an integer from 1 to 2");
    refused(with_field_parameter(good, "cube_resolution", "1"), "cube_resolution: 1 is not an integer from 2 to 256");
    refused(with_field_parameter(good, "vdt_resolution", "4e20"), "vdt_resolution: 4e+20 is not an integer");
    refused(with_field_parameter(good, "inner_radius", "-0.5"), "inner_radius: -0.5 is not a positive number");
    refused(with_field_parameter(good, "outer_radius", "0.1"), "outer_radius: not above inner_radius");
    refused(with_field_parameter(good, "spacing", "7"), "spacing: 7 is not an integer from 0 to 2");
    refused(with_field_parameter(good, "half_precision_tables", "3"), "half_precision_tables: 3 is not true or false");
    refused(with_field_parameter(good, "seed", "-1"), "seed: -1 is not an unsigned integer");
    refused(with_field_parameter(good, "cube_resolution", "4"), "model sizes do not match the OVDF parameters");
}
