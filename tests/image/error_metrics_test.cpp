// Error measures against hand-computed values.
#include <cmath>
#include <random>

#include <fmt/core.h>

#include <catch2/catch.hpp>

#include "src/core/error.h"
#include "src/image/error_metrics.h"
#include "tests/random_cases.h"

using namespace rsl;

TEST_CASE("Relative L2, max and per-part errors over vertices", "[trace][error]") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> uni(0.1f, 2.0f);
    VertexColors b;
    b.add_part("p0", 50);
    b.add_part("p1", 70);
    for (auto& part : b.parts)
        for (Color& c : part) c = test::random_vec3(uni, rng);
    // A = B scaled by (1 + e) on part 0 only: part 0's error is exactly e.
    VertexColors a = b;
    const float e = 0.03f;
    for (Color& c : a.parts[0]) c *= 1.0f + e;
    const VertexErrorReport r = compare_vertex_colors(a, b);
    REQUIRE(r.parts[0].relative_l2() == Approx(e).epsilon(1e-4));
    REQUIRE(r.parts[1].relative_l2() == 0.0);
    REQUIRE(r.parts[1].count == 70);
    double n0 = 0, n1 = 0, max0 = 0;
    for (const Color& c : b.parts[0]) n0 += glm::dot(DVec3(c), DVec3(c)), max0 = std::max(max0, double(glm::length(c)));
    for (const Color& c : b.parts[1]) n1 += glm::dot(DVec3(c), DVec3(c));
    REQUIRE(r.total.relative_l2() == Approx(e * std::sqrt(n0 / (n0 + n1))).epsilon(1e-4));
    REQUIRE(r.total.max_error == Approx(e * max0).epsilon(1e-4));
    REQUIRE(r.total.count == 120);
}

TEST_CASE("One relative L2 for lists of colours, a zero reference included", "[trace][error]") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uni(-1.0f, 2.0f);
    for (int trial = 0; trial < 50; ++trial) {
        std::vector<Color> a(size_t(1 + trial * 7)), b(a.size());
        double diff = 0, norm = 0;
        for (size_t i = 0; i < a.size(); ++i) {
            a[i] = test::random_vec3(uni, rng);
            b[i] = test::random_vec3(uni, rng);
            const DVec3 d = DVec3(a[i]) - DVec3(b[i]);
            diff += glm::dot(d, d);
            norm += glm::dot(DVec3(b[i]), DVec3(b[i]));
        }
        CHECK(relative_l2(a, b) == Approx(std::sqrt(diff / norm)).epsilon(1e-12));
    }
    // As ErrorStats: 0 when both are 0, infinite when only the reference is.
    const std::vector<Color> zero(3, Color(0)), one(3, Color(1));
    CHECK(relative_l2(zero, zero) == 0.0);
    CHECK(std::isinf(relative_l2(one, zero)));
    CHECK_THROWS(relative_l2(one, std::vector<Color>(2, Color(1))));
}

TEST_CASE("Image errors: covered pixels only, H1 ignores constant offsets", "[trace][error]") {
    Image b(8, 6, 4), a(8, 6, 4);
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 8; ++x) {
            const bool inside = x >= 2 && x < 7 && y >= 1 && y < 5;
            const Color c = inside ? Color(1.0f + 0.1f * x, 0.5f + 0.2f * y, 0.3f) : Color(0);
            b.set_rgb(x, y, c);
            b.at(x, y)[3] = inside ? 1.0f : 0.0f;
            a.set_rgb(x, y, inside ? c + Color(0.05f) : Color(0));
            a.at(x, y)[3] = b.at(x, y)[3];
        }
    const ImageErrorReport r = compare_images(a, b);
    REQUIRE(r.covered == 20);
    REQUIRE(r.total == 48);
    double b2 = 0;
    for (int y = 1; y < 5; ++y)
        for (int x = 2; x < 7; ++x) b2 += glm::dot(DVec3(b.rgb(x, y)), DVec3(b.rgb(x, y)));
    REQUIRE(r.pixels.relative_l2() == Approx(std::sqrt(20 * 3 * 0.05 * 0.05 / b2)).epsilon(1e-4));
    REQUIRE(r.relative_h1() == Approx(0.0).margin(1e-6));  // constant offset: same gradients
    REQUIRE(r.pixels.max_error == Approx(0.05 * std::sqrt(3.0)).epsilon(1e-4));

    // A gradient difference is seen by H1: double B's slope in x.
    Image steep = b;
    for (int y = 1; y < 5; ++y)
        for (int x = 2; x < 7; ++x) steep.at(x, y)[0] = 1.0f + 0.2f * x;
    REQUIRE(compare_images(steep, b).relative_h1() > 0.2);

    REQUIRE_THROWS_AS(compare_images(Image(8, 5, 4), b), Error);

    // Only the reference's coverage counts: a pixel A covers outside B's
    // silhouette is not measured, a pixel of B's that A misses is (in full).
    Image spill = a;
    spill.set_rgb(0, 0, Color(5.0f));
    spill.at(0, 0)[3] = 1.0f;
    const ImageErrorReport spilled = compare_images(spill, b);
    REQUIRE(spilled.covered == 20);
    REQUIRE(spilled.pixels.relative_l2() == Approx(r.pixels.relative_l2()).epsilon(1e-6));
    Image hole = a;
    hole.set_rgb(3, 2, Color(0));
    hole.at(3, 2)[3] = 0.0f;
    const ImageErrorReport holed = compare_images(hole, b);
    REQUIRE(holed.covered == 20);
    const DVec3 b32 = DVec3(b.rgb(3, 2));
    REQUIRE(holed.pixels.diff_squared ==
            Approx(19 * 3 * 0.05 * 0.05 + glm::dot(b32, b32)).epsilon(1e-4));
    const Image err = error_image(a, b);
    REQUIRE(err.rgb(0, 0) == Color(0));           // covered by neither: black
    REQUIRE(err.rgb(3, 2) == false_color(1.0f));  // uniform error at full scale
}

TEST_CASE("Receivers match an exporter's names: any case, a copy number", "[trace][error]") {
    for (const char* name : {"ground", "Ground", "GROUND", "ground.001", "Ground_2", "ground-17"})
        CHECK(is_receiver(name, "ground"));
    for (const char* name : {"Plane", "Plane.001", "plane_3"}) CHECK(is_receiver(name, "plane"));
    for (const char* name : {"planet", "airplane", "ground.", "ground.a1", "Plane.001.002", "groundwork", "", "3"})
        CHECK_FALSE(is_receiver(name, "plane"));
    CHECK_FALSE(is_receiver("ground.", "ground"));
    CHECK_FALSE(is_receiver("ground.a1", "ground"));
    // Blender's plane under a glTF's objects is a receiver by default.
    VertexColors b;
    b.add_part("Plane", 40);
    b.add_part("Teapot.000", 5);
    b.add_part("Teapot.001", 5);
    for (auto& part : b.parts)
        for (Color& c : part) c = Color(1.0f);
    VertexColors a = b;
    for (Color& c : a.parts[0]) c = Color(2.0f);  // the plane far off, the teapots exact
    const ObjectErrorReport r = object_errors(compare_vertex_colors(a, b));
    CHECK(r.object_parts == 2);
    CHECK(r.objects.relative_l2() == 0.0);
}

TEST_CASE("False colours are ordered from dark to red and clamp", "[trace][error]") {
    REQUIRE(luminance(false_color(0.0f)) < luminance(false_color(0.5f)));
    REQUIRE(false_color(1.0f).r > false_color(1.0f).b);
    REQUIRE(false_color(-3.0f) == false_color(0.0f));
    REQUIRE(false_color(7.0f) == false_color(1.0f));
}

TEST_CASE("The objects' error leaves out the receivers, and names the worst object", "[trace][error]") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uni(0.1f, 2.0f), scale(0.5f, 1.5f);
    for (int round = 0; round < 50; ++round) {
        // A ground of many vertices nearly right, objects of few vertices off by a random factor each.
        VertexColors b, a;
        const int objects = 1 + round % 5;
        b.add_part("ground", 400);
        for (int o = 0; o < objects; ++o) b.add_part(fmt::format("object{}", o), 10 + 7 * o);
        for (auto& part : b.parts)
            for (Color& c : part) c = test::random_vec3(uni, rng);
        a = b;
        std::vector<float> factor(b.parts.size(), 1.001f);
        for (size_t p = 1; p < factor.size(); ++p) factor[p] = scale(rng);
        for (size_t p = 0; p < a.parts.size(); ++p)
            for (Color& c : a.parts[p]) c *= factor[p];
        const ObjectErrorReport r = object_errors(compare_vertex_colors(a, b));

        // Brute force: the relative L2 over the object vertices, and the part whose factor is furthest from 1.
        double diff = 0, reference = 0;
        size_t worst = 1;
        for (size_t p = 1; p < b.parts.size(); ++p) {
            for (size_t v = 0; v < b.parts[p].size(); ++v) {
                const DVec3 d = DVec3(a.parts[p][v]) - DVec3(b.parts[p][v]);
                diff += glm::dot(d, d), reference += glm::dot(DVec3(b.parts[p][v]), DVec3(b.parts[p][v]));
            }
            if (std::abs(factor[p] - 1) > std::abs(factor[worst] - 1)) worst = p;
        }
        INFO("round " << round);
        REQUIRE(r.object_parts == size_t(objects));
        REQUIRE(r.objects.relative_l2() == Approx(std::sqrt(diff / reference)).epsilon(1e-6));
        REQUIRE(r.worst_part == b.part_names[worst]);
        REQUIRE(r.worst == Approx(std::abs(factor[worst] - 1)).epsilon(1e-4));
        // Named receivers are left out too; with every part a receiver, nothing is an object.
        REQUIRE(object_errors(compare_vertex_colors(a, b), {"ground", "object0"}).object_parts == size_t(objects - 1));
        REQUIRE(object_errors(compare_vertex_colors(a, b), b.part_names).worst_part.empty());
    }
}
