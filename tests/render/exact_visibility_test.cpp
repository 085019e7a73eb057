// The diagnostic ray-traced visibility (src/render/exact_visibility.h) for a
// vertex on a plane under a sphere, against the sphere's cap in the plane
// parameterization computed by brute force.
#include <catch2/catch.hpp>

#include <random>

#include "src/core/hemisphere.h"
#include "src/render/exact_visibility.h"
#include "tests/render/render_test_scenes.h"

namespace rsl {
namespace {

// A ball of radius 0.5 whose centre is 1 above a ground plane: from the
// ground vertex under it, a cap of half-angle 30°.
Scene ball_over_ground() {
    Scene scene = test::make_scene("under a ball");
    test::add_part(scene, test::make_plane(4.0f, 8, "ground"));
    Transform pose;
    pose.translation = Vec3(0, 1.0f, 0);
    test::add_part(scene, test::make_icosphere(0.5f, 4, "ball"), pose);
    return scene;
}

int vertex_under_ball(const Scene& scene) {
    const std::vector<Vec3>& ground = scene.parts[0].mesh.positions;
    for (size_t v = 0; v < ground.size(); ++v)
        if (glm::length(ground[v]) < 1e-4f) return int(v);
    FAIL("no ground vertex at the origin");
    return -1;
}

TEST_CASE("exact visibility of squares under a sphere", "[render][exact]") {
    const Scene scene = ball_over_ground();
    const int center = vertex_under_ball(scene);

    const int grid = 16;
    const ExactVisibility all(scene, 0.0f, ExactVisibilityMode::All, grid);
    const ExactVisibility self(scene, 0.0f, ExactVisibilityMode::Self, grid);
    const ExactVisibility others(scene, 0.0f, ExactVisibilityMode::Others, grid);
    const ExactVisibility product(scene, 0.0f, ExactVisibilityMode::OthersProduct, grid);
    const ExactVisibility split(scene, 0.0f, ExactVisibilityMode::SelfTimesOthers, grid);
    const ExactVisibility jittered(scene, 0.0f, ExactVisibilityMode::All, grid, true);
    // The ball (half-angle 30° from the vertex) in the plane: |p| < √2·sin(15°).
    const float cap = std::sqrt(2.0f) * std::sin(kPi / 12.0f);
    auto expected = [&](const Vec2& c, float h) {
        int inside = 0, visible = 0;
        const int n = 400;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const Vec2 p = c + h * Vec2(2.0f * (i + 0.5f) / n - 1.0f, 2.0f * (j + 0.5f) / n - 1.0f);
                if (glm::dot(p, p) >= 1.0f) continue;
                ++inside;
                visible += glm::length(p) > cap;
            }
        return float(visible) / float(inside);
    };
    struct Case {
        Vec2 center;
        float half_edge;
    };
    for (const Case& c : {Case{Vec2(0), 0.05f}, Case{Vec2(0.7f, 0.0f), 0.05f}, Case{Vec2(0), 0.3f},
                          Case{Vec2(0.2f, -0.1f), 0.25f}, Case{Vec2(0.8f, 0.5f), 0.4f}}) {
        const float want = expected(c.center, c.half_edge);
        INFO("square at " << c.center.x << ", " << c.center.y << " half-edge " << c.half_edge << ": " << want);
        // A 16² grid resolves the cap's edge to about a grid cell's share.
        CHECK(all.visible_fraction(0, center, 0, c.center, c.half_edge) == Approx(want).margin(0.04));
        CHECK(others.visible_fraction(0, center, 0, c.center, c.half_edge) == Approx(want).margin(0.04));
        CHECK(product.visible_fraction(0, center, 0, c.center, c.half_edge) == Approx(want).margin(0.04));
        CHECK(split.visible_fraction(0, center, 0, c.center, c.half_edge) == Approx(want).margin(0.04));  // a flat ground shadows nothing of itself
        CHECK(jittered.visible_fraction(0, center, 0, c.center, c.half_edge) == Approx(want).margin(0.04));
        CHECK(self.visible_fraction(0, center, 0, c.center, c.half_edge) == 1.0f);  // a plane never shadows itself
    }
    CHECK(all.visible_fraction(0, center, 0, Vec2(0), 0.05f) == 0.0f);
    CHECK(all.visible_fraction(0, center, 0, Vec2(0.7f, 0.0f), 0.05f) == 1.0f);
}

// The ray-traced many-light baseline's estimator: one jittered ray per
// square is unbiased (its mean over many seeds is the exact fraction, its
// variance a Bernoulli ray's), and stratifying lowers the variance (S = 2:
// under half of one ray's on a square the ball's edge crosses).
TEST_CASE("jittered ray-traced visibility is unbiased", "[render][exact]") {
    const Scene scene = ball_over_ground();
    const int center = vertex_under_ball(scene);
    const ExactVisibility exact(scene, 0.0f, ExactVisibilityMode::All, 16);
    const Vec2 c(0.3f, 0.1f);  // straddles the ball's edge at |p| ≈ 0.366
    const float h = 0.2f;
    const float want = exact.visible_fraction(0, center, 0, c, h);
    REQUIRE(want > 0.2f);
    REQUIRE(want < 0.8f);
    for (int side : {1, 2}) {
        const ExactVisibility jittered(scene, 0.0f, ExactVisibilityMode::All, side, true);
        double sum = 0, squares = 0;
        const int trials = 4000;
        for (int k = 0; k < trials; ++k) {
            // Another light index: another seed, the same square.
            const double v = jittered.visible_fraction(0, center, k, c, h);
            sum += v, squares += v * v;
        }
        const double mean = sum / trials, variance = squares / trials - mean * mean;
        INFO("S = " << side << ": mean " << mean << " (exact " << want << "), variance " << variance);
        CHECK(mean == Approx(want).margin(0.025));  // about 4 standard errors
        if (side == 1) CHECK(variance == Approx(want * (1 - want)).margin(0.03));  // one Bernoulli ray
        if (side == 2) CHECK(variance < 0.5 * want * (1 - want));  // strata: less than half of one ray's
    }
}

// The shared seeds (src/shading/ray_samples.h) do 64-bit arithmetic in
// two 32-bit words, for GLSL; they must be splitmix64 exactly.
TEST_CASE("the ray baseline's 64-bit words are splitmix64", "[render][exact]") {
    auto splitmix = [](uint64_t z) {
        z += 0x9e3779b97f4a7c15ull;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    };
    auto words = [](uint64_t z) { return shading::uvec2(uint32_t(z), uint32_t(z >> 32)); };
    auto join = [](shading::uvec2 w) { return uint64_t(w.y) << 32 | w.x; };
    std::mt19937_64 rng(42);
    for (int k = 0; k < 100000; ++k) {
        const uint64_t a = k < 4 ? ~uint64_t(0) * uint64_t(k & 1) : rng(), b = rng();
        INFO("a " << a << " b " << b);
        CHECK(join(shading::add64(words(a), words(b))) == a + b);
        CHECK(join(shading::multiply64(words(a), words(b))) == a * b);
        CHECK(join(shading::splitmix64(words(a))) == splitmix(a));
    }
    // u and v: bits 40-63 and 16-39, each in [0, 1).
    const shading::uvec2 seed = shading::ray_seed(3, 1234, 17);
    const uint64_t bits = splitmix(join(seed) + 5);
    const Vec2 in_cell = shading::jitter_in_cell(seed, 5);
    CHECK(in_cell.x == float(bits >> 40) / float(1 << 24));
    CHECK(in_cell.y == float((bits << 24) >> 40) / float(1 << 24));
}

// The renderer asks for a block's squares of one light at once; the batch
// must give exactly what one query at a time gives, in every mode, with
// and without jitter, whichever blocks came before on the thread.
TEST_CASE("ray-traced visibility: a batch equals its queries one at a time", "[render][exact]") {
    Scene scene = test::make_scene("ball and box");
    test::add_part(scene, test::make_plane(4.0f, 12, "ground"));
    Transform pose;
    pose.translation = Vec3(0.3f, 0.8f, 0);
    test::add_part(scene, test::make_icosphere(0.5f, 3, "ball"), pose);
    const int vertices = int(scene.parts[0].mesh.vertex_count());
    std::mt19937 rng(19);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (ExactVisibilityMode mode : {ExactVisibilityMode::All, ExactVisibilityMode::Self, ExactVisibilityMode::Others,
                                     ExactVisibilityMode::OthersProduct, ExactVisibilityMode::SelfTimesOthers})
        for (bool jitter : {false, true})
            for (int side : {1, 2, 4}) {
                const ExactVisibility visibility(scene, 0.0f, mode, side, jitter);
                for (int first : {0, 40, 0, 100}) {  // the per-thread vertex cache changes block and back
                    const int m = 64;
                    std::vector<int> offset(m);
                    std::vector<float> cx(m), cy(m), h(m), out(m);
                    bool skip[m];
                    for (int i = 0; i < m; ++i) {
                        offset[size_t(i)] = int(unit(rng) * float(std::min(64, vertices - first)));
                        const float radius = 0.95f * std::sqrt(unit(rng)), angle = 2.0f * kPi * unit(rng);
                        cx[size_t(i)] = radius * std::cos(angle), cy[size_t(i)] = radius * std::sin(angle);
                        h[size_t(i)] = 0.02f + 0.4f * unit(rng);
                        skip[i] = unit(rng) < 0.2f;
                    }
                    size_t batch_rays = 0, single_rays = 0;
                    visibility.visible_fraction_batch(0, first, 7, offset.data(), cx.data(), cy.data(), h.data(), skip, m,
                                                      out.data(), &batch_rays);
                    for (int i = 0; i < m; ++i) {
                        const float want = skip[i] ? 0.0f
                                                   : visibility.visible_fraction(0, first + offset[size_t(i)], 7,
                                                                                 Vec2(cx[size_t(i)], cy[size_t(i)]),
                                                                                 h[size_t(i)], &single_rays);
                        INFO("mode " << int(mode) << " jitter " << jitter << " S " << side << " query " << i);
                        CHECK(out[size_t(i)] == want);
                    }
                    CHECK(batch_rays == single_rays);
                }
            }
}

}  // namespace
}  // namespace rsl
