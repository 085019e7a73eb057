#pragma once
// The one place that knows which renderers exist: callers name a backend and
// get a VertexRenderer (src/render/vertex_renderer.h), with no #ifdef of their
// own. Cpu is the fields' sum on the CPU (CpuRenderer); Rays the same sum with
// every light's visibility traced by Embree (RayTracedRenderer, the ray-traced
// baseline). The GL backends exist when rsl was built with RSL_BUILD_GL: Gl
// has its own offscreen context (gl::HeadlessGlRenderer); GlCurrentContext
// renders in the context current on the calling thread (gl::GlRenderer: an
// engine's context, whose pipeline draws the vertex-colour buffer itself).
#include <memory>
#include <string>
#include <vector>

#include "src/render/vertex_renderer.h"

namespace rsl {

enum class Backend { Cpu, Rays, Gl, GlCurrentContext };

// "cpu" / "rays" / "gl" / "gl-current" → Backend; throws rsl::Error naming the known ones.
Backend parse_backend(const std::string& name);
std::string backend_name(Backend backend);
// The backends this build has ("cpu", "rays", and "gl", "gl-current" with RSL_BUILD_GL).
std::vector<std::string> available_backends();

// What a backend can do: callers (the `rsl` program, the API, Python) ask
// this rather than name backends, so that another backend is one more case
// here and in make_renderer.
struct BackendCapabilities {
    bool standalone = false;      // makes what it needs itself (no caller's context): `rsl render --backend`
    bool fields = false;          // shades with the SVDF/OVDF fields, which a RenderSession loads or bakes
                                  // (RenderOptions::self_visibility, occluders switch them off)
    bool ray_samples = false;     // its visibility is RenderOptions::ray_samples² traced rays per vertex and light
    bool device = false;          // runs on a device, which VertexRenderer::device() names
    bool per_pixel_pass = false;  // shades the image's per-pixel parts on the device
    bool gpu_rays = false;        // RenderOptions::gpu_rays: the ray-traced visibility baseline
    bool shadow_maps = false;     // RenderOptions::shadow_maps: the shadow-mapped visibility baseline
    bool timer_queries = false;   // times its passes on the device (VertexRenderer::pass_times)
    bool caller_context = false;  // renders in the caller's current OpenGL context, into a buffer of its
                                  // vertex colours (gl::GlRenderer::color_buffer: the API's gl_color_buffer)
};
BackendCapabilities backend_capabilities(Backend backend);
// The names of the backends this build has with `capability` set, in
// available_backends() order (e.g. &BackendCapabilities::shadow_maps).
std::vector<std::string> backends_with(bool BackendCapabilities::*capability);

// `scene` must outlive the renderer. A backend without `fields` ignores
// `fields`. Throws rsl::Error when the backend was not built (or, for gl, no
// OpenGL ≥ 4.3 context can be made; for gl-current, none is current) or
// refuses an option (the CPU ones the GL baselines, rays a bad ray_samples).
std::unique_ptr<VertexRenderer> make_renderer(Backend backend, const Scene& scene,
                                              EnvironmentLights environment_lights, PartFields fields,
                                              const RenderOptions& options);

}  // namespace rsl
