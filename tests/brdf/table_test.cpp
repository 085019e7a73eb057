// BRDF table properties: texel-aligned squares are exact, clipping at the
// table's edge, continuity in center, size and view, the batch API, the
// anisotropic table of an isotropic Ward, and the tabulated texel averages.
#include <catch2/catch.hpp>

#include "src/brdf/brdf_table.h"
#include "src/brdf/texel_sampler.h"
#include "tests/brdf/brdf_test_util.h"
#include "tests/brdf/table_test_util.h"
#include "src/shading/brdf_sat.h"
#include "tests/random_cases.h"

using namespace rsl;
using namespace rsl::test;

namespace {

MaterialDesc glossy() { return material("cook_torrance_ggx", {{"kd", {0.3f, 0.2f, 0.1f}}, {"f0", {0.9f, 0.6f, 0.3f}}, {"roughness", {0.2f}}}); }
MaterialDesc aniso() { return material("ward_anisotropic", {{"kd", {0.2f}}, {"ks", {0.6f}}, {"alpha_x", {0.1f}}, {"alpha_y", {0.3f}}}); }

float max_abs_stored(const BrdfTable& t, int s) {
    const size_t corners = size_t(t.grid().n + 1) * (t.grid().n + 1) * 3;  // layer 0 of the slice
    float m = 0;
    for (size_t k = 0; k < corners; ++k) m = std::max(m, std::abs(t.lookup_data()[2 * s * corners + k]));
    return m;
}

}  // namespace

TEST_CASE("texel-aligned squares are exact to float precision", "[brdf][table]") {
    for (SatStorage storage : {SatStorage::Float, SatStorage::FloatMeanOffset})
        for (const MaterialDesc& m : {glossy(), aniso(), material("lambert", {{"albedo", {0.7f}}})}) {
            BrdfTableOptions options;
            options.storage = storage;
            auto brdf = make_brdf(m);
            auto table = BrdfTable::build(*brdf, options);
            const int n = table->grid().n;
            std::mt19937 rng(12);
            for (int k = 0; k < 3000; ++k) {
                const int s = std::uniform_int_distribution<int>(0, table->slice_count() - 1)(rng);
                const int edge = std::uniform_int_distribution<int>(1, 12)(rng);
                // Lower-left texel may lie outside the table: those texels count 0.
                const int i0 = std::uniform_int_distribution<int>(-edge / 2, n - edge / 2)(rng);
                const int j0 = std::uniform_int_distribution<int>(-edge / 2, n - edge / 2)(rng);
                DVec3 sum(0.0);
                for (int j = std::max(j0, 0); j < std::min(j0 + edge, n); ++j)
                    for (int i = std::max(i0, 0); i < std::min(i0 + edge, n); ++i) sum += DVec3(table->texel(s, i, j));
                const DVec3 expected = sum / double(edge * edge);
                const float texel = table->grid().texel_size();
                const Vec2 center(-1.0f + (i0 + 0.5f * edge) * texel, -1.0f + (j0 + 0.5f * edge) * texel);
                const Color got = table->slice_square_average(s, center, 0.5f * edge * texel);
                // Float: 16 taps, each stored with relative error 2⁻²⁴ of the largest
                // SAT magnitude, divided by the square's area in texels; plus the
                // rounding of the corner coordinates (a few ulps of N).
                const double bound = 64.0 * 6e-8 * max_abs_stored(*table, s) / (edge * edge) + 1e-6 * std::abs(expected.g);
                INFO(describe(m) << " slice " << s << " square " << i0 << "," << j0 << " edge " << edge);
                for (int c = 0; c < 3; ++c) REQUIRE(std::abs(got[c] - expected[c]) <= bound);
            }
        }
}

TEST_CASE("squares outside the table count zero, the average is over the whole square", "[brdf][table]") {
    auto brdf = make_brdf(material("lambert", {{"albedo", {0.9f}}}));
    auto table = BrdfTable::build(*brdf);
    const Vec3 view(0, 0, 1);
    CHECK(luminance(table->square_average(Vec2(1.5f, 0.0f), 0.2f, view)) == 0.0f);
    CHECK(luminance(table->square_average(Vec2(-1.3f, 1.3f), 0.25f, view)) == 0.0f);
    // Half of this square lies beyond x = 1; the table's corner texels are
    // below the horizon and tabulated as 0, the part past the table is clipped.
    // 5%: where the square's edge cuts horizon texels, the table spreads their
    // (partial-coverage) average evenly over the texel, which the brute force
    // does not (measured 3% at (−0.75, −0.75)).
    for (Vec2 c : {Vec2(1.0f, 0.0f), Vec2(0.0f, -1.0f), Vec2(0.9f, 0.3f), Vec2(-0.75f, -0.75f)}) {
        const float h = 0.2f;
        const DVec3 ref = brute_square_average(*brdf, c, h, view, 256);
        INFO("center " << c.x << "," << c.y);
        CHECK(table->square_average(c, h, view).r == Approx(ref.r).epsilon(0.05).margin(2e-4));
    }
}

TEST_CASE("square averages are continuous in center, size and view", "[brdf][table]") {
    for (const MaterialDesc& m : {glossy(), aniso()}) {
        auto brdf = make_brdf(m);
        auto table = BrdfTable::build(*brdf);
        const float texel = table->grid().texel_size();
        const int n = table->grid().n;
        float peak = 0;
        for (int s = 0; s < table->slice_count(); ++s)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) peak = std::max(peak, luminance(table->texel(s, i, j)));
        std::mt19937 rng(31);
        std::uniform_real_distribution<float> u(-1, 1);
        const float d = 2e-4f;
        for (int k = 0; k < 3000; ++k) {
            // Put a square edge exactly on a texel boundary half of the time:
            // crossing it must not jump.
            Vec2 c = test::random_vec2(u, rng) * 0.8f;
            float h = 0.02f + 0.2f * std::abs(u(rng));
            if (k % 2) c.x = -1.0f + std::round((c.x - h + 1.0f) / texel) * texel + h;
            const Vec3 view = random_upper_direction(rng, 1.45f);
            const Color a = table->square_average(c, h, view);
            // |∂avg/∂c| ≤ peak / h per axis (one column of texels enters as one
            // leaves), |∂avg/∂h| ≤ 4·peak / h; 2× margin.
            const float bound = 2.0f * 4.0f * peak * d / h + 1e-5f * peak;
            INFO(describe(m) << " c " << c.x << "," << c.y << " h " << h);
            CHECK(std::abs(luminance(table->square_average(c + Vec2(d, 0), h, view)) - luminance(a)) <= bound);
            CHECK(std::abs(luminance(table->square_average(c - Vec2(0, d), h, view)) - luminance(a)) <= bound);
            CHECK(std::abs(luminance(table->square_average(c, h + d, view)) - luminance(a)) <= bound);
            // View: a 2e-4 rad turn moves the view by ≤ 2e-4·V/… slices; the
            // table changes by ≤ the largest slice-to-slice difference times that
            // fraction, far below 2% of the peak.
            const Vec3 turned = glm::normalize(view + Vec3(d, -d, d));
            CHECK(std::abs(luminance(table->square_average(c, h, turned)) - luminance(a)) <= 0.02f * peak);
        }
    }
}

TEST_CASE("the batched lookup equals the single lookup", "[brdf][table]") {
    for (const MaterialDesc& m : {glossy(), aniso()}) {
        auto brdf = make_brdf(m);
        auto table = BrdfTable::build(*brdf);
        const size_t n = 1000;
        std::vector<float> cx(n), cy(n), h(n), vx(n), vy(n), vz(n), r(n), g(n), b(n);
        std::mt19937 rng(2);
        std::uniform_real_distribution<float> u(-1, 1);
        for (size_t k = 0; k < n; ++k) {
            cx[k] = u(rng), cy[k] = u(rng), h[k] = 0.01f + 0.25f * std::abs(u(rng));
            const Vec3 v = random_upper_direction(rng);
            vx[k] = v.x, vy[k] = v.y, vz[k] = v.z;
        }
        SquareQueries q{cx.data(), cy.data(), h.data(), 0.0f, vx.data(), vy.data(), vz.data(), n};
        table->square_average_batch(q, {r.data(), g.data(), b.data()});
        for (size_t k = 0; k < n; ++k) {
            const Color one = table->square_average(Vec2(cx[k], cy[k]), h[k], Vec3(vx[k], vy[k], vz[k]));
            REQUIRE(r[k] == one.r);
            REQUIRE(g[k] == one.g);
            REQUIRE(b[k] == one.b);
        }
        // Uniform half-edge: the same as passing it per query.
        q.half_edge = nullptr;
        q.uniform_half_edge = 0.1f;
        table->square_average_batch(q, {r.data(), g.data(), b.data()});
        for (size_t k = 0; k < n; k += 37)
            REQUIRE(r[k] == table->square_average(Vec2(cx[k], cy[k]), 0.1f, Vec3(vx[k], vy[k], vz[k])).r);
    }
}

TEST_CASE("the anisotropic Ward table with α_x = α_y matches the isotropic table", "[brdf][table]") {
    auto iso = make_brdf(material("ward", {{"kd", {0.2f}}, {"ks", {0.6f}}, {"alpha", {0.25f}}}));
    auto aniso_same =
        make_brdf(material("ward_anisotropic", {{"kd", {0.2f}}, {"ks", {0.6f}}, {"alpha_x", {0.25f}}, {"alpha_y", {0.25f}}}));
    auto iso_table = BrdfTable::build(*iso);
    auto aniso_table = BrdfTable::build(*aniso_same);
    REQUIRE(iso_table->isotropic());
    REQUIRE_FALSE(aniso_table->isotropic());
    REQUIRE(aniso_table->slice_count() == 32 * 32);
    // Views at azimuths 0°, 90°, 180°, 270° (from +y towards +x): the
    // view-aligned frame is a quarter turn of the tangent frame, so an
    // axis-aligned square stays axis-aligned in both tables and the two
    // lookups describe the same region. They differ only by the view
    // interpolation (slices 1/32 apart in the view's plane radius for iso, a
    // 1/16 grid for aniso), largest at grazing views where the lobe moves
    // fastest: measured worst |Δ| = 3.0% and mean 0.09% of (iso + peak), peak
    // the normal-view lobe maximum. A transposed view grid, a wrong
    // view-aligned rotation or slice order moves the lobe and is off by a
    // large fraction of the peak.
    std::mt19937 rng(44);
    std::uniform_real_distribution<float> u(0, 1);
    const float peak = luminance(iso_table->square_average(Vec2(0), 0.05f, Vec3(0, 0, 1)));
    double worst = 0, mean = 0;
    const int cases = 2000;
    for (int k = 0; k < cases; ++k) {
        const float theta = 1.35f * u(rng);
        const float phi = 0.5f * kPi * std::floor(4.0f * u(rng));
        const Vec3 view(std::sin(theta) * std::sin(phi), std::sin(theta) * std::cos(phi), std::cos(theta));
        const Vec3 c = random_upper_direction(rng, 1.4f);
        const float h = 0.03f + 0.2f * u(rng);
        const float a = luminance(aniso_table->square_average(hemisphere_to_plane(c), h, view));
        const float i = luminance(iso_table->square_average(hemisphere_to_plane(to_view_aligned(c, view)), h, view));
        const double e = std::abs(a - i) / (i + peak);
        worst = std::max(worst, e);
        mean += e / cases;
        INFO("θ " << theta << " φ " << phi << " c " << c.x << "," << c.y << "," << c.z << " h " << h);
        CHECK(e <= 0.05);
    }
    CHECK(mean <= 0.003);
    WARN("aniso(α, α) vs iso Ward table: |Δ| / (iso + peak) worst " << worst << ", mean " << mean);
}

TEST_CASE("tabulated texels are texel averages, horizon texels included", "[brdf][table]") {
    for (const MaterialDesc& m : {material("lambert", {{"albedo", {1.0f}}}), glossy()}) {
        auto brdf = make_brdf(m);
        auto table = BrdfTable::build(*brdf);
        const PlaneGrid& grid = table->grid();
        for (int s : {0, 13, 31}) {
            const Vec3 wo = table->slice_view(s);
            double worst_edge = 0, worst_inside = 0, peak = 0;
            for (int j = 0; j < grid.n; ++j)
                for (int i = 0; i < grid.n; ++i) {
                    const DVec3 ref = brute_square_average(*brdf, grid.texel_center(i, j), 0.5f * grid.texel_size(), wo, 64);
                    const double err = std::abs(table->texel(s, i, j).g - ref.g);
                    const Vec2 c = grid.texel_center(i, j);
                    const bool edge = std::abs(glm::length(c) - 1.0f) < 0.75f * grid.texel_size();
                    (edge ? worst_edge : worst_inside) = std::max(edge ? worst_edge : worst_inside, err);
                    peak = std::max(peak, ref.g);
                }
            INFO(describe(m) << " slice " << s << ": peak " << peak << ", worst error inside " << worst_inside
                             << ", on the horizon " << worst_edge);
            // Horizon texels: 4×4 sub-samples of a function that falls to 0 at
            // the rim; a center sample alone would be off by up to half the
            // texel's value. Inside: 2×2 midpoint rule on a lobe of width ≥ 0.2.
            CHECK(worst_edge <= 0.01 * peak);
            CHECK(worst_inside <= 0.02 * peak);
        }
    }
}

TEST_CASE("view-aligned frame puts the view at azimuth 0 (+y)", "[brdf][table]") {
    std::mt19937 rng(1);
    for (int k = 0; k < 100; ++k) {
        const Vec3 wo = random_upper_direction(rng), w = random_upper_direction(rng);
        const Vec3 v = to_view_aligned(wo, wo);
        CHECK(v.x == Approx(0.0f).margin(1e-6));
        CHECK(v.y == Approx(std::sqrt(1 - wo.z * wo.z)).epsilon(1e-5));
        // A rotation about z: angles and the polar angle are preserved.
        CHECK(glm::dot(to_view_aligned(w, wo), v) == Approx(glm::dot(w, wo)).epsilon(1e-5).margin(1e-6));
        CHECK(to_view_aligned(w, wo).z == w.z);
    }
}

TEST_CASE("a square narrower than a texel reads as one texel wide, and is never negative", "[brdf][table]") {
    // A glTF sun is a square of 0.27°, a fifth of a 64² table's texel. The
    // table holds texel averages, so the narrowest square read is one texel
    // wide (shading::kMinSquareTexels): the same centre at any smaller size
    // gives the same value, and over the corner sums of a sliver of a texel
    // the float rounding (different in the GPU's sums) is not what is read.
    // Within one texel, that value lies between the averages of the texels
    // the one-texel square touches; and an average of ρ·cos is never below 0.
    size_t checked = 0;
    for (SatStorage storage : {SatStorage::Float, SatStorage::FloatMeanOffset})
        for (const MaterialDesc& m : {glossy(), aniso(), material("lambert", {{"albedo", {0.7f}}}),
                                      material("phong", {{"ks", {1.0f}}, {"exponent", {500}}})}) {
            BrdfTableOptions options;
            options.storage = storage;
            const auto table = BrdfTable::build(*make_brdf(m), options);
            INFO(describe(m) << (storage == SatStorage::Float ? " plain float" : " mean offset"));
            const int n = table->grid().n;
            const float texel = 2.0f / float(n);
            std::mt19937 rng(31);
            std::uniform_real_distribution<float> unit(0.0f, 1.0f);
            for (int k = 0; k < 2000; ++k) {
                // Inside the table, a texel from its border.
                const int i = std::uniform_int_distribution<int>(1, n - 2)(rng);
                const int j = std::uniform_int_distribution<int>(1, n - 2)(rng);
                const Vec2 lower(-1.0f + texel * float(i), -1.0f + texel * float(j));
                const Vec2 c = lower + texel * test::random_vec2(unit, rng);
                const float h = texel * 0.5f * unit(rng);  // narrower than a texel, down to a point
                const Vec3 view = random_upper_direction(rng, 1.4f);
                const Color small = table->square_average(c, h, view);
                const Color one_texel = table->square_average(c, 0.5f * texel, view);
                // The texels the one-texel square touches: the 3×3 around c's.
                Color lo(1e30f), hi(-1e30f);
                for (int dj = -1; dj <= 1; ++dj)
                    for (int di = -1; di <= 1; ++di) {
                        const Vec2 centre = lower + texel * Vec2(0.5f + float(di), 0.5f + float(dj));
                        const Color t = table->square_average(centre, 0.5f * texel, view);
                        lo = glm::min(lo, t), hi = glm::max(hi, t);
                    }
                for (int ch = 0; ch < 3; ++ch) {
                    REQUIRE(small[ch] >= 0.0f);
                    REQUIRE(small[ch] == one_texel[ch]);
                    const float slack = 1e-4f * std::max(1.0f, hi[ch]);
                    REQUIRE(small[ch] >= lo[ch] - slack);
                    REQUIRE(small[ch] <= hi[ch] + slack);
                    ++checked;
                }
            }
        }
    CHECK(checked == 2 * 4 * 2000 * 3);
}
