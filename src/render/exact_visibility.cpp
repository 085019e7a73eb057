#include "src/render/exact_visibility.h"

#include <array>
#include <atomic>

#include "src/core/error.h"
#include "src/core/hemisphere.h"

namespace rsl {

namespace {

std::atomic<uint64_t> next_id{1};

// Per thread: the surface points of the block being shaded (the renderer
// asks for every light of a block in turn) and the rays of one batch.
struct BatchScratch {
    uint64_t owner = 0;
    int part = -1, first_vertex = -1;
    std::vector<SurfacePoint> points;
    std::vector<Vec3> origins;  // per vertex, cached with its point
    std::vector<bool> cached;
    std::vector<Vec3> ray_origins, ray_dirs;
    std::vector<uint8_t> visible;
    std::vector<int> counted, first_ray;
};

}  // namespace

ExactVisibility::ExactVisibility(const Scene& scene, float t, ExactVisibilityMode mode, int samples_per_side,
                                 bool jitter)
    : mode_(mode), samples_(samples_per_side), jitter_(jitter), id_(next_id++), posed_(scene, t) {
    if (samples_per_side < 1 || samples_per_side > kMaxSamplesPerSide)
        throw_error("ray-traced visibility: {} samples per side is outside [1, {}]", samples_per_side,
                    kMaxSamplesPerSide);
    if (mode == ExactVisibilityMode::All) return;
    const int parts = int(scene.parts.size());
    // Per receiver the scene of itself alone (`alone`) or of every other part.
    auto add_scene = [&](int receiver, bool alone) {
        auto rays = std::make_unique<RayScene>(/*origins_outside_surfaces=*/true);
        for (int p = 0; p < parts; ++p) {
            if (alone != (p == receiver)) continue;
            const int mesh = rays->add_mesh(scene.parts[p].mesh);
            if (const PosedVertices* skinned = posed_.skinned(p)) rays->set_mesh_positions(mesh, skinned->positions);
            rays->add_instance(mesh, posed_.part_transform(p));
        }
        rays->commit();
        per_part_.push_back(std::move(rays));
    };
    for (int receiver = 0; receiver < parts; ++receiver) {
        if (mode == ExactVisibilityMode::SelfTimesOthers) {
            add_scene(receiver, true);
            add_scene(receiver, false);
        } else {
            add_scene(receiver, mode == ExactVisibilityMode::Self || mode == ExactVisibilityMode::OthersProduct);
        }
    }
}

const RayScene& ExactVisibility::occluders_of(int part) const {
    return mode_ == ExactVisibilityMode::All ? posed_.rays() : *per_part_[part];
}

shading::uvec2 ExactVisibility::seed(int part, int vertex, int light) const {
    return jitter_ ? shading::ray_seed(part, vertex, light) : shading::uvec2(0u);
}

float ExactVisibility::visible_fraction(int part, int vertex, int light, const Vec2& center, float half_edge,
                                        size_t* rays) const {
    const SurfacePoint x = posed_.vertex(part, vertex);
    const Vec3 origin = x.ray_origin();
    const shading::uvec2 bits = seed(part, vertex, light);
    if (mode_ == ExactVisibilityMode::SelfTimesOthers) {
        const float self = fraction(*per_part_[size_t(2 * part)], x, origin, center, half_edge, bits, rays);
        return self > 0.0f ? self * fraction(*per_part_[size_t(2 * part + 1)], x, origin, center, half_edge, bits, rays)
                           : 0.0f;
    }
    if (mode_ != ExactVisibilityMode::OthersProduct)
        return fraction(occluders_of(part), x, origin, center, half_edge, bits, rays);
    float product = 1.0f;
    for (size_t j = 0; j < per_part_.size() && product > 0.0f; ++j)
        if (int(j) != part) product *= fraction(*per_part_[j], x, origin, center, half_edge, bits, rays);
    return product;
}

void ExactVisibility::visible_fraction_batch(int part, int first_vertex, int light, const int* offset, const float* center_x,
                                             const float* center_y, const float* half_edge, const bool* skip, int m,
                                             float* out, size_t* rays) const {
    if (mode_ == ExactVisibilityMode::OthersProduct || mode_ == ExactVisibilityMode::SelfTimesOthers) {
        // a product of factors: one query at a time
        for (int i = 0; i < m; ++i)
            out[i] = skip && skip[i] ? 0.0f
                                     : visible_fraction(part, first_vertex + offset[i], light,
                                                        Vec2(center_x[i], center_y[i]), half_edge[i], rays);
        return;
    }
    thread_local BatchScratch s;
    if (s.owner != id_ || s.part != part || s.first_vertex != first_vertex) {
        s.owner = id_, s.part = part, s.first_vertex = first_vertex;
        s.cached.assign(s.cached.size(), false);
    }
    s.ray_origins.clear(), s.ray_dirs.clear();
    s.counted.resize(size_t(m));
    s.first_ray.resize(size_t(m) + 1);
    const size_t per_query = size_t(samples_) * size_t(samples_);
    for (int i = 0; i < m; ++i) {
        s.first_ray[size_t(i)] = int(s.ray_dirs.size());
        s.counted[size_t(i)] = 0;
        if (skip && skip[i]) continue;
        const size_t k = size_t(offset[i]);
        if (k >= s.cached.size()) s.points.resize(k + 1), s.origins.resize(k + 1), s.cached.resize(k + 1, false);
        if (!s.cached[k]) {
            s.points[k] = posed_.vertex(part, first_vertex + offset[i]);
            s.origins[k] = s.points[k].ray_origin();
            s.cached[k] = true;
        }
        const size_t first = s.ray_dirs.size();
        s.ray_dirs.resize(first + per_query);
        const Vec2 center(center_x[i], center_y[i]);
        const int cast = square_directions(s.points[k], center, half_edge[i], seed(part, first_vertex + offset[i], light),
                                           s.ray_dirs.data() + first, s.counted[size_t(i)]);
        s.ray_dirs.resize(first + size_t(cast));
        s.ray_origins.resize(first + size_t(cast), s.origins[k]);
    }
    s.first_ray[size_t(m)] = int(s.ray_dirs.size());
    const int total = int(s.ray_dirs.size());
    s.visible.resize(size_t(total));
    if (total > 0)
        occluders_of(part).occluded_batch(s.ray_origins.data(), s.ray_dirs.data(), total, 0.0f, 1e30f, s.visible.data());
    if (rays) *rays += size_t(total);
    for (int i = 0; i < m; ++i) {
        if (skip && skip[i]) {
            out[i] = 0.0f;
            continue;
        }
        int reached = 0;
        for (int r = s.first_ray[size_t(i)]; r < s.first_ray[size_t(i) + 1]; ++r) reached += s.visible[size_t(r)];
        out[i] = s.counted[size_t(i)] > 0 ? float(reached) / float(s.counted[size_t(i)]) : 1.0f;
    }
}

int ExactVisibility::square_directions(const SurfacePoint& x, const Vec2& center, float half_edge,
                                       shading::uvec2 seed, Vec3* dirs, int& counted) const {
    int cast = 0;
    counted = 0;
    for (int j = 0; j < samples_; ++j)
        for (int i = 0; i < samples_; ++i) {
            const Vec2 in_cell = jitter_ ? shading::jitter_in_cell(seed, j * samples_ + i) : Vec2(0.5f);
            const Vec2 p = shading::square_grid_point(center, half_edge, samples_, i, j, in_cell);
            if (glm::dot(p, p) >= 1.0f) continue;  // below the shading horizon
            const Vec3 dir = x.frame.to_world(plane_to_hemisphere(p));
            ++counted;
            // As the ground truth: a direction into the surface is occluded.
            if (glm::dot(dir, x.offset_normal) > 0.0f) dirs[cast++] = dir;
        }
    return cast;
}

float ExactVisibility::fraction(const RayScene& rays, const SurfacePoint& x, const Vec3& origin, const Vec2& center,
                                float half_edge, shading::uvec2 seed, size_t* traced) const {
    constexpr int kMax = kMaxSamplesPerSide * kMaxSamplesPerSide;
    std::array<Vec3, kMax> dirs;
    std::array<uint8_t, kMax> visible;
    int counted = 0;
    const int cast = square_directions(x, center, half_edge, seed, dirs.data(), counted);
    if (counted == 0) return 1.0f;
    int reached = 0;
    if (cast == 1) {
        reached = rays.occluded(origin, dirs[0], 0.0f, 1e30f) ? 0 : 1;
    } else if (cast > 1) {
        rays.occluded_batch(origin, dirs.data(), cast, 0.0f, 1e30f, visible.data());
        for (int k = 0; k < cast; ++k) reached += visible[size_t(k)];
    }
    if (traced) *traced += size_t(cast);
    return float(reached) / float(counted);
}

}  // namespace rsl
