#pragma once
// The one place that knows which renderers exist: callers name a backend and
// get a VertexRenderer (src/render/vertex_renderer.h), with no #ifdef of their
// own. The GL backends exist when rsl was built with RSL_BUILD_GL: Gl has its
// own offscreen context (gl::HeadlessGlRenderer); GlCurrentContext renders in
// the context current on the calling thread (gl::GlRenderer: an engine's
// context, whose pipeline draws the vertex-colour buffer itself).
#include <memory>
#include <string>
#include <vector>

#include "src/render/vertex_renderer.h"

namespace rsl {

enum class Backend { Cpu, Gl, GlCurrentContext };

// "cpu" / "gl" / "gl-current" → Backend; throws rsl::Error naming the known ones.
Backend parse_backend(const std::string& name);
std::string backend_name(Backend backend);
// The backends this build has ("cpu", and "gl", "gl-current" with RSL_BUILD_GL).
std::vector<std::string> available_backends();

// `scene` must outlive the renderer. Throws rsl::Error when the backend was
// not built (or, for gl, no OpenGL ≥ 4.3 context can be made; for
// gl-current, none is current).
std::unique_ptr<VertexRenderer> make_renderer(Backend backend, const Scene& scene,
                                              EnvironmentLights environment_lights, PartFields fields,
                                              const RenderOptions& options);

}  // namespace rsl
