#pragma once
// The tables of gltf_pbr materials whose roughness and metallic vary over a
// surface (a metallicRoughnessTexture): the grey basis lobes of
// src/shading/pbr_basis.h, shared by every such material of a scene, and the
// per-point inputs the renderers and the truth read from the texture
// (docs/design/BRDF.md "Textured roughness and metallic").
#include <array>
#include <memory>
#include <vector>

#include "src/brdf/brdf.h"
#include "src/brdf/brdf_table.h"
#include "src/core/scene.h"
#include "src/shading/pbr_basis.h"

namespace rsl {

using shading::kPbrLevels;

// Roughness and metallic at a point: the factors times the texture's G and B.
struct PbrPoint {
    float roughness = 1.0f;
    float metallic = 1.0f;
};

// Whether a material's roughness and metallic vary per point.
inline bool varies_per_point(const MaterialDesc& material) {
    return material.model == "gltf_pbr" && material.metallic_roughness_texture != nullptr;
}
// The material's factors (the scene material's `roughness`, `metallic`; glTF's 1 when absent).
PbrPoint pbr_factors(const MaterialDesc& material);
// The material's base colour factor (`base_color`; 1 when absent).
Color pbr_base_color(const MaterialDesc& material);
// At texture coordinates uv (the texture's filter and wrap modes).
PbrPoint pbr_point(const MaterialDesc& material, const Vec2& uv);
// Per vertex of a mesh with texture coordinates (one per vertex).
std::vector<PbrPoint> pbr_points(const MaterialDesc& material, const TriangleMesh& mesh);
// The material with its roughness and metallic set to a point's: what the
// truth integrates there.
MaterialDesc material_at_point(const MaterialDesc& material, const PbrPoint& point);

// The basis lobes: D, and S(f0, roughness of level j) for f0 = 0.04 or 1.
std::shared_ptr<const Brdf> pbr_diffuse_lobe();
std::shared_ptr<const Brdf> pbr_specular_lobe(float f0, int level);

// What a material's texture can reach: the roughness levels (first..last)
// and whether any texel is metallic (S(1, ·) needed).
struct PbrLevelRange {
    int first = 0, last = -1;
    bool metal = false;
};
PbrLevelRange pbr_level_range(const MaterialDesc& material);

// The scene's basis tables; a level's tables are null until a material needs them.
struct PbrBasisTables {
    std::shared_ptr<const BrdfTable> diffuse;
    std::array<std::shared_ptr<const BrdfTable>, kPbrLevels> dielectric{}, metal{};
    // Builds what `range` needs and is missing; returns the seconds spent.
    double require(const PbrLevelRange& range, const BrdfTableOptions& options);
    int table_count() const;
};

}  // namespace rsl
