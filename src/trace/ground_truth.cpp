// Ground-truth shading: every environment texel and every sphere light, with
// shadow rays in coherent per-point batches (docs/design/TRUTH.md).
#include "src/trace/ground_truth.h"

#include "src/core/scene_environment.h"
#include "src/frame/image_formation.h"

#include <array>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "src/core/error.h"

namespace rsl {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Shadow rays are queued here and traced in packets; stack storage, so the
// per-point loops never allocate.
class ShadowBatch {
public:
    static constexpr int kCapacity = 64;

    ShadowBatch(const RayScene& rays, const Vec3& origin) : rays_(rays), origin_(origin) {}

    void add(const Vec3& dir, const Color& weight, float t_far = kInfinity) {
        dirs_[count_] = dir;
        weights_[count_] = weight;
        t_fars_[count_] = t_far;
        if (++count_ == kCapacity) flush();
    }
    // Sum of the weights of the visible rays so far.
    DVec3 flush_and_sum() {
        flush();
        return sum_;
    }
    uint64_t rays() const { return rays_traced_; }

private:
    void flush() {
        if (count_ == 0) return;
        rays_.occluded_batch(origin_, dirs_.data(), t_fars_.data(), count_, 0.0f, visible_.data());
        for (int k = 0; k < count_; ++k)
            if (visible_[k]) sum_ += DVec3(weights_[k]);
        rays_traced_ += uint64_t(count_);
        count_ = 0;
    }

    const RayScene& rays_;
    Vec3 origin_;
    std::array<Vec3, kCapacity> dirs_;
    std::array<Color, kCapacity> weights_;
    std::array<float, kCapacity> t_fars_;
    std::array<uint8_t, kCapacity> visible_;
    int count_ = 0;
    DVec3 sum_{0.0};
    uint64_t rays_traced_ = 0;
};

bool is_black(const Color& c) { return !(c.r > 0.0f || c.g > 0.0f || c.b > 0.0f); }

}  // namespace

EnvironmentSamples EnvironmentSamples::from_cube(const CubeMap& map, const Mat3& rotation, int subdivision) {
    RSL_CHECK_GE(subdivision, 1);
    EnvironmentSamples samples;
    const int n = map.resolution();
    for (int k = 0; k < map.texel_count(); ++k) {
        const Color radiance = map.radiance(k);
        if (is_black(radiance)) continue;  // contributes nothing: no ray
        if (subdivision == 1) {
            samples.directions.push_back(glm::normalize(rotation * map.texel_direction(k)));
            samples.radiance_weights.push_back(radiance * map.solid_angle(k));
            continue;
        }
        const CubeTexel texel = map.texel(k);
        const double cell = 2.0 / (double(n) * subdivision);
        for (int b = 0; b < subdivision; ++b)
            for (int a = 0; a < subdivision; ++a) {
                const double s0 = -1.0 + (double(texel.i) * subdivision + a) * cell;
                const double t0 = -1.0 + (double(texel.j) * subdivision + b) * cell;
                const Vec3 dir = CubeMap::face_direction(texel.face, float(s0 + 0.5 * cell), float(t0 + 0.5 * cell));
                samples.directions.push_back(glm::normalize(rotation * glm::normalize(dir)));
                samples.radiance_weights.push_back(
                    radiance * float(cube_face_solid_angle(s0, t0, s0 + cell, t0 + cell)));
            }
    }
    return samples;
}

GroundTruth::GroundTruth(const Scene& scene, const CubeMap& environment, float t, GroundTruthOptions options)
    : scene_(scene), cube_(environment), options_(options), posed_(scene, t) {
    RSL_CHECK_GE(options_.texel_subdivision, 1);
    RSL_CHECK_GE(options_.light_max_side, 8);
    materials_ = make_scene_brdfs(scene);
    whole_materials_ = materials_;
    specular_.assign(materials_.size(), nullptr);
    for (size_t m = 0; m < scene.materials.size(); ++m)
        if (scene.materials[m].base_color_texture) {
            BrdfLobes lobes = make_brdf_lobes(scene.materials[m]);
            materials_[m] = std::move(lobes.diffuse);
            specular_[m] = std::move(lobes.specular);
        }
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const Part& part = scene.parts[p];
        if (part.material < 0 || part.material >= int(materials_.size()))
            throw_file_error(scene.source, "part '{}' has material index {} of {}", part.name, part.material,
                             materials_.size());
        if (specular_[size_t(part.material)] && part.mesh.texcoords.size() != part.mesh.positions.size())
            throw_file_error(scene.source, "part '{}': its material has a base colour texture, the part no "
                             "texture coordinates", part.name);
        if (part.mesh.normals.size() != part.mesh.positions.size())
            throw_file_error(scene.source, "part '{}' has {} normals for {} vertices", part.name,
                             part.mesh.normals.size(), part.mesh.positions.size());
    }
    for (const LocalLight& light : scene.lights)
        if (!(light.radius > 0.0f)) throw_file_error(scene.source, "local light with radius {}", light.radius);
    set_time(t);
}

void GroundTruth::set_time(float t) {
    if (posed_.time() != t) posed_.set_time(t);
    if (options_.environment && cube_.resolution() > 0)
        environment_ = EnvironmentSamples::from_cube(cube_, scene_.environment.rotation_at(t),
                                                     options_.texel_subdivision);
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
    light_positions_.clear();
    light_axes_.clear();
    light_cones_.clear();
    for (const LocalLight& light : scene_.lights) {
        light_positions_.push_back(light.position_at(scene_, t));
        light_axes_.push_back(light.axis_at(scene_, t));
        light_cones_.push_back(spot_cone_scale_offset(light));
    }
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
            const float cone = spot_cone_factor_at(x.position, light_positions_[i], light_axes_[i], light_cones_[i]);
            if (!(cone > 0.0f)) continue;
            result += shade_light(x, origin, wo, brdf, light_positions_[i], scene_.lights[i].radius,
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
    for (size_t k = 0; k < count; ++k) {
        const Vec3 wi = x.frame.to_local(dirs[k]);
        // Below the shading horizon ρ·cos is 0; below the geometric surface the
        // ray would enter the surface it starts on (occluded by definition).
        if (wi.z <= 0.0f || glm::dot(dirs[k], x.offset_normal) <= 0.0f) continue;
        const Color f = brdf.eval(wi, wo) * (wi.z * weights[k]);
        if (is_black(f)) continue;
        batch.add(dirs[k], f);
    }
    const DVec3 sum = batch.flush_and_sum();
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
    const Brdf* specular = part_specular_brdf(hit.instance);
    if (!specular) return shade(x, -ray_direction, part_brdf(hit.instance));
    const Vec2 uv = interpolate_texcoords(scene_, hit);
    return shade(x, -ray_direction, part_brdf(hit.instance)) * part_texture(hit.instance)->sample(uv) +
           shade(x, -ray_direction, *specular);
}

VertexColors GroundTruth::shade_vertices(const ProgressCallback& progress) const {
    VertexColors colors;
    colors.scene_name = scene_.name;
    colors.producer = "truth";
    colors.time = time();
    std::vector<size_t> first;  // flattened index of each part's first vertex
    size_t total = 0;
    for (size_t p = 0; p < scene_.parts.size(); ++p) {
        const Part& part = scene_.parts[p];
        colors.add_part(part.name, part.mesh.vertex_count(),
                        specular_[size_t(part.material)] ? scene_.materials[size_t(part.material)].base_color_texture
                                                         : nullptr);
        first.push_back(total);
        total += part.mesh.vertex_count();
    }
    std::atomic<size_t> done{0};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, total, 64), [&](const tbb::blocked_range<size_t>& range) {
        int part = int(std::upper_bound(first.begin(), first.end(), range.begin()) - first.begin()) - 1;
        for (size_t index = range.begin(); index != range.end(); ++index) {
            while (part + 1 < int(first.size()) && index >= first[part + 1]) ++part;
            const int vertex = int(index - first[part]);
            const SurfacePoint x = posed_.vertex(part, vertex);
            const Vec3 wo = glm::normalize(camera_ - x.position);
            colors.parts[part][vertex] = shade(x, wo, part_brdf(part));
            if (const Brdf* specular = part_specular_brdf(part)) colors.specular[part][vertex] = shade(x, wo, *specular);
        }
        const size_t now = done.fetch_add(range.size()) + range.size();
        if (progress) progress(now, total);
    });
    return colors;
}

}  // namespace rsl
