#pragma once
// The rays backend (`rsl render --backend rays`, docs/BASELINES.md "Many
// lights"): the CPU renderer's sum with every light's visibility — what
// replaces SVDF × Π OVDF — from S×S jittered shadow rays per vertex and
// light, traced by Embree through the scene posed at the renderer's time
// (ExactVisibility, mode All, RenderOptions::ray_samples). It needs no
// fields (make_renderer's capabilities say so, and a RenderSession bakes
// none). The rays are those of the ray-traced rows of `rsl baselines
// --many-light` and of the GL backend's --gpu-rays (the same seeds,
// src/shading/ray_samples.h), so a frame is reproducible bit for bit.
#include <vector>

#include "src/render/cpu_renderer.h"

namespace rsl {

class RayTracedRenderer final : public CpuRenderer {
public:
    // As VertexRenderer's constructor; `fields` are not used (none are
    // kept). Throws rsl::Error when options.ray_samples is outside
    // [1, RenderOptions::kMaxRaySamples], naming the scene file.
    RayTracedRenderer(const Scene& scene, EnvironmentLights environment_lights, const RenderOptions& options);

    std::string backend() const override { return "rays"; }

protected:
    // The rays' scene follows the frame: posed again when the time or a
    // part's transform changed (the API moves parts between frames).
    void frame_changed() override;

private:
    float posed_time_ = 0;
    std::vector<Mat4> posed_transforms_;  // per part, the transforms the rays' scene was built with
};

}  // namespace rsl
