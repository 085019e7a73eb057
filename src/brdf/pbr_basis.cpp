#include "src/brdf/pbr_basis.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "src/brdf/analytic.h"
#include "src/core/error.h"

namespace rsl {

namespace {

float scalar_param(const MaterialDesc& material, const char* key, float fallback) {
    const auto it = material.params.find(key);
    return it == material.params.end() || it->second.empty() ? fallback : it->second[0];
}

// gltf_pbr's α = roughness², no narrower than make_brdf's.
float pbr_alpha(float roughness) { return std::max(roughness * roughness, kMinRoughness); }

}  // namespace

PbrPoint pbr_factors(const MaterialDesc& material) {
    return {scalar_param(material, "roughness", 1.0f), scalar_param(material, "metallic", 1.0f)};
}

Color pbr_base_color(const MaterialDesc& material) {
    const auto it = material.params.find("base_color");
    if (it == material.params.end() || it->second.empty()) return Color(1);
    if (it->second.size() == 1) return Color(it->second[0]);
    return Color(it->second[0], it->second[1], it->second[2]);
}

PbrPoint pbr_point(const MaterialDesc& material, const Vec2& uv) {
    const PbrPoint factors = pbr_factors(material);
    if (!material.metallic_roughness_texture) return factors;
    const Color texel = material.metallic_roughness_texture->lookup(uv);
    return {std::clamp(factors.roughness * texel.g, 0.0f, 1.0f), std::clamp(factors.metallic * texel.b, 0.0f, 1.0f)};
}

std::vector<PbrPoint> pbr_points(const MaterialDesc& material, const TriangleMesh& mesh) {
    std::vector<PbrPoint> points(mesh.vertex_count(), pbr_factors(material));
    if (!material.metallic_roughness_texture) return points;
    if (mesh.texcoords.size() != mesh.vertex_count())
        throw_error("material '{}': its metallic-roughness texture needs texture coordinates, and the mesh has none",
                    material.name);
    for (size_t v = 0; v < points.size(); ++v) points[v] = pbr_point(material, mesh.texcoords[v]);
    return points;
}

MaterialDesc material_at_point(const MaterialDesc& material, const PbrPoint& point) {
    MaterialDesc at = material;
    at.params["roughness"] = {point.roughness};
    at.params["metallic"] = {point.metallic};
    at.metallic_roughness_texture = nullptr;
    return at;
}

std::shared_ptr<const Brdf> pbr_diffuse_lobe() {
    return std::make_shared<CookTorranceBrdf>(MicrofacetDistribution::GGX, Color(1), Color(0), 1.0f,
                                              BrdfLobe::Diffuse, "gltf_pbr");
}

std::shared_ptr<const Brdf> pbr_specular_lobe(float f0, int level) {
    return std::make_shared<CookTorranceBrdf>(MicrofacetDistribution::GGX, Color(0), Color(f0),
                                              pbr_alpha(shading::pbr_level_roughness(level)), BrdfLobe::Specular,
                                              "gltf_pbr");
}

PbrLevelRange pbr_level_range(const MaterialDesc& material) {
    const PbrPoint factors = pbr_factors(material);
    float lo = factors.roughness, hi = factors.roughness, metal = factors.metallic;
    if (const Texture* texture = material.metallic_roughness_texture.get()) {
        float g_lo = 1, g_hi = 0, b_hi = 0;
        const std::vector<float>& pixels = texture->image.pixels;
        for (size_t p = 0; p + 2 < pixels.size(); p += 3) {
            g_lo = std::min(g_lo, pixels[p + 1]);
            g_hi = std::max(g_hi, pixels[p + 1]);
            b_hi = std::max(b_hi, pixels[p + 2]);
        }
        lo = factors.roughness * g_lo, hi = factors.roughness * g_hi, metal = factors.metallic * b_hi;
    }
    const auto level_of = [](float r) { return std::clamp(r, 0.0f, 1.0f) * float(kPbrLevels - 1); };
    PbrLevelRange range;
    // A point blends its level and the next (pbr_weights); the margin covers
    // a bilinear sample rounding past the texels' largest value.
    range.first = std::min(int(std::floor(level_of(lo))), kPbrLevels - 2);
    range.last = std::min(int(std::floor(level_of(hi) + 1e-3f)) + 1, kPbrLevels - 1);
    range.metal = metal > 0.0f;
    return range;
}

double PbrBasisTables::require(const PbrLevelRange& range, const BrdfTableOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    if (!diffuse) diffuse = BrdfTable::build(*pbr_diffuse_lobe(), options);
    for (int j = range.first; j <= range.last; ++j) {
        if (!dielectric[size_t(j)])
            dielectric[size_t(j)] = BrdfTable::build(*pbr_specular_lobe(shading::kPbrDielectricF0, j), options);
        if (range.metal && !metal[size_t(j)]) metal[size_t(j)] = BrdfTable::build(*pbr_specular_lobe(1.0f, j), options);
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int PbrBasisTables::table_count() const {
    int count = diffuse ? 1 : 0;
    for (int j = 0; j < kPbrLevels; ++j) count += (dielectric[size_t(j)] ? 1 : 0) + (metal[size_t(j)] ? 1 : 0);
    return count;
}

}  // namespace rsl
