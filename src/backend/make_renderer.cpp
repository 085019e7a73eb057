#include "src/backend/make_renderer.h"

#include "src/core/error.h"
#include "src/render/cpu_renderer.h"
#include "src/render/ray_traced_renderer.h"
#ifdef RSL_HAVE_GL
#include "src/gl/gl.h"
#include "src/gl/headless_renderer.h"
#endif

namespace rsl {

Backend parse_backend(const std::string& name) {
    if (name == "cpu") return Backend::Cpu;
    if (name == "rays") return Backend::Rays;
    if (name == "gl") return Backend::Gl;
    if (name == "gl-current") return Backend::GlCurrentContext;
    throw_error("unknown renderer backend '{}' (known: cpu, rays, gl, gl-current)", name);
}

std::string backend_name(Backend backend) {
    switch (backend) {
    case Backend::Cpu: return "cpu";
    case Backend::Rays: return "rays";
    case Backend::Gl: return "gl";
    case Backend::GlCurrentContext: return "gl-current";
    }
    return "unknown";
}

std::vector<std::string> available_backends() {
#ifdef RSL_HAVE_GL
    return {"cpu", "rays", "gl", "gl-current"};
#else
    return {"cpu", "rays"};
#endif
}

BackendCapabilities backend_capabilities(Backend backend) {
    BackendCapabilities can;
    switch (backend) {
    case Backend::Cpu: can.standalone = can.fields = true; break;
    case Backend::Rays: can.standalone = can.ray_samples = true; break;
    case Backend::Gl:
    case Backend::GlCurrentContext:
        can.standalone = backend == Backend::Gl;
        can.caller_context = backend == Backend::GlCurrentContext;
        can.fields = can.device = can.per_pixel_pass = can.gpu_rays = can.shadow_maps = can.timer_queries = true;
        break;
    }
    return can;
}

std::vector<std::string> backends_with(bool BackendCapabilities::*capability) {
    std::vector<std::string> names;
    for (const std::string& name : available_backends())
        if (backend_capabilities(parse_backend(name)).*capability) names.push_back(name);
    return names;
}

std::unique_ptr<VertexRenderer> make_renderer(Backend backend, const Scene& scene,
                                              EnvironmentLights environment_lights, PartFields fields,
                                              const RenderOptions& options) {
    switch (backend) {
    case Backend::Cpu:
        return std::make_unique<CpuRenderer>(scene, std::move(environment_lights), std::move(fields), options);
    case Backend::Rays: return std::make_unique<RayTracedRenderer>(scene, std::move(environment_lights), options);
    case Backend::Gl:
#ifdef RSL_HAVE_GL
        return std::make_unique<gl::HeadlessGlRenderer>(scene, std::move(environment_lights), std::move(fields),
                                                        options);
#else
        throw_error("the gl backend: this rsl was built without OpenGL (RSL_BUILD_GL=OFF)");
#endif
    case Backend::GlCurrentContext:
#ifdef RSL_HAVE_GL
        if (!gl::has_current_context())
            throw_error("the gl-current backend: no OpenGL context is current on this thread (make the "
                        "engine's OpenGL >= 4.3 core context current first, or use the gl backend)");
        return std::make_unique<gl::GlRenderer>(scene, std::move(environment_lights), std::move(fields), options);
#else
        throw_error("the gl-current backend: this rsl was built without OpenGL (RSL_BUILD_GL=OFF)");
#endif
    }
    throw_error("unknown renderer backend {}", int(backend));
}

}  // namespace rsl
