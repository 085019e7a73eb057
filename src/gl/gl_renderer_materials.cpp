// The GL renderer's BRDF tables on the GPU: one stacked 3D texture of every
// table the parts use (gpu_layout.h pack_materials), and live material
// edits, which upload a changed table into its own slices (gl_renderer.h).
#include <algorithm>

#include "src/brdf/material_library.h"
#include "src/brdf/pbr_basis.h"
#include "src/core/error.h"
#include "src/gl/gl_renderer.h"

namespace rsl::gl {

std::vector<std::shared_ptr<const BrdfTable>> GlRenderer::wanted_tables() const {
    std::vector<std::shared_ptr<const BrdfTable>> wanted;
    for (int p = 0; p < library_.part_count(); ++p) wanted.push_back(library_.table(library_.part_material(p)));
    for (int p = 0; p < library_.part_count(); ++p)
        wanted.push_back(library_.specular_table(library_.part_material(p)));
    RSL_CHECK_EQ(wanted.size(), 2 * scene_.parts.size());
    const PbrBasisTables& basis = library_.pbr_basis();
    wanted.push_back(basis.diffuse);
    wanted.insert(wanted.end(), basis.dielectric.begin(), basis.dielectric.end());
    wanted.insert(wanted.end(), basis.metal.begin(), basis.metal.end());
    return wanted;
}

void GlRenderer::upload_pbr_points() {
    std::vector<Vec4> points(std::max<size_t>(size_t(vertex_count_), 1), Vec4(0.0f));
    for (size_t p = 0; p < scene_.parts.size(); ++p) {
        const MaterialDesc& desc = library_.desc(library_.part_material(int(p)));
        const bool varies = varies_per_point(desc);
        part_records_[p * kPartStride + kSlotPbr] = varies ? Vec4(pbr_base_color(desc), 1.0f) : Vec4(0.0f);
        if (!varies) continue;
        const std::vector<PbrPoint> part_points = pbr_points(desc, scene_.parts[p].mesh);
        for (size_t v = 0; v < part_points.size(); ++v)
            points[size_t(first_vertex_[p]) + v] = Vec4(part_points[v].roughness, part_points[v].metallic, 0.0f, 0.0f);
    }
    if (pbr_points_.texture)
        update_array_texture(pbr_points_, points);
    else
        pbr_points_ = make_array_texture(points);
}

void GlRenderer::write_material_record(size_t i, const BrdfTable* table, int first_slice) {
    const size_t parts = scene_.parts.size();
    if (i >= 2 * parts) {  // a basis table
        pbr_basis_records_[i - 2 * parts] = table ? material_record(*table, first_slice, false) : Vec4(0.0f);
        return;
    }
    const bool specular = i >= parts;
    part_records_[(i % parts) * kPartStride + (specular ? kSlotSpecular : kSlotMaterial)] =
        table ? material_record(*table, first_slice, specular) : Vec4(0.0f);
    if (!specular)
        part_records_[i * kPartStride + kSlotDiffuseLight] =
            Vec4(library_.brdf(library_.part_material(int(i))).constant_part(), 0.0f);
}

void GlRenderer::set_part_tables(std::vector<std::shared_ptr<const BrdfTable>> tables) {
    part_tables_ = std::move(tables);
    const auto specular = part_tables_.begin() + std::ptrdiff_t(scene_.parts.size());
    layered_ = std::any_of(specular, specular + std::ptrdiff_t(scene_.parts.size()),
                           [](const auto& table) { return table != nullptr; });
}

void GlRenderer::upload_all_tables() {
    set_part_tables(wanted_tables());
    const size_t parts = scene_.parts.size();
    const size_t old_bytes = materials_.texture.size() * sizeof(float) + materials_.offsets.size() * 16;
    materials_ = pack_materials({part_tables_.begin(), part_tables_.begin() + std::ptrdiff_t(parts)},
                                {part_tables_.begin() + std::ptrdiff_t(parts),
                                 part_tables_.begin() + std::ptrdiff_t(2 * parts)},
                                {part_tables_.begin() + std::ptrdiff_t(2 * parts), part_tables_.end()});
    pbr_basis_records_.assign(size_t(kPbrBasisRecords), Vec4(0.0f));
    const int corners = materials_.resolution + 1;
    GLint max_3d = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max_3d);
    // More slices than a 3D texture's depth (llvmpipe: 2048; a scene with
    // many materials and the basis tables of textured ones) stack several
    // slices along y in each depth layer.
    brdf_tiles_ = (materials_.slices + max_3d - 1) / std::max(max_3d, 1);
    if (brdf_tiles_ * corners > max_3d)
        throw_file_error(scene_.source, "GL renderer: the BRDF tables have {} slices; this driver's 3D textures hold {}",
                         materials_.slices, max_3d * (max_3d / corners));
    const int layers = (materials_.slices + brdf_tiles_ - 1) / brdf_tiles_;
    if (!brdf_) brdf_ = make_texture();
    glBindTexture(GL_TEXTURE_3D, brdf_.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage3D(GL_TEXTURE_3D, 0, GL_RGB32F, 2 * corners, corners * brdf_tiles_, layers, 0, GL_RGB, GL_FLOAT,
                 brdf_tiles_ == 1 ? materials_.texture.data() : nullptr);
    if (brdf_tiles_ > 1) upload_brdf_slices(0, materials_.slices, materials_.texture.data());
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAX_LEVEL, 0);
    if (brdf_offsets_.texture)
        update_array_texture(brdf_offsets_, materials_.offsets);
    else
        brdf_offsets_ = make_array_texture(materials_.offsets);
    slots_.clear();
    for (size_t i = 0; i < part_tables_.size(); ++i) {
        const BrdfTable* table = part_tables_[i].get();
        const int first = int(i < parts       ? materials_.part_material[i].x
                              : i < 2 * parts ? materials_.part_specular[i - parts].x
                                              : materials_.pbr_basis[i - 2 * parts].x);
        write_material_record(i, table, first);
        if (table &&
            std::none_of(slots_.begin(), slots_.end(), [&](const TableSlot& s) { return s.first_slice == first; }))
            slots_.push_back(TableSlot{part_tables_[i], first, table->slice_count()});
    }
    gpu_bytes_ = gpu_bytes_ - old_bytes + materials_.texture.size() * sizeof(float) + materials_.offsets.size() * 16;
    upload_pbr_points();
    ++uploads_.full;
    check_gl("uploading the BRDF tables");
}

// Slices [first, first + count) of the bound BRDF texture from `data` (per
// slice its rows, append_texture_rows), each in its layer and tile.
void GlRenderer::upload_brdf_slices(int first, int count, const float* data) {
    const int corners = materials_.resolution + 1;
    const size_t slice_floats = size_t(2 * corners) * size_t(corners) * 3;
    if (brdf_tiles_ == 1) {
        glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, first, 2 * corners, corners, count, GL_RGB, GL_FLOAT, data);
        return;
    }
    for (int i = 0; i < count; ++i) {
        const int slice = first + i;
        glTexSubImage3D(GL_TEXTURE_3D, 0, 0, (slice % brdf_tiles_) * corners, slice / brdf_tiles_, 2 * corners,
                        corners, 1, GL_RGB, GL_FLOAT, data + size_t(i) * slice_floats);
    }
}

void GlRenderer::sync_materials() {
    bool changed = false;
    const size_t parts = scene_.parts.size();
    for (int p = 0; p < library_.part_count(); ++p)
        changed = changed || library_.table(library_.part_material(p)) != part_tables_[size_t(p)] ||
                  library_.specular_table(library_.part_material(p)) != part_tables_[parts + size_t(p)];
    // A basis table built since (a material's texture reaching a new roughness level).
    const PbrBasisTables& basis = library_.pbr_basis();
    changed = changed || basis.diffuse != part_tables_[2 * parts];
    for (int j = 0; j < kPbrLevels; ++j)
        changed = changed || basis.dielectric[size_t(j)] != part_tables_[2 * parts + 1 + size_t(j)] ||
                  basis.metal[size_t(j)] != part_tables_[2 * parts + 1 + kPbrLevels + size_t(j)];
    if (!changed) return;  // the common frame: nothing to compare or allocate
    const std::vector<std::shared_ptr<const BrdfTable>> wanted = wanted_tables();
    // In place: every table the parts now use either already has slices, or
    // takes over the slices of a table no part uses any more, of the same
    // layout (slice count, resolution).
    std::vector<int> slot_of(wanted.size(), -1);
    std::vector<bool> slot_used(slots_.size(), false);
    for (size_t p = 0; p < wanted.size(); ++p)
        for (size_t s = 0; s < slots_.size(); ++s)
            if (slots_[s].table == wanted[p]) slot_of[p] = int(s), slot_used[s] = true;
    std::vector<std::pair<int, std::shared_ptr<const BrdfTable>>> moves;  // slot ← new table
    for (size_t p = 0; p < wanted.size(); ++p) {
        if (slot_of[p] >= 0 || !wanted[p]) continue;  // null: an untextured part's specular table
        for (size_t q = 0; q < p; ++q)  // a new table shared by an earlier part
            if (wanted[q] == wanted[p]) slot_of[p] = slot_of[q];
        if (slot_of[p] >= 0) continue;
        for (size_t s = 0; s < slots_.size() && slot_of[p] < 0; ++s)
            if (!slot_used[s] && slots_[s].slices == wanted[p]->slice_count() &&
                slots_[s].table->grid().n == wanted[p]->grid().n &&
                slots_[s].table->isotropic() == wanted[p]->isotropic() &&
                slots_[s].table->options().view_samples == wanted[p]->options().view_samples) {
                slot_of[p] = int(s), slot_used[s] = true;
                moves.emplace_back(int(s), wanted[p]);
            }
        if (slot_of[p] < 0) return upload_all_tables();
    }
    if (std::find(slot_used.begin(), slot_used.end(), false) != slot_used.end()) return upload_all_tables();
    const int corners = materials_.resolution + 1;
    glBindTexture(GL_TEXTURE_3D, brdf_.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    std::vector<float> rows;
    for (const auto& [s, table] : moves) {
        TableSlot& slot = slots_[size_t(s)];
        slot.table = table;
        rows.clear();
        append_texture_rows(*table, rows);
        upload_brdf_slices(slot.first_slice, slot.slices, rows.data());
        // The CPU copy of the tables stays as packed (it is only read by a full upload).
        for (int i = 0; i < slot.slices; ++i)
            materials_.offsets[size_t(slot.first_slice + i)] = Vec4(table->offset(i), 0.0f);
        ++uploads_.tables;
    }
    if (!moves.empty()) update_array_texture(brdf_offsets_, materials_.offsets);
    for (size_t p = 0; p < wanted.size(); ++p)
        write_material_record(p, wanted[p].get(), wanted[p] ? slots_[size_t(slot_of[p])].first_slice : 0);
    set_part_tables(wanted);
    upload_pbr_points();
    check_gl("uploading a BRDF table");
}

}  // namespace rsl::gl
