// Environment maps: the orientation convention, exact texel solid angles,
// cube adjacency, energy-preserving resampling (lat-long, strips, rotation)
// and environment files, checked against brute-force references.
#include <cmath>
#include <filesystem>
#include <map>
#include <random>
#include <set>

#include <OpenEXR/ImfEnvmap.h>
#include <catch2/catch.hpp>
#include <glm/gtc/quaternion.hpp>

#include "src/core/envmap.h"
#include "src/core/error.h"
#include "src/formats/environment_file.h"
#include "src/formats/image_file.h"
#include "tests/raw_exr.h"
#include "tests/test_support.h"
#include "tests/random_cases.h"

using namespace rsl;
namespace fs = std::filesystem;

namespace {

constexpr double kFourPi = 4.0 * std::numbers::pi;

double angle_between(const Vec3& a, const Vec3& b) {
    return std::atan2(double(glm::length(glm::cross(a, b))), double(glm::dot(a, b)));
}

// Largest angle from a texel center to its corners: "within one texel".
double texel_radius(int n) { return std::atan(std::sqrt(2.0) * 2.0 / n) + 1e-4; }

double relative_error(const DVec3& a, const DVec3& b) {
    return glm::length(a - b) / glm::length(b);
}

int brightest(const CubeMap& map) {
    int best = 0;
    for (int k = 1; k < map.texel_count(); ++k)
        if (luminance(map.radiance(k)) > luminance(map.radiance(best))) best = k;
    return best;
}

Image constant_latlong(int w, int h, Color value) {
    Image image(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) image.set_rgb(x, y, value);
    return image;
}

// A smooth, strictly positive test function of direction.
Color smooth(const Vec3& d) { return Color(1.5f + d.x, 1.5f + d.y * d.z, 1.2f + 0.8f * d.z * d.z - 0.3f * d.y); }

}  // namespace

TEST_CASE("Lat-long convention: +Y on top, u = 1/4 is +X, u = 1/2 is +Z", "[envmap][convention]") {
    auto near = [](Vec3 a, Vec3 b) { return glm::length(a - b) < 1e-6f; };
    CHECK(near(latlong_direction(0.25f, 0.5f), Vec3(1, 0, 0)));
    CHECK(near(latlong_direction(0.5f, 0.5f), Vec3(0, 0, 1)));
    CHECK(near(latlong_direction(0.75f, 0.5f), Vec3(-1, 0, 0)));
    CHECK(near(latlong_direction(0.0f, 0.5f), Vec3(0, 0, -1)));
    CHECK(near(latlong_direction(0.3f, 0.0f), Vec3(0, 1, 0)));
    CHECK(near(latlong_direction(0.3f, 1.0f), Vec3(0, -1, 0)));
    // The map seen from inside: looking at +Z with +Y up, −X is on the right,
    // and moving right in the image (u grows) turns from +Z towards −X.
    CHECK(latlong_direction(0.55f, 0.5f).x < 0.0f);

    std::mt19937 rng(1);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int k = 0; k < 1000; ++k) {
        const float u = unit(rng), v = 0.001f + 0.998f * unit(rng);
        const Vec3 d = latlong_direction(u, v);
        REQUIRE(glm::length(d) == Approx(1.0f).margin(1e-6));
        const Vec2 uv = latlong_coords(d);
        REQUIRE(uv.x >= 0.0f);
        REQUIRE(uv.x < 1.0f);
        REQUIRE(std::min(std::abs(uv.x - u), 1.0f - std::abs(uv.x - u)) < 1e-5f);
        REQUIRE(uv.y == Approx(v).margin(1e-5));
    }
    // It is OpenEXR's lat-long convention (which spaces pixel centers edge to
    // edge, hence the fine grid and the tolerance).
    const int w = 4001, h = 2001;
    const Imath::Box2i window(Imath::V2i(0, 0), Imath::V2i(w - 1, h - 1));
    for (int k = 0; k < 200; ++k) {
        const float x = unit(rng) * (w - 1), y = unit(rng) * (h - 1);
        const Imath::V3f e = Imf::LatLongMap::direction(window, Imath::V2f(x, y));
        const Vec3 ours = latlong_direction(x / (w - 1), y / (h - 1));
        REQUIRE(glm::length(ours - glm::normalize(Vec3(e.x, e.y, e.z))) < 1e-4f);
    }
    CHECK(latlong_coords(Vec3(0, 1, 0)).y == 0.0f);
    CHECK(latlong_coords(Vec3(0, -1, 0)).y == 1.0f);
}

TEST_CASE("Lat-long image rows and columns land on the right cube faces", "[envmap][convention]") {
    // The top row of the image lights the +Y face; the column at u = 1/4 lights +X.
    Image top = constant_latlong(64, 32, Color(0.0f));
    for (int x = 0; x < 64; ++x) top.set_rgb(x, 0, Color(1.0f));
    const CubeMap from_top = cube_from_latlong(top, 8);
    CHECK(from_top.texel(brightest(from_top)).face == 2);
    CHECK(luminance(from_top.lookup(Vec3(0, 1, 0))) > 0.0f);
    CHECK(luminance(from_top.lookup(Vec3(0, -1, 0))) == 0.0f);

    Image column = constant_latlong(64, 32, Color(0.0f));
    column.set_rgb(16, 16, Color(1.0f));  // center u = 16.5/64 ≈ 1/4, v = 16.5/32 ≈ 1/2
    const CubeMap from_column = cube_from_latlong(column, 8);
    CHECK(from_column.texel(brightest(from_column)).face == 0);
}

TEST_CASE("Cube faces follow OpenGL's order and orientation", "[envmap][convention]") {
    const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int f = 0; f < 6; ++f) CHECK(glm::length(CubeMap::face_direction(f, 0, 0) - axes[f]) < 1e-6f);
    // OpenGL's table (GL 4.6 §8.13): on +X, s grows towards −Z and t towards −Y;
    // on +Y, s towards +X and t towards +Z; on −Z, s towards −X.
    CHECK(CubeMap::face_direction(0, 0.5f, 0).z < 0);
    CHECK(CubeMap::face_direction(0, 0, 0.5f).y < 0);
    CHECK(CubeMap::face_direction(2, 0.5f, 0).x > 0);
    CHECK(CubeMap::face_direction(2, 0, 0.5f).z > 0);
    CHECK(CubeMap::face_direction(5, 0.5f, 0).x < 0);
    CHECK(CubeMap::face_direction(3, 0, 0.5f).z < 0);

    const CubeMap map(16);
    std::mt19937 rng(2);
    std::normal_distribution<float> gauss;
    for (int k = 0; k < 2000; ++k) {
        const Vec3 d = glm::normalize(test::random_vec3(gauss, rng));
        const int texel = map.index_of(d);
        REQUIRE(angle_between(map.texel_direction(texel), d) <= texel_radius(16));
    }
    for (int k = 0; k < map.texel_count(); ++k) REQUIRE(map.index_of(map.texel_direction(k)) == k);
}

TEST_CASE("Texel solid angles are exact and sum to 4π", "[envmap][solid-angle]") {
    for (int n : {1, 2, 3, 32, 64, 128}) {
        const CubeMap map(n);
        double sum = 0;
        for (float omega : map.solid_angles()) sum += omega;
        INFO("N = " << n);
        CHECK(std::abs(sum - kFourPi) / kFourPi < 1e-6);
    }
    // Brute force: midpoint rule on dω = ds dt / (1 + s² + t²)^{3/2}.
    auto integrate = [](double s0, double t0, double s1, double t1) {
        const int m = 400;
        double sum = 0;
        for (int b = 0; b < m; ++b)
            for (int a = 0; a < m; ++a) {
                const double s = s0 + (s1 - s0) * (a + 0.5) / m, t = t0 + (t1 - t0) * (b + 0.5) / m;
                sum += std::pow(1.0 + s * s + t * t, -1.5);
            }
        return sum * (s1 - s0) * (t1 - t0) / (double(m) * m);
    };
    for (int n : {1, 4, 32}) {
        const CubeMap map(n);
        for (int k = 0; k < n * n; k += std::max(1, n * n / 12)) {
            const CubeTexel t = map.texel(k);
            const double s0 = -1.0 + 2.0 * t.i / n, t0 = -1.0 + 2.0 * t.j / n;
            const double reference = integrate(s0, t0, s0 + 2.0 / n, t0 + 2.0 / n);
            INFO("N = " << n << " texel " << k);
            REQUIRE(std::abs(cube_face_solid_angle(s0, t0, s0 + 2.0 / n, t0 + 2.0 / n) - reference) / reference < 5e-6);
            REQUIRE(std::abs(map.solid_angle(k) - reference) / reference < 5e-6);
        }
    }
}

TEST_CASE("Cube neighbors: 4 distinct, symmetric, exactly the edge-sharing texels", "[envmap][neighbors]") {
    for (int n : {1, 2, 3, 8}) {
        const CubeMap map(n);
        // Reference: two texels share an edge iff they share two corner points.
        std::vector<std::array<Vec3, 4>> corners(map.texel_count());
        for (int k = 0; k < map.texel_count(); ++k) {
            const CubeTexel t = map.texel(k);
            for (int c = 0; c < 4; ++c)
                corners[k][c] = CubeMap::face_direction(t.face, -1.0f + 2.0f * (t.i + c % 2) / n,
                                                        -1.0f + 2.0f * (t.j + c / 2) / n);
        }
        auto shares_edge = [&](int a, int b) {
            int shared = 0;
            for (const Vec3& p : corners[a])
                for (const Vec3& q : corners[b]) shared += glm::length(p - q) < 1e-5f;
            return shared == 2;
        };
        for (int a = 0; a < map.texel_count(); ++a) {
            const std::array<int, 4> nb = map.neighbors(a);
            const std::set<int> distinct(nb.begin(), nb.end());
            INFO("N = " << n << " texel " << a);
            REQUIRE(distinct.size() == 4);
            REQUIRE(!distinct.count(a));
            for (int b : nb) {
                const std::array<int, 4> back = map.neighbors(b);
                REQUIRE(std::find(back.begin(), back.end(), a) != back.end());
            }
            std::set<int> reference;
            for (int b = 0; b < map.texel_count(); ++b)
                if (b != a && shares_edge(a, b)) reference.insert(b);
            REQUIRE(distinct == reference);
        }
    }
}

TEST_CASE("A bright pixel keeps its direction and its energy through resampling", "[envmap][resample]") {
    std::mt19937 rng(3);
    const int w = 256, h = 128;
    // Interior pixels at random, plus the rows next to the poles and the seam.
    std::vector<std::pair<int, int>> pixels = {{0, 0}, {100, h - 1}, {w - 1, 64}, {0, 64}, {64, 1}, {200, 90}};
    for (int k = 0; k < 10; ++k) pixels.push_back({int(rng() % w), int(rng() % h)});
    for (int n : {32, 64, 128}) {
        for (auto [x, y] : pixels) {
            Image image = constant_latlong(w, h, Color(0.01f));
            image.set_rgb(x, y, Color(1e5f, 5e4f, 2e4f));
            const DVec3 source = latlong_energy(image);
            const CubeMap map = cube_from_latlong(image, n);
            INFO("N = " << n << " pixel (" << x << ", " << y << ")");
            REQUIRE(relative_error(map.energy(), source) < 1e-4);
            const Vec3 pixel_dir = latlong_direction((x + 0.5f) / w, (y + 0.5f) / h);
            const int texel = brightest(map);
            REQUIRE(angle_between(map.texel_direction(texel), pixel_dir) <= texel_radius(n));
            REQUIRE(luminance(map.lookup(pixel_dir)) > 100.0f);
        }
    }
}

TEST_CASE("Resampling keeps constant maps constant and smooth maps accurate", "[envmap][resample]") {
    for (int n : {32, 64, 128}) {
        const CubeMap flat = cube_from_latlong(constant_latlong(256, 128, Color(2.0f)), n);
        float lo = 1e9f, hi = 0;
        for (const Color& c : flat.radiances()) lo = std::min(lo, c.g), hi = std::max(hi, c.g);
        INFO("N = " << n << " constant map range " << lo << " .. " << hi);
        CHECK(lo > 2.0f * 0.99f);
        CHECK(hi < 2.0f * 1.01f);

        Image image(256, 128, 3);
        for (int y = 0; y < 128; ++y)
            for (int x = 0; x < 256; ++x) image.set_rgb(x, y, smooth(latlong_direction((x + 0.5f) / 256, (y + 0.5f) / 128)));
        const CubeMap map = cube_from_latlong(image, n);
        double worst = 0;
        for (int k = 0; k < map.texel_count(); ++k) {
            const Color want = smooth(map.texel_direction(k));
            worst = std::max(worst, double(glm::length(map.radiance(k) - want) / glm::length(want)));
        }
        INFO("worst relative error on a smooth map " << worst);
        CHECK(worst < 0.05);
        CHECK(relative_error(map.energy(), latlong_energy(image)) < 1e-5);
    }
}

TEST_CASE("Energy of the real probes is preserved at N = 32, 64, 128", "[envmap][resample][probes]") {
    const fs::path probes = fs::path(RSL_SHARED_ASSETS) / "probes";
    if (!fs::exists(probes / "grace.hdr")) {
        WARN("SKIPPED: " << probes.string() << " is absent");
        return;
    }
    for (const char* name : {"grace.hdr", "uffizi.hdr", "ennis.hdr"}) {
        const Image image = read_hdr_image(probes / name);
        REQUIRE(image.width == 256);
        REQUIRE(image.height == 128);
        const DVec3 source = latlong_energy(image);
        for (int n : {32, 64, 128}) {
            const CubeMap map = load_environment(probes / name, n);
            INFO(name << " N = " << n << ": " << map.energy().g << " vs " << source.g);
            for (int c = 0; c < 3; ++c) CHECK(std::abs(map.energy()[c] - source[c]) / source[c] < 0.01);
        }
    }
}

TEST_CASE("A bright pixel survives EXR file → load → resample → lookup", "[envmap][files]") {
    const fs::path dir = test::scratch_dir("envmap_load");
    Image image = constant_latlong(128, 64, Color(0.1f));
    const int x = 37, y = 20;
    image.set_rgb(x, y, Color(5000.0f));
    write_exr(dir / "probe.exr", image);
    const CubeMap map = load_environment(dir / "probe.exr", 32);
    const Vec3 dir_pixel = latlong_direction((x + 0.5f) / 128, (y + 0.5f) / 64);
    CHECK(angle_between(map.texel_direction(brightest(map)), dir_pixel) <= texel_radius(32));
    CHECK(luminance(map.lookup(dir_pixel)) > 100.0f);
    CHECK(relative_error(map.energy(), latlong_energy(image)) < 1e-4);
    fs::remove_all(dir);
}

namespace {
// A strip built with OpenEXR's own functions: pixel ↔ direction per ImfEnvmap.h.
Image exr_strip(int size, Color (*f)(const Vec3&)) {
    Image strip(size, 6 * size, 3);
    const Imath::Box2i window(Imath::V2i(0, 0), Imath::V2i(size - 1, 6 * size - 1));
    for (int face = 0; face < 6; ++face)
        for (int py = 0; py < size; ++py)
            for (int px = 0; px < size; ++px) {
                const auto exr_face = Imf::CubeMapFace(face);
                const float scale = float(size - 1) / size;  // cell centers, as cube_from_strip reads them
                const Imath::V3f d = Imf::CubeMap::direction(exr_face, window, Imath::V2f((px + 0.5f) * scale, (py + 0.5f) * scale));
                const Imath::V2f p = Imf::CubeMap::pixelPosition(exr_face, window, Imath::V2f(px, py));
                strip.set_rgb(int(p.x + 0.5f), int(p.y + 0.5f), f(glm::normalize(Vec3(d.x, d.y, d.z))));
            }
    return strip;
}
}  // namespace

TEST_CASE("OpenEXR cube strips map to the right directions", "[envmap][strip]") {
    const Image strip = exr_strip(16, smooth);
    const CubeMap native = cube_from_strip(strip, 16);
    for (int k = 0; k < native.texel_count(); ++k)
        REQUIRE(glm::length(native.radiance(k) - smooth(native.texel_direction(k))) < 1e-4f);
    const CubeMap coarse = cube_from_strip(strip, 8);
    CHECK(relative_error(coarse.energy(), native.energy()) < 1e-5);
    for (int k = 0; k < coarse.texel_count(); ++k)
        REQUIRE(glm::length(coarse.radiance(k) - smooth(coarse.texel_direction(k))) < 0.05f);

    // Files: by the envmap attribute, and by the 1:6 shape when it is absent.
    const fs::path dir = test::scratch_dir("envmap_strip");
    write_exr(dir / "cube.exr", strip, ExrWriteOptions{.envmap = EnvmapKind::Cube});
    write_exr(dir / "plain.exr", strip);
    for (const char* name : {"cube.exr", "plain.exr"}) {
        const CubeMap map = load_environment(dir / name, 16);
        for (int k = 0; k < map.texel_count(); ++k) REQUIRE(map.radiance(k) == native.radiance(k));
    }
    fs::remove_all(dir);
}

TEST_CASE("Rotation moves content to R d and preserves energy", "[envmap][rotate]") {
    std::mt19937 rng(4);
    std::normal_distribution<float> gauss;
    const int n = 32;
    for (int trial = 0; trial < 8; ++trial) {
        const Quat q = glm::normalize(test::random_quat(gauss, rng));
        const Mat3 r = glm::mat3_cast(q);
        CubeMap map(n);
        for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = Color(0.05f);
        const Vec3 bright = glm::normalize(test::random_vec3(gauss, rng));
        map.radiance(map.index_of(bright)) = Color(1e4f);
        const CubeMap rotated = rotate(map, r);
        INFO("trial " << trial);
        REQUIRE(relative_error(rotated.energy(), map.energy()) < 1e-4);
        const Vec3 moved = r * map.texel_direction(map.index_of(bright));
        REQUIRE(angle_between(rotated.texel_direction(brightest(rotated)), moved) <= texel_radius(n));
    }
    // Against brute force on a smooth map: rotated(d) = map(Rᵀ d).
    CubeMap map(n);
    for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = smooth(map.texel_direction(k));
    const Mat3 r = glm::mat3_cast(glm::angleAxis(0.7f, glm::normalize(Vec3(1, 2, 3))));
    const CubeMap rotated = rotate(map, r);
    double worst = 0;
    for (int k = 0; k < map.texel_count(); ++k) {
        const Color want = smooth(glm::transpose(r) * rotated.texel_direction(k));
        worst = std::max(worst, double(glm::length(rotated.radiance(k) - want) / glm::length(want)));
    }
    CHECK(worst < 0.06);
    // A quarter turn about +Y takes +Z to +X.
    const Mat3 quarter = glm::mat3_cast(glm::angleAxis(kPi / 2, Vec3(0, 1, 0)));
    CHECK(glm::length(quarter * Vec3(0, 0, 1) - Vec3(1, 0, 0)) < 1e-6f);
    CHECK_THROWS_AS(rotate(map, Mat3(2.0f)), Error);
}

TEST_CASE("cube_to_latlong inverts cube_from_latlong on smooth maps", "[envmap][resample]") {
    CubeMap map(32);
    for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = smooth(map.texel_direction(k));
    const Image image = cube_to_latlong(map, 256);
    REQUIRE(image.width == 256);
    REQUIRE(image.height == 128);
    CHECK(relative_error(latlong_energy(image), map.energy()) < 1e-4);
    for (int y = 0; y < 128; y += 9)
        for (int x = 0; x < 256; x += 7) {
            const Color want = smooth(latlong_direction((x + 0.5f) / 256, (y + 0.5f) / 128));
            REQUIRE(glm::length(image.rgb(x, y) - want) / glm::length(want) < 0.06f);
        }
}

TEST_CASE("Environment files of the wrong shape or content are refused by name", "[envmap][bad]") {
    const fs::path dir = test::scratch_dir("envmap_bad");
    write_exr(dir / "square.exr", constant_latlong(32, 32, Color(1.0f)));
    CHECK_THROWS_WITH(load_environment(dir / "square.exr", 32),
                      Catch::Contains("square.exr") && Catch::Contains("32×32"));
    write_exr(dir / "wide.exr", constant_latlong(64, 32, Color(1.0f)), ExrWriteOptions{.envmap = EnvmapKind::Cube});
    CHECK_THROWS_WITH(load_environment(dir / "wide.exr", 32), Catch::Contains("wide.exr") && Catch::Contains("cube"));
    CHECK_THROWS_WITH(load_environment(dir / "wide.exr", 0), Catch::Contains("wide.exr"));
    Image nan = constant_latlong(64, 32, Color(1.0f));
    nan.at(3, 2)[0] = std::nanf("");
    test::write_unchecked_exr(dir / "nan.exr", nan);  // write_exr refuses it
    CHECK_THROWS_WITH(load_environment(dir / "nan.exr", 32), Catch::Contains("nan.exr") && Catch::Contains("NaN"));
    CHECK_THROWS_WITH(load_environment(dir / "absent.hdr", 32), Catch::Contains("absent.hdr"));
    CHECK_THROWS_AS(cube_from_latlong(Image(), 8), Error);
    CHECK_THROWS_AS(CubeMap(0), Error);
    fs::remove_all(dir);
}
