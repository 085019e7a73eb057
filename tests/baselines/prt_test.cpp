// SH and Haar PRT against the ground truth on small analytic scenes.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "src/image/error_metrics.h"
#include "tests/baselines/baseline_scenes.h"
#include "tools/baselines/prt.h"

using namespace rsl;
using namespace rsl::test;

TEST_CASE("SH diffuse transfer of an unoccluded upward plane under a constant sky is albedo × L") {
    Scene scene;
    scene.name = "plane";
    scene.source = "plane.json";
    const Color albedo(0.8f, 0.5f, 0.25f), L(2.0f, 1.0f, 0.5f);
    scene.materials.push_back(material("lambert", {{"albedo", {albedo.r, albedo.g, albedo.b}}}));
    add_part(scene, make_plane(1.0f, 2, 0.0f, "plane"), 0);
    scene.camera.position = Vec3(0, 5, 1);
    CubeMap sky(16);
    for (Color& c : sky.radiances()) c = L;
    const GroundTruth truth(scene, sky, 0.0f);
    PrtOptions options;
    options.haar = false;
    options.check_lighting = &sky;
    const PrtPrecompute prt = precompute_prt(truth, sky, options);
    const ShRenderer renderer(prt, sky);
    for (int order : {3, 5, 10}) {
        std::vector<Color> out;
        renderer.render(order, Mat3(1.0f), out);
        for (size_t v = 0; v < out.size(); ++v) {
            // π·L·albedo/π: exact up to the texel-center cosine quadrature,
            // which the ground truth shares (checked tightly).
            for (int c = 0; c < 3; ++c) {
                REQUIRE(out[v][c] == Approx(albedo[c] * L[c]).epsilon(2e-3));
                REQUIRE(out[v][c] == Approx(prt.texel_sum[v][c]).epsilon(1e-5));
            }
        }
    }
}

TEST_CASE("PRT transport reproduces the ground truth, and Haar with every term is exact") {
    for (bool glossy : {false, true}) {
        const Scene scene = make_shadow_scene(glossy);
        const CubeMap sky = make_sky(16);
        GroundTruthOptions truth_options;
        truth_options.local_lights = false;
        truth_options.max_sample_share = 0.0f;  // the texel-centre sum the transport samples
        const GroundTruth truth(scene, sky, 0.0f, truth_options);
        const std::vector<Color> reference = flatten(truth.shade_vertices());
        PrtOptions options;
        options.check_lighting = &sky;
        options.haar_drop = 0.0f;
        options.block_vertices = 17;  // several blocks, one partial
        const PrtPrecompute prt = precompute_prt(truth, sky, options);
        CHECK(relative_l2(prt.texel_sum, reference) < 1e-5);

        HaarRenderer haar(prt);
        std::vector<Color> out;
        haar.render(sky, sky.texel_count(), out);
        CHECK(relative_l2(out, reference) < 1e-4);
        // Few terms: a real approximation, with an error that the full set removes.
        haar.render(sky, 10, out);
        const double error_10 = relative_l2(out, reference);
        haar.render(sky, 200, out);
        const double error_200 = relative_l2(out, reference);
        CHECK(error_10 > 1e-3);
        CHECK(error_200 < error_10);

        // SH: the sun's hard shadow is beyond order 10, but order 10 beats order 3.
        const ShRenderer sh_renderer(prt, sky);
        sh_renderer.render(3, Mat3(1.0f), out);
        const double sh_3 = relative_l2(out, reference);
        sh_renderer.render(10, Mat3(1.0f), out);
        const double sh_10 = relative_l2(out, reference);
        CHECK(sh_10 < sh_3);
        CHECK(sh_10 > 1e-3);  // not exact: band-limited
    }
}

TEST_CASE("Haar transport dropping tiny coefficients stays close and stores fewer entries") {
    const Scene scene = make_shadow_scene(true);
    const CubeMap sky = make_sky(16);
    GroundTruthOptions truth_options;
    truth_options.local_lights = false;
    const GroundTruth truth(scene, sky, 0.0f, truth_options);
    PrtOptions options;
    options.sh = false;
    options.check_lighting = &sky;
    options.haar_drop = 0.0f;
    const PrtPrecompute full = precompute_prt(truth, sky, options);
    options.haar_drop = 1e-3f;
    const PrtPrecompute sparse = precompute_prt(truth, sky, options);
    CHECK(sparse.haar.entries() < full.haar.entries());
    HaarRenderer renderer(sparse);
    std::vector<Color> out;
    renderer.render(sky, sky.texel_count(), out);
    CHECK(relative_l2(out, full.texel_sum) < 1e-2);
}

TEST_CASE("SH rendering with a turned environment matches re-projecting the turned map") {
    const Scene scene = make_shadow_scene(false);
    const CubeMap sky = make_sky(32);
    const GroundTruth truth(scene, sky, 0.0f);
    PrtOptions options;
    options.haar = false;
    options.sh_order = 5;
    const PrtPrecompute prt = precompute_prt(truth, sky, options);
    const Mat3 turn = glm::mat3_cast(glm::angleAxis(0.7f, glm::normalize(Vec3(1.0f, 0.3f, 0.2f))));
    std::vector<Color> rotated, reprojected;
    ShRenderer(prt, sky).render(5, turn, rotated);
    ShRenderer(prt, rotate(sky, turn)).render(5, Mat3(1.0f), reprojected);
    INFO("turned vs re-projected");
    CHECK(relative_l2(rotated, reprojected) < 5e-3);
    // Turning the other way is visibly different: the check can fail.
    ShRenderer(prt, sky).render(5, glm::transpose(turn), rotated);
    CHECK(relative_l2(rotated, reprojected) > 0.2);
}

TEST_CASE("Unshadowed transport (no rays) is the shadowed one where nothing occludes, and brighter in shadows") {
    const Scene scene = make_shadow_scene(false);
    const CubeMap sky = make_sky(16);
    const GroundTruth truth(scene, sky, 0.0f);
    PrtOptions options;
    options.sh = options.haar = false;
    options.check_lighting = &sky;
    const PrtPrecompute shadowed = precompute_prt(truth, sky, options);
    options.visibility = false;
    const PrtPrecompute unshadowed = precompute_prt(truth, sky, options);
    CHECK(unshadowed.rays == 0);
    int darker = 0;
    for (size_t v = 0; v < shadowed.texel_sum.size(); ++v) {
        for (int c = 0; c < 3; ++c) REQUIRE(unshadowed.texel_sum[v][c] >= shadowed.texel_sum[v][c] * (1 - 1e-6f));
        if (luminance(shadowed.texel_sum[v]) < 0.9f * luminance(unshadowed.texel_sum[v])) ++darker;
    }
    // The roof (its top is unoccluded) matches; the ground under it is shadowed.
    const size_t roof = shadowed.layout.first(1);
    for (size_t v = roof; v < shadowed.texel_sum.size(); ++v)
        REQUIRE(luminance(unshadowed.texel_sum[v]) == Approx(luminance(shadowed.texel_sum[v])).epsilon(1e-6));
    CHECK(darker >= 3);  // the roof's sun shadow covers a few ground vertices
}
