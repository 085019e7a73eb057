// The diagnostic ray-traced visibility (src/render/exact_visibility.h) for a
// vertex on a plane under a sphere, against the sphere's cap in the plane
// parameterization computed by brute force.
#include <catch2/catch.hpp>

#include "src/core/hemisphere.h"
#include "src/render/exact_visibility.h"
#include "tests/render/render_test_scenes.h"

namespace rsl {
namespace {

TEST_CASE("exact visibility of squares under a sphere", "[render][exact]") {
    Scene scene = test::make_scene("under a ball");
    test::add_part(scene, test::make_plane(4.0f, 8, "ground"));
    Transform pose;
    pose.translation = Vec3(0, 1.0f, 0);
    test::add_part(scene, test::make_icosphere(0.5f, 4, "ball"), pose);
    int center = 0;  // the ground vertex under the ball
    for (size_t v = 0; v < scene.parts[0].mesh.positions.size(); ++v)
        if (glm::length(scene.parts[0].mesh.positions[v]) < 1e-4f) center = int(v);

    const int grid = 16;
    const ExactVisibility all(scene, 0.0f, ExactVisibilityMode::All, grid);
    const ExactVisibility self(scene, 0.0f, ExactVisibilityMode::Self, grid);
    const ExactVisibility others(scene, 0.0f, ExactVisibilityMode::Others, grid);
    const ExactVisibility product(scene, 0.0f, ExactVisibilityMode::OthersProduct, grid);
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
        CHECK(all.visible_fraction(0, center, c.center, c.half_edge) == Approx(want).margin(0.04));
        CHECK(others.visible_fraction(0, center, c.center, c.half_edge) == Approx(want).margin(0.04));
        CHECK(product.visible_fraction(0, center, c.center, c.half_edge) == Approx(want).margin(0.04));
        CHECK(self.visible_fraction(0, center, c.center, c.half_edge) == 1.0f);  // a plane never shadows itself
    }
    CHECK(all.visible_fraction(0, center, Vec2(0), 0.05f) == 0.0f);
    CHECK(all.visible_fraction(0, center, Vec2(0.7f, 0.0f), 0.05f) == 1.0f);
}

}  // namespace
}  // namespace rsl
