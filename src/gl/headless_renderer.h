#pragma once
// The GPU renderer with its own offscreen context: the VertexRenderer that
// make_renderer(Backend::Gl, …) returns (`rsl render --backend gl`, the API,
// the benchmarks, anything that wants GPU vertex colours and images without
// a window). Every call that reaches the GPU makes its context current first.
#include <string>

#include "src/gl/gl_renderer.h"
#include "src/core/error.h"
#include "src/gl/headless_context.h"

namespace rsl::gl {

// A base of HeadlessGlRenderer before GlRenderer, so that the context is
// made (and current) before the renderer builds its GL objects.
struct OwnContext {
    HeadlessContext context;
};

class HeadlessGlRenderer final : private OwnContext, public GlRenderer {
public:
    HeadlessGlRenderer(const Scene& scene, EnvironmentLights environment_lights, PartFields fields,
                       const RenderOptions& options)
        : GlRenderer(scene, std::move(environment_lights), std::move(fields), options) {}
    // The renderer's GL objects are deleted in this context (GlRenderer is
    // destroyed after this body runs, the context after it).
    ~HeadlessGlRenderer() override {
        try {
            context.make_current();
        } catch (const Error& e) {
            warn("deleting the GL renderer's objects without its context: {}", e.what());
        }
    }

    // "GPU: EGL surfaceless: OpenGL 4.5 (Core Profile) Mesa … on llvmpipe …"
    std::string device() const override { return "GPU: " + context.description(); }
    void shade(VertexColors& out) override {
        context.make_current();
        GlRenderer::shade(out);
    }
    using GlRenderer::shade;
    // GlRenderer's own calls that reach the GPU, in this context.
    void shade_on_device() {
        context.make_current();
        GlRenderer::shade_on_device();
    }
    void read_colors(VertexColors& out) {
        context.make_current();
        GlRenderer::read_colors(out);
    }
    void draw(const Mat4& view_projection, float exposure) {
        context.make_current();
        GlRenderer::draw(view_projection, exposure);
    }

protected:
    Image backend_image(const VertexColors& colors, const PinholeCamera& camera,
                        const ImageFormationOptions& options) override {
        context.make_current();
        return GlRenderer::backend_image(colors, camera, options);
    }
};

}  // namespace rsl::gl
