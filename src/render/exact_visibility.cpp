#include "src/render/exact_visibility.h"

#include "src/core/hemisphere.h"

namespace rsl {

ExactVisibility::ExactVisibility(const Scene& scene, float t, ExactVisibilityMode mode, int samples_per_side)
    : mode_(mode), samples_(samples_per_side), posed_(scene, t) {
    if (mode == ExactVisibilityMode::All) return;
    const int parts = int(scene.parts.size());
    for (int receiver = 0; receiver < parts; ++receiver) {
        auto rays = std::make_unique<RayScene>();
        for (int p = 0; p < parts; ++p) {
            const bool alone = mode == ExactVisibilityMode::Self || mode == ExactVisibilityMode::OthersProduct;
            if (alone != (p == receiver)) continue;
            rays->add_instance(rays->add_mesh(scene.parts[p].mesh), posed_.part_transform(p));
        }
        rays->commit();
        per_part_.push_back(std::move(rays));
    }
}

const RayScene& ExactVisibility::occluders_of(int part) const {
    return mode_ == ExactVisibilityMode::All ? posed_.rays() : *per_part_[part];
}

float ExactVisibility::visible_fraction(int part, int vertex, const Vec2& center, float half_edge) const {
    const SurfacePoint x = posed_.vertex(part, vertex);
    const Vec3 origin = posed_.offset().origin(x.position, x.offset_normal);
    if (mode_ != ExactVisibilityMode::OthersProduct) return fraction(occluders_of(part), x, origin, center, half_edge);
    float product = 1.0f;
    for (size_t j = 0; j < per_part_.size() && product > 0.0f; ++j)
        if (int(j) != part) product *= fraction(*per_part_[j], x, origin, center, half_edge);
    return product;
}

float ExactVisibility::fraction(const RayScene& rays, const SurfacePoint& x, const Vec3& origin, const Vec2& center,
                                float half_edge) const {
    int counted = 0, visible = 0;
    for (int j = 0; j < samples_; ++j)
        for (int i = 0; i < samples_; ++i) {
            const Vec2 p = center + half_edge * Vec2(2.0f * (i + 0.5f) / samples_ - 1.0f, 2.0f * (j + 0.5f) / samples_ - 1.0f);
            if (glm::dot(p, p) >= 1.0f) continue;  // below the shading horizon
            const Vec3 dir = x.frame.to_world(plane_to_hemisphere(p));
            ++counted;
            // As the ground truth: a direction into the surface is occluded.
            if (glm::dot(dir, x.offset_normal) > 0.0f && !rays.occluded(origin, dir, 0.0f, 1e30f)) ++visible;
        }
    return counted > 0 ? float(visible) / float(counted) : 1.0f;
}

}  // namespace rsl
