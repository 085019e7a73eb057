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
        const OccluderField* field = occluder_fields_.back().get();
        culling_parts_.emplace_back();
        culling_parts_.back().field = field;
        culling_parts_.back().local_reach = field ? field->reach() : BoundingSphere{};
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

// The CPU renderer's occluder lists (culling.h, the same function) as bit
// masks.
void FrameState::update_masks(const Scene& scene, const RenderOptions& options) {
    const size_t parts = poses_.size();
    for (size_t p = 0; p < parts; ++p) {
        culling_parts_[p].transform = poses_[p].transform;
        culling_parts_[p].world_bounds = poses_[p].world_bounds;
    }
    update_occluder_lists(culling_parts_, CullingLights{squares_, light_positions_, scene.lights}, options, lists_);
    light_count_ = int(squares_.size() + light_positions_.size());
    masks_.assign(parts * size_t(light_count_), 0u);
    for (size_t slot = 0; slot < masks_.size(); ++slot)
        for (size_t e = lists_.offsets[slot]; e < lists_.offsets[slot + 1]; ++e) masks_[slot] |= 1u << lists_.occluders[e];
}

}  // namespace rsl::gl
