// make_brdf: scene material → model, with every parameter validated and every
// error naming the material and the parameter (docs/design/BRDF.md lists them).
#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include "src/brdf/analytic.h"
#include "src/brdf/merl.h"
#include "src/core/error.h"

namespace rsl {
namespace {

// Reads and validates one material's parameters; remembers which were used so
// that unknown (misspelled) parameters are reported, not silently ignored.
class ParamReader {
public:
    explicit ParamReader(const MaterialDesc& m) : m_(m) {}

    // RGB parameter: 3 values, or 1 value used for all channels.
    Color rgb(const std::string& key, std::optional<Color> fallback, float lo, float hi) {
        const std::vector<float>* v = find(key);
        if (!v) return required(key, fallback);
        if (v->size() != 1 && v->size() != 3)
            fail(key, fmt::format("must be an RGB triple or one number, got {} values", v->size()));
        const Color c = v->size() == 1 ? Color((*v)[0]) : Color((*v)[0], (*v)[1], (*v)[2]);
        for (int k = 0; k < 3; ++k) check_range(key, c[k], lo, hi, false);
        return c;
    }

    // Scalar parameter in [lo, hi], or (lo, hi] when lo_exclusive.
    float scalar(const std::string& key, std::optional<float> fallback, float lo, float hi, bool lo_exclusive) {
        const std::vector<float>* v = find(key);
        if (!v) return required(key, fallback);
        if (v->size() != 1) fail(key, fmt::format("must be one number, got {} values", v->size()));
        check_range(key, (*v)[0], lo, hi, lo_exclusive);
        return (*v)[0];
    }

    // kd + ks ≤ 1 per channel: each lobe has albedo ≤ its weight, so the sum stays ≤ 1.
    void check_energy(const Color& kd, const Color& ks) {
        for (int c = 0; c < 3; ++c)
            if (kd[c] + ks[c] > 1.0f + 1e-6f)
                throw_error("material '{}' ({}): kd + ks = {} in channel {} exceeds 1 (the material would "
                            "reflect more light than it receives)",
                            m_.name, m_.model, kd[c] + ks[c], "RGB"[c]);
    }

    void reject_unknown() const {
        for (auto& [key, value] : m_.params)
            if (!used_.count(key))
                throw_error("material '{}' ({}): unknown parameter '{}' (accepted: {})", m_.name, m_.model, key,
                            fmt::join(used_, ", "));
    }

private:
    const std::vector<float>* find(const std::string& key) {
        used_.insert(key);
        auto it = m_.params.find(key);
        return it == m_.params.end() ? nullptr : &it->second;
    }
    template <typename T>
    T required(const std::string& key, const std::optional<T>& fallback) {
        if (!fallback) fail(key, "is missing");
        return *fallback;
    }
    void check_range(const std::string& key, float x, float lo, float hi, bool lo_exclusive) {
        const bool ok = std::isfinite(x) && (lo_exclusive ? x > lo : x >= lo) && x <= hi;
        if (!ok) fail(key, fmt::format("must be in {}{}, {}] (got {})", lo_exclusive ? "(" : "[", lo, hi, x));
    }
    [[noreturn]] void fail(const std::string& key, const std::string& what) const {
        throw_error("material '{}' ({}): parameter '{}' {}", m_.name, m_.model, key, what);
    }

    const MaterialDesc& m_;
    std::set<std::string> used_;
};

constexpr float kMaxExponent = 1e5f;  // beyond this the lobe is narrower than any table texel by far
constexpr float kMaxRoughness = 1.0f;
// The narrowest lobe any model gets: already far narrower than a table texel
// (docs/design/BRDF.md), and below about 1e-19 the models' 1/α² overflows to
// Inf and their pixels to NaN. glTF allows roughness 0 (a mirror), so
// gltf_pbr's α = roughness² stops here silently; the other models warn.
constexpr float kMinGltfAlpha = kMinRoughness;

// A roughness below kMinRoughness, raised to it with a warning.
float at_least_min_roughness(const MaterialDesc& m, const char* key, float value) {
    if (value >= kMinRoughness) return value;
    warn("material '{}' ({}): parameter '{}' {:g} is below {:g}, the narrowest lobe the BRDF tables resolve; "
         "using {:g}", m.name, m.model, key, value, kMinRoughness, kMinRoughness);
    return kMinRoughness;
}

std::shared_ptr<const Brdf> build(const MaterialDesc& m, ParamReader& p, BrdfLobe lobe) {
    const std::string& model = m.model;
    if (model == "gltf_pbr") {
        // glTF 2.0's defaults: a white, fully metallic, fully rough surface.
        const Color base = p.rgb("base_color", Color(1), 0, 1);
        const float metallic = p.scalar("metallic", 1.0f, 0, 1, false);
        const float roughness = p.scalar("roughness", 1.0f, 0, kMaxRoughness, false);
        const Color kd = base * (1.0f - metallic);
        const Color f0 = glm::mix(Color(0.04f), base, metallic);
        return std::make_shared<CookTorranceBrdf>(MicrofacetDistribution::GGX, kd, f0,
                                                  std::max(roughness * roughness, kMinGltfAlpha), lobe, model);
    }
    if (lobe != BrdfLobe::Both)
        throw_error("material '{}' ({}): only gltf_pbr materials take a base colour texture", m.name, model);
    if (model == "lambert") return std::make_shared<LambertBrdf>(p.rgb("albedo", std::nullopt, 0, 1));
    if (model == "phong" || model == "blinn_phong") {
        const Color kd = p.rgb("kd", Color(0), 0, 1), ks = p.rgb("ks", std::nullopt, 0, 1);
        const float n = p.scalar("exponent", std::nullopt, 0, kMaxExponent, false);
        p.check_energy(kd, ks);
        if (model == "phong") return std::make_shared<PhongBrdf>(kd, ks, n);
        return std::make_shared<BlinnPhongBrdf>(kd, ks, n);
    }
    if (model == "cook_torrance_beckmann" || model == "cook_torrance_ggx") {
        const Color kd = p.rgb("kd", Color(0), 0, 1), f0 = p.rgb("f0", std::nullopt, 0, 1);
        const float roughness =
            at_least_min_roughness(m, "roughness", p.scalar("roughness", std::nullopt, 0, kMaxRoughness, true));
        const auto d = model == "cook_torrance_ggx" ? MicrofacetDistribution::GGX : MicrofacetDistribution::Beckmann;
        return std::make_shared<CookTorranceBrdf>(d, kd, f0, roughness);
    }
    if (model == "ward" || model == "ward_anisotropic") {
        const Color kd = p.rgb("kd", Color(0), 0, 1), ks = p.rgb("ks", std::nullopt, 0, 1);
        p.check_energy(kd, ks);
        if (model == "ward") {
            const float a = at_least_min_roughness(m, "alpha", p.scalar("alpha", std::nullopt, 0, kMaxRoughness, true));
            return std::make_shared<WardBrdf>(kd, ks, a, a, true);
        }
        const float ax =
            at_least_min_roughness(m, "alpha_x", p.scalar("alpha_x", std::nullopt, 0, kMaxRoughness, true));
        const float ay =
            at_least_min_roughness(m, "alpha_y", p.scalar("alpha_y", std::nullopt, 0, kMaxRoughness, true));
        return std::make_shared<WardBrdf>(kd, ks, ax, ay, false);
    }
    if (model == "merl") {
        if (m.file.empty()) throw_error("material '{}' (merl): the measured BRDF 'file' is missing", m.name);
        return MerlBrdf::load(m.file);
    }
    throw_error("material '{}': unknown BRDF model '{}' (known: {})", m.name, model,
                fmt::join(brdf_model_names(), ", "));
}

}  // namespace

const std::vector<std::string>& brdf_model_names() {
    static const std::vector<std::string> names = {"lambert", "phong", "blinn_phong", "cook_torrance_beckmann",
                                                   "cook_torrance_ggx", "ward", "ward_anisotropic", "merl",
                                                   "gltf_pbr"};
    return names;
}

std::shared_ptr<const Brdf> make_brdf(const MaterialDesc& material) {
    ParamReader params(material);
    auto brdf = build(material, params, BrdfLobe::Both);
    params.reject_unknown();
    return brdf;
}

BrdfLobes make_brdf_lobes(const MaterialDesc& material) {
    ParamReader diffuse_params(material), specular_params(material);
    BrdfLobes lobes{build(material, diffuse_params, BrdfLobe::Diffuse),
                    build(material, specular_params, BrdfLobe::Specular)};
    diffuse_params.reject_unknown();
    return lobes;
}

std::vector<std::shared_ptr<const Brdf>> make_scene_brdfs(const Scene& scene) {
    std::vector<std::shared_ptr<const Brdf>> brdfs;
    for (const MaterialDesc& material : scene.materials) {
        try {
            brdfs.push_back(make_brdf(material));
        } catch (const Error& e) {
            if (scene.source.empty()) throw;
            throw_file_error(scene.source, "{}", e.what());
        }
    }
    return brdfs;
}

}  // namespace rsl
