// Meshes: OBJ parsing and its errors, degenerate triangles, normals, tangents.
#include <catch2/catch.hpp>

#include <fstream>
#include <random>

#include <unistd.h>

#include "src/core/error.h"
#include "src/core/mesh.h"
#include "src/core/scene.h"
#include "src/formats/obj_loader.h"
#include "src/formats/scene_file.h"
#include "tests/test_support.h"

using namespace rsl;

namespace {

std::filesystem::path temp_dir() { return test::scratch_dir("mesh"); }

std::filesystem::path write_file(const std::string& name, const std::string& text) {
    const auto path = temp_dir() / name;
    test::write_text(path, text);
    return path;
}

// Expects load_obj to throw an rsl::Error whose message names the file and contains `fragment`.
void require_obj_error(const std::string& name, const std::string& text, const std::string& fragment) {
    const auto path = write_file(name, text);
    try {
        load_obj(path);
        FAIL("no error for " << name);
    } catch (const Error& e) {
        const std::string message = e.what();
        INFO(message);
        CHECK(message.find(path.string()) != std::string::npos);
        CHECK(message.find(fragment) != std::string::npos);
    }
}

// UV sphere of radius r around c with outward (counter-clockwise seen from outside) winding, no normals.
TriangleMesh uv_sphere(int stacks, int slices, float r = 1.0f, Vec3 c = Vec3(0)) {
    TriangleMesh m;
    m.positions.push_back(c + Vec3(0, r, 0));
    for (int i = 1; i < stacks; ++i) {
        const float theta = kPi * i / stacks;
        for (int j = 0; j < slices; ++j) {
            const float phi = 2 * kPi * j / slices;
            m.positions.push_back(c + r * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
        }
    }
    m.positions.push_back(c + Vec3(0, -r, 0));
    const uint32_t south = uint32_t(m.positions.size() - 1);
    auto ring = [&](int i, int j) { return uint32_t(1 + (i - 1) * slices + (j % slices)); };
    for (int j = 0; j < slices; ++j) {
        m.indices.insert(m.indices.end(), {0, ring(1, j + 1), ring(1, j)});
        m.indices.insert(m.indices.end(), {south, ring(stacks - 1, j), ring(stacks - 1, j + 1)});
    }
    for (int i = 1; i + 1 < stacks; ++i)
        for (int j = 0; j < slices; ++j) {
            m.indices.insert(m.indices.end(), {ring(i, j), ring(i, j + 1), ring(i + 1, j + 1)});
            m.indices.insert(m.indices.end(), {ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)});
        }
    return m;
}

}  // namespace

TEST_CASE("OBJ faces in every syntax share vertices unless normals differ", "[mesh][obj]") {
    const auto path = write_file("variants.obj",
                                 "# a unit quad and a triangle\n"
                                 "o quad\n"
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                 "vt 0 0\nvt 1 0\n"
                                 "vn 0 0 1\nvn 0 0 2\n"
                                 "f 1 2 3 4\n"              // plain quad: fan → 2 triangles
                                 "f 1/1 2/2 3/1\n"          // v/t: the same 3 vertices again
                                 "f 1//1 2//1 3//2\n"       // v//n: new vertices (normal given)
                                 "f -4/1/1 -3/2/1 -1/1/1\n"  // negative indices: 1, 2, 4 with normal 1
                                 "g ignored\ns 1\nusemtl x\n");
    const TriangleMesh m = load_obj(path);
    CHECK(m.name == "quad");
    CHECK(m.triangle_count() == 5);
    // (pos, normal) pairs: 1-4 without normal; (1,1) (2,1) (3,2) (4,1) with normals.
    CHECK(m.vertex_count() == 8);
    const std::vector<uint32_t> first{0, 1, 2, 0, 2, 3};
    CHECK(std::vector<uint32_t>(m.indices.begin(), m.indices.begin() + 6) == first);
    CHECK(m.indices[6] == 0);  // "f 1/1 2/2 3/1" reuses the plain vertices
    CHECK(m.indices[7] == 1);
    CHECK(m.indices[8] == 2);
    // Given normals are renormalized; missing ones are computed (+z for this flat mesh).
    for (const Vec3& n : m.normals) CHECK(glm::length(n - Vec3(0, 0, 1)) < 1e-6f);
    CHECK(m.positions[m.indices[14]] == Vec3(0, 1, 0));  // -1 → the 4th (latest) vertex
    CHECK(m.degenerate_dropped == 0);
}

TEST_CASE("OBJ errors name the file, the line and the problem", "[mesh][obj]") {
    require_obj_error("bad_number.obj", "v 0 0 0\nv 1 abc 0\nv 0 1 0\nf 1 2 3\n", "line 2: 'abc' is not a number");
    require_obj_error("few_coords.obj", "v 0 0\n", "line 1: a vertex needs 3 coordinates");
    require_obj_error("nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n", "line 3: coordinate 'nan' is not finite");
    require_obj_error("inf.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n", "line 2: coordinate 'inf' is not finite");
    require_obj_error("out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
                      "line 4: vertex index 4 is out of range (3 defined so far)");
    require_obj_error("negative_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "vertex index -4 is out of range");
    require_obj_error("zero_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "vertex index 0 is out of range");
    require_obj_error("normal_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//1\n",
                      "normal index 2 is out of range");
    require_obj_error("two_corners.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "a face needs at least 3 vertices");
    require_obj_error("empty.obj", "# nothing\nv 0 0 0\n", "empty mesh");
    require_obj_error("all_degenerate.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n",
                      "no triangles (2 degenerate triangles dropped)");
    require_obj_error("binary.obj", std::string("v 0 0 0\0\x01\x02", 10), "NUL");
    CHECK_THROWS_WITH(load_obj(temp_dir() / "does_not_exist.obj"), Catch::Contains("does_not_exist.obj: does not exist"));
}

TEST_CASE("A triangle is degenerate by its own edges, not the mesh's size: a 1 m box beside a 1e6 m triangle keeps "
          "its faces", "[mesh][obj]") {
    // Issue 56: the threshold was relative to the mesh's bounds, so the box's 12 triangles were dropped.
    const auto path = write_file("box_and_huge_triangle.obj",
                                 std::string(test::kUnitBoxObj) + "v -1e6 0 -1e6\nv 1e6 0 -1e6\nv 0 0 1e6\nf -3 -2 -1\n");
    test::WarningCapture warnings;
    const TriangleMesh m = load_obj(path);
    CHECK(m.triangle_count() == 13);
    CHECK(m.degenerate_dropped == 0);
    CHECK(warnings.messages().empty());
    // Tiny triangles far from the origin are as good as large ones; slivers at float noise level are not.
    TriangleMesh small;
    small.positions = {{1e-6f, 0, 0}, {2e-6f, 0, 0}, {1e-6f, 1e-6f, 0}, {0, 0, 0}, {1, 0, 0}, {2, 1e-14f, 0}};
    small.indices = {0, 1, 2, 3, 4, 5};
    CHECK(small.count_degenerate_triangles() == 1);
    // An area too small for a normal (its squared doubled area underflows) is degenerate.
    TriangleMesh underflow;
    underflow.positions = {{0, 0, 0}, {1e-20f, 0, 0}, {0, 1e-20f, 0}};
    underflow.indices = {0, 1, 2};
    CHECK(underflow.count_degenerate_triangles() == 1);
}

TEST_CASE("Loading a mesh with degenerate triangles warns once, naming the file and the count", "[mesh][obj]") {
    // A unit quad plus three degenerate triangles (collinear, repeated index, a point).
    const auto path = write_file("some_degenerate.obj",
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 2 0\n"
                                 "f 1 2 3\nf 1 3 4\nf 1 3 5\nf 2 2 3\nf 4 4 4\n");
    {
        test::WarningCapture warnings;
        const TriangleMesh m = load_obj(path);
        CHECK(m.triangle_count() == 2);
        REQUIRE(warnings.messages().size() == 1);
        CHECK(warnings.messages()[0] == path.string() + ": 3 degenerate triangles dropped");
    }
    {
        test::WarningCapture warnings;  // through load_scene too (a bare .obj scene)
        const Scene scene = load_scene(path);
        REQUIRE(warnings.messages().size() == 1);
        CHECK(warnings.messages()[0] == path.string() + ": 3 degenerate triangles dropped");
    }
    {
        test::WarningCapture warnings;  // a clean mesh says nothing
        load_obj(write_file("clean.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
        CHECK(warnings.messages().empty());
    }
}

TEST_CASE("Degenerate triangles are dropped and counted", "[mesh]") {
    TriangleMesh m;
    m.name = "test";
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 2, 0}, {5, 5, 5}};  // vertex 5: only in a bad triangle
    m.indices = {0, 1, 2,   // good
                 1, 3, 2,   // good
                 0, 3, 4,   // collinear: zero area
                 2, 2, 1,   // repeated index
                 5, 5, 5};  // a point
    CHECK(m.count_degenerate_triangles() == 3);
    const size_t dropped = validate_and_complete(m, "test.obj");
    CHECK(dropped == 3);
    CHECK(m.degenerate_dropped == 3);
    CHECK(m.triangle_count() == 2);
    CHECK(m.count_degenerate_triangles() == 0);
    CHECK(m.vertex_count() == 4);  // vertices 4 and 5 are no longer used
    CHECK(m.normals.size() == 4);
    CHECK(m.tangents.size() == 4);
    for (uint32_t i : m.indices) CHECK(i < 4);

    TriangleMesh bad;
    bad.name = "bad";
    bad.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    bad.indices = {0, 1, 3};
    CHECK_THROWS_WITH(validate_and_complete(bad, "bad.gltf"), Catch::Contains("bad.gltf") && Catch::Contains("out of range"));
    bad.indices = {0, 1, 2};
    bad.positions[1].y = std::numeric_limits<float>::infinity();
    CHECK_THROWS_WITH(validate_and_complete(bad, "bad.gltf"), Catch::Contains("bad.gltf") && Catch::Contains("non-finite"));
}

TEST_CASE("Bounds and bounding sphere", "[mesh]") {
    TriangleMesh m;
    m.positions = {{-1, 0, 2}, {3, 1, 2}, {1, 5, -2}};
    m.indices = {0, 1, 2};
    const Bounds b = m.bounds();
    CHECK(b.lo == Vec3(-1, 0, -2));
    CHECK(b.hi == Vec3(3, 5, 2));
    const BoundingSphere s = m.bounding_sphere();
    CHECK(s.center == Vec3(1, 2.5f, 0));
    // The farthest vertex from (1, 2.5, 0): (1, 5, -2) at √(6.25 + 4) or (−1, 0, 2) at √(4 + 6.25 + 4).
    CHECK(s.radius == Approx(std::sqrt(14.25f)));
}

TEST_CASE("Area-weighted normals: a fold and a sphere", "[mesh]") {
    // Two triangles sharing edge (0, 1): one in the xy-plane (area 1/2, normal +z),
    // one in the xz-plane below it (area 2, normal +y).
    TriangleMesh fold;
    fold.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, -4}};
    fold.indices = {0, 1, 2, 0, 1, 3};
    compute_normals(fold);
    const Vec3 expected = glm::normalize(0.5f * Vec3(0, 0, 1) + 2.0f * Vec3(0, 1, 0));
    CHECK(glm::length(fold.normals[0] - expected) < 1e-6f);
    CHECK(glm::length(fold.normals[1] - expected) < 1e-6f);
    CHECK(glm::length(fold.normals[2] - Vec3(0, 0, 1)) < 1e-6f);
    CHECK(glm::length(fold.normals[3] - Vec3(0, 1, 0)) < 1e-6f);

    // On a sphere the computed normals must point outward, close to the analytic (p − c)/r.
    const Vec3 center(0.3f, -2, 1);
    TriangleMesh sphere = uv_sphere(48, 96, 2.0f, center);
    validate_and_complete(sphere, "sphere");
    double worst = 0;
    for (size_t v = 0; v < sphere.vertex_count(); ++v) {
        const Vec3 analytic = glm::normalize(sphere.positions[v] - center);
        worst = std::max(worst, double(glm::length(sphere.normals[v] - analytic)));
        REQUIRE(glm::dot(sphere.normals[v], analytic) > 0.99f);
    }
    CHECK(worst < 0.02);
}

TEST_CASE("Tangents are unit, orthogonal to the normal and smooth", "[mesh]") {
    TriangleMesh sphere = uv_sphere(40, 80);
    validate_and_complete(sphere, "sphere");
    REQUIRE(sphere.tangents.size() == sphere.vertex_count());
    for (size_t v = 0; v < sphere.vertex_count(); ++v) {
        const Vec3 t(sphere.tangents[v]);
        REQUIRE(std::abs(glm::length(t) - 1) < 1e-5f);
        REQUIRE(std::abs(glm::dot(t, sphere.normals[v])) < 1e-5f);
        REQUIRE(std::abs(sphere.tangents[v].w) == 1.0f);
    }
    // Smoothness: away from the two polar caps of the field (normals near ±X),
    // neighbouring tangents differ by at most a few times their normals
    // (|d t| ≤ 2 |d n| / √(1 − n_x²) ≤ 6.4 |d n| for this field).
    size_t edges = 0;
    for (size_t tri = 0; tri < sphere.triangle_count(); ++tri)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = sphere.indices[3 * tri + k], b = sphere.indices[3 * tri + (k + 1) % 3];
            const Vec3 na = sphere.normals[a], nb = sphere.normals[b];
            if (std::abs(na.x) > 0.95f || std::abs(nb.x) > 0.95f) continue;
            const float dt = glm::length(Vec3(sphere.tangents[a]) - Vec3(sphere.tangents[b]));
            REQUIRE(dt <= 8 * glm::length(na - nb) + 1e-5f);
            ++edges;
        }
    CHECK(edges > sphere.triangle_count());

    // Given tangents are kept but made orthogonal to the normal; zero ones are replaced.
    TriangleMesh quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    quad.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    quad.tangents = {{1, 1, 1, -1}, {0, 1, 0, 1}, {0, 0, 0, 1}, {0, 0, 3, 1}};
    validate_and_complete(quad, "quad");
    CHECK(glm::length(Vec3(quad.tangents[0]) - glm::normalize(Vec3(1, 1, 0))) < 1e-6f);
    CHECK(quad.tangents[0].w == -1.0f);
    CHECK(glm::length(Vec3(quad.tangents[1]) - Vec3(0, 1, 0)) < 1e-6f);
    CHECK(glm::length(Vec3(quad.tangents[2]) - Vec3(1, 0, 0)) < 1e-6f);  // the mesh-wide rule: X projected
    CHECK(glm::length(Vec3(quad.tangents[3]) - Vec3(1, 0, 0)) < 1e-6f);  // parallel to n: replaced
}

TEST_CASE("OBJ meshes from the shared assets load cleanly", "[mesh][obj][assets]") {
    const std::filesystem::path dir = std::filesystem::path(RSL_SHARED_ASSETS) / "meshes";
    if (!std::filesystem::exists(dir / "suzanne.obj")) {
        WARN("SKIPPED: " << dir << " is absent");
        return;
    }
    const TriangleMesh m = load_obj(dir / "suzanne.obj");
    CHECK(m.vertex_count() > 400);
    CHECK(m.triangle_count() > 900);
    CHECK(m.count_degenerate_triangles() == 0);
    for (size_t v = 0; v < m.vertex_count(); ++v) REQUIRE(std::abs(glm::length(m.normals[v]) - 1) < 1e-5f);
}
