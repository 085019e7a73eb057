// BRDF models: reciprocity, energy (albedo ≤ 1 and exact normalizations),
// microfacet identities, Ward anisotropic ⊇ isotropic, parameter validation.
#include <catch2/catch.hpp>

#include "src/brdf/analytic.h"
#include "src/core/error.h"
#include "tests/brdf/brdf_test_util.h"

using namespace rsl;
using namespace rsl::test;

TEST_CASE("every model is reciprocal", "[brdf][models]") {
    std::mt19937 rng(11);
    for (const MaterialDesc& m : analytic_materials()) {
        INFO(describe(m));
        auto brdf = make_brdf(m);
        for (int k = 0; k < 2000; ++k) {
            const Vec3 wi = random_upper_direction(rng), wo = random_upper_direction(rng);
            const Color a = brdf->eval(wi, wo), b = brdf->eval(wo, wi);
            for (int c = 0; c < 3; ++c) {
                INFO("wi " << wi.x << "," << wi.y << "," << wi.z << " wo " << wo.x << "," << wo.y << "," << wo.z);
                REQUIRE(std::isfinite(a[c]));
                REQUIRE(a[c] >= 0.0f);
                // float evaluation of the same expression with the roles swapped
                REQUIRE(a[c] == Approx(b[c]).epsilon(2e-4).margin(1e-6));
            }
        }
        CHECK(brdf->eval(Vec3(0, 0.6f, -0.8f), Vec3(0, 0, 1)) == Color(0.0f));
        CHECK(brdf->eval(Vec3(0, 0, 1), Vec3(0.6f, 0, -0.8f)) == Color(0.0f));
    }
}

TEST_CASE("directional albedo is at most 1 over many view directions", "[brdf][models]") {
    // Stratified 320×320 integral of ρ·cos; the tolerance is 4 estimated
    // standard deviations (a conservative, collapsed-strata estimate) plus the
    // float evaluation's 1e-4 — an energy gain larger than that fails.
    std::mt19937 rng(5);
    std::vector<float> thetas = {0.0f, 0.4f, 0.8f, 1.1f, 1.3f, 1.45f, 1.53f, 1.56f};
    for (const MaterialDesc& m : analytic_materials()) {
        auto brdf = make_brdf(m);
        for (float theta : thetas)
            for (float phi : {0.0f, 0.9f, 2.0f}) {
                if (brdf->isotropic() && phi != 0.0f) continue;
                const Vec3 wo(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
                for (int c = 0; c < 3; ++c) {
                    const Estimate albedo = stratified_hemisphere_integral(
                        [&](const Vec3& wi) { return double(brdf->eval(wi, wo)[c]) * wi.z; }, 320, rng);
                    INFO(describe(m) << " θo=" << theta << " φo=" << phi << " channel " << c << ": albedo "
                                     << albedo.value << " ± " << albedo.stddev);
                    CHECK(albedo.value <= 1.0 + 4.0 * albedo.stddev + 1e-4);
                }
            }
    }
}

TEST_CASE("normalizations: Lambert, Phong and Blinn-Phong reflect exactly their weights at normal view",
          "[brdf][models]") {
    std::mt19937 rng(8);
    const Vec3 normal_view(0, 0, 1);
    struct Case {
        MaterialDesc m;
        double expected;  // albedo at normal view, channel 0
    };
    std::vector<Case> cases = {
        {material("lambert", {{"albedo", {0.37f}}}), 0.37},
        {material("phong", {{"kd", {0.25f}}, {"ks", {0.75f}}, {"exponent", {30}}}), 1.0},
        {material("phong", {{"ks", {0.6f}}, {"exponent", {3}}}), 0.6},
        {material("blinn_phong", {{"kd", {0.1f}}, {"ks", {0.9f}}, {"exponent", {60}}}), 1.0},
        {material("blinn_phong", {{"ks", {0.5f}}, {"exponent", {2}}}), 0.5},
    };
    for (auto& [m, expected] : cases) {
        auto brdf = make_brdf(m);
        const Estimate albedo = stratified_hemisphere_integral(
            [&](const Vec3& wi) { return double(brdf->eval(wi, normal_view)[0]) * wi.z; }, 400, rng);
        INFO(describe(m) << ": " << albedo.value << " ± " << albedo.stddev);
        CHECK(std::abs(albedo.value - expected) <= 4.0 * albedo.stddev + 2e-4);
    }
    // Lambert's albedo is its parameter at every view, and ρ is the constant albedo/π.
    auto lambert = make_brdf(material("lambert", {{"albedo", {0.8f, 0.5f, 0.1f}}}));
    for (float theta : {0.3f, 1.2f, 1.55f}) {
        const Vec3 wo(std::sin(theta), 0, std::cos(theta));
        const Estimate e = stratified_hemisphere_integral(
            [&](const Vec3& wi) { return double(lambert->eval(wi, wo)[1]) * wi.z; }, 300, rng);
        CHECK(std::abs(e.value - 0.5) <= 4.0 * e.stddev + 2e-4);
        CHECK(lambert->eval(Vec3(0.6f, 0, 0.8f), wo)[1] == Approx(0.5f / kPi).epsilon(1e-6));
    }
}

TEST_CASE("microfacet distributions are normalized and the Smith Λ is exact", "[brdf][models]") {
    std::mt19937 rng(21);
    for (auto d : {MicrofacetDistribution::Beckmann, MicrofacetDistribution::GGX})
        for (float alpha : {0.1f, 0.4f, 1.0f}) {
            CookTorranceBrdf ct(d, Color(0), Color(1), alpha);
            INFO(ct.model() << " α=" << alpha);
            // ∫ D(h) cosθ_h dω_h = 1 (projected microfacet area = macro-surface area).
            const Estimate area = stratified_hemisphere_integral(
                [&](const Vec3& h) { return double(ct.distribution(h.z)) * h.z; }, 400, rng);
            CHECK(std::abs(area.value - 1.0) <= 4.0 * area.stddev + 1e-3);
            // Masking identity: ∫ G1(ω_o) ⟨ω_o·h⟩ D(h) dω_h = cosθ_o with G1 = 1/(1 + Λ(ω_o)).
            for (float theta : {0.5f, 1.2f, 1.5f}) {
                const Vec3 wo(std::sin(theta), 0, std::cos(theta));
                const double g1 = 1.0 / (1.0 + ct.smith_lambda(wo.z));
                const Estimate projected = stratified_hemisphere_integral(
                    [&](const Vec3& h) { return g1 * std::max(0.0f, glm::dot(wo, h)) * ct.distribution(h.z); }, 400,
                    rng);
                INFO("θo=" << theta << ": " << projected.value << " vs " << wo.z);
                CHECK(std::abs(projected.value - wo.z) <= 4.0 * projected.stddev + 2e-3 * wo.z);
            }
        }
}

TEST_CASE("anisotropic Ward with α_x = α_y is the isotropic Ward", "[brdf][models]") {
    auto iso = make_brdf(material("ward", {{"kd", {0.2f}}, {"ks", {0.5f}}, {"alpha", {0.2f}}}));
    auto aniso =
        make_brdf(material("ward_anisotropic", {{"kd", {0.2f}}, {"ks", {0.5f}}, {"alpha_x", {0.2f}}, {"alpha_y", {0.2f}}}));
    CHECK(iso->isotropic());
    CHECK_FALSE(aniso->isotropic());
    std::mt19937 rng(4);
    for (int k = 0; k < 2000; ++k) {
        const Vec3 wi = random_upper_direction(rng), wo = random_upper_direction(rng);
        CHECK(aniso->eval(wi, wo).r == Approx(iso->eval(wi, wo).r).epsilon(1e-6));
    }
}

TEST_CASE("anisotropic Ward follows the tangent: swapping α_x and α_y is a 90° turn", "[brdf][models]") {
    auto a = make_brdf(material("ward_anisotropic", {{"ks", {0.9f}}, {"alpha_x", {0.1f}}, {"alpha_y", {0.4f}}}));
    auto b = make_brdf(material("ward_anisotropic", {{"ks", {0.9f}}, {"alpha_x", {0.4f}}, {"alpha_y", {0.1f}}}));
    auto turn = [](const Vec3& w) { return Vec3(-w.y, w.x, w.z); };
    std::mt19937 rng(6);
    bool differs = false;
    for (int k = 0; k < 2000; ++k) {
        const Vec3 wi = random_upper_direction(rng), wo = random_upper_direction(rng);
        CHECK(b->eval(turn(wi), turn(wo)).r == Approx(a->eval(wi, wo).r).epsilon(1e-5).margin(1e-7));
        differs |= std::abs(a->eval(wi, wo).r - b->eval(wi, wo).r) > 1e-3f * a->eval(wi, wo).r + 1e-6f;
    }
    CHECK(differs);  // the model really is anisotropic
}

TEST_CASE("make_brdf names the material and the bad parameter", "[brdf][models]") {
    auto fails_with = [](const MaterialDesc& m, const std::string& needle) {
        try {
            make_brdf(m);
        } catch (const Error& e) {
            const std::string what = e.what();
            INFO(what);
            CHECK(what.find(m.name) != std::string::npos);
            CHECK(what.find(needle) != std::string::npos);
            return;
        }
        FAIL("no error for " << describe(m) << " (expected '" << needle << "')");
    };
    fails_with(material("lambert", {{"albedo", {-0.1f, 0.5f, 0.5f}}}), "albedo");
    fails_with(material("lambert", {{"albedo", {1.2f}}}), "albedo");
    fails_with(material("lambert", {{"albedo", {0.5f, 0.5f}}}), "albedo");
    fails_with(material("lambert", {}), "'albedo' is missing");
    fails_with(material("lambert", {{"albedo", {0.5f}}, {"albdo", {0.5f}}}), "albdo");
    fails_with(material("phong", {{"kd", {0.5f}}, {"ks", {0.6f}}, {"exponent", {10}}}), "kd + ks");
    fails_with(material("phong", {{"ks", {0.5f}}, {"exponent", {-1}}}), "exponent");
    fails_with(material("blinn_phong", {{"ks", {0.5f}}}), "exponent");
    fails_with(material("cook_torrance_ggx", {{"f0", {0.04f}}, {"roughness", {0.0f}}}), "roughness");
    fails_with(material("cook_torrance_beckmann", {{"f0", {1.5f}}, {"roughness", {0.2f}}}), "f0");
    fails_with(material("ward", {{"ks", {0.5f}}, {"alpha", {-0.2f}}}), "alpha");
    fails_with(material("ward_anisotropic", {{"ks", {0.5f}}, {"alpha_x", {0.2f}}}), "alpha_y");
    fails_with(material("ward", {{"ks", {0.5f}}, {"alpha", {std::nanf("")}}}), "alpha");
    fails_with(material("velvet", {}), "unknown BRDF model 'velvet'");
    fails_with(material("merl", {}), "file");
    // And the accepted edge of each range builds.
    CHECK_NOTHROW(make_brdf(material("ward", {{"kd", {0.5f}}, {"ks", {0.5f}}, {"alpha", {1.0f}}})));
    CHECK_NOTHROW(make_brdf(material("phong", {{"ks", {1.0f}}, {"exponent", {0}}})));
}

TEST_CASE("make_scene_brdfs builds every material in order and names the scene file on errors", "[brdf][models]") {
    Scene scene;
    scene.source = "scenes/kitchen.json";
    scene.materials = {material("lambert", {{"albedo", {0.5f}}}),
                       material("phong", {{"ks", {0.5f}}, {"exponent", {20}}})};
    const auto brdfs = make_scene_brdfs(scene);
    REQUIRE(brdfs.size() == 2);
    CHECK(brdfs[0]->model() == "lambert");
    CHECK(brdfs[1]->model() == "phong");

    scene.materials.push_back(material("phong", {{"ks", {0.5f}}}));
    scene.materials.back().name = "shiny";
    CHECK_THROWS_WITH(make_scene_brdfs(scene), Catch::StartsWith("scenes/kitchen.json: material 'shiny' (phong)") &&
                                                   Catch::Contains("exponent"));
    scene.source.clear();  // a scene built in code has no file to name
    CHECK_THROWS_WITH(make_scene_brdfs(scene), Catch::StartsWith("material 'shiny' (phong)"));
}

TEST_CASE("gltf_pbr is GGX Cook-Torrance with glTF's metallic-roughness mapping", "[brdf][models]") {
    // kd = base (1 − metallic), f0 = mix(0.04, base, metallic), α = roughness².
    std::mt19937 rng(21);
    const Color base(0.8f, 0.4f, 0.1f);
    for (float metallic : {0.0f, 0.3f, 1.0f})
        for (float roughness : {0.2f, 0.6f, 1.0f}) {
            auto pbr = make_brdf(material("gltf_pbr", {{"base_color", {base.r, base.g, base.b}},
                                                       {"metallic", {metallic}}, {"roughness", {roughness}}}));
            const Color kd = base * (1.0f - metallic), f0 = Color(0.04f) * (1.0f - metallic) + base * metallic;
            auto reference = make_brdf(material("cook_torrance_ggx", {{"kd", {kd.r, kd.g, kd.b}},
                                                                      {"f0", {f0.r, f0.g, f0.b}},
                                                                      {"roughness", {roughness * roughness}}}));
            CHECK(pbr->model() == "gltf_pbr");
            CHECK(pbr->isotropic());
            const BrdfLobes lobes = make_brdf_lobes(material("gltf_pbr", {{"base_color", {base.r, base.g, base.b}},
                                                                          {"metallic", {metallic}},
                                                                          {"roughness", {roughness}}}));
            for (int k = 0; k < 500; ++k) {
                const Vec3 wi = random_upper_direction(rng), wo = random_upper_direction(rng);
                const Color a = pbr->eval(wi, wo), b = reference->eval(wi, wo);
                const Color sum = lobes.diffuse->eval(wi, wo) + lobes.specular->eval(wi, wo);
                for (int c = 0; c < 3; ++c) {
                    REQUIRE(a[c] == Approx(b[c]).epsilon(1e-5).margin(1e-7));
                    REQUIRE(sum[c] == Approx(a[c]).epsilon(1e-5).margin(1e-7));
                }
                // The diffuse lobe is the Fresnel-weighted Lambert term alone: view independent up to F(θ_o).
                const Color d = lobes.diffuse->eval(wi, wo);
                for (int c = 0; c < 3; ++c) REQUIRE(d[c] <= kd[c] / kPi + 1e-6f);
            }
        }
    // glTF's defaults when a parameter is absent: base 1, metallic 1, roughness 1.
    auto defaults = make_brdf(material("gltf_pbr", {}));
    auto explicit_defaults = make_brdf(
        material("gltf_pbr", {{"base_color", {1.0f}}, {"metallic", {1.0f}}, {"roughness", {1.0f}}}));
    CHECK(defaults->eval(Vec3(0.3f, 0, 0.954f), Vec3(0, 0.5f, 0.866f)) ==
          explicit_defaults->eval(Vec3(0.3f, 0, 0.954f), Vec3(0, 0.5f, 0.866f)));
    // Roughness 0 (allowed by glTF) is a finite, very sharp lobe.
    auto mirror = make_brdf(material("gltf_pbr", {{"metallic", {1.0f}}, {"roughness", {0.0f}}}));
    CHECK(std::isfinite(mirror->eval(Vec3(0.6f, 0, 0.8f), Vec3(-0.6f, 0, 0.8f)).r));
    CHECK(mirror->eval(Vec3(0.6f, 0, 0.8f), Vec3(-0.6f, 0, 0.8f)).r > 100.0f);
}

TEST_CASE("gltf_pbr parameters are validated, and only it splits into lobes", "[brdf][models]") {
    const auto fails_with = [](const MaterialDesc& m, const std::string& needle) {
        CHECK_THROWS_WITH(make_brdf(m), Catch::Contains(m.name) && Catch::Contains(needle));
    };
    fails_with(material("gltf_pbr", {{"metallic", {1.5f}}}), "metallic");
    fails_with(material("gltf_pbr", {{"roughness", {-0.1f}}}), "roughness");
    fails_with(material("gltf_pbr", {{"base_color", {0.5f, 0.5f}}}), "base_color");
    fails_with(material("gltf_pbr", {{"basecolor", {0.5f}}}), "basecolor");
    CHECK_THROWS_WITH(make_brdf_lobes(material("lambert", {{"albedo", {0.5f}}})),
                      Catch::Contains("only gltf_pbr materials take a base colour texture"));
}
