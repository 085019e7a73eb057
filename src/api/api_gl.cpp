// The "gl-current" backend's output (include/rsl/rsl.h): the GPU renderer
// in the caller's context fills its vertex-colour buffer, which the caller
// draws with its own pipeline; nothing is read back.
#include <fmt/ranges.h>

#include "src/api/renderer_state.h"
#include "src/core/error.h"
#ifdef RSL_HAVE_GL
#include "src/gl/gl_renderer.h"
#endif

namespace rsl::api {

#ifdef RSL_HAVE_GL
namespace {
// The backends that render in the caller's context make a gl::GlRenderer
// (make_renderer.h, BackendCapabilities::caller_context).
gl::GlRenderer& caller_context_renderer(Backend backend, VertexRenderer& renderer) {
    auto* gl_renderer = dynamic_cast<gl::GlRenderer*>(&renderer);
    if (!backend_capabilities(backend).caller_context || !gl_renderer)
        throw_error("the GL colour buffer belongs to a backend that renders in the caller's context ({}; this "
                    "renderer is {})", fmt::join(backends_with(&BackendCapabilities::caller_context), ", "),
                    backend_name(backend));
    return *gl_renderer;
}
}  // namespace

void Renderer::shade_gl() {
    gl::GlRenderer& renderer = caller_context_renderer(state_->session->backend(), state_->renderer());
    state_->update_frame();
    renderer.shade_on_device();  // nothing is read back
}

unsigned Renderer::gl_color_buffer() const {
    return caller_context_renderer(state_->session->backend(), state_->renderer()).color_buffer();
}
#else
void Renderer::shade_gl() { throw_error("the gl-current backend: this rsl was built without OpenGL"); }
unsigned Renderer::gl_color_buffer() const {
    throw_error("the gl-current backend: this rsl was built without OpenGL");
}
#endif

}  // namespace rsl::api
