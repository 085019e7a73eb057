#pragma once
// What changes every frame, computed on the CPU exactly as the CPU renderer
// does (src/render/renderer.cpp set_time; the occluder lists by the same
// culling.h function): part
// poses, the environment's square lights rotated to time t, local light
// positions, the camera, and per (receiver part, light) the set of occluder
// parts whose OVDF lookups run (culling.h decides). The GPU pass receives it
// as small textures.
#include <cstdint>
#include <memory>
#include <vector>

#include "lightfit/rsl.h"
#include "src/core/scene.h"
#include "src/render/culling.h"
#include "src/render/part_fields.h"
#include "src/render/render_options.h"
#include "src/render/square_lights.h"

namespace rsl::gl {

// Occluder sets are bit masks: at most this many parts.
inline constexpr int kMaxParts = 32;

struct PartPose {
    Mat4 transform{1.0f};
    Mat3 normal{1.0f};
    Mat4 inverse{1.0f};
    BoundingSphere world_bounds;
};

class FrameState {
public:
    FrameState(const Scene& scene, const PartFields& fields);

    // Poses and lights at time t; the environment additionally turned by
    // `extra_rotation` (the viewer's), the camera at `camera` (the scene's
    // camera at t when null).
    void update(const Scene& scene, const RslSet& environment, const RenderOptions& options, float t,
                const Mat3& extra_rotation = Mat3(1.0f), const Vec3* camera = nullptr);

    const std::vector<PartPose>& poses() const { return poses_; }
    const std::vector<SquareLight>& environment_squares() const { return squares_; }
    const std::vector<Vec3>& light_positions() const { return light_positions_; }
    const Vec3& camera() const { return camera_; }
    // Occluder mask of receiver part p for light l (environment lights first,
    // then local lights): bit o set when part o's OVDF is looked up.
    uint32_t occluder_mask(int part, int light) const { return masks_[size_t(part) * light_count_ + light]; }
    const std::vector<uint32_t>& masks() const { return masks_; }  // part-major, light_count per part
    int light_count() const { return light_count_; }
    size_t occluder_pairs() const { return lists_.pairs; }
    size_t occluder_pairs_culled() const { return lists_.culled; }

private:
    void update_masks(const Scene& scene, const RenderOptions& options);

    std::vector<BoundingSphere> local_bounds_;
    std::vector<std::shared_ptr<const OccluderField>> occluder_fields_;  // keeps culling_parts_' fields alive
    std::vector<CullingPart> culling_parts_;
    OccluderLists lists_;
    std::vector<PartPose> poses_;
    std::vector<SquareLight> squares_;
    std::vector<Vec3> light_positions_;
    Vec3 camera_{0};
    std::vector<uint32_t> masks_;
    int light_count_ = 0;
};

}  // namespace rsl::gl
