#include "src/brdf/material_library.h"

#include <chrono>
#include <set>

#include <fmt/format.h>

#include "src/brdf/table_resolution.h"
#include "src/core/emission.h"
#include "src/core/error.h"

namespace rsl {

MaterialLibrary::MaterialLibrary(BrdfTableOptions options) : options_(options) {}

MaterialLibrary MaterialLibrary::from_scene(const Scene& scene, BrdfTableOptions options) {
    MaterialLibrary library(options);
    for (const MaterialDesc& m : scene.materials) library.add(m);
    library.resize_parts(static_cast<int>(scene.parts.size()));
    for (size_t p = 0; p < scene.parts.size(); ++p) library.assign(static_cast<int>(p), scene.parts[p].material);
    return library;
}

std::string MaterialLibrary::identity(const MaterialDesc& desc) {
    // Model, every parameter at full float precision, and the measured file.
    // Textured materials have two tables; which texture does not matter.
    std::string key = desc.model + "|" + desc.file.string() + (desc.base_color_texture ? "|textured" : "");
    for (const auto& [name, values] : desc.params) {
        key += "|" + name + "=";
        for (float v : values) key += fmt::format("{:a},", v);
    }
    return key;
}

std::shared_ptr<const MaterialLibrary::Shared> MaterialLibrary::obtain(const MaterialDesc& desc) {
    if (const std::string problem = emission_problem(desc.emissive); !problem.empty())
        throw_error("material '{}': emissive {}", desc.name, problem);
    const std::string key = identity(desc);
    if (auto it = by_identity_.find(key); it != by_identity_.end())
        if (auto alive = it->second.lock()) {
            last_build_seconds_ = 0;
            return alive;
        }
    // Validates: throws before anything changes.
    BrdfLobes lobes = desc.base_color_texture ? make_brdf_lobes(desc) : BrdfLobes{make_brdf(desc), nullptr};
    const auto start = std::chrono::steady_clock::now();
    auto table = BrdfTable::build(*lobes.diffuse, options_);
    auto specular = lobes.specular ? BrdfTable::build(*lobes.specular, options_) : nullptr;
    last_build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // A highlight the table blurs is an error rsl knows of: say so, once per table.
    const BrdfTable& glossy_table = specular ? *specular : *table;
    const Brdf& glossy_brdf = lobes.specular ? *lobes.specular : *lobes.diffuse;
    if (const std::string w = sharp_material_warning(desc, glossy_table, table_peak_error(glossy_table, glossy_brdf));
        !w.empty())
        warn("{}", w);
    auto shared = std::make_shared<const Shared>(Shared{std::move(lobes.diffuse), std::move(table), std::move(specular)});
    by_identity_[key] = shared;
    // Forget entries whose tables no material uses any more.
    std::erase_if(by_identity_, [](const auto& entry) { return entry.second.expired(); });
    return shared;
}

void MaterialLibrary::require_pbr_basis(const MaterialDesc& desc) {
    if (!rsl::varies_per_point(desc)) return;
    const PbrLevelRange range = pbr_level_range(desc);
    last_build_seconds_ += pbr_basis_.require(range, options_);
    // The sharpest lobes its texture reaches, as for an untextured material
    // (sharp_material_warning): the smoothest level the tables resolve.
    const auto peak = [&](int j) {
        return table_peak_error(*pbr_basis_.dielectric[size_t(j)], *pbr_specular_lobe(shading::kPbrDielectricF0, j));
    };
    const TablePeakError sharpest = peak(range.first);
    if (!(sharpest.relative_error > kTablePeakErrorLimit)) return;
    int resolved = range.first + 1;
    while (resolved <= range.last && peak(resolved).relative_error > kTablePeakErrorLimit) ++resolved;
    warn("material '{}' (gltf_pbr): its metallic-roughness texture reaches roughness {:g}, a highlight sharper than "
         "the BRDF table resolves ({}² texels): under a small light such as a sun, points smoother than roughness {:g} "
         "are off by up to {:.0f}% (docs/design/BRDF.md, \"Table resolution\")",
         desc.name, shading::pbr_level_roughness(range.first), pbr_basis_.dielectric[size_t(range.first)]->grid().n,
         shading::pbr_level_roughness(std::min(resolved, kPbrLevels - 1)), 100 * sharpest.relative_error);
}

int MaterialLibrary::add(const MaterialDesc& desc) {
    auto shared = obtain(desc);
    require_pbr_basis(desc);
    materials_.push_back(Material{desc, std::move(shared), next_revision_++});
    return material_count() - 1;
}

int MaterialLibrary::find(const std::string& name) const {
    for (int m = 0; m < material_count(); ++m)
        if (materials_[m].desc.name == name) return m;
    return -1;
}

const MaterialLibrary::Material& MaterialLibrary::at(int material) const {
    if (material < 0 || material >= material_count())
        throw_error("material index {} out of range (the library has {} materials)", material, material_count());
    return materials_[material];
}

void MaterialLibrary::set_parameter(int material, const std::string& key, const std::vector<float>& value) {
    MaterialDesc desc = at(material).desc;
    if (key == "emissive")  // not the BRDF's: the table stays (src/core/emission.h)
        desc.emissive = checked_emission(desc.name, value);
    else
        desc.params[key] = value;
    replace(material, std::move(desc));
}

void MaterialLibrary::replace(int material, MaterialDesc desc) {
    desc.name = at(material).desc.name;
    auto shared = obtain(desc);  // may throw: the material keeps its old state
    require_pbr_basis(desc);
    Material& m = materials_[material];
    m.desc = std::move(desc);
    m.shared = std::move(shared);
    m.revision = next_revision_++;
    std::erase_if(by_identity_, [](const auto& entry) { return entry.second.expired(); });
}

void MaterialLibrary::resize_parts(int parts, int material) {
    at(material);  // validates the index
    part_materials_.resize(parts, material);
}

void MaterialLibrary::assign(int part, int material) {
    at(material);
    if (part < 0 || part >= part_count())
        throw_error("part index {} out of range (the library has {} parts)", part, part_count());
    part_materials_[part] = material;
}

int MaterialLibrary::part_material(int part) const {
    if (part < 0 || part >= part_count())
        throw_error("part index {} out of range (the library has {} parts)", part, part_count());
    return part_materials_[part];
}

int MaterialLibrary::distinct_table_count() const {
    std::set<const BrdfTable*> tables;
    for (const Material& m : materials_) {
        tables.insert(m.shared->table.get());
        if (m.shared->specular_table) tables.insert(m.shared->specular_table.get());
    }
    return static_cast<int>(tables.size()) + pbr_basis_.table_count();
}

}  // namespace rsl
