#pragma once
// What a renderer needs to know about time t, computed once for every
// backend (the CPU renderer and the GL one read the same numbers, so they
// cannot drift apart): part poses, the environment's square lights rotated
// and blend-weighted to t, local light positions, the camera, and the
// occluder lists of the culling (culling.h).
//
// The environment blend (scene format `second_file`, docs/SCENE_FORMAT.md):
// at time t the environment is (1 − w(t))·first map + w(t)·second map. The
// rendering sum is linear in the radiance, so the blended environment's
// lighting is the two maps' RSL sets, each fitted on its own map, with their
// integrals scaled by (1 − w) and w: the square lights are the first set's
// followed by the second set's. A set whose weight is 0 is left out, so a
// frame at w = 0 or 1 costs one set.
#include <optional>
#include <span>
#include <vector>

#include "src/lightfit/square_light.h"
#include "src/core/scene.h"
#include "src/core/skinning.h"
#include "src/render/occluder_culling.h"
#include "src/render/part_fields.h"
#include "src/render/render_options.h"
#include "src/render/square_lights.h"

namespace rsl {

// The environment's RSL sets at rotation 0: `first` fitted on
// environment.file, `second` (empty unless the scene blends) on
// environment.second_file. Implicit from one set: no blend.
struct EnvironmentLights {
    RslSet first, second;
    EnvironmentLights() = default;
    EnvironmentLights(RslSet first_set, RslSet second_set = {})  // NOLINT: a single set is the common case
        : first(std::move(first_set)), second(std::move(second_set)) {}
    bool blends() const { return !second.lights.empty(); }
    size_t light_count() const { return first.lights.size() + second.lights.size(); }
};

// The weights of the two sets at time t: (1 − w, w) with w =
// environment.blend_weight_at(t) when `lights` blends, (1, 0) otherwise.
struct BlendWeights {
    float first = 1, second = 0;
};
BlendWeights environment_blend_weights(const EnvironmentDesc& environment, const EnvironmentLights& lights, float t);

// One part's pose at t and what the kernels derive from it.
struct PartPose {
    Mat4 transform{1.0f};
    Mat3 linear{1.0f}, normal{1.0f};
    Mat4 inverse{1.0f};
    Mat3 inverse_linear{1.0f};
    // Lengths of inverse_linear's rows: a world direction w lies at
    // (inverse_linear·w)_a / face_scale_a from the part's box face a (the slab rule).
    Vec3 face_scale{1.0f};
    bool uniform_scale = true;  // the block-level cone test measures angles in the world
    BoundingSphere world_bounds;
};

class FrameSetup {
public:
    // `fields` gives each part's occluder field (the culling's reach); the
    // pointers must stay alive as long as this object.
    FrameSetup(const Scene& scene, const PartFields& fields);

    // Sizes the buffers for at most this many environment and local lights,
    // so that update() does not allocate.
    void reserve(size_t environment_lights, size_t local_lights);

    // Everything at time t. The viewer turns the environment further by
    // `extra_rotation` and puts the camera where it wants (`camera`; the
    // scene's camera at t when empty). Allocation-free after reserve() once the
    // occluder lists have grown to the most pairs a frame has had.
    void update(const Scene& scene, const EnvironmentLights& environment, std::span<const LocalLight> lights,
                const RenderOptions& options, float t, const Mat3& extra_rotation = Mat3(1.0f),
                const std::optional<Vec3>& camera = std::nullopt);

    const std::vector<PartPose>& poses() const { return poses_; }
    // A skinned part's vertices at t in its own frame (src/core/skinning.h),
    // which replace its mesh's positions, normals and tangents; null for a
    // rigid part.
    const PosedVertices* skinned(size_t part) const { return skinned_[part].positions.empty() ? nullptr : &skinned_[part]; }
    // Environment lights first (first set, then second set), world space,
    // integrals already weighted by the blend.
    const std::vector<SquareLight>& environment_squares() const { return squares_; }
    const std::vector<Vec3>& light_positions() const { return light_positions_; }
    const std::vector<Vec3>& light_axes() const { return light_axes_; }  // spot axes (unit), per local light
    const Vec3& camera() const { return camera_; }
    BlendWeights blend() const { return blend_; }
    // The environment's rotation at t (the map's frame → the world).
    const Mat3& environment_rotation() const { return environment_rotation_; }
    // Occluders of receiver p for light l (culling.h): occluders[offsets[p·L + l] ..
    // offsets[p·L + l + 1]), L = environment_squares().size() + light_positions().size().
    const OccluderLists& occluder_lists() const { return lists_; }
    const std::vector<CullingPart>& culling_parts() const { return culling_parts_; }

private:
    std::vector<BoundingSphere> local_bounds_;
    std::vector<CullingPart> culling_parts_;
    OccluderLists lists_;
    std::vector<PartPose> poses_;
    std::vector<PosedVertices> skinned_;  // per part; empty for a rigid one
    std::vector<SquareLight> squares_;
    std::vector<Vec3> light_positions_;
    std::vector<Vec3> light_axes_;
    Vec3 camera_{0};
    BlendWeights blend_;
    Mat3 environment_rotation_{1.0f};
};

// The environment's exact irradiance at world normal n in this frame
// (src/lightfit/irradiance.h): the blend of the sets' maps at the normal
// turned back into the maps' frame. Valid only where has_irradiance.
bool has_irradiance(const EnvironmentLights& environment);
Color environment_irradiance(const EnvironmentLights& environment, const FrameSetup& frame, const Vec3& world_normal);

}  // namespace rsl
