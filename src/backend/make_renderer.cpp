#include "src/backend/make_renderer.h"

#include "src/core/error.h"
#include "src/render/renderer.h"
#ifdef RSL_HAVE_GL
#include "src/gl/headless_renderer.h"
#endif

namespace rsl {

Backend parse_backend(const std::string& name) {
    if (name == "cpu") return Backend::Cpu;
    if (name == "gl") return Backend::Gl;
    throw_error("unknown renderer backend '{}' (known: cpu, gl)", name);
}

std::string backend_name(Backend backend) { return backend == Backend::Gl ? "gl" : "cpu"; }

std::vector<std::string> available_backends() {
#ifdef RSL_HAVE_GL
    return {"cpu", "gl"};
#else
    return {"cpu"};
#endif
}

std::unique_ptr<VertexRenderer> make_renderer(Backend backend, const Scene& scene,
                                              EnvironmentLights environment_lights, PartFields fields,
                                              const RenderOptions& options) {
    switch (backend) {
    case Backend::Cpu:
        return std::make_unique<Renderer>(scene, std::move(environment_lights), std::move(fields), options);
    case Backend::Gl:
#ifdef RSL_HAVE_GL
        return std::make_unique<gl::HeadlessGlRenderer>(scene, std::move(environment_lights), std::move(fields),
                                                        options);
#else
        throw_error("the gl backend: this rsl was built without OpenGL (RSL_BUILD_GL=OFF)");
#endif
    }
    throw_error("unknown renderer backend {}", int(backend));
}

}  // namespace rsl
