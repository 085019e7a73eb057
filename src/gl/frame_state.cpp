#include "src/gl/frame_state.h"

#include "src/core/error.h"
#include "src/render/culling.h"

namespace rsl::gl {

FrameState::FrameState(const Scene& scene, const PartFields& fields) {
    const size_t parts = scene.parts.size();
    if (parts > size_t(kMaxParts))
        throw_file_error(scene.source, "the GL renderer handles at most {} parts; the scene has {}", kMaxParts, parts);
    for (size_t p = 0; p < parts; ++p) {
        local_bounds_.push_back(scene.parts[p].mesh.bounding_sphere());
        occluder_fields_.push_back(p < fields.occluder.size() ? fields.occluder[p] : nullptr);
        local_reach_.push_back(occluder_fields_.back() ? occluder_fields_.back()->reach() : BoundingSphere{});
    }
    poses_.resize(parts);
}

void FrameState::update(const Scene& scene, const RslSet& environment, const RenderOptions& options, float t,
                        const Mat3& extra_rotation, const Vec3* camera) {
    for (size_t p = 0; p < poses_.size(); ++p) {
        PartPose& pose = poses_[p];
        pose.transform = scene.part_transform_at(int(p), t);
        pose.normal = glm::transpose(glm::inverse(Mat3(pose.transform)));
        pose.inverse = glm::inverse(pose.transform);
        pose.world_bounds = transform_sphere(pose.transform, local_bounds_[p]);
    }
    const Mat3 rotation = extra_rotation * scene.environment.rotation_at(t);
    squares_.resize(environment.lights.size());
    for (size_t l = 0; l < squares_.size(); ++l) {
        const RotatableSquareLight& rsl = environment.lights[l];
        SquareLight& square = squares_[l];
        square.direction = glm::normalize(rotation * rsl.center);
        square.half_edge = square_half_edge_for_rsl(rsl.half_diagonal);
        square.solid_angle = rsl.solid_angle();
        square.integral = rsl.radiance * square.solid_angle;
    }
    light_positions_.resize(scene.lights.size());
    for (size_t i = 0; i < scene.lights.size(); ++i) light_positions_[i] = scene.lights[i].position_at(t);
    camera_ = camera ? *camera : scene.camera.position_at(t);
    update_masks(scene, options);
}

// The CPU renderer's occluder lists as bit masks (renderer.cpp,
// update_occluder_lists): the same tests in the same order.
void FrameState::update_masks(const Scene& scene, const RenderOptions& options) {
    const size_t parts = poses_.size();
    const size_t environment = squares_.size();
    light_count_ = int(environment + light_positions_.size());
    masks_.assign(parts * size_t(light_count_), 0u);
    spheres_.assign(parts * parts, Vec4(0.0f));
    for (size_t receiver = 0; receiver < parts; ++receiver)
        for (size_t o = 0; o < parts; ++o) {
            if (o == receiver || !occluder_fields_[o]) continue;
            const BoundingSphere& r = poses_[receiver].world_bounds;
            const BoundingSphere reach = transform_sphere(poses_[o].transform, local_reach_[o]);
            const float scale = reach.radius / std::max(local_reach_[o].radius, 1e-30f);
            const float distance = glm::length(r.center - reach.center) / scale;
            const float grow = scale * occluder_fields_[o]->footprint(
                                           std::max(0.0f, distance - r.radius / scale),
                                           std::min(local_reach_[o].radius, distance + r.radius / scale));
            const BoundingSphere& sphere = poses_[o].world_bounds;
            spheres_[receiver * parts + o] = Vec4(sphere.center, sphere.radius + grow);
        }
    pairs_ = culled_ = 0;
    for (size_t receiver = 0; receiver < parts; ++receiver) {
        const BoundingSphere& r = poses_[receiver].world_bounds;
        for (size_t l = 0; l < size_t(light_count_); ++l) {
            const bool lit = l < environment ? options.environment : options.local_lights;
            if (!options.occluders || !lit) continue;
            uint32_t& mask = masks_[receiver * light_count_ + l];
            for (size_t o = 0; o < parts; ++o) {
                if (o == receiver || !occluder_fields_[o]) continue;
                ++pairs_;
                bool keep = true;
                if (options.occluder_culling) {
                    const BoundingSphere& occluder = poses_[o].world_bounds;
                    const BoundingSphere reach = transform_sphere(poses_[o].transform, local_reach_[o]);
                    // The field blends samples up to `footprint` away from the
                    // receiver: test the receiver grown by it, so that culling
                    // never changes a lookup's result.
                    const float scale = reach.radius / std::max(local_reach_[o].radius, 1e-30f);
                    const float distance = glm::length(r.center - reach.center) / scale;
                    const float grow = scale * occluder_fields_[o]->footprint(
                                                   std::max(0.0f, distance - r.radius / scale),
                                                   std::min(local_reach_[o].radius, distance + r.radius / scale));
                    const BoundingSphere grown{r.center, r.radius + grow};
                    if (beyond_reach(r, reach)) {
                        keep = false;
                    } else if (l < environment) {
                        const SquareLight& square = squares_[l];
                        keep = may_shadow_direction(grown, occluder, square.direction,
                                                    square_cone_half_angle(square.half_edge));
                    } else {
                        const size_t i = l - environment;
                        keep = may_shadow_sphere_light(grown, occluder, light_positions_[i], scene.lights[i].radius);
                    }
                }
                if (keep)
                    mask |= 1u << o;
                else
                    ++culled_;
            }
        }
    }
}

}  // namespace rsl::gl
