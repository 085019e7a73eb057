#pragma once
// What changes every frame, as the GPU pass receives it: the frame of time t
// computed by the code the CPU renderer uses (src/render/frame_setup.h: part
// poses, the environment's square lights rotated and blend-weighted to t,
// local light positions, the camera, the culling's occluder lists), and what
// the shader needs on top: the occluder lists, flattened into one array of
// uint texels (occluder_list_texels) that the shader walks per (receiver
// part, light). Any number of parts: the lists hold what the culling kept.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "src/core/scene.h"
#include "src/render/frame_setup.h"
#include "src/render/part_fields.h"
#include "src/render/render_options.h"

namespace rsl::gl {

class FrameState {
public:
    // `fields` must outlive this object (the culling reads the occluder fields).
    FrameState(const Scene& scene, const PartFields& fields);

    void reserve(size_t environment_lights, size_t local_lights) { setup_.reserve(environment_lights, local_lights); }
    // The frame at time t (FrameSetup::update), then the flattened lists.
    void update(const Scene& scene, const EnvironmentLights& environment, std::span<const LocalLight> lights,
                const RenderOptions& options, float t, const Mat3& extra_rotation = Mat3(1.0f),
                const std::optional<Vec3>& camera = std::nullopt);

    const FrameSetup& setup() const { return setup_; }
    const std::vector<PartPose>& poses() const { return setup_.poses(); }
    const std::vector<SquareLight>& environment_squares() const { return setup_.environment_squares(); }
    const std::vector<Vec3>& light_positions() const { return setup_.light_positions(); }
    const std::vector<Vec3>& light_axes() const { return setup_.light_axes(); }
    const Vec3& camera() const { return setup_.camera(); }
    // The CPU renderer's occluder lists (culling.h) as the shader reads them:
    // texel s = p·L + l (light l of receiver part p, environment lights
    // first) holds the index of the slot's first occluder texel and texel
    // s + 1 the end; the occluder part indices follow the P·L + 1 offsets.
    const std::vector<uint32_t>& occluder_list_texels() const { return list_texels_; }
    int light_count() const { return light_count_; }
    size_t occluder_pairs() const { return setup_.occluder_lists().pairs; }
    size_t occluder_pairs_culled() const { return setup_.occluder_lists().culled; }

private:
    void update_list_texels();

    FrameSetup setup_;
    std::vector<uint32_t> list_texels_;
    int light_count_ = 0;
};

}  // namespace rsl::gl
