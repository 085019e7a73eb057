#include "src/gl/gpu_layout.h"

#include <array>
#include <bit>
#include <map>

#include "src/core/envmap.h"
#include "src/core/error.h"
#include "src/core/skinning.h"
#include "src/render/ovdf_occluder.h"
#include "src/render/occluder_shape.h"
#include "src/shading/ovdf_tables.h"

namespace rsl::gl {

namespace {

constexpr size_t kExactFloatIndex = size_t(1) << 24;

// Pads `out` to the next block start (gpu_layout.h block_start) and returns it.
size_t start_block(std::vector<Vec4>& out) {
    out.resize(block_start(out.size()), Vec4(0.0f));
    RSL_CHECK_EQ(size_t(float(out.size())), out.size());
    return out.size();
}

bool is_half_exact(float v) { return round_to_half(v) == v; }

// Appends a CPCA model's tables ([μ, b…] per (cluster, texel)) and returns
// the first texel; records whether every value is exactly a half.
size_t append_tables(const CpcaModel& model, std::vector<Vec4>& out, bool& half_exact) {
    const int stride = cpca_stride(model.vectors);
    const size_t base = start_block(out);
    out.resize(base + size_t(model.clusters) * model.dims * stride, Vec4(0.0f));
    for (int c = 0; c < model.clusters; ++c)
        for (int d = 0; d < model.dims; ++d) {
            const float* row = model.row(c, d);
            float* texels = &out[base + (size_t(c) * model.dims + d) * stride].x;
            for (int i = 0; i <= model.vectors; ++i) {
                texels[i] = row[i];
                half_exact = half_exact && is_half_exact(row[i]);
            }
        }
    return base;
}

// Appends [1, w…] per sample and returns the first texel.
size_t append_coefficients(const CpcaModel& model, std::vector<Vec4>& out) {
    const int stride = cpca_stride(model.vectors);
    const size_t base = start_block(out);
    out.resize(base + size_t(model.samples()) * stride, Vec4(0.0f));
    for (int s = 0; s < model.samples(); ++s) {
        float* texels = &out[base + size_t(s) * stride].x;
        texels[0] = 1.0f;
        const float* w = model.coefficients_of(s);
        for (int i = 0; i < model.vectors; ++i) texels[i + 1] = w[i];
    }
    return base;
}

void check_index(const Scene& scene, size_t size, const char* what) {
    if (size >= kExactFloatIndex)
        throw_file_error(scene.source, "GL renderer: {} needs {} texels, more than float indices address (2^24)",
                         what, size);
}

// The records of the fields packed so far, by field object: instances share
// a field object (src/fields/field_cache.h), whose tables go up once and
// whose records every part that uses it points at.
struct SharedFieldRecords {
    std::map<const Svdf*, Vec4> svdf;
    std::map<const Ovdf*, std::array<Vec4, 5>> ovdf;
    std::map<const Svdf*, std::vector<uint8_t>> enclosed;
};

// The part record's slots of an OVDF, in the order the records cache them.
constexpr int kOvdfSlots[5] = {kSlotOvdfCenter, kSlotOvdfBases, kSlotOvdfShells, kSlotOvdfGrid, kSlotOvdfRecords};

// Phase: the cube faces' normal and (s, t) axes, as Ovdf::prepare.
void pack_face_frames(PackedGeometry& g) {
    const float root2 = std::sqrt(2.0f);
    for (int f = 0; f < 6; ++f) {  // as Ovdf::prepare
        g.face_normal[f] = CubeMap::face_direction(f, 0, 0);
        g.face_s[f] = root2 * CubeMap::face_direction(f, 1, 0) - g.face_normal[f];
        g.face_t[f] = root2 * CubeMap::face_direction(f, 0, 1) - g.face_normal[f];
    }
}

// Part phase: the record's first vertex, bounding box and (with exact_shapes) occluder shape.
void write_part_shape(const TriangleMesh& mesh, bool exact_shapes, PackedGeometry& g, Vec4* record) {
    const int first = int(g.positions.size());
    g.first_vertex.push_back(first);
    record[kSlotVertices] = Vec4(float(first), 0, 0, 0);
    const Bounds box = mesh.bounds();
    record[kSlotBoxLow] = Vec4(box.lo, 0.0f);
    record[kSlotBoxHigh] = Vec4(box.hi, 0.0f);
    if (exact_shapes) {
        const OccluderShape shape = find_occluder_shape(mesh);
        record[kSlotShape] = Vec4(shape.center, float(shape.kind));
        record[kSlotShapeS] = Vec4(shape.s, 0.0f);
        record[kSlotShapeT] = Vec4(shape.t, 0.0f);
        record[kSlotShapeNormal] = Vec4(shape.normal, 0.0f);
        record[kSlotShapeLow] = Vec4(shape.lo, 0.0f);
        record[kSlotShapeHigh] = Vec4(shape.hi, 0.0f);
    }
}

// Part phase: the SVDF's slot, its tables and coefficients appended the first time the field is seen.
void pack_part_svdf(const Svdf& svdf, PackedGeometry& g, SharedFieldRecords& shared, Vec4* record) {
    if (shared.svdf.count(&svdf)) {
        record[kSlotSvdf] = shared.svdf[&svdf];
        return;
    }
    const CpcaModel& m = svdf.model;
    const int stride = cpca_stride(m.vectors);
    g.max_stride = std::max(g.max_stride, stride);
    g.svdf_stride = shared_stride(g.svdf_stride, stride);
    const size_t tables = append_tables(m, g.svdf_tables, g.svdf_tables_half);
    const size_t coefficients = append_coefficients(m, g.svdf_coefficients);
    record[kSlotSvdf] = Vec4(float(tables), float(coefficients), float(svdf.resolution()), float(stride));
    shared.svdf[&svdf] = record[kSlotSvdf];
}

// Part phase: the mesh's vertices as texels, with part index, SVDF cluster, and in the tangent's w
// the enclosed flag e and the seam partner s (skinning.h seam_partners, -1: none) as e + 2(s + 1).
void append_part_vertices(const TriangleMesh& mesh, size_t p, const Svdf* svdf, const std::vector<int>& partners,
                          PackedGeometry& g, SharedFieldRecords& shared) {
    // The enclosed flag: where the SVDF finds the vertex enclosed (the per-pixel pass's corners).
    const std::vector<uint8_t>* enclosed = nullptr;
    if (svdf) {
        auto [it, added] = shared.enclosed.try_emplace(svdf);
        if (added) it->second = svdf->enclosed_vertices();
        enclosed = &it->second;
    }
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        g.positions.push_back(Vec4(mesh.positions[v], float(p)));
        const float cluster = svdf ? float(svdf->model.assignment[v]) : -1.0f;
        g.normals.push_back(Vec4(mesh.normals[v], cluster));
        const float enclosed_flag = enclosed && (*enclosed)[v] ? 1.0f : 0.0f;
        const float partner = partners.empty() ? -1.0f : float(partners[v]);
        g.tangents.push_back(Vec4(mesh.tangents.empty() ? Vec3(0.0f) : Vec3(mesh.tangents[v]),
                                  enclosed_flag + 2.0f * (partner + 1.0f)));
    }
}

// Throws unless every sample of the OVDF is clustered by its segment: the
// shader computes a sample's cluster as its segment (as the bake assigns it).
void check_clustered_by_segment(const Scene& scene, size_t p, const Ovdf& o) {
    const OvdfParams& op = o.params;
    const int n = op.cube_resolution;
    for (int shell = 0; shell < op.shells; ++shell)
        for (int face = 0; face < 6; ++face)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i)
                    if (o.model.assignment[o.sample_index(shell, face, i, j)] != o.segment_of(shell, face, i, j))
                        throw_file_error(scene.source, "GL renderer: OVDF of part '{}' is not clustered by segment",
                                         scene.parts[p].name);
}

// Where an OVDF's blocks start in PackedGeometry::ovdf_frames.
struct OvdfFrameBlocks {
    size_t frames = 0, zoom_records = 0, surfaces = 0, spans = 0;
};

// OVDF phase: its sample frames, shell zooms, surface distances and occluded
// areas, and radial spans, each block appended to `out` in turn.
OvdfFrameBlocks append_ovdf_frames(const Ovdf& o, std::vector<Vec4>& out) {
    const OvdfParams& op = o.params;
    const int n = op.cube_resolution;
    OvdfFrameBlocks blocks;
    blocks.frames = start_block(out);
    for (int face = 0; face < shading::kCubeFaces; ++face)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const Frame& frame = o.sample_frame(face, i, j);
                out.push_back(Vec4(frame.x, 0.0f));  // kOvdfFrameTexels
                out.push_back(Vec4(frame.z, 0.0f));
            }
    blocks.zoom_records = start_block(out);
    for (int shell = 0; shell < op.shells; ++shell)  // after the frames: (zoom, cone, 0, 0)
        out.push_back(Vec4(o.shell_zoom(shell).zoom, o.shell_zoom(shell).cone, 0.0f, 0.0f));
    // Then the samples' surface distances and occluded areas, two samples
    // to a texel (1: outside, and no area bound, for a field without them).
    blocks.surfaces = start_block(out);
    const size_t samples = op.sample_count();
    for (size_t s = 0; s < samples; s += kSamplesPerTexel) {
        Vec4 texel(1.0f, shading::kOvdfNoAreaBound, 1.0f, shading::kOvdfNoAreaBound);
        for (size_t c = 0; c < kSamplesPerTexel && s + c < samples; ++c) {
            if (!o.surface_distance.empty()) texel[int(2 * c)] = o.surface_distance[s + c];
            if (!o.occluded_area.empty()) texel[int(2 * c + 1)] = o.occluded_area[s + c];
        }
        out.push_back(texel);
    }
    // Then the radial spans, two lines (enter, exit) to a texel.
    blocks.spans = start_block(out);
    for (size_t k = 0; k < o.radial_span.size(); k += 4) {
        Vec4 texel(0.0f);
        for (size_t c = 0; c < 4 && k + c < o.radial_span.size(); ++c) texel[int(c)] = o.radial_span[k + c];
        out.push_back(texel);
    }
    return blocks;
}

// Part phase: the occluder field's OVDF slots, its tables, coefficients and
// frames appended the first time the field is seen; none without a field.
void pack_part_ovdf(const Scene& scene, size_t p, const OccluderField* field, PackedGeometry& g,
                    SharedFieldRecords& shared, Vec4* record) {
    if (!field) return;
    const auto* occluder = dynamic_cast<const OvdfOccluder*>(field);
    if (!occluder)
        throw_file_error(scene.source, "GL renderer: part '{}' has an occluder field that is not an OVDF",
                         scene.parts[p].name);
    const Ovdf& o = occluder->field();
    if (const auto it = shared.ovdf.find(&o); it != shared.ovdf.end()) {
        for (int k = 0; k < 5; ++k) record[kOvdfSlots[k]] = it->second[size_t(k)];
        return;
    }
    const OvdfParams& op = o.params;
    const int n = op.cube_resolution;
    check_clustered_by_segment(scene, p, o);
    const int stride = cpca_stride(o.model.vectors);
    g.max_stride = std::max(g.max_stride, stride);
    g.ovdf_stride = shared_stride(g.ovdf_stride, stride);
    const size_t tables = append_tables(o.model, g.ovdf_tables, g.ovdf_tables_half);
    const size_t coefficients = append_coefficients(o.model, g.ovdf_coefficients);
    const OvdfFrameBlocks blocks = append_ovdf_frames(o, g.ovdf_frames);
    record[kSlotOvdfCenter] = Vec4(o.center, o.radius);
    record[kSlotOvdfBases] =
        Vec4(float(tables), float(coefficients), float(blocks.frames), o.shell_radius(op.shells - 1));
    record[kSlotOvdfShells] = Vec4(float(op.shells), float(int(op.spacing)), op.inner_radius, op.outer_radius);
    record[kSlotOvdfGrid] = Vec4(float(n), float(op.vdt_resolution), float(stride), float(op.segments_per_side));
    record[kSlotOvdfRecords] = Vec4(float(blocks.zoom_records), float(blocks.surfaces), float(blocks.spans),
                                    o.radial_span.empty() ? 0.0f : float(o.span_resolution));
    for (int k = 0; k < 5; ++k) shared.ovdf[&o][size_t(k)] = record[kOvdfSlots[k]];
}

}  // namespace

std::string shader_layout_constants() {
    std::string text = "// Generated from src/gl/gpu_layout.h (shader_layout_constants).\n";
    for (const GlslConstant& c : kShaderIntConstants) text += fmt::format("const int {} = {};\n", c.name, c.value);
    // {:.9g} round-trips a float exactly.
    text += fmt::format("const float kPi = {:.9g}f;\nconst float kSqrt2 = {:.9g}f;\n", shading::kPi, shading::kSqrt2);
    return text + shader_interface_glsl();
}

void write_pose(const Mat4& transform, const Mat3& normal, const Mat4& inverse, Vec4* record) {
    for (int c = 0; c < 4; ++c) record[kSlotTransform + c] = transform[c];
    for (int c = 0; c < 3; ++c) record[kSlotNormal + c] = Vec4(normal[c], 0.0f);
    for (int c = 0; c < 4; ++c) record[kSlotInverse + c] = inverse[c];
}

PackedGeometry pack_geometry(const Scene& scene, const PartFields& fields, bool exact_shapes) {
    PackedGeometry g;
    const size_t parts = scene.parts.size();
    g.part_static.assign(parts * kPartStride, Vec4(0.0f));
    pack_face_frames(g);
    SharedFieldRecords shared;
    const std::vector<std::vector<int>> partners = seam_partners(scene);
    for (size_t p = 0; p < parts; ++p) {
        const TriangleMesh& mesh = scene.parts[p].mesh;
        Vec4* record = &g.part_static[p * kPartStride];
        write_part_shape(mesh, exact_shapes, g, record);
        const Svdf* svdf = p < fields.self.size() ? fields.self[p].get() : nullptr;
        if (svdf) pack_part_svdf(*svdf, g, shared, record);
        append_part_vertices(mesh, p, svdf, partners[p], g, shared);
        const OccluderField* field = p < fields.occluder.size() ? fields.occluder[p].get() : nullptr;
        pack_part_ovdf(scene, p, field, g, shared, record);
    }
    g.first_vertex.push_back(int(g.positions.size()));
    // A vertex's part and first vertex are float texels too (the tables'
    // block starts are exact by start_block; their textures' size is the
    // driver's to allow, gl_objects.cpp).
    check_index(scene, g.positions.size(), "the vertices");
    return g;
}

void append_texture_rows(const BrdfTable& table, std::vector<float>& out) {
    const int n = table.grid().n;
    const size_t row = size_t(n + 1) * 3, layer = row * size_t(n + 1);
    const float* data = table.lookup_data().data();
    out.reserve(out.size() + table.lookup_data().size());
    for (int s = 0; s < table.slice_count(); ++s)
        for (size_t b = 0; b <= size_t(n); ++b)
            for (const size_t texels : {size_t(0), layer}) {  // row b of the corner sums, then of the texels
                const float* from = data + 2 * layer * size_t(s) + texels + b * row;
                out.insert(out.end(), from, from + row);
            }
}

Vec4 material_record(const BrdfTable& table, int first_slice, bool specular) {
    // 2: isotropic and the same in every view (Lambert): one slice, as the CPU's batch kernel reads.
    const float isotropy = table.isotropic() ? (table.view_independent() ? 2.0f : 1.0f) : 0.0f;
    return Vec4(float(first_slice), isotropy, float(table.options().view_samples),
                specular ? 1.0f : 0.0f);
}

PackedMaterials pack_materials(const std::vector<std::shared_ptr<const BrdfTable>>& part_tables,
                               const std::vector<std::shared_ptr<const BrdfTable>>& part_specular_tables,
                               const std::vector<std::shared_ptr<const BrdfTable>>& pbr_basis_tables) {
    RSL_CHECK(pbr_basis_tables.empty() || pbr_basis_tables.size() == size_t(kPbrBasisRecords));
    RSL_CHECK(part_specular_tables.empty() || part_specular_tables.size() == part_tables.size());
    PackedMaterials out;
    std::map<const BrdfTable*, int> first_slice;
    auto place = [&](const BrdfTable& table) {
        const int n = table.grid().n;
        if (out.resolution == 0) out.resolution = n;
        if (n != out.resolution)
            throw Error(fmt::format("GL renderer: BRDF tables of {}² and {}² texels; all must share one resolution",
                                    out.resolution, n));
        auto [it, inserted] = first_slice.emplace(&table, out.slices);
        if (inserted) {
            append_texture_rows(table, out.texture);
            for (int s = 0; s < table.slice_count(); ++s) out.offsets.push_back(Vec4(table.offset(s), 0.0f));
            out.slices += table.slice_count();
        }
        return it->second;
    };
    for (const auto& table : part_tables) {
        RSL_CHECK(table != nullptr);
        out.part_material.push_back(material_record(*table, place(*table), false));
    }
    for (size_t p = 0; p < part_tables.size(); ++p) {
        const BrdfTable* specular = part_specular_tables.empty() ? nullptr : part_specular_tables[p].get();
        // One view parametrization per vertex: the shader aligns the square
        // once, by the diffuse table's isotropy.
        if (specular && specular->isotropic() != part_tables[p]->isotropic())
            throw Error("GL renderer: a specular table and its diffuse table differ in isotropy");
        out.part_specular.push_back(specular ? material_record(*specular, place(*specular), true) : Vec4(0.0f));
    }
    out.pbr_basis.assign(size_t(kPbrBasisRecords), Vec4(0.0f));
    for (size_t i = 0; i < pbr_basis_tables.size(); ++i)
        if (const BrdfTable* table = pbr_basis_tables[i].get()) out.pbr_basis[i] = material_record(*table, place(*table), false);
    return out;
}

PackedBlocks pack_blocks(const Scene& scene, const std::vector<int>& first_vertex) {
    std::vector<std::vector<int>> orders;
    for (const Part& part : scene.parts) orders.push_back(spatial_block_order(part.mesh.positions, kShadeBlock));
    PackedBlocks packed;
    for (const VertexBlock& block : vertex_blocks(orders)) {
        const std::vector<int>& order = orders[size_t(block.part)];
        packed.blocks.emplace_back(block.part, int(packed.vertices.size()), block.end - block.begin, 0);
        for (int i = block.begin; i < block.end; ++i)
            packed.vertices.push_back(first_vertex[size_t(block.part)] + order[size_t(i)]);
    }
    return packed;
}

void pack_block_candidates(const OccluderLists& lists, std::vector<uint32_t>& words) {
    const size_t parts = lists.candidate_offsets.empty() ? 0 : lists.candidate_offsets.size() - 1;
    const size_t stride = kCandidateHeader + lists.light_words;
    const size_t total = parts + 1 + lists.candidate_occluders.size() * stride;
    if (total > size_t(UINT32_MAX))
        throw Error(fmt::format("GL renderer: the frame's occluder candidates need {} words, more than uint indices address",
                                total));
    words.resize(total);
    for (size_t p = 0; p <= parts; ++p) words[p] = uint32_t(lists.candidate_offsets[p]);
    if (parts == 0) words[0] = 0;
    uint32_t* entry = words.data() + parts + 1;
    for (size_t c = 0; c < lists.candidate_occluders.size(); ++c, entry += stride) {
        entry[0] = uint32_t(lists.candidate_occluders[c]);
        entry[1] = std::bit_cast<uint32_t>(lists.candidate_growths[c]);
        for (size_t w = 0; w < lists.light_words; ++w) entry[kCandidateHeader + w] = lists.candidate_lights[c * lists.light_words + w];
    }
}

void pack_part_culling(const std::vector<PartPose>& poses, const std::vector<BoundingSphere>& local_reach,
                       const std::vector<BoundingSphere>& split_fields, std::vector<Vec4>& out) {
    out.resize(std::max<size_t>(poses.size(), 1) * kCullingStride, Vec4(0.0f));
    for (size_t p = 0; p < poses.size(); ++p) {
        // The CPU renderer's spheres, moved by the same function (shade_block.cpp prepare_occluder).
        const PartPose& pose = poses[p];
        Vec4* record = &out[p * kCullingStride];
        record[kCullingBounds] = as_vec4(pose.world_bounds);
        record[kCullingReach] = as_vec4(transform_sphere(pose.transform, local_reach[p]));
        record[kCullingField] = as_vec4(transform_sphere(pose.transform, split_fields[p]));
        record[kCullingFlags] = Vec4(pose.uniform_scale ? 1.0f : 0.0f, split_fields[p].radius > 0.0f ? 1.0f : 0.0f, 0, 0);
    }
}

}  // namespace rsl::gl
