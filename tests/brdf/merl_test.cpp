// MERL measured BRDFs: the file layout and index mapping of the standard
// format, reproduction of an analytic BRDF tabulated into it, and errors.
#include <cstring>
#include <filesystem>
#include <fstream>

#include <catch2/catch.hpp>

#include "src/brdf/analytic.h"
#include "src/brdf/merl.h"
#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "tests/brdf/brdf_test_util.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

namespace {

// Directions whose Rusinkiewicz coordinates are (θ_h, θ_d, φ_d), φ_h = 0.
std::pair<Vec3, Vec3> from_half_diff(double theta_h, double theta_d, double phi_d) {
    const DVec3 d(std::sin(theta_d) * std::cos(phi_d), std::sin(theta_d) * std::sin(phi_d), std::cos(theta_d));
    const DVec3 h(std::sin(theta_h), 0, std::cos(theta_h));
    const DVec3 in(d.x * std::cos(theta_h) + d.z * std::sin(theta_h), d.y, d.z * std::cos(theta_h) - d.x * std::sin(theta_h));
    const DVec3 out = 2.0 * glm::dot(in, h) * h - in;
    return {Vec3(in), Vec3(out)};
}

}  // namespace

TEST_CASE("MERL layout: channel-major, φ_d fastest, √θ_h index, channel scales", "[brdf][merl]") {
    const int n = MerlBrdf::kSamples;
    std::vector<double> raw(3 * static_cast<size_t>(n));
    // A distinct value per bin and channel: 1 + ih + 100·id + 10⁴·ip + 10⁶·c.
    for (int c = 0; c < 3; ++c)
        for (int ih = 0; ih < 90; ++ih)
            for (int id = 0; id < 90; ++id)
                for (int ip = 0; ip < 180; ++ip)
                    raw[c * size_t(n) + ip + 180 * (id + 90 * size_t(ih))] = 1 + ih + 100.0 * id + 1e4 * ip + 1e6 * c;
    const MerlBrdf merl(raw, "layout");
    const double half_pi = std::numbers::pi / 2;
    for (auto [ih, id, ip] : {std::tuple{3, 20, 40}, {40, 60, 100}, {70, 10, 170}, {10, 45, 7}}) {
        // Bin centers: θ_h = ((ih + ½)/90)²·π/2, θ_d = (id + ½)/90·π/2, φ_d = (ip + ½)/180·π.
        const double u = (ih + 0.5) / 90;
        auto [wi, wo] = from_half_diff(u * u * half_pi, (id + 0.5) / 90 * half_pi, (ip + 0.5) / 180 * std::numbers::pi);
        if (wi.z <= 0 || wo.z <= 0) continue;
        const Color v = merl.eval(wi, wo);
        for (int c = 0; c < 3; ++c) {
            const double expected = (1 + ih + 100.0 * id + 1e4 * ip + 1e6 * c) * MerlBrdf::kScale[c];
            INFO("bin " << ih << "," << id << "," << ip << " channel " << c);
            CHECK(v[c] == Approx(expected).epsilon(2e-5));
        }
    }
    CHECK(MerlBrdf::kScale[1] == Approx(1.15 / 1500));
    CHECK(MerlBrdf::kScale[2] == Approx(1.66 / 1500));
}

TEST_CASE("MERL: a tabulated analytic BRDF is reproduced away from grazing", "[brdf][merl]") {
    const fs::path file = scratch_dir("merl") / "ggx.binary";
    auto analytic =
        make_brdf(material("cook_torrance_ggx", {{"kd", {0.4f, 0.3f, 0.2f}}, {"f0", {0.9f, 0.6f, 0.3f}}, {"roughness", {0.35f}}}));
    MerlBrdf::save(file, MerlBrdf::tabulate(*analytic));
    CHECK(fs::file_size(file) == 12 + 3 * size_t(MerlBrdf::kSamples) * 8);

    MaterialDesc m = material("merl", {});
    m.file = file;
    auto merl = make_brdf(m);
    CHECK(merl->isotropic());
    CHECK(merl->model() == "merl");
    std::mt19937 rng(17);
    double worst = 0;
    for (int k = 0; k < 5000; ++k) {
        // θ ≤ 70°: the tabulation's bins are 1° wide in θ_d and φ_d and finer
        // than 1° in θ_h near the lobe, so trilinear interpolation of this
        // smooth lobe is within 1% (measured worst 0.22%; a swapped or shifted
        // axis is off by far more).
        const Vec3 wi = random_upper_direction(rng, 1.22f), wo = random_upper_direction(rng, 1.22f);
        const Color a = analytic->eval(wi, wo), b = merl->eval(wi, wo);
        for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, std::abs(double(b[c]) - a[c]) / a[c]);
            REQUIRE(b[c] == Approx(a[c]).epsilon(0.01));
        }
        REQUIRE(merl->eval(wi, wo).g == Approx(merl->eval(wo, wi).g).epsilon(1e-4));  // reciprocal
    }
    WARN("MERL round trip: worst relative error " << worst << " over 5000 direction pairs, θ ≤ 70°");
    fs::remove(file);
}

TEST_CASE("MERL: wrong dimensions, truncated or oversized files are refused, naming the file", "[brdf][merl]") {
    const fs::path dir = scratch_dir("merl");
    auto expect_error = [](const fs::path& path, const std::string& needle) {
        try {
            MerlBrdf::load(path);
        } catch (const Error& e) {
            const std::string what = e.what();
            INFO(what);
            CHECK(what.find(path.string()) != std::string::npos);
            CHECK(what.find(needle) != std::string::npos);
            return;
        }
        FAIL("no error for " << path);
    };
    auto header = [](int a, int b, int c) {
        std::string s(12, '\0');
        const int32_t dims[3] = {a, b, c};
        std::memcpy(s.data(), dims, 12);
        return s;
    };
    write_file_atomically(dir / "dims.binary", header(90, 90, 360) + std::string(1000, '\0'));
    expect_error(dir / "dims.binary", "not a MERL file (bad header");
    // A file that is not a MERL table at all: its bytes are never echoed, as text or as numbers.
    write_file_atomically(dir / "secret.binary", "password=hunter2 and more secret text here");
    expect_error(dir / "secret.binary", "not a MERL file (bad header: a MERL BRDF starts with the dimensions 90×90×180)");
    const std::string secret_error = error_of([&] { MerlBrdf::load(dir / "secret.binary"); });
    CHECK(secret_error.find("hunter2") == std::string::npos);
    CHECK(secret_error.find("1936941424") == std::string::npos);  // "pass" read as an int32
    write_file_atomically(dir / "short_header.binary", std::string(7, '\0'));
    expect_error(dir / "short_header.binary", "header");
    write_file_atomically(dir / "truncated.binary", header(90, 90, 180) + std::string(8 * 1000, '\0'));
    expect_error(dir / "truncated.binary", "truncated");
    write_file_atomically(dir / "long.binary",
                          header(90, 90, 180) + std::string(3 * size_t(MerlBrdf::kSamples) * 8 + 5, '\0'));
    expect_error(dir / "long.binary", "trailing bytes");
    expect_error(dir / "missing.binary", "does not exist");
    for (auto name : {"dims", "secret", "short_header", "truncated", "long"}) fs::remove(dir / (std::string(name) + ".binary"));
}
