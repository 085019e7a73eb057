#include "src/brdf/table_resolution.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "src/core/hemisphere.h"

namespace rsl {
namespace {

constexpr float kMaxViewTheta = glm::radians(60.0f);

// The exact average of ρ·cos θ_i over the plane square (the map is equal-area,
// so a plane average is a solid-angle average).
float exact_square_average(const Brdf& brdf, const Vec3& view, const Vec2& center, float half_edge) {
    constexpr int kPoints = 8;
    double sum = 0;
    for (int j = 0; j < kPoints; ++j)
        for (int i = 0; i < kPoints; ++i) {
            const Vec2 p = center + half_edge * Vec2(-1 + (2 * i + 1.0f) / kPoints, -1 + (2 * j + 1.0f) / kPoints);
            if (glm::dot(p, p) >= 1) continue;  // below the horizon: the table counts 0 there too
            const Vec3 wi = plane_to_hemisphere(p);
            const Color f = brdf.eval(wi, view) * std::max(wi.z, 0.0f);
            sum += double(f.r) + f.g + f.b;
        }
    return float(sum / (kPoints * kPoints));
}

}  // namespace

TablePeakError table_peak_error(const BrdfTable& table, const Brdf& brdf) {
    TablePeakError worst;
    // View plane points at and halfway between tabulated views: isotropic
    // tables at radii (k + ½)/V in the view-aligned frame (the view on +y);
    // anisotropic ones on the V×V grid of the tangent frame, along x, y and
    // the diagonal.
    const int v = table.isotropic() ? table.options().view_samples
                                    : std::min(table.options().view_samples, table.options().anisotropic_view_samples);
    const float spacing = table.isotropic() ? 1.0f / v : 2.0f / v;
    const float max_radius = std::sqrt(2.0f) * std::sin(kMaxViewTheta / 2);
    std::vector<Vec2> directions{Vec2(0, 1)};
    if (!table.isotropic()) directions = {Vec2(1, 0), Vec2(0, 1), glm::normalize(Vec2(1, 1))};
    const float half_edge = table.grid().texel_size() / 8;  // a quarter of a texel wide
    for (const Vec2& direction : directions)
        for (float r = spacing / 2; r <= max_radius; r += spacing / 2) {
            const Vec2 view_point = r * direction;
            const Vec3 view = plane_to_hemisphere(view_point);
            const Vec2 center = -view_point;  // the mirror direction (−x, −y, z)
            const float exact = exact_square_average(brdf, view, center, half_edge);
            if (!(exact > 0)) continue;
            const Color t = table.square_average(center, half_edge, view);
            const float error = std::abs(t.r + t.g + t.b - exact) / exact;
            if (error > worst.relative_error) worst = {error, glm::degrees(std::acos(std::clamp(view.z, -1.0f, 1.0f)))};
        }
    return worst;
}

std::string sharp_material_warning(const MaterialDesc& material, const BrdfTable& table, const TablePeakError& error) {
    if (!(error.relative_error > kTablePeakErrorLimit)) return "";
    // The error falls with the lobe's angular width σ at least as 1/σ
    // (measured at the default table: GGX α 0.04 → 0.07, 27% → 11%, σ^−1.6;
    // α 0.0144 → 0.0625, 72% → 13%, σ^−1.2), and σ grows with roughness or
    // alpha, with roughness² for gltf_pbr, and as 1/√exponent.
    const float widen = error.relative_error / kTablePeakErrorLimit;
    std::string advice;
    const auto param = [&](const char* name) -> float {
        const auto it = material.params.find(name);
        return it == material.params.end() || it->second.empty() ? -1.0f : it->second[0];
    };
    if (material.model == "gltf_pbr" && param("roughness") >= 0)
        advice = fmt::format("roughness {:.2g} or more", std::min(1.0f, param("roughness") * std::sqrt(widen)));
    else if (param("roughness") > 0)
        advice = fmt::format("roughness {:.2g} or more", std::min(1.0f, param("roughness") * widen));
    else if (param("alpha") > 0)
        advice = fmt::format("alpha {:.2g} or more", std::min(1.0f, param("alpha") * widen));
    else if (param("alpha_x") > 0 && param("alpha_y") > 0)
        advice = fmt::format("alpha_x, alpha_y {:.2g}, {:.2g} or more", std::min(1.0f, param("alpha_x") * widen),
                             std::min(1.0f, param("alpha_y") * widen));
    else if (param("exponent") > 0)
        advice = fmt::format("exponent {:.3g} or less", param("exponent") / (widen * widen));
    const int n = table.grid().n;
    const float texel_degrees = glm::degrees(std::sqrt(kSolidAnglePerPlaneArea) * table.grid().texel_size());
    return fmt::format(
        "material '{}' ({}): its highlight is sharper than the BRDF table resolves ({}² texels of about {:.1f}°, {} "
        "views): under a small light such as a sun it is off by up to {:.0f}% (view {:.0f}° from the normal); give it "
        "a wider lobe{}{}, or a finer table (docs/design/BRDF.md, \"Table resolution\")",
        material.name, material.model, n, texel_degrees, table.slice_count(), 100 * error.relative_error,
        error.view_theta_degrees, advice.empty() ? "" : ": ", advice);
}

}  // namespace rsl
