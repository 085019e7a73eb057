#include "src/gl/frame_state.h"

#include <fmt/format.h>

#include "src/core/error.h"

namespace rsl::gl {

FrameState::FrameState(const Scene& scene, const PartFields& fields) : setup_(scene, fields) {}

void FrameState::update(const Scene& scene, const EnvironmentLights& environment, std::span<const LocalLight> lights,
                        const RenderOptions& options, float t, const Mat3& extra_rotation,
                        const std::optional<Vec3>& camera) {
    setup_.update(scene, environment, lights, options, t, extra_rotation, camera);
    update_list_texels();
}

// The CPU renderer's occluder lists (the same FrameSetup), offsets first.
void FrameState::update_list_texels() {
    const OccluderLists& lists = setup_.occluder_lists();
    light_count_ = int(setup_.environment_squares().size() + setup_.light_positions().size());
    const size_t slots = lists.offsets.size();  // P·L + 1
    if (slots + lists.occluders.size() > size_t(UINT32_MAX))
        throw Error(fmt::format("{} occluder list entries are more than the GPU lists can index", lists.occluders.size()));
    list_texels_.resize(slots + lists.occluders.size());
    for (size_t s = 0; s < slots; ++s) list_texels_[s] = uint32_t(slots + lists.offsets[s]);
    for (size_t e = 0; e < lists.occluders.size(); ++e) list_texels_[slots + e] = uint32_t(lists.occluders[e]);
}

}  // namespace rsl::gl
