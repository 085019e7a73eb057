// The renderer's fields from the scene's field cache (src/fields/field_cache.h):
// the first load bakes and writes every field, the second reads them all back,
// and both shade exactly as fields baked in memory.
#include <catch2/catch.hpp>

#include <filesystem>

#include "src/render/cpu_renderer.h"
#include "tests/render/render_test_scenes.h"

namespace rsl {
namespace {

TEST_CASE("rendering loads fields from the cache and bakes only what is missing", "[render][cache]") {
    namespace fs = std::filesystem;
    const fs::path folder = fs::path(RSL_BINARY_DIR) / "render-field-cache-test";
    fs::remove_all(folder);
    fs::create_directories(folder);

    Scene scene = test::make_scene("cached", Color(0.6f));
    test::add_part(scene, test::make_plane(3.0f, 6, "ground"));
    Transform pose;
    pose.translation = Vec3(0, 0.4f, 0);
    test::add_part(scene, test::make_icosphere(0.3f, 2, "ball"), pose);
    scene.camera.position = Vec3(1, 3, 4);
    scene.source = folder / "cached.json";  // the cache lives beside it; the file itself is not read
    PrecomputeSettings& pre = scene.precompute;
    pre.svdf_resolution = 8, pre.svdf_clusters = 4, pre.svdf_vectors = 3, pre.svdf_supersampling = 1;
    pre.ovdf_shells = 3, pre.ovdf_cube_resolution = 4, pre.ovdf_vdt_resolution = 8, pre.ovdf_vectors = 3;

    FieldLoadReport first, second;
    const PartFields baked = load_part_fields(scene, FieldBakeOptions{}, &first);
    CHECK(first.baked == 4);  // SVDF and OVDF of both parts
    CHECK(first.loaded == 0);
    const PartFields loaded = load_part_fields(scene, FieldBakeOptions{}, &second);
    CHECK(second.baked == 0);
    CHECK(second.loaded == 4);
    CHECK(fs::exists(folder / ".rsl-cache"));

    // Changing a parameter selects other files: only that kind is baked again.
    scene.precompute.ovdf_shells = 4;
    FieldLoadReport third;
    load_part_fields(scene, FieldBakeOptions{}, &third);
    CHECK(third.baked == 2);
    CHECK(third.loaded == 2);
    scene.precompute.ovdf_shells = 3;

    Scene in_memory = scene;
    in_memory.source.clear();
    const PartFields reference = load_part_fields(in_memory, FieldBakeOptions{});

    const RslSet lights = test::single_rsl(glm::normalize(Vec3(0.3f, 1.0f, 0.2f)), 0.4f, Color(1.0f));
    RenderOptions options;
    CpuRenderer a(scene, lights, baked, options), b(scene, lights, loaded, options), c(scene, lights, reference, options);
    const VertexColors ca = a.shade(), cb = b.shade(), cc = c.shade();
    for (size_t p = 0; p < ca.parts.size(); ++p)
        for (size_t v = 0; v < ca.parts[p].size(); ++v) {
            REQUIRE(ca.parts[p][v].r == cb.parts[p][v].r);  // the file holds what was baked
            // Baking is deterministic: the in-memory fields equal the cached ones
            // up to the file's half-precision tables.
            REQUIRE(std::abs(ca.parts[p][v].g - cc.parts[p][v].g) <= 2e-3f * std::max(1.0f, cc.parts[p][v].g));
        }
    fs::remove_all(folder);
}

}  // namespace
}  // namespace rsl
