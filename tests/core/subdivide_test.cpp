// Subdivision at load: long edges split to a target, watertight, creases and
// attributes kept; the scene file's switch and `rsl info`'s counts.
#include <catch2/catch.hpp>

#include <map>
#include <random>

#include "src/core/scene.h"
#include "src/core/subdivide.h"
#include "src/formats/scene_file.h"
#include "tests/test_support.h"
#include "tests/trace/trace_test_scenes.h"
#include "tests/random_cases.h"

using namespace rsl;

namespace {

Vec3 corner(const TriangleMesh& m, size_t t, int k) { return m.positions[m.indices[3 * t + size_t(k)]]; }
Vec3 area_vector(const TriangleMesh& m, size_t t) {
    return 0.5f * glm::cross(corner(m, t, 1) - corner(m, t, 0), corner(m, t, 2) - corner(m, t, 0));
}
double total_area(const TriangleMesh& m) {
    double area = 0;
    for (size_t t = 0; t < m.triangle_count(); ++t) area += glm::length(area_vector(m, t));
    return area;
}
float longest_edge(const TriangleMesh& m) {
    float longest = 0;
    for (size_t t = 0; t < m.triangle_count(); ++t)
        for (int k = 0; k < 3; ++k) longest = std::max(longest, glm::distance(corner(m, t, k), corner(m, t, (k + 1) % 3)));
    return longest;
}

// Brute-force watertightness: vertices welded by exact position, every welded
// directed edge must be met by its reverse exactly once. A T-junction (a
// vertex on one side of an edge and not on the other) or a crack leaves an
// edge without its twin.
size_t unmatched_edges(const TriangleMesh& m) {
    std::map<std::tuple<float, float, float>, int> id;
    auto weld = [&](const Vec3& p) { return id.try_emplace({p.x, p.y, p.z}, int(id.size())).first->second; };
    std::map<std::pair<int, int>, int> directed;
    for (size_t t = 0; t < m.triangle_count(); ++t)
        for (int k = 0; k < 3; ++k) ++directed[{weld(corner(m, t, k)), weld(corner(m, t, (k + 1) % 3))}];
    size_t unmatched = 0;
    for (const auto& [edge, count] : directed) {
        const auto twin = directed.find({edge.second, edge.first});
        if (count != 1 || twin == directed.end() || twin->second != 1) ++unmatched;
    }
    return unmatched;
}

TEST_CASE("subdivision: a flat-shaded box is split to the target, watertight, creases kept", "[core][subdivide]") {
    TriangleMesh box = test::make_flat_box(Vec3(0.5f, 0.3f, 0.8f), 2);
    REQUIRE(unmatched_edges(box) == 0);
    const double area = total_area(box);
    const size_t before = box.vertex_count();
    const float target = 0.13f;
    const size_t added = subdivide_long_edges(box, target, "box.obj");

    CHECK(added == box.vertex_count() - before);
    CHECK(added > 10 * before);
    CHECK(longest_edge(box) <= target);
    CHECK(unmatched_edges(box) == 0);
    CHECK(total_area(box) == Approx(area).epsilon(1e-5));
    // Creases: every vertex keeps its face's normal, which is each of its triangles' normal.
    for (size_t t = 0; t < box.triangle_count(); ++t) {
        const Vec3 face = glm::normalize(area_vector(box, t));
        for (int k = 0; k < 3; ++k) CHECK(glm::dot(box.normals[box.indices[3 * t + size_t(k)]], face) > 0.99999f);
    }
    // Attributes: the per-face uv is affine in position, so its interpolation is exact.
    for (size_t v = 0; v < box.vertex_count(); ++v) {
        const Vec3 n = box.normals[v];
        const int axis = std::abs(n.x) > 0.5f ? 0 : std::abs(n.y) > 0.5f ? 1 : 2;
        const Vec3 h(0.5f, 0.3f, 0.8f);
        const float u = 0.5f * (box.positions[v][(axis + 1) % 3] / h[(axis + 1) % 3] + 1);
        const float w = 0.5f * (n[axis] * box.positions[v][(axis + 2) % 3] / h[(axis + 2) % 3] + 1);
        CHECK(box.texcoords[v].x == Approx(u).margin(1e-5));
        CHECK(box.texcoords[v].y == Approx(w).margin(1e-5));
        CHECK(Vec3(box.tangents[v])[(axis + 1) % 3] == Approx(1.0f));
        CHECK(box.tangents[v].w == 1.0f);
    }
}

TEST_CASE("subdivision: random closed meshes and targets (property test)", "[core][subdivide]") {
    std::mt19937 rng(16);
    std::uniform_real_distribution<float> jitter(0.6f, 1.4f), targets(0.05f, 0.6f);
    for (int trial = 0; trial < 40; ++trial) {
        // A lumpy icosahedron (smooth: shared vertices) with random tangents' handedness.
        TriangleMesh mesh = test::make_icosphere(1.0f, trial % 2);
        for (Vec3& p : mesh.positions) p *= test::random_vec3(jitter, rng);
        for (Vec4& t : mesh.tangents) t.w = jitter(rng) < 1 ? -1.0f : 1.0f;
        const TriangleMesh original = mesh;
        const float target = targets(rng);
        INFO("trial " << trial << ", target " << target);
        subdivide_long_edges(mesh, target, "lumpy.obj");

        CHECK(longest_edge(mesh) <= target);
        CHECK(unmatched_edges(mesh) == 0);
        CHECK(total_area(mesh) == Approx(total_area(original)).epsilon(1e-5));
        // The loaded vertices are kept as they were, in front.
        for (size_t v = 0; v < original.vertex_count(); ++v) CHECK(mesh.positions[v] == original.positions[v]);
        // Still closed (its area vectors sum to 0); new vertices have unit
        // normals and unit tangents ⟂ normal.
        Vec3 area_sum(0);
        for (size_t t = 0; t < mesh.triangle_count(); ++t) area_sum += area_vector(mesh, t);
        CHECK(glm::length(area_sum) < 1e-4f);
        for (size_t v = original.vertex_count(); v < mesh.vertex_count(); ++v) {
            CHECK(glm::length(mesh.normals[v]) == Approx(1.0f).epsilon(1e-5));
            CHECK(glm::length(Vec3(mesh.tangents[v])) == Approx(1.0f).epsilon(1e-5));
            CHECK(std::abs(glm::dot(Vec3(mesh.tangents[v]), mesh.normals[v])) < 1e-5f);
            CHECK(std::abs(mesh.tangents[v].w) == 1.0f);
        }
    }
}

TEST_CASE("subdivision: a midpoint takes the mean of its edge's attributes", "[core][subdivide]") {
    TriangleMesh tri;
    tri.positions = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0.5f, 0)};
    tri.normals = {glm::normalize(Vec3(0, 0, 1)), glm::normalize(Vec3(1, 0, 1)), Vec3(0, 0, 1)};
    tri.tangents = {Vec4(1, 0, 0, -1), Vec4(1, 0, 0, -1), Vec4(1, 0, 0, -1)};
    tri.texcoords = {Vec2(0, 0), Vec2(1, 0.5f), Vec2(0, 1)};
    tri.indices = {0, 1, 2};
    subdivide_long_edges(tri, 1.5f, "");
    // Only the edge 0–1 (length 2; the others 1.12) is over 1.5, so one vertex is added: 1 → 2 triangles.
    REQUIRE(tri.vertex_count() == 4);
    REQUIRE(tri.triangle_count() == 2);
    CHECK(tri.positions[3] == Vec3(1, 0, 0));
    CHECK(tri.texcoords[3] == Vec2(0.5f, 0.25f));
    const Vec3 n = glm::normalize(tri.normals[0] + tri.normals[1]);
    CHECK(glm::distance(tri.normals[3], n) < 1e-6f);
    CHECK(glm::length(Vec3(tri.tangents[3])) == Approx(1.0f));
    CHECK(std::abs(glm::dot(Vec3(tri.tangents[3]), n)) < 1e-6f);
    CHECK(tri.tangents[3].w == -1.0f);
    // Nothing to do: nothing changes.
    TriangleMesh short_edges = tri;
    CHECK(subdivide_long_edges(short_edges, 10.0f, "") == 0);
    CHECK(short_edges.indices == tri.indices);
}

TEST_CASE("subdivision: an absurd target is an error naming the file", "[core][subdivide]") {
    TriangleMesh box = test::make_flat_box(Vec3(50.0f), 1);
    const std::string message = test::error_of([&] { subdivide_long_edges(box, 1e-4f, "huge.obj"); });
    CHECK(message.find("huge.obj") != std::string::npos);
    CHECK(message.find("subdivision") != std::string::npos);
}

TEST_CASE("subdivision: the scene file's setting, its default (on) and its switches", "[core][subdivide]") {
    const auto dir = test::scratch_dir("subdivide_scene");
    test::write_text(dir / "box.obj", test::kUnitBoxObj);
    test::write_text(dir / "none.hdr", "");  // load_scene checks that it exists; the renderers read it
    auto scene_with = [&](const std::string& setting) {
        const auto path = dir / "scene.json";
        test::write_text(path, R"({"parts": [{"obj": "box.obj"}], "environment": {"file": "none.hdr"})" +
                                   (setting.empty() ? std::string() : ", \"subdivision\": " + setting) + "}");
        return path;
    };
    const Scene off = load_scene(scene_with("false"));
    CHECK(off.parts[0].loaded_vertices == 8);  // no `vn`: smooth normals, one vertex per corner
    CHECK(off.parts[0].mesh.vertex_count() == 8);
    const Scene by_default = load_scene(scene_with(""));  // on unless switched off (subdivide.h says why)
    CHECK(by_default.vertex_count() > 8);
    CHECK(load_scene(scene_with(R"({"enabled": false, "edge": 0.2})")).vertex_count() == 8);

    const Scene on = load_scene(scene_with("true"));
    CHECK(by_default.vertex_count() == on.vertex_count());
    const TriangleMesh& mesh = on.parts[0].mesh;
    CHECK(on.parts[0].loaded_vertices == 8);
    const float target = SubdivisionSettings{}.relative_edge * mesh.bounding_sphere().radius;
    CHECK(longest_edge(mesh) <= target);
    CHECK(longest_edge(mesh) > 0.5f * target);
    CHECK(unmatched_edges(mesh) == 0);
    CHECK(total_area(mesh) == Approx(6.0).epsilon(1e-5));

    const Scene absolute = load_scene(scene_with(R"({"edge": 0.26})"));
    CHECK(longest_edge(absolute.parts[0].mesh) <= 0.26f);
    CHECK(longest_edge(absolute.parts[0].mesh) > 0.13f);
    CHECK(load_scene(scene_with(R"({"relative_edge": 0.5})")).vertex_count() < on.vertex_count());

    const std::string bad = test::error_of([&] { load_scene(scene_with(R"({"edge": -1})")); });
    CHECK(bad.find("scene.json") != std::string::npos);
    CHECK(bad.find("subdivision.edge") != std::string::npos);
    CHECK(test::error_of([&] { load_scene(scene_with(R"({"edges": 1})")); }).find("unknown key") != std::string::npos);
    for (const char* tiny : {R"({"relative_edge": 1e-40})", R"({"relative_edge": 1e-45})", R"({"edge": 1e-9})"}) {
        const std::string message = test::error_of([&] { load_scene(scene_with(tiny)); });
        INFO(tiny << ": " << message);
        CHECK(message.find("scene.json") != std::string::npos);
        CHECK(message.find("subdivision") != std::string::npos);
    }
    CHECK(test::error_of([&] { load_scene(scene_with(R"({"enabled": 1})")); }).find("subdivision.enabled") !=
          std::string::npos);
}

}  // namespace
