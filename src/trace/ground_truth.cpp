// Ground-truth shading: every environment texel and every sphere light, with
// shadow rays in coherent per-point batches (docs/design/TRUTH.md).
#include "src/trace/ground_truth.h"

#include "src/formats/scene_environment.h"
#include "src/image/image_formation.h"

#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "src/core/error.h"
#include "src/core/memory_limit.h"
#include "src/trace/shadow_batch.h"

namespace rsl {

namespace {

bool is_black(const Color& c) { return !(c.r > 0.0f || c.g > 0.0f || c.b > 0.0f); }

}  // namespace

EnvironmentSamples EnvironmentSamples::from_cube(const CubeMap& map, const Mat3& rotation, int subdivision,
                                                 float max_sample_share) {
    RSL_CHECK_GE(subdivision, 1);
    RSL_CHECK_GE(max_sample_share, 0.0f);
    EnvironmentSamples samples;
    const int n = map.resolution();
    double total = 0.0;  // the map's luminance integral
    if (max_sample_share > 0.0f)
        for (int k = 0; k < map.texel_count(); ++k) total += double(luminance(map.radiance(k))) * map.solid_angle(k);
    for (int k = 0; k < map.texel_count(); ++k) {
        const Color radiance = map.radiance(k);
        if (is_black(radiance)) continue;  // contributes nothing: no ray
        int cells = subdivision;
        if (total > 0.0) {
            const double share = double(luminance(radiance)) * map.solid_angle(k) / total;
            const double side = std::ceil(std::sqrt(share / double(max_sample_share)) - 1e-9);
            cells = std::max(cells, int(std::min(side, double(GroundTruthOptions::kMaxAdaptiveSubdivision))));
        }
        if (cells == 1) {
            samples.directions.push_back(glm::normalize(rotation * map.texel_direction(k)));
            samples.radiance_weights.push_back(radiance * map.solid_angle(k));
            continue;
        }
        const CubeTexel texel = map.texel(k);
        const double cell = 2.0 / (double(n) * cells);
        for (int b = 0; b < cells; ++b)
            for (int a = 0; a < cells; ++a) {
                const double s0 = -1.0 + (double(texel.i) * cells + a) * cell;
                const double t0 = -1.0 + (double(texel.j) * cells + b) * cell;
                const Vec3 dir = CubeMap::face_direction(texel.face, float(s0 + 0.5 * cell), float(t0 + 0.5 * cell));
                samples.directions.push_back(glm::normalize(rotation * glm::normalize(dir)));
                samples.radiance_weights.push_back(
                    radiance * float(cube_face_solid_angle(s0, t0, s0 + cell, t0 + cell)));
            }
    }
    return samples;
}

namespace {

// The truth's memory (src/core/memory_limit.h), checked before Embree's scene
// is built (check_truth_memory).
const Scene& checked_for_truth(const Scene& scene) {
    check_truth_memory(scene);
    return scene;
}

}  // namespace

// About 300 bytes a vertex (the robot: 64 MB for 87,651 vertices), with start-up.
void check_truth_memory(const Scene& scene, int image_width, int image_height) {
    const uint64_t vertices = scene.vertex_count();
    const std::string image =
        image_width > 0 && image_height > 0 ? fmt::format(" and a {}×{} image", image_width, image_height) : "";
    check_memory_estimate((96ull << 20) + 400 * vertices + image_memory_bytes(image_width, image_height),
                          scene.source,
                          fmt::format("the truth of {} vertices in {} parts{}", vertices, scene.parts.size(), image));
}

GroundTruth::GroundTruth(const Scene& scene, const CubeMap& environment, float t, GroundTruthOptions options)
    : scene_(checked_for_truth(scene)), cube_(environment), options_(options), posed_(scene, t), lobes_(scene) {
    RSL_CHECK_GE(options_.texel_subdivision, 1);
    RSL_CHECK_GE(options_.light_max_side, 8);
    set_time(t);
}

void GroundTruth::set_time(float t) {
    if (posed_.time() != t) posed_.set_time(t);
    if (options_.environment && cube_.resolution() > 0)
        environment_ = EnvironmentSamples::from_cube(cube_, scene_.environment.rotation_at(t),
                                                     options_.texel_subdivision, options_.max_sample_share);
    else
        environment_ = {};
    // Each sun, a direction of irradiance E (a delta light: one shadow ray),
    // turning with the map as its RSL does (fit_scene_lights).
    if (options_.environment)
        for (const SunLight& sun : scene_.environment.suns) {
            environment_.directions.push_back(
                glm::normalize(scene_.environment.rotation_at(t) * sun_direction_in_map(scene_, sun)));
            environment_.radiance_weights.push_back(sun.irradiance);
        }
    lights_.set(scene_, t);
    camera_ = scene_.camera.position_at(t);
}

Color GroundTruth::shade(const SurfacePoint& x, const Vec3& wo_world, const Brdf& brdf) const {
    const Vec3 wo = x.frame.to_local(wo_world);
    // ρ is zero for a view below the shading horizon (Brdf contract): no rays.
    if (!(wo.z > 0.0f)) return Color(0);
    const Vec3 origin = x.ray_origin();
    uint64_t rays = 0;
    Color result = shade_environment(x, origin, wo, brdf, rays);
    if (options_.local_lights)
        for (size_t i = 0; i < scene_.lights.size(); ++i) {
            // A spot's cone scales the light by the direction from its centre to x.
            const float cone = spot_cone_factor_at(x.position, lights_.positions[i], lights_.axes[i], lights_.cones[i]);
            if (!(cone > 0.0f)) continue;
            result += shade_light(x, origin, wo, brdf, lights_.positions[i], scene_.lights[i].radius,
                                  sphere_light_radiance(scene_.lights[i]) * cone, rays);
        }
    rays_traced_.fetch_add(rays, std::memory_order_relaxed);
    return result;
}

Color GroundTruth::shade_environment(const SurfacePoint& x, const Vec3& origin, const Vec3& wo,
                                     const Brdf& brdf, uint64_t& rays) const {
    ShadowBatch batch(posed_.rays(), origin);
    const Vec3* dirs = environment_.directions.data();
    const Color* weights = environment_.radiance_weights.data();
    const size_t count = environment_.size();
    DVec3 unshadowed(0.0);
    for (size_t k = 0; k < count; ++k) {
        const Vec3 wi = x.frame.to_local(dirs[k]);
        // Below the shading horizon ρ·cos is 0; below the geometric surface the
        // ray would enter the surface it starts on (occluded by definition).
        if (wi.z <= 0.0f) continue;
        if (!options_.shadows) {
            unshadowed += DVec3(brdf.eval(wi, wo) * (wi.z * weights[k]));
            continue;
        }
        if (glm::dot(dirs[k], x.offset_normal) <= 0.0f) continue;
        const Color f = brdf.eval(wi, wo) * (wi.z * weights[k]);
        if (is_black(f)) continue;
        batch.add(dirs[k], f);
    }
    const DVec3 sum = batch.flush_and_sum() + unshadowed;
    rays += batch.rays();
    return Color(sum);
}

// ∫ over the cone subtended by the sphere: cos θ' = 1 − u (1 − cos α) and
// φ = 2π v are uniform in solid angle, so a midpoint grid in (u, v) is a
// stratified uniform-cone quadrature with Ω_cone / M weight per sample.
Color GroundTruth::shade_light(const SurfacePoint& x, const Vec3& origin, const Vec3& wo, const Brdf& brdf,
                               const Vec3& center, float radius, const Color& radiance, uint64_t& rays) const {
    const Vec3 to_center = center - origin;
    const float distance = glm::length(to_center);
    if (!(distance > radius)) return Color(0);  // inside the light: not a surface it lights
    const Frame cone = Frame::from_normal(to_center / distance);
    const float sin2_alpha = (radius / distance) * (radius / distance);
    const float cos_alpha = std::sqrt(std::max(0.0f, 1.0f - sin2_alpha));
    const float one_minus_cos_alpha = sin2_alpha / (1.0f + cos_alpha);  // no cancellation
    const float cone_solid_angle = 2.0f * kPi * one_minus_cos_alpha;

    DVec3 previous(-1.0);
    DVec3 estimate(0.0);
    for (int side = 8; side <= options_.light_max_side; side *= 2) {
        ShadowBatch batch(posed_.rays(), origin);
        for (int i = 0; i < side; ++i) {
            const float cos_theta = 1.0f - (float(i) + 0.5f) / float(side) * one_minus_cos_alpha;
            const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
            for (int j = 0; j < side; ++j) {
                const float phi = 2.0f * kPi * (float(j) + 0.5f) / float(side);
                const Vec3 dir =
                    cone.to_world(Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta));
                const Vec3 wi = x.frame.to_local(dir);
                if (wi.z <= 0.0f || glm::dot(dir, x.offset_normal) <= 0.0f) continue;
                const Color f = brdf.eval(wi, wo) * (wi.z * radiance);
                if (is_black(f)) continue;
                // The ray ends where it meets the light's surface (nearer root).
                const float b = distance * cos_theta;
                const float t_far = b - std::sqrt(std::max(0.0f, radius * radius - distance * distance + b * b));
                batch.add(dir, f, t_far);
            }
        }
        estimate = batch.flush_and_sum() * double(cone_solid_angle / float(side * side));
        rays += batch.rays();
        const double now = luminance(Color(estimate)), before = luminance(Color(previous));
        if (previous.x >= 0.0 && std::abs(now - before) <= options_.light_tolerance * std::max(now, 1e-30))
            break;
        previous = estimate;
    }
    return Color(estimate);
}

Color GroundTruth::shade_hit(const RayHit& hit, const Vec3& ray_direction) const {
    const SurfacePoint x = posed_.hit_point(hit, ray_direction);
    const Color emission = hit_emission(scene_, hit);
    const Brdf* specular = part_specular_brdf(hit.instance);
    const int material = scene_.parts[size_t(hit.instance)].material;
    if (lobes_.varies[size_t(material)]) {  // roughness and metallic at the hit
        const Vec2 uv = interpolate_texcoords(scene_, hit);
        const Color reflected = shade(x, -ray_direction, *lobes_.at_point(scene_, material, uv, false));
        if (!specular) return reflected + emission;
        return reflected * part_texture(hit.instance)->lookup(uv) +
               shade(x, -ray_direction, *lobes_.at_point(scene_, material, uv, true)) + emission;
    }
    if (!specular) return shade(x, -ray_direction, part_brdf(hit.instance)) + emission;
    const Vec2 uv = interpolate_texcoords(scene_, hit);
    return shade(x, -ray_direction, part_brdf(hit.instance)) * part_texture(hit.instance)->lookup(uv) +
           shade(x, -ray_direction, *specular) + emission;
}

VertexColors GroundTruth::shade_vertices(const ProgressCallback& progress) const {
    return shade_every_vertex(scene_, lobes_, "truth", time(), 64, [&](int part, int vertex, bool specular) {
        const SurfacePoint x = posed_.vertex(part, vertex);
        const Vec3 wo = glm::normalize(camera_ - x.position);
        if (const int m = scene_.parts[size_t(part)].material; lobes_.varies[size_t(m)])
            return shade(x, wo, *lobes_.at_point(scene_, m, scene_.parts[size_t(part)].mesh.texcoords[size_t(vertex)],
                                                 specular));
        return shade(x, wo, specular ? *part_specular_brdf(part) : part_brdf(part));
    }, progress);
}

}  // namespace rsl
