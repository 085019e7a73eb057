// The memory limit (src/core/memory_limit.h): sizes as users write them, and
// the load's refusal before the parts' subdivided meshes are copied; parts
// that instance one mesh are subdivided once, as each would be alone.
#include <catch2/catch.hpp>

#include "src/core/memory_limit.h"
#include "src/core/scene.h"
#include "src/core/subdivide.h"
#include "tests/test_support.h"

using namespace rsl;

namespace {

// Restores the process's limit when a test case ends.
struct LimitGuard {
    uint64_t previous = memory_limit();
    ~LimitGuard() { set_memory_limit(previous); }
};

TriangleMesh quad(float side) {
    TriangleMesh m;
    m.name = "quad";
    m.positions = {{0, 0, 0}, {side, 0, 0}, {side, 0, side}, {0, 0, side}};
    m.indices = {0, 2, 1, 0, 3, 2};
    compute_normals(m);
    compute_tangents(m);
    return m;
}

Scene scene_of(const std::vector<TriangleMesh>& meshes) {
    Scene scene;
    scene.source = "parts.json";
    scene.materials.emplace_back();
    for (size_t i = 0; i < meshes.size(); ++i) {
        Part part;
        part.name = "part" + std::to_string(i);
        part.mesh = meshes[i];
        part.mesh.name = part.name;
        part.material = 0;
        scene.parts.push_back(std::move(part));
    }
    return scene;
}

}  // namespace

TEST_CASE("memory sizes read as users write them; anything else names the flag", "[core][memory]") {
    CHECK(parse_memory_size("8G", "--memory-limit") == 8ull << 30);
    CHECK(parse_memory_size("512M", "--memory-limit") == 512ull << 20);
    CHECK(parse_memory_size("1.5GB", "--memory-limit") == 3ull << 29);
    CHECK(parse_memory_size("64K", "--memory-limit") == 64ull << 10);
    CHECK(parse_memory_size("123456", "--memory-limit") == 123456);
    CHECK(parse_memory_size("none", "--memory-limit") == 0);
    CHECK(parse_memory_size("0", "--memory-limit") == 0);
    for (const char* bad : {"", "G", "8X", "-1G", "nanG", "1e30T", "8G 2", "0.1"}) {
        INFO("'" << bad << "'");
        CHECK_THAT(test::error_of([&] { parse_memory_size(bad, "RSL_MEMORY_LIMIT"); }),
                   Catch::Contains("RSL_MEMORY_LIMIT") && Catch::Contains("not a memory size"));
    }
}

TEST_CASE("the default limit is most of this machine's memory", "[core][memory]") {
    const uint64_t limit = default_memory_limit();
    CHECK(limit > (256ull << 20));  // any machine that builds rsl
    CHECK(limit < (1ull << 50));
}

TEST_CASE("instanced parts are subdivided once, each equal to its mesh subdivided alone", "[core][memory][subdivide]") {
    const std::vector<TriangleMesh> meshes = {quad(4), quad(4), quad(2), quad(4), quad(2), quad(1)};
    Scene scene = scene_of(meshes);
    subdivide_scene_parts(scene);
    for (size_t i = 0; i < meshes.size(); ++i) {
        TriangleMesh alone = meshes[i];
        subdivide_for_shading(alone, scene.subdivision, scene.source);
        const TriangleMesh& got = scene.parts[i].mesh;
        INFO("part " << i << ": " << got.vertex_count() << " vertices, alone " << alone.vertex_count());
        CHECK(got.vertex_count() > meshes[i].vertex_count());
        CHECK(got.positions == alone.positions);
        CHECK(got.normals == alone.normals);
        CHECK(got.tangents == alone.tangents);
        CHECK(got.indices == alone.indices);
        CHECK(got.name == "part" + std::to_string(i));  // each part keeps its own name
        CHECK(scene.parts[i].loaded_vertices == 4);
    }
}

TEST_CASE("a scene whose subdivided parts pass the memory limit is refused before they are copied", "[core][memory]") {
    LimitGuard guard;
    TriangleMesh one = quad(1);
    subdivide_for_shading(one, SubdivisionSettings{}, "quad");
    const size_t per_part = one.vertex_count(), total = 200 * per_part;
    const uint64_t needed = kMeshBytesPerVertex * total + kMeshBytesPerPart * 200;
    REQUIRE(per_part > 100);

    Scene scene = scene_of(std::vector<TriangleMesh>(200, quad(1)));
    set_memory_limit(needed - 1);
    const std::string error = test::error_of([&] { subdivide_scene_parts(scene); });
    CHECK_THAT(error, Catch::Contains("parts.json") &&
                          Catch::Contains(fmt::format("{} vertices after subdivision in 200 parts", total)) &&
                          Catch::Contains("raise the limit with rsl::api::set_memory_limit or RSL_MEMORY_LIMIT"));
    CHECK(scene.parts[1].mesh.vertex_count() == 4);  // the instances were not copied
    set_memory_limit_setter("--memory-limit");  // as the program says it
    CHECK_THAT(test::error_of([&] { subdivide_scene_parts(scene); }),
               Catch::Contains("raise the limit with --memory-limit or RSL_MEMORY_LIMIT"));
    set_memory_limit_setter("rsl::api::set_memory_limit");

    Scene again = scene_of(std::vector<TriangleMesh>(200, quad(1)));
    set_memory_limit(needed);
    subdivide_scene_parts(again);
    CHECK(again.vertex_count() == total);
    set_memory_limit(0);  // none
    Scene unlimited = scene_of(std::vector<TriangleMesh>(200, quad(1)));
    subdivide_scene_parts(unlimited);
    CHECK(unlimited.vertex_count() == total);
}
