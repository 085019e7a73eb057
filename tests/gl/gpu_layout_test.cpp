// The GPU data layout (no GL needed): what the shader computes from the packed
// texels equals what the CPU computes from the fields and tables.
#include <catch2/catch.hpp>

#include <random>
#include <set>

#include <fmt/format.h>

#include "src/core/error.h"
#include "src/gl/gpu_layout.h"
#include "src/gl/shader_sources.h"
#include "src/render/occluder_shape.h"
#include "src/render/ovdf_occluder.h"
#include "tests/trace/trace_test_scenes.h"
#include "src/shading/shapes.h"

namespace rsl {
namespace {

// Σ_t dot(table_t, coefficients_t): the shader's reconstruction.
float packed_reconstruct(const std::vector<Vec4>& tables, int tables_base, const std::vector<Vec4>& coefficients,
                         int coefficients_base, int stride, int dims, int cluster, int sample, int texel) {
    float value = 0;
    for (int t = 0; t < stride; ++t)
        value += glm::dot(tables[tables_base + (size_t(cluster) * dims + texel) * stride + t],
                          coefficients[coefficients_base + size_t(sample) * stride + t]);
    return value;
}

TEST_CASE("packed SVDF and OVDF rows reconstruct the fields' values", "[gl-layout]") {
    Scene scene = test::make_scene("layout", Color(0.5f));
    test::add_part(scene, test::make_plane(2.0f, 6, "ground"));
    Transform lifted;
    lifted.translation = Vec3(0, 0.4f, 0);
    test::add_part(scene, test::make_icosphere(0.3f, 2, "ball"), lifted);
    PrecomputeSettings& pre = scene.precompute;
    pre.svdf_resolution = 8, pre.svdf_clusters = 4, pre.svdf_vectors = 5, pre.svdf_supersampling = 1;
    pre.ovdf_shells = 3, pre.ovdf_cube_resolution = 4, pre.ovdf_vdt_resolution = 8, pre.ovdf_vectors = 3;
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    const gl::PackedGeometry g = gl::pack_geometry(scene, fields);

    REQUIRE(g.first_vertex.size() == 3);
    CHECK(size_t(g.first_vertex[2]) == scene.vertex_count());
    std::mt19937 rng(5);
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const Vec4* record = &g.part_static[p * gl::kPartStride];
        CHECK(record[gl::kSlotVertices].x == float(g.first_vertex[p]));
        const Svdf& svdf = *fields.self[p];
        const Vec4 s = record[gl::kSlotSvdf];
        CHECK(s.z == float(svdf.resolution()));
        CHECK(s.w == float(gl::cpca_stride(svdf.model.vectors)));
        for (int k = 0; k < 200; ++k) {
            const int v = int(rng() % svdf.vertex_count()), texel = int(rng() % svdf.model.dims);
            const int global = g.first_vertex[p] + v;
            CHECK(g.positions[global] == Vec4(scene.parts[p].mesh.positions[v], float(p)));
            const int cluster = int(g.normals[global].w);
            CHECK(cluster == svdf.model.assignment[v]);
            const float packed = packed_reconstruct(g.svdf_tables, int(s.x), g.svdf_coefficients, int(s.y), int(s.w),
                                                    svdf.model.dims, cluster, v, texel);
            CHECK(packed == Approx(svdf.model.reconstruct(v, texel)).margin(1e-5));
        }
        const Ovdf& ovdf = dynamic_cast<const OvdfOccluder&>(*fields.occluder[p]).field();
        const Vec4 bases = record[gl::kSlotOvdfBases], grid = record[gl::kSlotOvdfGrid];
        CHECK(record[gl::kSlotOvdfCenter] == Vec4(ovdf.center, ovdf.radius));
        CHECK(bases.w == ovdf.shell_radius(ovdf.params.shells - 1));
        for (int k = 0; k < 200; ++k) {
            const int sample = int(rng() % ovdf.model.samples()), texel = int(rng() % ovdf.model.dims);
            const float packed = packed_reconstruct(g.ovdf_tables, int(bases.x), g.ovdf_coefficients, int(bases.y),
                                                    int(grid.z), ovdf.model.dims, ovdf.model.assignment[sample],
                                                    sample, texel);
            CHECK(packed == Approx(ovdf.model.reconstruct(sample, texel)).margin(1e-5));
        }
    }
    // The fields store half-precision tables: RGBA16F holds them exactly.
    CHECK(g.svdf_tables_half);
    CHECK(g.ovdf_tables_half);
    // Every block starts on the alignment that keeps its float start exact.
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const Vec4* record = &g.part_static[p * gl::kPartStride];
        for (const Vec4& starts : {record[gl::kSlotOvdfBases], record[gl::kSlotOvdfRecords]})
            for (int k = 0; k < 3; ++k) CHECK(size_t(starts[k]) % gl::kBlockAlign == 0);
        for (int k = 0; k < 2; ++k) CHECK(size_t(record[gl::kSlotSvdf][k]) % gl::kBlockAlign == 0);
    }
}

TEST_CASE("Block starts stay exact in float texels past 2^24 texels", "[gl-layout]") {
    // The robot's 32-shell OVDF tables are 18.9 M texels: a block starting
    // beyond 2^24 at any texel could not be read back exactly from its float
    // record, so the layout refused the scene (and `rsl view` the robot).
    // Random sizes up to 2^30 texels (16 GB of RGBA32F, past any texture a
    // driver allows).
    std::mt19937_64 rng(24);
    for (int trial = 0; trial < 10000; ++trial) {
        const size_t size = (size_t(1) << 24) + rng() % ((size_t(1) << 30) - (size_t(1) << 24) - gl::kBlockAlign);
        const size_t start = gl::block_start(size);
        CHECK(start >= size);
        CHECK(start < size + gl::kBlockAlign);
        CHECK(size_t(float(start)) == start);
        CHECK(size_t(int(float(start))) == start);  // the shader's int(bases.x)
    }
}

// An anisotropic material and small tables for the BRDF packing tests.
MaterialDesc anisotropic_ward() {
    MaterialDesc ward;
    ward.name = "ward";
    ward.model = "ward_anisotropic";
    ward.params = {{"kd", {0.2f, 0.2f, 0.2f}}, {"ks", {0.2f, 0.2f, 0.2f}}, {"alpha_x", {0.2f}}, {"alpha_y", {0.4f}}};
    return ward;
}
BrdfTableOptions small_tables() {
    BrdfTableOptions options;
    options.resolution = 8, options.view_samples = 4;
    return options;
}

TEST_CASE("BRDF tables are stacked once each, corner sums beside texels", "[gl-layout]") {
    MaterialDesc lambert = test::lambert(Color(0.5f));
    const MaterialDesc ward = anisotropic_ward();
    BrdfTableOptions options = small_tables();
    const auto iso = BrdfTable::build(*make_brdf(lambert), options);
    const auto aniso = BrdfTable::build(*make_brdf(ward), options);
    const gl::PackedMaterials m = gl::pack_materials({iso, aniso, iso});
    CHECK(m.resolution == 8);
    CHECK(m.slices == 4 + 16);
    REQUIRE(m.part_material.size() == 3);
    REQUIRE(iso->view_independent());
    CHECK(m.part_material[0] == Vec4(0, 2, 4, 0));  // isotropic and view-independent (Lambert): one slice
    CHECK(m.part_material[1] == Vec4(4, 0, 4, 0));
    CHECK(m.part_material[2] == m.part_material[0]);
    const size_t slice = 9 * 18 * 3;  // 9 rows of 9 corner sums and 9 texel entries
    REQUIRE(m.texture.size() == 20 * slice);
    // Slice 5 of the anisotropic table, row 7: its corner sums, then its texels (texel (i, 7) at column 9 + i).
    const float* row = m.texture.data() + (4 + 5) * slice + 7 * 18 * 3;
    CHECK(row[3 * 2 + 1] == aniso->lookup_data()[((2 * 5 * 9 + 7) * 9 + 2) * 3 + 1]);
    for (int i = 0; i < 8; ++i) CHECK(row[3 * (9 + i)] == aniso->texel(5, i, 7).r);
    CHECK(row[3 * 17] == 0.0f);  // the texels' last column
    CHECK(m.offsets[4 + 5] == Vec4(aniso->offset(5), 0.0f));
    options.resolution = 16;
    CHECK_THROWS_AS(gl::pack_materials({iso, BrdfTable::build(*make_brdf(lambert), options)}), Error);
}

// Textured parts' second lobe (kSlotSpecular): its table is stacked after the
// diffuse ones (once, however many parts share it), its record carries w = 1,
// and untextured parts get an all-zero record. A specular table whose
// isotropy differs from its diffuse table's is refused.
TEST_CASE("Specular tables of textured parts get their own records and slices", "[gl-layout]") {
    MaterialDesc lambert = test::lambert(Color(1.0f));
    MaterialDesc glossy;
    glossy.name = "glossy";
    glossy.model = "blinn_phong";
    glossy.params = {{"kd", {0.0f, 0.0f, 0.0f}}, {"ks", {0.3f, 0.3f, 0.3f}}, {"exponent", {20.0f}}};
    const MaterialDesc ward = anisotropic_ward();
    BrdfTableOptions options = small_tables();
    const auto diffuse = BrdfTable::build(*make_brdf(lambert), options);
    const auto specular = BrdfTable::build(*make_brdf(glossy), options);
    REQUIRE(diffuse->isotropic());
    REQUIRE(specular->isotropic());
    const gl::PackedMaterials m = gl::pack_materials({diffuse, diffuse, diffuse}, {specular, nullptr, specular});
    CHECK(m.slices == 2 * diffuse->slice_count());  // each table once
    REQUIRE(m.part_specular.size() == 3);
    CHECK(m.part_specular[0] == gl::material_record(*specular, diffuse->slice_count(), true));
    CHECK(m.part_specular[0].w == 1.0f);
    CHECK(m.part_specular[1] == Vec4(0.0f));
    CHECK(m.part_specular[2] == m.part_specular[0]);
    CHECK(m.part_material[0].w == 0.0f);  // the diffuse record is not layered
    const size_t slice = 9 * 18 * 3;
    std::vector<float> rows;
    gl::append_texture_rows(*specular, rows);
    CHECK(std::equal(rows.begin(), rows.end(), m.texture.begin() + size_t(diffuse->slice_count()) * slice));
    CHECK(m.offsets[size_t(diffuse->slice_count())] == Vec4(specular->offset(0), 0.0f));
    const auto aniso = BrdfTable::build(*make_brdf(ward), options);
    CHECK_THROWS_AS(gl::pack_materials({diffuse}, {aniso}), Error);
}

// Exact shapes (src/render/occluder_shape.h) reach the part records only when
// asked for: the ground's rectangle, nothing for a sphere.
TEST_CASE("Part records carry a flat part's rectangle when exact shapes are on", "[gl-layout]") {
    Scene scene = test::make_scene("shapes", Color(0.5f));
    test::add_part(scene, test::make_plane(2.0f, 6, "ground"));
    test::add_part(scene, test::make_icosphere(0.3f, 1, "ball"));
    PartFields fields;
    fields.self.assign(2, nullptr);
    fields.occluder.assign(2, nullptr);
    const gl::PackedGeometry off = gl::pack_geometry(scene, fields), on = gl::pack_geometry(scene, fields, true);
    const OccluderShape ground = find_occluder_shape(scene.parts[0].mesh);
    REQUIRE(ground.kind == shading::kShapeRectangle);
    const Vec4* record = &on.part_static[0];
    CHECK(record[gl::kSlotShape] == Vec4(ground.center, float(shading::kShapeRectangle)));
    CHECK(record[gl::kSlotShapeS] == Vec4(ground.s, 0.0f));
    CHECK(record[gl::kSlotShapeNormal] == Vec4(ground.normal, 0.0f));
    CHECK(record[gl::kSlotShapeHigh] == Vec4(ground.hi, 0.0f));
    CHECK(on.part_static[gl::kPartStride + gl::kSlotShape].w == 0.0f);  // the ball: none
    for (int slot = gl::kSlotShape; slot <= gl::kSlotShapeHigh; ++slot) CHECK(off.part_static[size_t(slot)] == Vec4(0.0f));
}

}  // namespace
}  // namespace rsl

namespace rsl {
namespace {

// How many times `needle` stands in `text`.
size_t occurrences(const std::string& text, const std::string& needle) {
    size_t count = 0;
    for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++count;
    return count;
}

}  // namespace

TEST_CASE("the GPU interface's table gives each pass distinct bindings and each sampler its unit", "[gl-layout]") {
    // The bindings one program binds at once: the vertex pass's (and the
    // per-pixel pass's), with the GPU rays'; then the two passes of their own.
    const std::vector<std::vector<int>> programs = {
        {gl::kBindingBlocks, gl::kBindingBlockVertices, gl::kBindingCandidates, gl::kBindingPartCulling,
         gl::kBindingCounters, gl::kBindingColors, gl::kBindingRecorded, gl::kBindingRecordOffsets,
         gl::kBindingBvhNodes, gl::kBindingBvhTriangles, gl::kBindingBvhInstances, gl::kBindingRayInward},
        {gl::kBindingBvhNodes, gl::kBindingBvhInstances, gl::kBindingBvhLevels},
        {gl::kBindingRays, gl::kBindingHits, gl::kBindingBvhNodes, gl::kBindingBvhTriangles, gl::kBindingBvhInstances},
    };
    for (const std::vector<int>& bindings : programs) {
        const std::set<int> distinct(bindings.begin(), bindings.end());
        CHECK(distinct.size() == bindings.size());
    }
    // Every binding reaches the shaders once, as `#define NAME value`.
    const std::string glsl = gl::shader_interface_glsl();
    for (const gl::GlslConstant& b : gl::kStorageBindings) {
        INFO(b.name);
        CHECK(occurrences(glsl, fmt::format("#define {} {}\n", b.name, b.value)) == 1);
        CHECK(occurrences(glsl, std::string(" ") + b.name + " ") == 1);
    }
    // One sampler per unit, in unit order, each declared once.
    const std::string samplers = gl::shader_sampler_declarations();
    std::set<std::string> names;
    for (int unit = 0; unit < gl::kUnitCount; ++unit) {
        const gl::Sampler& s = gl::kShadingSamplers[unit];
        CHECK(s.unit == unit);
        CHECK(names.insert(s.name).second);
        CHECK(occurrences(samplers, fmt::format("uniform {} {};", s.type, s.name)) == 1);
    }
    CHECK(gl::kUnitUpload >= gl::kUnitCount);
    // Every included file is an embedded shader; the pass itself is source 0.
    CHECK(gl::kShaderSourceFiles[gl::kSourcePass] == nullptr);
    for (int source = 1; source < gl::kSourceCount; ++source) CHECK(gl::embedded_shader(gl::kShaderSourceFiles[source]));
}

}  // namespace rsl
