// The single-region RSL fit: its chart, its objective against a brute-force
// integral, and the squares it finds.
#include <random>

#include <catch2/catch.hpp>

#include "src/lightfit/square_fit.h"
#include "tests/random_cases.h"

using namespace rsl;
using namespace rsl::lightfit;

namespace {

constexpr int kFacePlusZ = 4;

// Texels of face +Z with i ∈ [i0, i1), j ∈ [j0, j1).
std::vector<int> face_block(const CubeMap& map, int i0, int i1, int j0, int j1) {
    std::vector<int> out;
    for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i) out.push_back(map.index(kFacePlusZ, i, j));
    return out;
}

RegionStats stats_of(const std::vector<FitTexel>& texels, const std::vector<int>& region) {
    RegionStats s;
    for (int k : region) s += RegionStats::of_texel(texels[k]);
    return s;
}

// |S′|·E_θ[∫_{S′}(T − F_θ)²] by brute force: every texel of the map is
// subsampled m×m and each subsample tested against each turned square exactly;
// |S ∪ O_r| = |S| + πr² − |S ∩ O_r| (the chart is equal-area, so |O_r| = πr²).
double brute_force_objective(const CubeMap& map, const std::vector<int>& region, const Vec3& center, float r,
                             int m) {
    std::vector<bool> in_region(map.texel_count(), false);
    for (int k : region) in_region[k] = true;
    DVec3 energy(0.0);
    double region_area = 0;
    for (int k : region) energy += DVec3(map.radiance(k)) * double(map.solid_angle(k)), region_area += map.solid_angle(k);
    const DVec3 intensity = energy / (2.0 * r * r);
    const Frame frame = Frame::from_normal(center);
    const float h = r / std::sqrt(2.0f);
    double squared_error = 0, region_in_disk = 0;
    double outside_region_in_square = 0;  // ∫ F² over the square's part outside S, per turn (summed)
    const int n = map.resolution();
    for (int k = 0; k < map.texel_count(); ++k) {
        const CubeTexel t = map.texel(k);
        const DVec3 target = in_region[k] ? DVec3(map.radiance(k)) : DVec3(0.0);
        for (int b = 0; b < m; ++b)
            for (int a = 0; a < m; ++a) {
                const double s = -1.0 + 2.0 * (t.i + (a + 0.5) / m) / n, u = -1.0 + 2.0 * (t.j + (b + 0.5) / m) / n;
                const double w = map.solid_angle(k) / (m * m);  // subsample solid angle (texels are small)
                const Vec2 q = fit_chart(frame, glm::normalize(CubeMap::face_direction(t.face, float(s), float(u))));
                if (in_region[k] && glm::length(q) <= r) region_in_disk += w;
                for (float theta : kFitTurns) {
                    const float x = q.x * std::cos(theta) + q.y * std::sin(theta);
                    const float y = -q.x * std::sin(theta) + q.y * std::cos(theta);
                    const bool inside = std::abs(x) <= h && std::abs(y) <= h;
                    const DVec3 fitted = inside ? intensity : DVec3(0.0);
                    if (in_region[k]) squared_error += glm::dot(target - fitted, target - fitted) * w;
                    else if (inside) outside_region_in_square += glm::dot(fitted, fitted) * w;
                }
            }
    }
    const double mean_error = (squared_error + outside_region_in_square) / kFitTurns.size();
    const double extended_area = region_area + std::numbers::pi * r * r - region_in_disk;
    return extended_area * mean_error;
}

}  // namespace

TEST_CASE("the fit chart is the √2-scaled equal-area projection and inverts", "[lightfit][fit]") {
    std::mt19937 rng(7);
    std::normal_distribution<float> g;
    for (int trial = 0; trial < 200; ++trial) {
        const Frame frame = Frame::from_normal(glm::normalize(test::random_vec3(g, rng)));
        Vec3 d = glm::normalize(test::random_vec3(g, rng));
        if (glm::dot(d, frame.z) < -0.9f) d = -d;  // stay away from the antipode
        const Vec2 q = fit_chart(frame, d);
        // Chart radius is the chord 2 sin(α/2) to the center.
        const float alpha = std::acos(std::clamp(glm::dot(d, frame.z), -1.0f, 1.0f));
        CHECK(glm::length(q) == Approx(2 * std::sin(alpha / 2)).margin(1e-5));
        const Vec3 back = fit_chart_inverse(frame, q);
        CHECK(glm::length(back - d) < 1e-5f);
    }
    // Equal area: the texels whose centers fall in the chart disk of radius ρ
    // add up to πρ² (up to the boundary texels).
    const CubeMap map(64);
    const Frame frame = Frame::from_normal(glm::normalize(Vec3(0.3f, 0.5f, 0.8f)));
    for (float rho : {0.3f, 0.8f, 1.4f}) {
        double area = 0;
        for (int k = 0; k < map.texel_count(); ++k)
            if (glm::length(fit_chart(frame, map.texel_direction(k))) <= rho) area += map.solid_angle(k);
        CHECK(area == Approx(kPi * rho * rho).epsilon(0.02));
    }
}

TEST_CASE("the fit objective matches a brute-force integral", "[lightfit][fit]") {
    CubeMap map(16);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uni(0.2f, 2.0f);
    for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = test::random_vec3(uni, rng);
    const auto texels = make_fit_texels(map);
    const auto region = face_block(map, 5, 11, 6, 10);  // 6×4 texels
    const RegionStats stats = stats_of(texels, region);
    const Vec3 c = stats.energy_centroid();
    const float patch_r = std::sqrt(float(stats.solid_angle) / 2);
    SquareFitter fitter;
    for (float scale : {0.5f, 0.8f, 1.0f, 1.3f, 2.0f}) {
        for (Vec3 shift : {Vec3(0), Vec3(0.03f, 0.0f, 0.0f)}) {
            const Vec3 center = glm::normalize(c + shift);
            const float r = scale * patch_r;
            const double ours = fitter.objective(texels, stats, region, center, r);
            const double reference = brute_force_objective(map, region, center, r, 12);
            INFO("r = " << r << " (x" << scale << "), shift " << shift.x);
            // The box model of a texel is exact in the interior and linear
            // across the square's boundary (measured: within 3%).
            CHECK(std::abs(ours - reference) < 0.04 * reference);
        }
    }
}

TEST_CASE("a single texel is fitted by a square of its own size on its center", "[lightfit][fit]") {
    CubeMap map(32);
    const int k = map.index(kFacePlusZ, 9, 21);
    map.radiance(k) = Color(4, 2, 1);
    const auto texels = make_fit_texels(map);
    const std::vector<int> region = {k};
    SquareFitter fitter;
    const SquareFit fit = fitter.fit(texels, stats_of(texels, region), region);
    CHECK(2 * fit.half_diagonal * fit.half_diagonal == Approx(map.solid_angle(k)).epsilon(0.03));
    CHECK(glm::length(fit.center - map.texel_direction(k)) < 0.1f * std::sqrt(map.solid_angle(k)));
    const DVec3 light_energy = DVec3(fit.radiance) * double(2 * fit.half_diagonal * fit.half_diagonal);
    const DVec3 texel_energy = DVec3(map.radiance(k)) * double(map.solid_angle(k));
    for (int ch = 0; ch < 3; ++ch) CHECK(light_energy[ch] == Approx(texel_energy[ch]).epsilon(1e-5));
}

TEST_CASE("a uniform square patch is recovered: center within a texel, r within 10%", "[lightfit][fit]") {
    CubeMap map(32);
    for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = Color(0.01f);
    // Off-center on the face, so the patch's chart is not aligned with the face.
    const auto patch = face_block(map, 17, 25, 6, 14);  // 8×8 texels
    for (int k : patch) map.radiance(k) = Color(5.0f, 4.0f, 3.0f);
    const auto texels = make_fit_texels(map);
    RegionStats stats = stats_of(texels, patch);
    DVec3 center_sum(0.0);
    for (int k : patch) center_sum += DVec3(map.texel_direction(k)) * double(map.solid_angle(k));
    const Vec3 patch_center(glm::normalize(center_sum));
    const float patch_r = std::sqrt(float(stats.solid_angle) / 2);
    const float texel = std::sqrt(map.solid_angle(patch[0]));

    SquareFitter fitter;
    for (bool refine : {false, true}) {
        const SquareFit fit = fitter.fit(texels, stats, patch, {}, FitOptions{.refine_center = refine});
        INFO("refine_center " << refine);
        CHECK(std::acos(std::min(1.0f, glm::dot(fit.center, patch_center))) < texel);
        CHECK(fit.half_diagonal == Approx(patch_r).epsilon(0.10));
    }
}

TEST_CASE("the fitted square is the best of a dense brute-force search over r", "[lightfit][fit]") {
    CubeMap map(16);
    std::mt19937 rng(3);
    std::lognormal_distribution<float> lognormal(0.0f, 1.0f);
    for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = Color(lognormal(rng));
    const auto texels = make_fit_texels(map);
    const auto region = face_block(map, 3, 9, 4, 13);
    const RegionStats stats = stats_of(texels, region);
    SquareFitter fitter;
    const SquareFit fit = fitter.fit(texels, stats, region, {}, FitOptions{.refine_center = false});
    double dense_best = std::numeric_limits<double>::max();
    for (float r = 0.01f; r < 1.5f; r *= 1.01f)
        dense_best = std::min(dense_best, fitter.objective(texels, stats, region, fit.center, r));
    CHECK(fit.error <= dense_best * 1.01);
    // Refining the center never makes the fit worse.
    const SquareFit refined = fitter.fit(texels, stats, region, {}, FitOptions{.refine_center = true});
    CHECK(refined.error <= fit.error);
}
