#pragma once
// The scene's materials and their BRDF tables, shared between parts, swappable
// and editable at run time (RSL paper §4.2: the BRDF lives apart from the
// geometry, so changing it costs one table rebuild, not a precomputation).
//
// - Materials with identical model, parameters and file share one table (and
//   one Brdf), whatever their names.
// - A part's material can be swapped for any other material at any time.
// - Editing a material's parameter rebuilds (or reuses) only its table; parts
//   using other materials are untouched. revision(m) increases on every change
//   so that renderers (the GL one re-uploads) can tell what changed.
// - Invalid edits throw rsl::Error (naming the material and parameter) and
//   leave the library unchanged.
// Tables are immutable and held by shared_ptr: a renderer holding the old
// table can finish its frame while an edit swaps in the new one. The library
// itself is not synchronized: edit it from one thread between frames.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "src/brdf/brdf.h"
#include "src/brdf/brdf_table.h"
#include "src/brdf/pbr_basis.h"
#include "src/core/scene.h"

namespace rsl {

class MaterialLibrary {
public:
    explicit MaterialLibrary(BrdfTableOptions options = {});
    // All materials of the scene and every part's material.
    static MaterialLibrary from_scene(const Scene& scene, BrdfTableOptions options = {});

    // Adds a material; returns its index. Builds its table unless an identical
    // material already has one.
    int add(const MaterialDesc& desc);
    int material_count() const { return static_cast<int>(materials_.size()); }
    int find(const std::string& name) const;  // −1 if absent
    const MaterialDesc& desc(int material) const { return at(material).desc; }
    // A textured material (MaterialDesc::base_color_texture) is two lobes:
    // brdf/table are its diffuse lobe at unit texture, specular_table (null
    // otherwise) the specular lobe; renderers shade both (layered colours).
    const Brdf& brdf(int material) const { return *at(material).shared->brdf; }
    const std::shared_ptr<const BrdfTable>& table(int material) const { return at(material).shared->table; }
    const std::shared_ptr<const BrdfTable>& specular_table(int material) const {
        return at(material).shared->specular_table;
    }
    const std::shared_ptr<const Texture>& texture(int material) const { return at(material).desc.base_color_texture; }
    uint64_t revision(int material) const { return at(material).revision; }
    // A material with a metallic-roughness texture (varies_per_point) is
    // shaded from the scene's basis tables, which the library builds as its
    // materials need them (src/brdf/pbr_basis.h).
    bool varies_per_point(int material) const { return rsl::varies_per_point(at(material).desc); }
    const PbrBasisTables& pbr_basis() const { return pbr_basis_; }

    // Live editing: one parameter (scalars as 1-vectors, RGB as 3-vectors), or
    // the whole material (model included). The name is kept. "emissive" (RGB,
    // or one number) sets MaterialDesc::emissive and rebuilds no table.
    void set_parameter(int material, const std::string& key, const std::vector<float>& value);
    void replace(int material, MaterialDesc desc);

    // Parts: part p uses material part_material(p).
    void resize_parts(int parts, int material = 0);
    int part_count() const { return static_cast<int>(part_materials_.size()); }
    void assign(int part, int material);
    int part_material(int part) const;
    const BrdfTable& part_table(int part) const { return *table(part_material(part)); }
    const BrdfTable* part_specular_table(int part) const { return specular_table(part_material(part)).get(); }
    const std::shared_ptr<const Texture>& part_texture(int part) const { return texture(part_material(part)); }

    // Distinct tables alive in the library (shared ones counted once, the basis tables included).
    int distinct_table_count() const;
    // Seconds spent building the most recent table (0 when it was shared).
    double last_build_seconds() const { return last_build_seconds_; }

private:
    struct Shared {
        std::shared_ptr<const Brdf> brdf;
        std::shared_ptr<const BrdfTable> table;
        std::shared_ptr<const BrdfTable> specular_table;  // textured materials only
    };
    struct Material {
        MaterialDesc desc;
        std::shared_ptr<const Shared> shared;
        uint64_t revision = 0;
    };
    const Material& at(int material) const;
    // The shared BRDF + table for a description: reused if an identical one is
    // alive, built otherwise. Throws (before any change) on invalid parameters.
    std::shared_ptr<const Shared> obtain(const MaterialDesc& desc);
    static std::string identity(const MaterialDesc& desc);
    void require_pbr_basis(const MaterialDesc& desc);

    BrdfTableOptions options_;
    std::vector<Material> materials_;
    std::vector<int> part_materials_;
    std::map<std::string, std::weak_ptr<const Shared>> by_identity_;
    PbrBasisTables pbr_basis_;
    uint64_t next_revision_ = 1;
    double last_build_seconds_ = 0;
};

}  // namespace rsl
