#include "src/render/frame_setup.h"

#include <algorithm>

#include "src/core/error.h"
#include "src/core/scene_limits.h"
#include "src/lightfit/irradiance.h"

namespace rsl {

BlendWeights environment_blend_weights(const EnvironmentDesc& environment, const EnvironmentLights& lights, float t) {
    if (!lights.blends()) return BlendWeights{};
    const float w = environment.blend_weight_at(t);
    return BlendWeights{1.0f - w, w};
}

FrameSetup::FrameSetup(const Scene& scene, const PartFields& fields) {
    const size_t parts = scene.parts.size();
    for (size_t p = 0; p < parts; ++p) {
        local_bounds_.push_back(scene.parts[p].mesh.bounding_sphere());
        const OccluderField* field = p < fields.occluder.size() ? fields.occluder[p].get() : nullptr;
        culling_parts_.emplace_back();
        culling_parts_.back().field = field;
        culling_parts_.back().local_reach = field ? field->reach() : BoundingSphere{};
    }
    poses_.resize(parts);
    skinned_.resize(parts);
}

void FrameSetup::reserve(size_t environment_lights, size_t local_lights) {
    const size_t parts = poses_.size();
    const size_t lights = environment_lights + local_lights;
    squares_.reserve(environment_lights);
    light_positions_.reserve(local_lights);
    light_axes_.reserve(local_lights);
    lists_.offsets.reserve(parts * lights + 1);
    // The lists themselves grow to what the first frames need and keep that
    // capacity: reserving parts² × lights would be gigabytes for a large scene.
}

namespace {

void append_squares(const RslSet& set, const Mat3& rotation, float weight, std::vector<SquareLight>& out) {
    if (weight == 0.0f) return;
    for (const RotatableSquareLight& rsl : set.lights) {
        SquareLight square;
        square.direction = glm::normalize(rotation * rsl.center);
        square.half_edge = square_half_edge_for_rsl(rsl.half_diagonal);
        square.solid_angle = rsl.solid_angle();
        square.integral = rsl.radiance * square.solid_angle;
        // Scaling by exactly 1 leaves an unblended frame bit for bit as before.
        if (weight != 1.0f) square.integral *= weight;
        out.push_back(square);
    }
}

}  // namespace

void FrameSetup::update(const Scene& scene, const EnvironmentLights& environment, std::span<const LocalLight> lights,
                        const RenderOptions& options, float t, const Mat3& extra_rotation,
                        const std::optional<Vec3>& camera) {
    RSL_CHECK_EQ(poses_.size(), scene.parts.size());
    for (size_t p = 0; p < poses_.size(); ++p) {
        PartPose& pose = poses_[p];
        pose.transform = scene.part_transform_at(int(p), t);
        check_part_pose(scene, int(p), t, pose.transform);
        pose.linear = Mat3(pose.transform);
        pose.normal = glm::transpose(glm::inverse(pose.linear));
        pose.inverse = glm::inverse(pose.transform);
        pose.inverse_linear = Mat3(pose.inverse);
        for (int a = 0; a < 3; ++a)
            pose.face_scale[a] =
                glm::length(Vec3(pose.inverse_linear[0][a], pose.inverse_linear[1][a], pose.inverse_linear[2][a]));
        const Vec3 axes(glm::length(pose.linear[0]), glm::length(pose.linear[1]), glm::length(pose.linear[2]));
        pose.uniform_scale =
            std::max({axes.x, axes.y, axes.z}) <= (1.0f + 1e-4f) * std::min({axes.x, axes.y, axes.z});
        BoundingSphere local = local_bounds_[p];
        if (scene.parts[p].skin) {
            pose_skinned_part(scene, int(p), t, skinned_[p]);
            local = posed_bounding_sphere(skinned_[p]);
        }
        pose.world_bounds = transform_sphere(pose.transform, local);
    }
    // Both maps turn together: the blend is of the two rotated maps.
    const Mat3 rotation = extra_rotation * scene.environment.rotation_at(t);
    environment_rotation_ = rotation;
    blend_ = environment_blend_weights(scene.environment, environment, t);
    squares_.clear();
    append_squares(environment.first, rotation, blend_.first, squares_);
    append_squares(environment.second, rotation, blend_.second, squares_);
    light_positions_.resize(lights.size());
    light_axes_.resize(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
        light_positions_[i] = lights[i].position_at(scene, t);
        light_axes_[i] = lights[i].axis_at(scene, t);
    }
    camera_ = camera ? *camera : scene.camera.position_at(t);

    for (size_t p = 0; p < poses_.size(); ++p) {
        culling_parts_[p].transform = poses_[p].transform;
        culling_parts_[p].world_bounds = poses_[p].world_bounds;
    }
    update_occluder_lists(culling_parts_, CullingLights{squares_, light_positions_, lights}, options, lists_);
}

bool has_irradiance(const EnvironmentLights& environment) {
    return environment.first.irradiance && (!environment.blends() || environment.second.irradiance);
}

Color environment_irradiance(const EnvironmentLights& environment, const FrameSetup& frame, const Vec3& world_normal) {
    const Vec3 n = glm::transpose(frame.environment_rotation()) * world_normal;
    const BlendWeights w = frame.blend();
    Color e = w.first * environment.first.irradiance->at(n);
    if (environment.blends() && w.second > 0.0f) e += w.second * environment.second.irradiance->at(n);
    return e;
}

}  // namespace rsl
