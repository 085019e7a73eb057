// Material library: sharing, swapping, live editing, validation.
#include <catch2/catch.hpp>

#include "src/brdf/material_library.h"
#include "src/core/error.h"
#include "tests/brdf/brdf_test_util.h"

using namespace rsl;
using namespace rsl::test;

namespace {
MaterialDesc named(std::string name, MaterialDesc m) {
    m.name = std::move(name);
    return m;
}
MaterialDesc steel() { return named("steel", material("phong", {{"kd", {0.1f}}, {"ks", {0.6f}}, {"exponent", {60}}})); }
MaterialDesc floor_() { return named("floor", material("lambert", {{"albedo", {0.5f}}})); }
MaterialDesc chrome() { return named("chrome", material("phong", {{"kd", {0.1f}}, {"ks", {0.6f}}, {"exponent", {60}}})); }
float center_value(const BrdfTable& t) { return t.square_average(Vec2(0, -0.3f), 0.1f, Vec3(0, 0.5f, 0.866f)).g; }
}  // namespace

TEST_CASE("identical materials share one table, parts can swap materials", "[brdf][library]") {
    BrdfTableOptions small;
    small.view_samples = 8;
    MaterialLibrary lib(small);
    const int s = lib.add(steel()), f = lib.add(floor_()), c = lib.add(chrome());
    CHECK(lib.find("chrome") == c);
    CHECK(lib.find("gold") == -1);
    CHECK(lib.table(s) == lib.table(c));  // same model and parameters, different names
    CHECK(lib.table(s) != lib.table(f));
    CHECK(lib.distinct_table_count() == 2);

    lib.resize_parts(3, f);
    lib.assign(1, s);
    CHECK(&lib.part_table(0) == lib.table(f).get());
    CHECK(&lib.part_table(1) == lib.table(s).get());
    lib.assign(1, f);  // swap at run time
    CHECK(&lib.part_table(1) == lib.table(f).get());
    CHECK_THROWS_AS(lib.assign(5, f), Error);
    CHECK_THROWS_AS(lib.assign(0, 9), Error);
}

TEST_CASE("editing a parameter rebuilds only that material's table", "[brdf][library]") {
    BrdfTableOptions small;
    small.view_samples = 8;
    MaterialLibrary lib(small);
    const int s = lib.add(steel()), c = lib.add(chrome());
    auto before = lib.table(s);
    const uint64_t rev_s = lib.revision(s), rev_c = lib.revision(c);
    const float glossy_before = center_value(*before);

    lib.set_parameter(s, "exponent", {5});
    CHECK(lib.table(s) != before);
    CHECK(lib.table(c) == before);  // the material that shared it keeps the old table
    CHECK(lib.revision(s) > rev_s);
    CHECK(lib.revision(c) == rev_c);
    CHECK(lib.desc(s).name == "steel");
    CHECK(lib.desc(s).params.at("exponent")[0] == 5.0f);
    CHECK(center_value(*lib.table(s)) != Approx(glossy_before).epsilon(0.05));
    // The rebuilt table is the table of the edited material, built from scratch.
    MaterialDesc expected = steel();
    expected.params["exponent"] = {5};
    auto fresh = BrdfTable::build(*make_brdf(expected), small);
    CHECK(center_value(*lib.table(s)) == center_value(*fresh));

    // Editing it back shares the existing table again, without a rebuild.
    lib.set_parameter(s, "exponent", {60});
    CHECK(lib.table(s) == lib.table(c));
    CHECK(lib.last_build_seconds() == 0.0);
    CHECK(lib.distinct_table_count() == 1);

    // Swapping the model (isotropic → anisotropic) changes the table's layout.
    MaterialDesc brushed = material("ward_anisotropic", {{"ks", {0.7f}}, {"alpha_x", {0.1f}}, {"alpha_y", {0.3f}}});
    lib.replace(c, brushed);
    CHECK_FALSE(lib.table(c)->isotropic());
    CHECK(lib.table(c)->slice_count() == 64);
    CHECK(lib.desc(c).name == "chrome");
}

TEST_CASE("invalid edits throw and leave the material unchanged", "[brdf][library]") {
    BrdfTableOptions small;
    small.view_samples = 4;
    MaterialLibrary lib(small);
    const int s = lib.add(steel());
    auto table = lib.table(s);
    const uint64_t rev = lib.revision(s);
    try {
        lib.set_parameter(s, "ks", {0.95f});  // kd + ks > 1
        FAIL("no error");
    } catch (const Error& e) {
        CHECK(std::string(e.what()).find("steel") != std::string::npos);
    }
    CHECK_THROWS_WITH(lib.set_parameter(s, "exponent", {-3}), Catch::Contains("exponent"));
    CHECK(lib.table(s) == table);
    CHECK(lib.revision(s) == rev);
    CHECK(lib.desc(s).params.at("ks")[0] == 0.6f);
}

TEST_CASE("a library from a scene follows part_materials", "[brdf][library]") {
    Scene scene;
    scene.materials = {floor_(), steel(), chrome()};
    scene.parts.resize(4);
    scene.parts[0].material = 0, scene.parts[1].material = 1, scene.parts[2].material = 2, scene.parts[3].material = 1;
    BrdfTableOptions small;
    small.view_samples = 4;
    MaterialLibrary lib = MaterialLibrary::from_scene(scene, small);
    CHECK(lib.material_count() == 3);
    CHECK(lib.part_count() == 4);
    CHECK(lib.part_material(3) == 1);
    CHECK(&lib.part_table(1) == &lib.part_table(2));  // steel and chrome are identical
    CHECK(lib.distinct_table_count() == 2);
}
