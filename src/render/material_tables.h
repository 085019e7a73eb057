#pragma once
// The BRDF summed-area table of every part, built once per material and
// shared by all the parts that use it; a per-part override swaps in another
// scene material (RenderOptions::material_override).
#include <memory>
#include <string>
#include <vector>

#include "src/brdf/brdf_table.h"
#include "src/core/scene.h"
#include "src/render/render_options.h"

namespace rsl {

class MaterialTables {
public:
    // Builds the tables of the materials the parts use (after overrides).
    // Throws rsl::Error naming the scene file for an unknown part or material.
    MaterialTables(const Scene& scene, const RenderOptions& options);

    // Material index (into Scene::materials) a part is shaded with.
    int material_of(int part) const { return part_material_[part]; }
    const BrdfTable& table_of(int part) const { return *tables_[part_material_[part]]; }
    // Number of distinct tables built.
    size_t table_count() const;
    size_t memory_bytes() const;

private:
    std::vector<int> part_material_;
    std::vector<std::shared_ptr<const BrdfTable>> tables_;  // per scene material, null when unused
};

}  // namespace rsl
