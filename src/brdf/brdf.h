#pragma once
// BRDF models, shared by every renderer. ρ(ω_i, ω_o) is evaluated in the local
// shading frame (z = normal, x = tangent for anisotropic models), *without*
// the cosine: renderers fold in cos θ_i themselves.
//
// Models and their parameters are described in docs/design/BRDF.md; the concrete
// classes are in analytic.h (closed-form models) and merl.h (measured).
#include <memory>
#include <string>
#include <vector>

#include "src/core/math.h"
#include "src/core/scene.h"

namespace rsl {

class Brdf {
public:
    virtual ~Brdf() = default;
    // ω_i, ω_o unit, local frame. Returns 0 when either is below the horizon.
    virtual Color eval(const Vec3& wi, const Vec3& wo) const = 0;
    // Isotropic models depend on φ_i − φ_o only (3D tables); others need 4D tables.
    virtual bool isotropic() const = 0;
    virtual std::string model() const = 0;
    // A constant part a of ρ (ρ = a + the rest), what the renderers shade
    // with the environment's exact irradiance (docs/design/RENDERER.md
    // "Exact diffuse light"); 0 for models without one.
    virtual Color constant_part() const { return Color(0); }
};

// The smallest roughness (Cook–Torrance) or alpha (Ward) a model gets:
// make_brdf raises a smaller one in (0, kMinRoughness) to it, with a warning
// (rsl::warn), since narrower lobes overflow to NaN (docs/design/BRDF.md).
inline constexpr float kMinRoughness = 1e-3f;

// Builds a model from a scene material; throws rsl::Error naming the material
// and the bad parameter (unknown model, missing/out-of-range value).
std::shared_ptr<const Brdf> make_brdf(const MaterialDesc& material);
// A textured material's BRDF in two lobes (MaterialDesc::base_color_texture):
// the diffuse one, which the texture multiplies per pixel, and the specular
// one; their sum is make_brdf's. Only gltf_pbr splits (others throw).
struct BrdfLobes {
    std::shared_ptr<const Brdf> diffuse, specular;
};
BrdfLobes make_brdf_lobes(const MaterialDesc& material);
// make_brdf for every material of a scene, in order; errors also name the
// scene file ("scene.json: material 'm' (phong): parameter ...").
std::vector<std::shared_ptr<const Brdf>> make_scene_brdfs(const Scene& scene);

// The model names make_brdf accepts (the `model` key of a scene material).
const std::vector<std::string>& brdf_model_names();

// Mirror direction of ω about the normal (z) in the local frame.
inline Vec3 mirror_about_normal(const Vec3& w) { return Vec3(-w.x, -w.y, w.z); }

}  // namespace rsl
