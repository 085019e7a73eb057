#pragma once
// The GPU renderer with its own offscreen context, used like rsl::Renderer:
// the entry point of `rsl render --backend gl` (and anything else that wants
// GPU vertex colours without a window). Image formation stays the shared
// CPU one (src/frame/image_formation.h), so images compare like for like.
//
//   gl::HeadlessGlRenderer renderer(scene, setup.environment_lights, setup.fields, options);
//   VertexColors colors = renderer.make_output();
//   renderer.set_time(t);
//   renderer.shade(colors);   // shading pass on the GPU, colours read back
#include <string>

#include "src/gl/gl_renderer.h"
#include "src/gl/headless_context.h"

namespace rsl::gl {

class HeadlessGlRenderer {
public:
    HeadlessGlRenderer(const Scene& scene, RslSet environment_lights, PartFields fields, const RenderOptions& options)
        : renderer_(scene, std::move(environment_lights), std::move(fields), options) {}
    // The renderer's GL objects are deleted in this context (members are
    // destroyed after the body runs).
    ~HeadlessGlRenderer() { context_.make_current(); }
    HeadlessGlRenderer(const HeadlessGlRenderer&) = delete;
    HeadlessGlRenderer& operator=(const HeadlessGlRenderer&) = delete;

    void set_time(float t) { renderer_.set_time(t); }
    VertexColors make_output() const { return renderer_.make_output(); }
    void shade(VertexColors& out) {
        context_.make_current();
        renderer_.shade();
        renderer_.read_colors(out);
    }
    // "EGL surfaceless: OpenGL 4.5 (Core Profile) Mesa … on llvmpipe …"
    const std::string& device() const { return context_.description(); }
    const GlRenderer& renderer() const { return renderer_; }

private:
    HeadlessContext context_;  // first: current before the renderer is built
    GlRenderer renderer_;
};

}  // namespace rsl::gl
