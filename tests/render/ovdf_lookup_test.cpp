// The renderer's split OVDF lookup (src/render/ovdf_lookup.h) against the
// field's own lookup, Ovdf::distance with aligned-coefficient blending, at
// random receiver points (inside the inner shell, between shells, on cube-face
// and PCA-segment seams, beyond the outer shell) and random lights; its
// cheap cone test against the full lookup; and the renderer's lazy forms
// (locate, then complete only for lights that need the tables: the
// small-occluder rule needs none; the near half from Ovdf::locate_near and
// the small-occluder rule on it, the full location only for lights that
// need the tables) against the field's visible fraction.
#include <catch2/catch.hpp>

#include <random>

#include "src/render/ovdf_lookup.h"
#include "tests/render/render_test_scenes.h"
#include "src/shading/ovdf_small_occluder.h"
#include "tests/random_cases.h"

namespace rsl {
namespace {

TEST_CASE("split OVDF lookup equals the field's own lookup", "[render][ovdf]") {
    // A box-like, asymmetric occluder: a stretched icosphere off the origin.
    TriangleMesh mesh = test::make_icosphere(0.5f, 2, "blob");
    for (Vec3& p : mesh.positions) p = Vec3(1.6f * p.x + 0.2f, 0.7f * p.y, p.z - 0.1f);
    OvdfParams params;
    params.shells = 4, params.cube_resolution = 8, params.vdt_resolution = 8, params.vectors = 4;
    params.inner_radius = 0.5f, params.outer_radius = 5.0f;
    const Ovdf field = bake_ovdf(mesh, params);
    const OvdfLookup lookup(field);
    REQUIRE(lookup.usable());

    std::mt19937 rng{11};
    std::normal_distribution<float> normal;
    std::uniform_real_distribution<float> uniform(0, 1);
    int fast = 0, seam = 0, outside = 0, shadowed = 0, unshadowed = 0, bounded = 0, small = 0, completed = 0;
    int near_small = 0, relocated = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        const Vec3 dir = glm::normalize(test::random_vec3(normal, rng));
        const float distance = field.radius * params.outer_radius * 1.2f * uniform(rng);
        const Vec3 point = field.center + distance * dir;
        OvdfPoint q;
        OvdfTerm terms[OvdfPoint::kMaxTerms];
        const int used = lookup.prepare(point, q, terms);
        if (q.kind == OvdfPoint::Prepared) {
            REQUIRE(used == q.term_count[0] + q.term_count[1]);
            REQUIRE(used <= OvdfPoint::kMaxTerms);
            // On a PCA-segment seam the samples of a shell fall in several segments.
            (q.term_count[0] > 1 || q.term_count[1] > 1 ? seam : fast)++;
        }
        outside += q.kind == OvdfPoint::Outside;
        OvdfPoint lazy;  // as the renderer: located first, terms on a light's need
        OvdfTerm lazy_terms[OvdfPoint::kMaxTerms];
        lookup.locate(point, lazy);
        REQUIRE((lazy.kind == OvdfPoint::Located) == (q.kind == OvdfPoint::Prepared));
        // As the CPU renderer now: the near half first (Ovdf::locate_near,
        // a batch of one here), the full location on a light's need.
        float near_cone = 0, near_area = 0, pole_x = 0, pole_y = 0, pole_z = 0;
        int32_t is_near = 0;
        OvdfNearPoints batch;
        batch.count = 1;
        batch.x = &point.x, batch.y = &point.y, batch.z = &point.z;
        batch.cone = &near_cone, batch.occluded_area = &near_area;
        batch.pole_x = &pole_x, batch.pole_y = &pole_y, batch.pole_z = &pole_z;
        batch.near = &is_near;
        field.locate_near(batch);
        const float d = glm::length(point - field.center);
        REQUIRE(bool(is_near) == (lazy.kind == OvdfPoint::Located && d >= field.radius));
        const Vec3 near_pole(pole_x, pole_y, pole_z);
        if (is_near) {
            REQUIRE(near_cone == lazy.cone);
            REQUIRE(near_area == lazy.occluded_area);
            REQUIRE(glm::length(near_pole - lazy.pole) < 1e-6f);
        }
        for (int l = 0; l < 4; ++l) {
            // Lights biased towards the occluder so that many lookups see it.
            const Vec3 light = glm::normalize(test::random_vec3(normal, rng) - 1.5f * dir);
            const float expected = field.distance(point, light, OvdfBlend::AlignedCoefficients);
            const float got = lookup.distance(q, point, light);
            REQUIRE(got == Approx(expected).margin(2e-5f).epsilon(1e-5f));
            shadowed += expected < 0.0f;
            // The visible fraction with the silhouette's area bound, as the field's own.
            const float h = 0.3f * uniform(rng);
            const float field_fraction = field.visible_fraction(point, light, h);
            REQUIRE(lookup.visible_fraction(q, point, light, h) == Approx(field_fraction).margin(1e-4f));
            const bool needs = OvdfLookup::needs_terms(lazy, h);
            if (needs) {
                REQUIRE(lookup.complete(lazy, lazy_terms) == used);
                ++completed;
            }
            REQUIRE(!OvdfLookup::needs_terms(lazy, h));
            REQUIRE(lookup.visible_fraction(lazy, point, light, h) == Approx(field_fraction).margin(1e-4f));
            if (is_near && shading::ovdf_small_occluder_weight(near_cone, h, near_area) >= 1.0f) {
                // The renderer's batched small-occluder rule (ovdf_factors.cpp).
                const float small = shading::ovdf_small_occluder_fraction(
                    shading::ovdf_pole_radial(glm::dot(light, near_pole)), near_area, near_cone, h);
                REQUIRE(small == Approx(field_fraction).margin(1e-4f));
                ++near_small;
            } else if (is_near) {
                ++relocated;  // a narrower light: the lazy path above
            }
            small += q.kind == OvdfPoint::Prepared && shading::ovdf_small_occluder_weight(q.cone, h, q.occluded_area) > 0.0f;
            bounded += field_fraction > visible_fraction_from_distance(expected, h) + 1e-3f;
            // The cheap cone test claims 1 only where the lookup gives it.
            if (q.kind != OvdfPoint::Outside && OvdfLookup::unshadowed(glm::dot(light, q.pole), q.cone, h)) {
                ++unshadowed;
                REQUIRE(visible_fraction_from_distance(expected, h) >= 1.0f - 1e-5f);
            }
        }
    }
    // Every kind of point occurred, and most lookups take the fast path.
    CHECK(outside > 100);
    CHECK(seam > 100);
    CHECK(fast > 2 * seam);
    CHECK(shadowed > 500);
    CHECK(unshadowed > 1000);
    CHECK(bounded > 100);  // the area bound raised some fractions, alike in both
    CHECK(small > 500);     // squares wider than the part's cone: the small-occluder rule, alike in both
    CHECK(completed > 500);
    CHECK(near_small > 300);  // answered by the small-occluder rule with no pole frame
    CHECK(relocated > 300);
}

}  // namespace
}  // namespace rsl
