// Per-vertex transport on cube-map texels, with the ground truth's rules.
#include "tools/baselines/transport.h"

#include <algorithm>
#include <limits>

#include "src/core/error.h"

namespace rsl {

VertexLayout::VertexLayout(const Scene& scene) {
    first_.push_back(0);
    for (const Part& part : scene.parts) first_.push_back(first_.back() + part.mesh.vertex_count());
}

std::pair<int, int> VertexLayout::locate(size_t flat) const {
    const int part = int(std::upper_bound(first_.begin(), first_.end(), flat) - first_.begin()) - 1;
    return {part, int(flat - first_[part])};
}

VertexColors VertexLayout::to_colors(const Scene& scene, const std::vector<Color>& flat, const std::string& producer,
                                     float time) const {
    RSL_CHECK_EQ(flat.size(), total());
    VertexColors colors;
    colors.scene_name = scene.name;
    colors.producer = producer;
    colors.time = time;
    for (int p = 0; p < parts(); ++p) {
        colors.add_part(scene.parts[p].name, first_[p + 1] - first_[p]);
        std::copy(flat.begin() + first_[p], flat.begin() + first_[p + 1], colors.parts[p].begin());
    }
    return colors;
}

TransportSampler::TransportSampler(const GroundTruth& truth, const CubeMap& grid, const Mat3& environment_rotation,
                                   bool visibility)
    : truth_(truth), visibility_(visibility) {
    directions_.reserve(size_t(grid.texel_count()));
    // Exactly as EnvironmentSamples::from_cube (subdivision 1) turns them.
    for (int k = 0; k < grid.texel_count(); ++k)
        directions_.push_back(glm::normalize(environment_rotation * grid.texel_direction(k)));
}

TransportSampler::Scratch TransportSampler::make_scratch() const {
    Scratch s;
    s.dirs.resize(directions_.size());
    s.texels.resize(directions_.size());
    s.weights.resize(directions_.size());
    s.visible.resize(directions_.size());
    return s;
}

namespace {

// The truth's horizon rules: below the shading horizon ρ·cos is 0; below the
// geometric surface the ray would enter its own surface.
bool above_horizons(const SurfacePoint& x, const Vec3& dir, const Vec3& wi) {
    return wi.z > 0.0f && glm::dot(dir, x.offset_normal) > 0.0f;
}

}  // namespace

uint64_t TransportSampler::sample(int part, int vertex, Color* f, Scratch& scratch) const {
    const int count = texel_count();
    std::fill(f, f + count, Color(0.0f));
    const PosedScene& posed = truth_.posed();
    const SurfacePoint x = posed.vertex(part, vertex);
    const Vec3 wo = x.frame.to_local(glm::normalize(truth_.camera_position() - x.position));
    if (!(wo.z > 0.0f)) return 0;  // ρ is 0 for a view below the horizon (Brdf contract)
    const Brdf& brdf = truth_.part_unit_texture_brdf(part);  // colours at unit texture (docs/BASELINES.md)
    const Vec3 origin = x.ray_origin();
    int rays = 0;
    for (int k = 0; k < count; ++k) {
        const Vec3& dir = directions_[k];
        const Vec3 wi = x.frame.to_local(dir);
        if (!above_horizons(x, dir, wi)) continue;
        const Color weight = brdf.eval(wi, wo) * wi.z;
        if (!(weight.r > 0.0f || weight.g > 0.0f || weight.b > 0.0f)) continue;
        scratch.dirs[rays] = dir;
        scratch.texels[rays] = k;
        scratch.weights[rays] = weight;
        ++rays;
    }
    if (!visibility_) {
        for (int r = 0; r < rays; ++r) f[scratch.texels[r]] = scratch.weights[r];
        return 0;
    }
    posed.rays().occluded_batch(origin, scratch.dirs.data(), rays, 0.0f, std::numeric_limits<float>::infinity(),
                                scratch.visible.data());
    for (int r = 0; r < rays; ++r)
        if (scratch.visible[r]) f[scratch.texels[r]] = scratch.weights[r];
    return uint64_t(rays);
}

uint64_t TransportSampler::sample_visibility(int part, int vertex, float* V, Scratch& scratch) const {
    const int count = texel_count();
    std::fill(V, V + count, 0.0f);
    const SurfacePoint x = truth_.posed().vertex(part, vertex);
    int rays = 0;
    for (int k = 0; k < count; ++k) {
        if (!above_horizons(x, directions_[k], x.frame.to_local(directions_[k]))) continue;
        scratch.dirs[rays] = directions_[k];
        scratch.texels[rays] = k;
        ++rays;
    }
    if (!visibility_) {
        for (int r = 0; r < rays; ++r) V[scratch.texels[r]] = 1.0f;
        return 0;
    }
    truth_.posed().rays().occluded_batch(x.ray_origin(), scratch.dirs.data(), rays, 0.0f,
                                         std::numeric_limits<float>::infinity(), scratch.visible.data());
    for (int r = 0; r < rays; ++r)
        if (scratch.visible[r]) V[scratch.texels[r]] = 1.0f;
    return uint64_t(rays);
}

}  // namespace rsl
