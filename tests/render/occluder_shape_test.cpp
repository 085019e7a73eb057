// Occluders of exact shape (src/render/occluder_shape.h): which meshes are
// found to be one rectangle or one box, and the taps' visible share of a
// square against rays cast at the mesh itself.
#include <catch2/catch.hpp>

#include <array>
#include <functional>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "src/core/hemisphere.h"
#include "src/rays/ray_scene.h"
#include "src/render/occluder_shape.h"
#include "tests/trace/trace_test_scenes.h"
#include "src/shading/frames.h"
#include "src/shading/shadow_maps.h"
#include "src/shading/shapes.h"
#include "tests/random_cases.h"

namespace rsl {
namespace {

TriangleMesh moved(TriangleMesh mesh, const Mat4& m) {
    for (Vec3& p : mesh.positions) p = Vec3(m * Vec4(p, 1.0f));
    for (Vec3& n : mesh.normals) n = glm::normalize(Mat3(m) * n);
    return mesh;
}

Mat4 tilted() {
    return glm::translate(Mat4(1.0f), Vec3(0.3f, -0.2f, 0.5f)) * glm::rotate(Mat4(1.0f), 0.7f, glm::normalize(Vec3(1, 2, 3)));
}

}  // namespace

TEST_CASE("A grid plane is found as its rectangle, anywhere; boxes, holes and bends are not", "[render][shape]") {
    const TriangleMesh plane = test::make_plane(6.0f, 12, "ground");  // 6 × 6 at y = 0
    const std::optional<OccluderShape> r = find_rectangle(plane);
    REQUIRE(r);
    CHECK(r->kind == shading::kShapeRectangle);
    CHECK(find_occluder_shape(plane).kind == shading::kShapeRectangle);
    CHECK(std::abs(std::abs(r->normal.y) - 1.0f) < 1e-6f);
    CHECK(r->hi.x == Approx(3.0f));
    CHECK(r->hi.y == Approx(3.0f));
    CHECK(r->lo == -r->hi);
    CHECK(glm::length(r->center) < 1e-5f);
    // The plane's vertices map onto the rectangle's border or inside it, at height 0.
    for (const Vec3& p : plane.positions) {
        const Vec3 q = r->to_shape(p);
        CHECK(std::abs(q.z) < 1e-5f);
        CHECK(std::abs(q.x) <= r->hi.x + 1e-5f);
        CHECK(std::abs(q.y) <= r->hi.y + 1e-5f);
    }

    const std::optional<OccluderShape> t = find_rectangle(moved(plane, tilted()));
    REQUIRE(t);
    CHECK(t->hi.x == Approx(3.0f));
    CHECK(glm::length(t->center - Vec3(tilted()[3])) < 1e-5f);
    CHECK(std::abs(glm::dot(t->normal, glm::normalize(Mat3(tilted()) * Vec3(0, 1, 0)))) == Approx(1.0f));

    CHECK_FALSE(find_rectangle(test::make_flat_box(Vec3(0.5f), 2)));
    TriangleMesh holed = plane;  // one cell's two triangles gone
    holed.indices.erase(holed.indices.begin() + 6 * 40, holed.indices.begin() + 6 * 41);
    CHECK_FALSE(find_rectangle(holed));
    CHECK(find_occluder_shape(holed).kind == shading::kShapeNone);
    TriangleMesh bent = plane;
    bent.positions[plane.positions.size() / 2].y += 1e-3f;
    CHECK_FALSE(find_rectangle(bent));
}

TEST_CASE("A quad of two triangles is its rectangle in any index order an exporter writes; a rhombus is not",
          "[render][shape]") {
    // 4 × 2 at y = 0: corners 0 (−2, −1), 1 (2, −1), 2 (2, 1), 3 (−2, 1) in x, z.
    TriangleMesh quad;
    quad.positions = {{-2, 0, -1}, {2, 0, -1}, {2, 0, 1}, {-2, 0, 1}};
    quad.normals.assign(4, Vec3(0, 1, 0));
    // Both diagonals, each triangle's indices in each of its three rotations:
    // a triangle's first edge is then a side or the diagonal.
    const std::array<std::array<uint32_t, 6>, 2> splits = {{{0, 2, 1, 0, 3, 2}, {1, 3, 2, 1, 0, 3}}};
    int tried = 0;
    for (const auto& split : splits)
        for (int first = 0; first < 3; ++first)
            for (int second = 0; second < 3; ++second) {
                quad.indices.clear();
                for (int k = 0; k < 3; ++k) quad.indices.push_back(split[size_t((first + k) % 3)]);
                for (int k = 0; k < 3; ++k) quad.indices.push_back(split[size_t(3 + (second + k) % 3)]);
                const std::optional<OccluderShape> r = find_rectangle(quad);
                INFO("indices " << quad.indices[0] << quad.indices[1] << quad.indices[2] << " " << quad.indices[3]
                                << quad.indices[4] << quad.indices[5]);
                REQUIRE(r);
                CHECK(std::max(r->hi.x, r->hi.y) == Approx(2.0f));
                CHECK(std::min(r->hi.x, r->hi.y) == Approx(1.0f));
                CHECK(glm::length(r->center) < 1e-6f);
                ++tried;
            }
    CHECK(tried == 18);
    // A rhombus: no edge and no diagonal spans a rectangle of its area.
    quad.positions = {{-2, 0, 0}, {0, 0, -1}, {2, 0, 0}, {0, 0, 1}};
    quad.indices = {0, 2, 1, 0, 3, 2};
    CHECK_FALSE(find_rectangle(quad));
    quad.indices = {0, 1, 3, 1, 2, 3};
    CHECK_FALSE(find_rectangle(quad));
}

TEST_CASE("A closed box mesh is found as its box; an open box, a moved vertex and a sphere are not", "[render][shape]") {
    const TriangleMesh box = test::make_flat_box(Vec3(0.6f, 0.4f, 0.5f), 3);
    const OccluderShape shape = find_occluder_shape(box);
    REQUIRE(shape.kind == shading::kShapeBox);
    CHECK(shape.lo == Vec3(-0.6f, -0.4f, -0.5f));
    CHECK(shape.hi == Vec3(0.6f, 0.4f, 0.5f));
    CHECK(shape.to_shape(Vec3(0.1f, 0.2f, 0.3f)) == Vec3(0.1f, 0.2f, 0.3f));  // the mesh's own frame
    TriangleMesh open = box;  // one face's triangles gone (each face has 3 × 3 cells, 2 triangles each)
    open.indices.resize(open.indices.size() - 3 * 18);
    CHECK_FALSE(find_box(open));
    TriangleMesh dented = box;
    dented.positions[5] *= 0.9f;
    CHECK_FALSE(find_box(dented));
    CHECK(find_occluder_shape(test::make_icosphere(1.0f, 2)).kind == shading::kShapeNone);
}

// Shape coordinates of a receiver frame, and the share both ways: the 21
// taps of shape_visible_fraction, and a 32 × 32 grid of rays over the square
// cast at the mesh. The taps step the share by about 1/21, so the mean error
// is small and the largest a few steps; a wrong side, axis or sign misses by
// far more. Receivers above, below and on a tilted rectangle, and around and
// on the faces of a box.
struct ShapeCase {
    Vec3 p, normal;
};

void check_against_rays(const TriangleMesh& mesh, const OccluderShape& shape, const std::function<ShapeCase(std::mt19937&)>& make) {
    RayScene rays;
    rays.add_instance(rays.add_mesh(mesh), Mat4(1.0f));
    rays.commit();
    std::mt19937 rng(1717);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    double total_error = 0;
    float worst = 0;
    int cases = 0, partial = 0;
    constexpr int kSide = 32;
    while (cases < 400) {
        const ShapeCase x = make(rng);
        const Frame frame = Frame::from_normal_tangent(x.normal, Vec3(0));
        const Vec2 c = 0.8f * test::random_vec2(uniform, rng);
        const float h = 0.05f + 0.3f * std::abs(uniform(rng));
        int reference_taps = 0, reference_lit = 0;
        for (int j = 0; j < kSide; ++j)
            for (int i = 0; i < kSide; ++i) {
                const Vec2 q = c + h * Vec2(2.0f * (i + 0.5f) / kSide - 1.0f, 2.0f * (j + 0.5f) / kSide - 1.0f);
                if (glm::dot(q, q) >= 1.0f) continue;
                const Vec3 dir = frame.to_world(plane_to_hemisphere(q));
                ++reference_taps;
                // From just off the receiver's surface, along its normal.
                if (!rays.occluded(x.p + 1e-4f * x.normal, dir, 0.0f, 1e30f)) ++reference_lit;
            }
        if (reference_taps < kSide * kSide / 2) continue;  // mostly below the horizon: few taps to compare
        shading::LocalFrame f;
        f.x = shape.direction_to_shape(frame.x), f.y = shape.direction_to_shape(frame.y), f.z = shape.direction_to_shape(frame.z);
        const float ours = shading::shape_visible_fraction(shape.kind, shape.to_shape(x.p), f, c, h, shape.lo, shape.hi);
        const float reference = float(reference_lit) / float(reference_taps);
        const float error = std::abs(ours - reference);
        INFO("case " << cases << ": ours " << ours << ", rays " << reference);
        CHECK(error < 0.2f);
        total_error += error;
        worst = std::max(worst, error);
        partial += reference > 0.02f && reference < 0.98f;
        ++cases;
    }
    INFO("mean error " << total_error / cases << ", worst " << worst << ", partly shadowed cases " << partial);
    CHECK(total_error / cases < 0.02);
    CHECK(partial > 40);  // the cases cross shadow edges, not only all-lit or all-dark squares
}

TEST_CASE("A flat rectangle's visible share of a square matches rays cast at it", "[render][shape]") {
    const TriangleMesh mesh = moved(test::make_plane(4.0f, 8, "ground"), tilted());
    const std::optional<OccluderShape> r = find_rectangle(mesh);
    REQUIRE(r);
    int index = 0;
    check_against_rays(mesh, *r, [&](std::mt19937& rng) {
        std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
        // Over the rectangle (±1.5 of its ±2), within 1 of its plane on either
        // side; every fifth on the plane itself, facing along it like a box
        // side resting on the ground (the rays then start on the normal's side).
        const bool on_plane = index++ % 5 == 0;
        const float height = on_plane ? 0.0f : uniform(rng);
        ShapeCase x;
        const Vec2 st = 1.5f * test::random_vec2(uniform, rng);
        x.p = r->center + st.x * r->s + st.y * r->t + height * r->normal;
        x.normal = glm::normalize(test::random_vec3(uniform, rng) + Vec3(1e-3f));
        if (on_plane) {
            x.normal = glm::normalize(x.normal - r->normal * glm::dot(x.normal, r->normal));
            x.p += 2e-4f * r->normal;  // the rays' origin above the plane, as the shape counts it
        }
        return x;
    });
}

TEST_CASE("A box's visible share of a square matches rays cast at it", "[render][shape]") {
    const TriangleMesh mesh = test::make_flat_box(Vec3(0.6f, 0.4f, 0.5f), 3);
    const OccluderShape box = find_occluder_shape(mesh);
    REQUIRE(box.kind == shading::kShapeBox);
    int index = 0;
    check_against_rays(mesh, box, [&](std::mt19937& rng) {
        std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
        ShapeCase x;
        x.normal = glm::normalize(test::random_vec3(uniform, rng) + Vec3(1e-3f));
        if (index++ % 4 == 0) {  // on the top face, looking out of it or along it (a part resting on the box)
            const Vec2 xz = 0.8f * test::random_vec2(uniform, rng);
            x.p = Vec3(xz.x, 0.4f, xz.y);
            if (x.normal.y < 0.0f) x.normal.y = -x.normal.y;
            return x;
        }
        do x.p = 1.5f * test::random_vec3(uniform, rng);  // around it, outside
        while (std::abs(x.p.x) <= 0.6f && std::abs(x.p.y) <= 0.4f && std::abs(x.p.z) <= 0.5f);
        return x;
    });
}

// The whole-square tests decide only what every tap would: wherever they
// answer, the 21 taps (above the horizon, one by one against the shape) give
// that same share. And they answer often (below an object over the ground,
// most squares), or they would save nothing.
namespace {

struct WholeSquareCount {
    int checked = 0, decided = 0, shadowed = 0;
};

// Random receivers around (and on the faces of) the shape [lo, hi], random
// frames and squares; whole(point, directions) is the test under check and
// blocks(point, dir) the per-tap ray test it must agree with.
template <class Whole, class Blocks>
WholeSquareCount check_whole_square(uint32_t seed, Vec3 lo, Vec3 hi, Whole whole, Blocks blocks) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    WholeSquareCount count;
    for (int n = 0; n < 20000; ++n) {
        Vec3 point = 1.1f * test::random_vec3(uniform, rng) * glm::max(glm::abs(lo), glm::abs(hi)) +
                     Vec3(0.0f, 0.0f, 1.5f * uniform(rng));
        if (n % 7 == 0) point.z = hi.z;  // on the top face (a part resting on the shape)
        const Frame frame = Frame::from_normal_tangent(glm::normalize(test::random_vec3(uniform, rng) + Vec3(1e-3f)), Vec3(0));
        shading::LocalFrame f;
        f.x = frame.x, f.y = frame.y, f.z = frame.z;
        const Vec2 c = 1.2f * test::random_vec2(uniform, rng);
        const float h = 0.01f + 0.4f * std::abs(uniform(rng));
        int above = 0, lit = 0;
        float reach2 = 0.0f;  // the farthest counted tap's plane radius²
        for (int i = 0; i < shading::kShadowTaps; ++i) {
            const Vec2 tap = shading::shadow_tap_point(c, h, i);
            if (glm::dot(tap, tap) >= 1.0f) continue;
            ++above;
            reach2 = std::max(reach2, glm::dot(tap, tap));
            lit += !blocks(point, frame.to_world(plane_to_hemisphere(tap)));
        }
        if (above == 0) continue;
        ++count.checked;
        const float answer = whole(point, shading::square_directions(f, c, h, reach2));
        if (answer < 0.0f) continue;
        ++count.decided;
        count.shadowed += answer == 0.0f;
        INFO("case " << n << ": whole-square " << answer << ", taps " << lit << " of " << above);
        CHECK(answer == float(lit) / float(above));
        // And the renderer's function gives it too.
        CHECK(answer == blocks.fraction(point, f, c, h));
    }
    return count;
}

template <class Test>
struct ShapeBlocks {
    int kind;
    Vec3 lo, hi;
    Test test;
    bool operator()(Vec3 point, Vec3 dir) const { return test(point, dir); }
    float fraction(Vec3 point, shading::LocalFrame f, Vec2 c, float h) const {
        return shading::shape_visible_fraction(kind, point, f, c, h, lo, hi);
    }
};

}  // namespace

TEST_CASE("A rectangle's whole-square answer is always the taps' own", "[render][shape]") {
    const Vec2 half_extent(3.0f, 2.0f);
    const Vec3 hi(half_extent, 0.0f);
    auto test = [&](Vec3 p, Vec3 d) { return shading::planar_blocks(p, d, half_extent); };
    const ShapeBlocks<decltype(test)> blocks{shading::kShapeRectangle, -hi, hi, test};
    const WholeSquareCount count = check_whole_square(
        4242, -hi, hi, [&](Vec3 p, shading::SquareDirections d) { return shading::rectangle_decides_square(p, d, half_extent); },
        blocks);
    INFO(count.decided << " of " << count.checked << " decided whole, " << count.shadowed << " of them shadowed");
    CHECK(count.decided > count.checked / 4);
    CHECK(count.shadowed > count.decided / 10);
}

TEST_CASE("A box's whole-square answer is always the taps' own", "[render][shape]") {
    const Vec3 lo(-0.6f, -0.4f, -0.5f), hi(0.6f, 0.4f, 0.5f);
    auto test = [&](Vec3 p, Vec3 d) { return shading::box_blocks(p, d, lo, hi); };
    const ShapeBlocks<decltype(test)> blocks{shading::kShapeBox, lo, hi, test};
    const WholeSquareCount count = check_whole_square(
        777, lo, hi, [&](Vec3 p, shading::SquareDirections d) { return shading::box_decides_square(p, d, lo, hi); },
        blocks);
    INFO(count.decided << " of " << count.checked << " decided whole, " << count.shadowed << " of them shadowed");
    CHECK(count.decided > count.checked / 4);
    CHECK(count.shadowed > count.decided / 20);
}

}  // namespace rsl

namespace rsl {

// The yard's common case: a receiver facing up, above the ground, with a
// light's square across its horizon. Every tap above the horizon points up,
// and the whole-square test must see it without casting them (bounded at the
// horizon itself, its margin reached "down" and sent every such query to the taps).
TEST_CASE("An upward-facing receiver's squares across its horizon are decided whole", "[render][shape]") {
    const Vec3 hi(3.0f, 2.0f, 0.0f);
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    int decided = 0, cases = 0;
    for (int n = 0; n < 2000; ++n) {
        const Vec2 tangent_angles = test::random_vec2(uniform, rng);
        const Frame frame = Frame::from_normal_tangent(Vec3(0, 0, 1), Vec3(std::cos(6.3f * tangent_angles.x), std::sin(6.3f * tangent_angles.y), 0));
        shading::LocalFrame f;
        f.x = frame.x, f.y = frame.y, f.z = frame.z;
        const float angle = 6.2832f * uniform(rng);
        const float h = 0.05f + 0.3f * uniform(rng);
        const Vec2 c = (1.0f - 0.5f * h) * Vec2(std::cos(angle), std::sin(angle));  // across the horizon
        const Vec3 point(0.5f, -0.3f, 0.05f + uniform(rng));
        ++cases;
        const float answer = shading::shape_visible_fraction(shading::kShapeRectangle, point, f, c, h, -hi, hi);
        CHECK(answer == 1.0f);
        float reach2 = 0.0f;
        for (int i = 0; i < shading::kShadowTaps; ++i) {
            const Vec2 tap = shading::shadow_tap_point(c, h, i);
            if (glm::dot(tap, tap) < 1.0f) reach2 = std::max(reach2, glm::dot(tap, tap));
        }
        decided += shading::rectangle_decides_square(point, shading::square_directions(f, c, h, reach2), Vec2(hi)) == 1.0f;
    }
    INFO(decided << " of " << cases << " decided whole");
    CHECK(decided > cases * 9 / 10);
}

}  // namespace rsl
