// env-rays: Monte Carlo with the map's and the BRDF's importance sampling,
// multiple importance sampling and Embree shadow rays (environment_rays.h).
#include "src/trace/environment_rays.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "src/core/error.h"
#include "src/formats/scene_environment.h"
#include "src/core/sphere_light.h"
#include "src/trace/sample_sequence.h"
#include "src/trace/shadow_batch.h"

namespace rsl {

namespace {

// Dimensions of a point's random numbers (sample_bits): each draw its own.
constexpr uint32_t kTechniqueDimension = 0;  // ξ, which samples come from the BRDF
constexpr uint32_t kEnvironmentDimension = 1;
constexpr uint32_t kBrdfDimension = 2;
constexpr uint32_t kSliceDimension = 3;  // the BRDF slice (u2)
constexpr uint32_t kFirstLightDimension = 16;

// A pixel sample's stream is kept apart from every vertex stream.
constexpr uint64_t kPixelStreamBit = 1ull << 62;

bool is_black(const Color& c) { return !(c.r > 0.0f || c.g > 0.0f || c.b > 0.0f); }

// The bits of a direction, hashed: distinct primary rays, distinct streams.
uint64_t direction_stream(const Vec3& d) {
    uint32_t bits[3];
    static_assert(sizeof(bits) == sizeof(float) * 3);
    std::memcpy(&bits[0], &d.x, 4), std::memcpy(&bits[1], &d.y, 4), std::memcpy(&bits[2], &d.z, 4);
    return mix64(mix64((uint64_t(bits[0]) << 32) | bits[1]) ^ bits[2]);
}

}  // namespace

EnvironmentRays::EnvironmentRays(const Scene& scene, const CubeMap& environment, float t,
                                 EnvironmentRaysOptions options)
    : scene_(scene), options_(options), posed_(scene, t), lobes_(scene), environment_(environment) {
    if (options_.samples < 1 || options_.samples > EnvironmentRaysOptions::kMaxSamples)
        throw_error("env-rays: {} samples per point, outside [1, {}]", options_.samples,
                    EnvironmentRaysOptions::kMaxSamples);
    if (!(options_.brdf_sampling_share >= 0.0f && options_.brdf_sampling_share <= 1.0f))
        throw_error("env-rays: BRDF sampling share {} is outside [0, 1]", options_.brdf_sampling_share);
    // Tables for every lobe a part shades with (each built once).
    for (const auto* lobes : {&lobes_.lobe, &lobes_.specular})
        for (const auto& brdf : *lobes)
            if (brdf && std::find(sampled_brdfs_.begin(), sampled_brdfs_.end(), brdf.get()) == sampled_brdfs_.end()) {
                sampled_brdfs_.push_back(brdf.get());
                brdf_samplers_.push_back(std::make_unique<BrdfSampler>(*brdf, options_.brdf_sampler));
            }
    set_time(t);
}

EnvironmentRays::~EnvironmentRays() = default;

void EnvironmentRays::set_time(float t) {
    if (posed_.time() != t) posed_.set_time(t);
    rotation_ = scene_.environment.rotation_at(t);
    inverse_rotation_ = glm::transpose(rotation_);  // a rotation: its transpose turns back
    // Suns turn with the map, as the truth's (GroundTruth::set_time).
    sun_directions_.clear();
    for (const SunLight& sun : scene_.environment.suns)
        sun_directions_.push_back(glm::normalize(rotation_ * sun_direction_in_map(scene_, sun)));
    lights_.set(scene_, t);
    camera_ = scene_.camera.position_at(t);
}

const BrdfSampler& EnvironmentRays::brdf_sampler(const Brdf& brdf) const {
    const auto it = std::find(sampled_brdfs_.begin(), sampled_brdfs_.end(), &brdf);
    if (it == sampled_brdfs_.end()) throw_error("env-rays: a BRDF that is none of the scene's lobes");
    return *brdf_samplers_[size_t(it - sampled_brdfs_.begin())];
}

// A stream's points in one dimension: the scrambled Sobol sequence, or
// (unstratified) independent pairs.
class EnvironmentRays::Points {
public:
    Points(const EnvironmentRaysOptions& options, uint64_t stream, uint32_t dimension)
        : sobol_(options.seed, stream, dimension), stratified_(options.stratified), seed_(options.seed),
          stream_(stream), dimension_(dimension) {}
    UnitPair operator[](uint32_t index) const {
        return stratified_ ? sobol_.point(index) : independent_pair(seed_, stream_, index, dimension_);
    }

private:
    ScrambledSobol sobol_;
    bool stratified_;
    uint64_t seed_, stream_;
    uint32_t dimension_;
};

Color EnvironmentRays::shade(const SurfacePoint& x, const Vec3& wo_world, const Brdf& brdf, uint64_t stream,
                             const Brdf* proposal) const {
    const Vec3 wo = x.frame.to_local(wo_world);
    // ρ is zero for a view below the shading horizon (Brdf contract): no rays.
    if (!(wo.z > 0.0f)) return Color(0);
    const Vec3 origin = x.ray_origin();
    ShadowBatch batch(posed_.rays(), origin);
    if (options_.environment) {
        shade_environment(x, wo, brdf, brdf_sampler(proposal ? *proposal : brdf), stream, batch);
        shade_suns(x, wo, brdf, batch);
    }
    if (options_.local_lights)
        for (size_t i = 0; i < scene_.lights.size(); ++i) {
            // A spot's cone scales the light by the direction from its centre to x.
            const float cone = spot_cone_factor_at(x.position, lights_.positions[i], lights_.axes[i], lights_.cones[i]);
            if (!(cone > 0.0f)) continue;
            shade_light(x, origin, wo, brdf, i, sphere_light_radiance(scene_.lights[i]) * cone, stream, batch);
        }
    const Color result(batch.flush_and_sum());
    rays_traced_.fetch_add(batch.rays(), std::memory_order_relaxed);
    return result;
}

// The map's integral: N samples, ⌈c_b·N − ξ⌉ of them from the BRDF (the
// first ones), the rest from the map, each weighted by the balance heuristic.
void EnvironmentRays::shade_environment(const SurfacePoint& x, const Vec3& wo, const Brdf& brdf,
                                        const BrdfSampler& sampler, uint64_t stream, ShadowBatch& batch) const {
    if (environment_.empty()) return;  // a black map: nothing to integrate
    const float brdf_share = sampler.empty() ? 0.0f : options_.brdf_sampling_share;
    const float environment_share = 1.0f - brdf_share;
    const BrdfSampler::View view = sampler.empty() ? BrdfSampler::View{} : sampler.view(wo);
    const int n = options_.samples;
    const double shift = unit_from_bits(sample_bits(options_.seed, stream, 0, kTechniqueDimension));
    const int brdf_samples = std::clamp(int(std::ceil(double(brdf_share) * n - shift)), 0, n);
    const float per_sample = 1.0f / float(n);
    const Points brdf_points(options_, stream, kBrdfDimension), environment_points(options_, stream, kEnvironmentDimension);
    for (int i = 0; i < n; ++i) {
        const bool from_brdf = i < brdf_samples;
        const uint32_t index = uint32_t(from_brdf ? i : i - brdf_samples);
        const auto [u0, u1] = from_brdf ? brdf_points[index] : environment_points[index];
        Vec3 dir, wi;
        Color radiance;
        float pdf_environment, pdf_brdf = 0.0f;
        if (from_brdf) {
            const double u2 = unit_from_bits(sample_bits(options_.seed, stream, index, kSliceDimension));
            if (!sampler.sample(view, u0, u1, u2, wi, pdf_brdf)) continue;  // below the horizon: 0
            dir = x.frame.to_world(wi);
            pdf_environment = environment_.lookup(inverse_rotation_ * dir, radiance);
            if (is_black(radiance)) continue;
        } else {
            const EnvironmentSampler::Sample s = environment_.sample(u0, u1);
            dir = rotation_ * s.direction;
            wi = x.frame.to_local(dir);
            radiance = s.radiance, pdf_environment = s.pdf;
            if (wi.z <= 0.0f) continue;
            if (brdf_share > 0.0f) pdf_brdf = sampler.pdf(view, wi);
        }
        // The truth's horizons: ρ·cos is 0 below the shading one; below the
        // geometric side the ray would enter the surface (occluded).
        if (wi.z <= 0.0f || glm::dot(dir, x.offset_normal) <= 0.0f) continue;
        const float density = environment_share * pdf_environment + brdf_share * pdf_brdf;
        if (!(density > 0.0f)) continue;
        const Color f = brdf.eval(wi, wo) * radiance * (wi.z * per_sample / density);
        if (is_black(f)) continue;
        batch.add(dir, f);
    }
}

// Each sun, a direction of irradiance E: one ray, as the truth.
void EnvironmentRays::shade_suns(const SurfacePoint& x, const Vec3& wo, const Brdf& brdf, ShadowBatch& batch) const {
    for (size_t k = 0; k < sun_directions_.size(); ++k) {
        const Vec3& dir = sun_directions_[k];
        const Vec3 wi = x.frame.to_local(dir);
        if (wi.z <= 0.0f || glm::dot(dir, x.offset_normal) <= 0.0f) continue;
        const Color f = brdf.eval(wi, wo) * (wi.z * scene_.environment.suns[k].irradiance);
        if (!is_black(f)) batch.add(dir, f);
    }
}

// N samples uniform in the cone the sphere subtends (pdf 1/Ω_cone):
// cos θ' = 1 − u (1 − cos α), φ = 2π v, (u, v) stratified; each ray ends
// where it meets the light's surface, as the truth's (GroundTruth::shade_light).
void EnvironmentRays::shade_light(const SurfacePoint& x, const Vec3& origin, const Vec3& wo, const Brdf& brdf,
                                  size_t light, const Color& radiance, uint64_t stream, ShadowBatch& batch) const {
    const Vec3 center = lights_.positions[light];
    const float radius = scene_.lights[light].radius;
    const Vec3 to_center = center - origin;
    const float distance = glm::length(to_center);
    if (!(distance > radius)) return;  // inside the light: not a surface it lights
    const Frame cone = Frame::from_normal(to_center / distance);
    const float sin2_alpha = (radius / distance) * (radius / distance);
    const float cos_alpha = std::sqrt(std::max(0.0f, 1.0f - sin2_alpha));
    const float one_minus_cos_alpha = sin2_alpha / (1.0f + cos_alpha);  // no cancellation
    const float weight = 2.0f * kPi * one_minus_cos_alpha / float(options_.samples);  // Ω_cone / N
    const Points points(options_, stream, kFirstLightDimension + uint32_t(light));
    for (int i = 0; i < options_.samples; ++i) {
        const auto [u, v] = points[uint32_t(i)];
        const float cos_theta = 1.0f - float(u) * one_minus_cos_alpha;
        const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
        const float phi = 2.0f * kPi * float(v);
        const Vec3 dir = cone.to_world(Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta));
        const Vec3 wi = x.frame.to_local(dir);
        if (wi.z <= 0.0f || glm::dot(dir, x.offset_normal) <= 0.0f) continue;
        const Color f = brdf.eval(wi, wo) * (wi.z * weight * radiance);
        if (is_black(f)) continue;
        const float b = distance * cos_theta;  // the nearer root: where the ray meets the sphere
        const float t_far = b - std::sqrt(std::max(0.0f, radius * radius - distance * distance + b * b));
        batch.add(dir, f, t_far);
    }
}

Color EnvironmentRays::shade_hit(const RayHit& hit, const Vec3& ray_direction, uint64_t pixel_stream) const {
    const SurfacePoint x = posed_.hit_point(hit, ray_direction);
    const uint64_t stream = pixel_stream | kPixelStreamBit;
    const Color emission = hit_emission(scene_, hit);
    const Brdf* specular = part_specular_brdf(hit.instance);
    const int material = scene_.parts[size_t(hit.instance)].material;
    if (lobes_.varies[size_t(material)]) {  // roughness and metallic at the hit
        const Vec2 uv = interpolate_texcoords(scene_, hit);
        const Color reflected =
            shade(x, -ray_direction, *lobes_.at_point(scene_, material, uv, false), stream, &part_brdf(hit.instance));
        if (!specular) return reflected + emission;
        return reflected * scene_.materials[size_t(material)].base_color_texture->lookup(uv) +
               shade(x, -ray_direction, *lobes_.at_point(scene_, material, uv, true), specular_stream(stream), specular) +
               emission;
    }
    if (!specular) return shade(x, -ray_direction, part_brdf(hit.instance), stream) + emission;
    const Texture& texture = *scene_.materials[size_t(scene_.parts[size_t(hit.instance)].material)].base_color_texture;
    return shade(x, -ray_direction, part_brdf(hit.instance), stream) * texture.lookup(interpolate_texcoords(scene_, hit)) +
           shade(x, -ray_direction, *specular, specular_stream(stream)) + emission;
}

HitShader EnvironmentRays::hit_shader() const {
    return [this](const RayHit& hit, const Vec3& ray_direction) {
        return shade_hit(hit, ray_direction, direction_stream(ray_direction));
    };
}

VertexColors EnvironmentRays::shade_vertices(const ProgressCallback& progress) const {
    return shade_every_vertex(scene_, lobes_, "env-rays", time(), 16, [&](int part, int vertex, bool specular) {
        const SurfacePoint x = posed_.vertex(part, vertex);
        const Vec3 wo = glm::normalize(camera_ - x.position);
        const uint64_t stream = vertex_stream(part, vertex);
        if (const int m = scene_.parts[size_t(part)].material; lobes_.varies[size_t(m)]) {
            const Vec2 uv = scene_.parts[size_t(part)].mesh.texcoords[size_t(vertex)];
            return shade(x, wo, *lobes_.at_point(scene_, m, uv, specular), specular ? specular_stream(stream) : stream,
                         specular ? part_specular_brdf(part) : &part_brdf(part));
        }
        return specular ? shade(x, wo, *part_specular_brdf(part), specular_stream(stream))
                        : shade(x, wo, part_brdf(part), stream);
    }, progress);
}

}  // namespace rsl
