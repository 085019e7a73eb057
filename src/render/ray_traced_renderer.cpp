#include "src/render/ray_traced_renderer.h"

#include "src/core/error.h"
#include "src/render/exact_visibility.h"

namespace rsl {

namespace {

// The options with the rays' visibility at t = 0, where the renderer's
// construction poses the scene.
RenderOptions with_rays(const Scene& scene, RenderOptions options) {
    if (options.ray_samples < 1 || options.ray_samples > RenderOptions::kMaxRaySamples)
        throw_file_error(scene.source, "the rays backend: {} ray samples per side is outside [1, {}]",
                         options.ray_samples, RenderOptions::kMaxRaySamples);
    options.exact_visibility =
        std::make_shared<ExactVisibility>(scene, 0.0f, ExactVisibilityMode::All, options.ray_samples, true);
    return options;
}

}  // namespace

RayTracedRenderer::RayTracedRenderer(const Scene& scene, EnvironmentLights environment_lights,
                                     const RenderOptions& options)
    : CpuRenderer(scene, std::move(environment_lights), PartFields{}, with_rays(scene, options)) {
    for (const PartPose& pose : frame_.poses()) posed_transforms_.push_back(pose.transform);
}

void RayTracedRenderer::frame_changed() {
    CpuRenderer::frame_changed();
    const std::vector<PartPose>& poses = frame_.poses();
    bool moved = time_ != posed_time_ || poses.size() != posed_transforms_.size();
    for (size_t p = 0; p < poses.size() && !moved; ++p) moved = poses[p].transform != posed_transforms_[p];
    if (!moved) return;
    options_.exact_visibility =
        std::make_shared<ExactVisibility>(scene_, time_, ExactVisibilityMode::All, options_.ray_samples, true);
    posed_time_ = time_;
    posed_transforms_.clear();
    for (const PartPose& pose : poses) posed_transforms_.push_back(pose.transform);
}

}  // namespace rsl
