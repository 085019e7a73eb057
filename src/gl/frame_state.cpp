#include "src/gl/frame_state.h"

#include "src/core/error.h"

namespace rsl::gl {

namespace {
const Scene& checked(const Scene& scene) {
    if (scene.parts.size() > size_t(kMaxParts))
        throw_file_error(scene.source, "the GL renderer handles at most {} parts; the scene has {}", kMaxParts,
                         scene.parts.size());
    return scene;
}
}  // namespace

FrameState::FrameState(const Scene& scene, const PartFields& fields) : setup_(checked(scene), fields) {}

void FrameState::update(const Scene& scene, const EnvironmentLights& environment, std::span<const LocalLight> lights,
                        const RenderOptions& options, float t, const Mat3& extra_rotation,
                        const std::optional<Vec3>& camera) {
    setup_.update(scene, environment, lights, options, t, extra_rotation, camera);
    update_masks();
}

// The CPU renderer's occluder lists (the same FrameSetup) as bit masks.
void FrameState::update_masks() {
    const OccluderLists& lists = setup_.occluder_lists();
    const auto& poses = setup_.poses();
    const size_t parts = poses.size();
    light_count_ = int(setup_.environment_squares().size() + setup_.light_positions().size());
    masks_.assign(parts * size_t(light_count_), 0u);
    for (size_t slot = 0; slot < masks_.size(); ++slot)
        for (size_t e = lists.offsets[slot]; e < lists.offsets[slot + 1]; ++e) masks_[slot] |= 1u << lists.occluders[e];
}

}  // namespace rsl::gl
