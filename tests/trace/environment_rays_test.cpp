// env-rays against the densities it claims and against the ground truth:
// the map's and the BRDF's samplers integrate to 1 and their histograms
// follow their densities; the estimator converges to the truth and its mean
// over seeds is the truth at N = 4; a frame is the same at any thread count.
#include <algorithm>
#include <cmath>
#include <random>

#include <catch2/catch.hpp>
#include <tbb/global_control.h>

#include "src/core/error.h"
#include "src/image/error_metrics.h"
#include "src/trace/environment_rays.h"
#include "src/trace/ground_truth.h"
#include "src/trace/sample_sequence.h"
#include "tests/trace/trace_test_scenes.h"
#include "tests/random_cases.h"

using namespace rsl;

namespace {

// Integrates f(direction) over θ ∈ [0, θ_max] and all φ on a θ × φ midpoint
// grid of rows × 2·rows cells (dω = sin θ dθ dφ), cells summed into
// bin_rows × 2·bin_rows bins (rows a multiple of bin_rows), so that the
// grid is independent of both samplers' own parameterizations.
template <class F>
std::vector<double> latlong_integrals(F f, double theta_max, int rows, int bin_rows) {
    const int columns = 2 * rows, bin_columns = 2 * bin_rows;
    const double dtheta = theta_max / rows, dphi = 2.0 * M_PI / columns;
    std::vector<double> bins(size_t(bin_rows) * bin_columns, 0.0);
    for (int r = 0; r < rows; ++r) {
        const double theta = (r + 0.5) * dtheta;
        for (int c = 0; c < columns; ++c) {
            const double phi = (c + 0.5) * dphi;
            const Vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                         float(std::cos(theta)));
            bins[size_t(r * bin_rows / rows) * bin_columns + size_t(c * bin_columns / columns)] +=
                double(f(d)) * std::sin(theta) * dtheta * dphi;
        }
    }
    return bins;
}

// The bin of latlong_integrals that direction d falls in.
int latlong_bin(const Vec3& d, double theta_max, int bin_rows) {
    const double theta = std::acos(std::clamp(double(d.z), -1.0, 1.0));
    double phi = std::atan2(double(d.y), double(d.x));
    if (phi < 0) phi += 2.0 * M_PI;
    const int r = std::min(int(theta / theta_max * bin_rows), bin_rows - 1);
    const int c = std::min(int(phi / (2.0 * M_PI) * 2 * bin_rows), 2 * bin_rows - 1);
    return r * 2 * bin_rows + c;
}

double sum(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s;
}

// Pearson's χ² of observed counts against expected probabilities × samples;
// a bin expected empty must be empty. Requires the statistic below
// dof + 6·√(2·dof) (a fixed-seed test: a correct sampler passes by far).
void check_histogram(const std::vector<double>& expected_probability, const std::vector<int>& counts, int samples) {
    double chi2 = 0;
    int dof = 0;
    for (size_t b = 0; b < counts.size(); ++b) {
        const double expected = expected_probability[b] * samples;
        if (expected < 1e-3) {
            CHECK(counts[b] <= 2);
            continue;
        }
        chi2 += (counts[b] - expected) * (counts[b] - expected) / expected;
        ++dof;
    }
    INFO("chi2 " << chi2 << " over " << dof << " bins");
    CHECK(chi2 < dof + 6.0 * std::sqrt(2.0 * dof));
}

// A map with black texels, dim ones, and a few very bright ones.
CubeMap random_map(int n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    CubeMap map(n);
    for (Color& c : map.radiances()) {
        if (unit(rng) < 0.3f) continue;
        c = test::random_vec3(unit, rng);
        if (unit(rng) < 0.02f) c *= 300.0f;
    }
    return map;
}

MaterialDesc anisotropic_ward(float kd, float ks, float alpha_x, float alpha_y) {
    MaterialDesc m;
    m.name = "brushed";
    m.model = "ward_anisotropic";
    m.params = {{"kd", {kd, kd, kd}}, {"ks", {ks, ks, ks}}, {"alpha_x", {alpha_x}}, {"alpha_y", {alpha_y}}};
    return m;
}

// A view above the horizon, elevation at least 10°.
Vec3 random_view(std::mt19937& rng) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float cos_theta = 0.17f + 0.83f * unit(rng), phi = 2.0f * kPi * unit(rng);
    const float sin_theta = std::sqrt(1.0f - cos_theta * cos_theta);
    return Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
}

// A ground plane and two balls, glossy (Blinn-Phong) and brushed (anisotropic
// Ward), a sphere light, the camera at an angle; the map turned by 30°.
Scene test_scene() {
    Scene scene = test::make_scene("env-rays");
    scene.materials[0] = test::lambert(Color(0.6f, 0.55f, 0.5f), "floor");
    scene.materials.push_back(test::blinn_phong(0.3f, 0.5f, 40.0f));
    scene.materials.push_back(anisotropic_ward(0.3f, 0.5f, 0.1f, 0.4f));
    test::add_part(scene, test::make_plane(4.0f, 8, "ground"));
    Transform a, b;
    a.translation = Vec3(-0.6f, 0.55f, 0.0f);
    b.translation = Vec3(0.7f, 0.45f, 0.3f);
    test::add_part(scene, test::make_icosphere(0.5f, 2, "glossy ball"), a, 1);
    test::add_part(scene, test::make_icosphere(0.4f, 2, "brushed ball"), b, 2);
    scene.camera.position = Vec3(2.0f, 3.0f, 4.0f);
    LocalLight light;
    light.radius = 0.15f, light.power = Color(30.0f), light.position = Vec3(0.2f, 2.0f, 1.2f);
    scene.lights.push_back(light);
    scene.environment.rotation_degrees = 30.0f;
    return scene;
}

// A smooth sky, brighter upwards, and a small bright region 25° above the +X horizon (4 texels).
CubeMap test_environment(int n = 16) {
    CubeMap map(n);
    for (int k = 0; k < map.texel_count(); ++k) {
        const Vec3 d = map.texel_direction(k);
        map.radiance(k) = Color(0.25f, 0.3f, 0.4f) * (0.4f + 0.6f * std::max(d.y, 0.0f));
    }
    for (int j = 3; j < 5; ++j)
        for (int i = 7; i < 9; ++i) map.radiance(map.index(0, i, j)) = Color(160.0f, 150.0f, 120.0f);
    return map;
}

EnvironmentRaysOptions rays_options(int samples) {
    EnvironmentRaysOptions o;
    o.samples = samples;
    return o;
}

}  // namespace

TEST_CASE("env-rays: the scrambled Sobol points are nets, the fast path the definition's", "[env-rays]") {
    for (uint64_t stream : {0ull, 1ull, 77ull, 1ull << 40}) {
        const ScrambledSobol sobol(9, stream, 3);
        const int m = 8, count = 1 << m;
        std::vector<UnitPair> points;
        for (uint32_t k = 0; k < uint32_t(count); ++k) {
            const UnitPair fast = sobol.point(k), slow = scrambled_sobol(9, stream, k, 3);
            REQUIRE(fast.u0 == slow.u0);
            REQUIRE(fast.u1 == slow.u1);
            REQUIRE((fast.u0 >= 0.0 && fast.u0 < 1.0 && fast.u1 >= 0.0 && fast.u1 < 1.0));
            points.push_back(fast);
        }
        // A (0, m, 2)-net: every 2^a × 2^(m−a) grid has one point per cell.
        for (int a = 0; a <= m; ++a) {
            std::vector<int> cells(size_t(count), 0);
            for (const UnitPair& p : points) ++cells[size_t(int(p.u0 * (1 << a)) * (1 << (m - a)) + int(p.u1 * (1 << (m - a))))];
            CHECK(std::count(cells.begin(), cells.end(), 1) == count);
        }
    }
}

TEST_CASE("env-rays: the map's density integrates to 1, and samples follow it", "[env-rays]") {
    const CubeMap map = random_map(8, 7);
    const EnvironmentSampler sampler(map);
    // The midpoint rule misses by ~1e-3 on the edges of the bright texels at
    // this grid (it wanders ±1e-3 with the grid); a lost Jacobian misses by 30%.
    const auto integrals = latlong_integrals([&](const Vec3& d) { return sampler.pdf(d); }, M_PI, 1536, 12);
    CHECK(sum(integrals) == Approx(1.0).epsilon(2e-3));

    const int samples = 400000;
    std::vector<int> counts(integrals.size(), 0);
    int inconsistent = 0;
    for (int k = 0; k < samples; ++k) {
        const UnitPair u = independent_pair(3, 0, uint32_t(k), 0);
        const EnvironmentSampler::Sample s = sampler.sample(u.u0, u.u1);
        REQUIRE(glm::length(s.direction) == Approx(1.0f).epsilon(1e-5));
        REQUIRE(luminance(s.radiance) > 0.0f);  // black texels are never drawn
        Color radiance;
        const float pdf = sampler.lookup(s.direction, radiance);
        // The density a sample carries is the one pdf() gives it (bar a
        // direction that rounds onto a neighbouring texel's edge).
        if (std::abs(pdf - s.pdf) > 1e-4f * s.pdf || !(radiance == s.radiance)) ++inconsistent;
        ++counts[size_t(latlong_bin(s.direction, M_PI, 12))];
    }
    CHECK(inconsistent <= samples / 10000);
    check_histogram(integrals, counts, samples);
}

TEST_CASE("env-rays: the BRDF sampler's density integrates to 1 with what falls below the horizon", "[env-rays]") {
    const std::vector<MaterialDesc> materials = {test::blinn_phong(0.2f, 0.6f, 60.0f), anisotropic_ward(0.2f, 0.5f, 0.08f, 0.35f),
                                                 test::lambert(Color(0.5f))};
    std::mt19937 rng(11);
    for (const MaterialDesc& material : materials) {
        const auto brdf = make_brdf(material);
        const BrdfSampler sampler(*brdf);
        CHECK(sampler.isotropic() == brdf->isotropic());
        CHECK(sampler.slice_count() == (material.model == "lambert" ? 1 : brdf->isotropic() ? 16 : 256));
        for (int view_index = 0; view_index < 3; ++view_index) {
            const Vec3 wo = random_view(rng);
            INFO(material.model << " view " << wo.x << ", " << wo.y << ", " << wo.z);
            const BrdfSampler::View view = sampler.view(wo);
            const auto integrals =
                latlong_integrals([&](const Vec3& d) { return sampler.pdf(view, d); }, M_PI / 2, 768, 8);
            const int samples = 200000;
            std::vector<int> counts(integrals.size(), 0);
            int below = 0, inconsistent = 0;
            for (int k = 0; k < samples; ++k) {
                const UnitPair u = independent_pair(5, uint64_t(view_index), uint32_t(k), 0);
                const double u2 = unit_from_bits(sample_bits(5, uint64_t(view_index), uint32_t(k), 1));
                Vec3 wi;
                float pdf = 0;
                if (!sampler.sample(view, u.u0, u.u1, u2, wi, pdf)) {
                    ++below;
                    continue;
                }
                REQUIRE(wi.z >= 0.0f);
                REQUIRE(glm::length(wi) == Approx(1.0f).epsilon(1e-4));
                if (std::abs(sampler.pdf(view, wi) - pdf) > 1e-4f * pdf) ++inconsistent;
                ++counts[size_t(latlong_bin(wi, M_PI / 2, 8))];
            }
            // The points outside the unit disk are the rest of the probability.
            const double below_share = double(below) / samples;
            CHECK(sum(integrals) + below_share == Approx(1.0).margin(2e-3 + 4.0 * std::sqrt(below_share / samples)));
            CHECK(inconsistent <= samples / 10000);
            check_histogram(integrals, counts, samples);
        }
    }
}

TEST_CASE("env-rays: sampled BRDF directions follow ρ·cos of the view", "[env-rays]") {
    // The proposal should put its mass where the lobe is: for a sharp lobe
    // most samples land within a few degrees of the mirror direction.
    const auto brdf = make_brdf(test::blinn_phong(0.0f, 1.0f, 400.0f));
    const BrdfSampler sampler(*brdf);
    std::mt19937 rng(3);
    for (int view_index = 0; view_index < 4; ++view_index) {
        const Vec3 wo = random_view(rng);
        const BrdfSampler::View view = sampler.view(wo);
        int near = 0, drawn = 0;
        for (int k = 0; k < 20000; ++k) {
            const UnitPair u = scrambled_sobol(1, uint64_t(view_index), uint32_t(k), 0);
            Vec3 wi;
            float pdf;
            if (!sampler.sample(view, u.u0, u.u1, unit_from_bits(sample_bits(1, 0, uint32_t(k), 1)), wi, pdf)) continue;
            ++drawn;
            if (glm::dot(wi, mirror_about_normal(wo)) > std::cos(0.25f)) ++near;
        }
        INFO("view " << wo.z << ": " << near << " of " << drawn << " within 14° of the mirror direction");
        CHECK(near > drawn / 2);
    }
}

TEST_CASE("env-rays: converges to the ground truth, and stratification lowers the error", "[env-rays]") {
    const Scene scene = test_scene();
    const CubeMap map = test_environment();
    const VertexColors truth = GroundTruth(scene, map, 0.0f).shade_vertices();
    auto error_at = [&](EnvironmentRaysOptions options) {
        const EnvironmentRays rays(scene, map, 0.0f, options);
        return compare_vertex_colors(rays.shade_vertices(), truth).total.relative_l2();
    };
    const double converged = error_at(rays_options(4096));
    INFO("relative L2 at N = 4096: " << converged);
    CHECK(converged < 0.01);

    EnvironmentRaysOptions independent = rays_options(64);
    independent.stratified = false;
    const double stratified_error = error_at(rays_options(64)), independent_error = error_at(independent);
    INFO("N = 64: stratified " << stratified_error << ", independent " << independent_error);
    CHECK(stratified_error < 0.8 * independent_error);
}

TEST_CASE("env-rays: the mean over seeds at N = 4 is the truth", "[env-rays]") {
    const Scene scene = test_scene();
    const CubeMap map = test_environment();
    const GroundTruth truth(scene, map, 0.0f);
    // Every sampling mix: MIS, the map alone, the BRDF alone. One technique
    // alone has heavy tails here (the BRDF rarely finds the bright region,
    // the map rarely the glossy lobe), so 64 seeds would underestimate its
    // standard error; those take 4096.
    const float default_share = EnvironmentRaysOptions{}.brdf_sampling_share;
    for (auto [share, seeds] : {std::pair{default_share, 64}, {0.5f, 64}, {0.0f, 4096}, {1.0f, 4096}}) {
        EnvironmentRaysOptions options = rays_options(4);
        options.brdf_sampling_share = share;
        const EnvironmentRays rays(scene, map, 0.0f, options);
        const Vec3 camera = scene.camera.position_at(0.0f);
        for (auto [part, vertex] : {std::pair{0, 30}, {0, 40}, {0, 50}, {0, 58}, {1, 0}, {1, 20}, {1, 100}, {2, 5}, {2, 60}}) {
            const SurfacePoint x = rays.posed().vertex(part, vertex);
            const Vec3 wo = glm::normalize(camera - x.position);
            const double expected = luminance(truth.shade(x, wo, truth.part_brdf(part)));
            double mean = 0, square = 0;
            for (int s = 0; s < seeds; ++s) {
                const double value = luminance(rays.shade(x, wo, rays.part_brdf(part), uint64_t(1000 + s)));
                mean += value / seeds, square += value * value / seeds;
            }
            const double standard_error = std::sqrt(std::max(square - mean * mean, 0.0) / (seeds - 1));
            INFO("share " << share << ", part " << part << " vertex " << vertex << ": truth " << expected << ", mean "
                          << mean << " ± " << standard_error);
            // Plus the truth's own error (its sub-texel cells: ~0.1%).
            CHECK(std::abs(mean - expected) <= 3.0 * standard_error + 2e-3 * expected);
        }
    }
}

TEST_CASE("env-rays: a frame is the same on one thread and on all", "[env-rays]") {
    const Scene scene = test_scene();
    const CubeMap map = test_environment();
    const EnvironmentRays rays(scene, map, 0.0f, rays_options(16));
    const VertexColors all = rays.shade_vertices();
    VertexColors one;
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        one = rays.shade_vertices();
    }
    CHECK(all.parts == one.parts);
    CHECK(rays.rays_traced() > 0);
    // The per-pixel image too: its streams come from the pixel's ray.
    const PinholeCamera camera = PinholeCamera::at_time(scene.camera, 0.0f, 24, 18);
    const Image image = trace_image(rays.posed(), camera, {}, rays.hit_shader());
    Image single_image;
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        single_image = trace_image(rays.posed(), camera, {}, rays.hit_shader());
    }
    CHECK(image.pixels == single_image.pixels);
}

TEST_CASE("env-rays: suns are the truth's, ray for ray", "[env-rays]") {
    Scene scene = test_scene();
    scene.lights.clear();
    SceneNode sun_node;
    sun_node.name = "sun";
    sun_node.rest.rotation = glm::angleAxis(glm::radians(-50.0f), Vec3(1, 0, 0));  // −Z tilted downwards
    scene.nodes.push_back(sun_node);
    SunLight sun;
    sun.node = int(scene.nodes.size()) - 1;
    sun.irradiance = Color(3.0f, 2.8f, 2.5f);
    scene.environment.suns.push_back(sun);
    const CubeMap black(8);
    const VertexColors truth = GroundTruth(scene, black, 0.0f).shade_vertices();
    const VertexColors rays = EnvironmentRays(scene, black, 0.0f, rays_options(4)).shade_vertices();
    CHECK(compare_vertex_colors(rays, truth).total.relative_l2() < 1e-6);
    CHECK(compare_vertex_colors(rays, truth).total.reference_squared > 0.0);
}

TEST_CASE("env-rays: bad options are errors", "[env-rays]") {
    const Scene scene = test_scene();
    const CubeMap map = test_environment(4);
    CHECK_THROWS_AS(EnvironmentRays(scene, map, 0.0f, rays_options(0)), Error);
    CHECK_THROWS_AS(EnvironmentRays(scene, map, 0.0f, rays_options(EnvironmentRaysOptions::kMaxSamples + 1)), Error);
    EnvironmentRaysOptions share = rays_options(4);
    share.brdf_sampling_share = 1.5f;
    CHECK_THROWS_AS(EnvironmentRays(scene, map, 0.0f, share), Error);
}
