#include "src/render/material_tables.h"

#include "src/core/error.h"

namespace rsl {

namespace {

int find_material(const Scene& scene, const std::string& name) {
    for (size_t m = 0; m < scene.materials.size(); ++m)
        if (scene.materials[m].name == name) return int(m);
    return -1;
}

int find_part(const Scene& scene, const std::string& name) {
    for (size_t p = 0; p < scene.parts.size(); ++p)
        if (scene.parts[p].name == name) return int(p);
    return -1;
}

}  // namespace

MaterialTables::MaterialTables(const Scene& scene, const RenderOptions& options) {
    for (const Part& part : scene.parts) part_material_.push_back(part.material);
    for (const auto& [part_name, material_name] : options.material_override) {
        const int part = find_part(scene, part_name);
        if (part < 0) throw_file_error(scene.source, "material override: no part named '{}'", part_name);
        const int material = find_material(scene, material_name);
        if (material < 0)
            throw_file_error(scene.source, "material override for part '{}': no material named '{}'", part_name,
                             material_name);
        part_material_[part] = material;
    }
    tables_.resize(scene.materials.size());
    for (size_t p = 0; p < part_material_.size(); ++p) {
        const int m = part_material_[p];
        if (m < 0 || m >= int(scene.materials.size()))
            throw_file_error(scene.source, "part '{}' has material index {} of {}", scene.parts[p].name, m,
                             scene.materials.size());
        if (!tables_[m]) tables_[m] = BrdfTable::build(*make_brdf(scene.materials[m]), options.brdf_table);
    }
}

size_t MaterialTables::table_count() const {
    size_t count = 0;
    for (const auto& table : tables_) count += table ? 1 : 0;
    return count;
}

size_t MaterialTables::memory_bytes() const {
    size_t bytes = 0;
    for (const auto& table : tables_)
        if (table) bytes += table->memory_bytes();
    return bytes;
}

}  // namespace rsl
