// Live material edits through the renderer interface (vertex_renderer.h): an
// edit rebuilds the edited material's table only, the parts of other
// materials keep theirs, and the next frame equals a renderer built on the
// edited scene.
#include <catch2/catch.hpp>

#include "src/core/error.h"
#include "src/render/cpu_renderer.h"
#include "tests/render/render_test_scenes.h"

namespace rsl {
namespace {

Scene three_balls() {
    Scene scene = test::make_scene("edits", Color(0.6f));  // material 0: Lambert
    MaterialDesc glossy;
    glossy.name = "glossy";
    glossy.model = "phong";
    glossy.params = {{"kd", {0.3f, 0.3f, 0.3f}}, {"ks", {0.4f, 0.4f, 0.4f}}, {"exponent", {20.0f}}};
    scene.materials.push_back(glossy);
    for (int i = 0; i < 3; ++i) {
        Transform pose;
        pose.translation = Vec3(1.2f * float(i - 1), 0.0f, 0.0f);
        test::add_part(scene, test::make_icosphere(0.4f, 2, "ball" + std::to_string(i)), pose, i == 1 ? 1 : 0);
    }
    scene.camera.position = Vec3(0.0f, 1.0f, 3.0f);
    scene.camera.target = Vec3(0.0f);
    return scene;
}

TEST_CASE("a material edit rebuilds its own table only and shades like a fresh renderer", "[render][materials]") {
    const Scene scene = three_balls();
    const RslSet lights = test::random_rsls(12, 9);
    CpuRenderer renderer(scene, lights, PartFields{}, RenderOptions{});
    VertexRenderer& r = renderer;
    const BrdfTable* before[3];
    for (int p = 0; p < 3; ++p) before[p] = &r.materials().part_table(p);
    CHECK(before[0] == before[2]);  // one table per material, shared by its parts
    const uint64_t lambert_revision = r.materials().revision(0);

    r.set_material_parameter("glossy", "exponent", {60.0f});
    CHECK(r.materials().last_build_seconds() > 0.0);
    CHECK(&r.materials().part_table(0) == before[0]);
    CHECK(&r.materials().part_table(2) == before[2]);
    CHECK(&r.materials().part_table(1) != before[1]);
    CHECK(r.materials().revision(0) == lambert_revision);

    Scene edited = scene;
    edited.materials[1].params["exponent"] = {60.0f};
    CpuRenderer fresh(edited, lights, PartFields{}, RenderOptions{});
    for (float t : {0.0f, 0.5f}) {
        r.set_time(t);
        fresh.set_time(t);
        const VertexColors a = r.shade(), b = fresh.shade();
        for (size_t p = 0; p < a.parts.size(); ++p) CHECK(a.parts[p] == b.parts[p]);
    }

    // Swapping a part onto another material: the same colours as the override option.
    r.set_part_material("ball0", "glossy");
    RenderOptions swapped;
    swapped.material_override["ball0"] = "glossy";
    CpuRenderer by_option(edited, lights, PartFields{}, swapped);
    const VertexColors a = r.shade(), b = by_option.shade();
    CHECK(a.parts[0] == b.parts[0]);

    // Refused edits name what is wrong and change nothing.
    CHECK_THROWS_WITH(r.set_material_parameter("glossy", "exponent", {-3.0f}), Catch::Contains("exponent"));
    CHECK_THROWS_WITH(r.set_material_parameter("nope", "exponent", {3.0f}), Catch::Contains("nope"));
    CHECK_THROWS_WITH(r.set_part_material("ball9", "glossy"), Catch::Contains("ball9"));
    CHECK_THROWS_AS(CpuRenderer(scene, lights, PartFields{}, [] {
                        RenderOptions o;
                        o.material_override["ball1"] = "missing";
                        return o;
                    }()),
                    Error);
    CHECK(r.shade().parts[0] == a.parts[0]);
}

}  // namespace
}  // namespace rsl
