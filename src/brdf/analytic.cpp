#include "src/brdf/analytic.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rsl {
namespace {

bool above_horizon(const Vec3& wi, const Vec3& wo) { return wi.z > 0.0f && wo.z > 0.0f; }

// Unit half vector (ω_i = −ω_o is impossible above the horizon).
Vec3 half_vector(const Vec3& wi, const Vec3& wo) { return glm::normalize(wi + wo); }

// Lobes far from their peak underflow to float denormals, where exp/pow take
// a slow path (~10× slower); anything below e^−80 ≈ 2e−35 is 0 for us.
constexpr float kUnderflowExponent = -80.0f;
inline float exp_or_zero(float x) { return x < kUnderflowExponent ? 0.0f : std::exp(x); }
inline float pow_or_zero(float base, float exponent) {
    if (base <= 0.0f) return exponent == 0.0f ? 1.0f : 0.0f;
    return exp_or_zero(exponent * std::log(base));
}

}  // namespace

Color LambertBrdf::eval(const Vec3& wi, const Vec3& wo) const {
    return above_horizon(wi, wo) ? albedo_ * kInvPi : Color(0.0f);
}

PhongBrdf::PhongBrdf(const Color& kd, const Color& ks, float exponent)
    : diffuse_(kd * kInvPi), specular_(ks * ((exponent + 2.0f) / (2.0f * kPi))), exponent_(exponent) {}

Color PhongBrdf::eval(const Vec3& wi, const Vec3& wo) const {
    if (!above_horizon(wi, wo)) return Color(0.0f);
    const float cos_alpha = std::max(glm::dot(wi, mirror_about_normal(wo)), 0.0f);
    return diffuse_ + specular_ * pow_or_zero(cos_alpha, exponent_);
}

double BlinnPhongBrdf::normalization(double n) {
    // Albedo of cos^n θ_h at normal view: 2π ∫ cos^n(θ/2) cosθ sinθ dθ over [0, π/2]
    // = 2π · 4 ∫_{1/√2}^{1} u^{n+1} (2u² − 1) du (u = cos(θ/2)), in closed form.
    const double s = std::sqrt(0.5);
    const double integral =
        4.0 * (2.0 * (1.0 - std::pow(s, n + 4.0)) / (n + 4.0) - (1.0 - std::pow(s, n + 2.0)) / (n + 2.0));
    return 1.0 / (2.0 * std::numbers::pi * integral);
}

BlinnPhongBrdf::BlinnPhongBrdf(const Color& kd, const Color& ks, float exponent)
    : diffuse_(kd * kInvPi), specular_(ks * static_cast<float>(normalization(exponent))), exponent_(exponent) {}

Color BlinnPhongBrdf::eval(const Vec3& wi, const Vec3& wo) const {
    if (!above_horizon(wi, wo)) return Color(0.0f);
    const float cos_h = std::max(half_vector(wi, wo).z, 0.0f);
    return diffuse_ + specular_ * pow_or_zero(cos_h, exponent_);
}

CookTorranceBrdf::CookTorranceBrdf(MicrofacetDistribution distribution, const Color& kd, const Color& f0,
                                   float roughness, BrdfLobe lobe, std::string model_name)
    : distribution_(distribution),
      kd_over_pi_(kd * kInvPi),
      f0_(f0),
      alpha_(roughness),
      lobe_(lobe),
      model_name_(std::move(model_name)) {}

std::string CookTorranceBrdf::model() const {
    if (!model_name_.empty()) return model_name_;
    return distribution_ == MicrofacetDistribution::Beckmann ? "cook_torrance_beckmann" : "cook_torrance_ggx";
}

Color CookTorranceBrdf::constant_part() const {
    if (lobe_ == BrdfLobe::Specular) return Color(0);
    const Color transmitted = Color(1.0f) - f0_;
    return kd_over_pi_ * transmitted * transmitted;
}

float CookTorranceBrdf::distribution(float cos_h) const {
    if (cos_h <= 0.0f) return 0.0f;
    const float c2 = cos_h * cos_h, a2 = alpha_ * alpha_;
    if (distribution_ == MicrofacetDistribution::Beckmann) {
        const float tan2 = (1.0f - c2) / c2;
        return exp_or_zero(-tan2 / a2) / (kPi * a2 * c2 * c2);
    }
    const float denom = c2 * (a2 - 1.0f) + 1.0f;
    return a2 / (kPi * denom * denom);
}

float CookTorranceBrdf::smith_lambda(float cos_theta) const {
    const float c2 = cos_theta * cos_theta;
    const float tan2 = std::max(1.0f - c2, 0.0f) / c2;
    if (tan2 == 0.0f) return 0.0f;
    if (distribution_ == MicrofacetDistribution::Beckmann) {
        // Exact Beckmann Λ (Walter et al. 2007): a = 1 / (α tanθ).
        const float a = 1.0f / (alpha_ * std::sqrt(tan2));
        if (a > 4.0f) return 0.0f;  // erf(a) = 1 in float and exp(−a²)/(2a√π) < 2e−8: Λ is 0
        return 0.5f * (std::erf(a) - 1.0f) + std::exp(-a * a) / (2.0f * a * std::sqrt(kPi));
    }
    return 0.5f * (std::sqrt(1.0f + alpha_ * alpha_ * tan2) - 1.0f);
}

Color CookTorranceBrdf::fresnel(float cos_theta) const {
    const float m = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
    const float m2 = m * m;
    return f0_ + (Color(1.0f) - f0_) * (m2 * m2 * m);
}

Color CookTorranceBrdf::eval(const Vec3& wi, const Vec3& wo) const {
    if (!above_horizon(wi, wo)) return Color(0.0f);
    Color rho(0.0f);
    if (lobe_ != BrdfLobe::Diffuse) {
        const Vec3 h = half_vector(wi, wo);
        const float g = 1.0f / (1.0f + smith_lambda(wi.z) + smith_lambda(wo.z));
        rho += fresnel(glm::dot(wi, h)) * (distribution(h.z) * g / (4.0f * wi.z * wo.z));
    }
    if (lobe_ != BrdfLobe::Specular)
        rho += kd_over_pi_ * (Color(1.0f) - fresnel(wi.z)) * (Color(1.0f) - fresnel(wo.z));
    return rho;
}

WardBrdf::WardBrdf(const Color& kd, const Color& ks, float alpha_x, float alpha_y, bool isotropic_model)
    : diffuse_(kd * kInvPi),
      specular_(ks / (kPi * alpha_x * alpha_y)),
      inv_ax2_(1.0f / (alpha_x * alpha_x)),
      inv_ay2_(1.0f / (alpha_y * alpha_y)),
      isotropic_(isotropic_model) {}

Color WardBrdf::eval(const Vec3& wi, const Vec3& wo) const {
    if (!above_horizon(wi, wo)) return Color(0.0f);
    const Vec3 h = wi + wo;  // unnormalized: the exponent is scale-invariant, h·h / h_z⁴ is not
    const float hz2 = h.z * h.z;
    const float exponent = -(h.x * h.x * inv_ax2_ + h.y * h.y * inv_ay2_) / hz2;
    return diffuse_ + specular_ * (exp_or_zero(exponent) * glm::dot(h, h) / (hz2 * hz2));
}

}  // namespace rsl
