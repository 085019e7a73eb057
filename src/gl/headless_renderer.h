#pragma once
// The GPU renderer with its own offscreen context: the VertexRenderer that
// make_renderer(Backend::Gl, …) returns (`rsl render --backend gl`, the
// benchmarks, anything that wants GPU vertex colours without a window).
// Image formation stays the shared CPU one (src/frame/image_formation.h), so
// images compare like for like. Every call makes its context current first.
#include <string>

#include "src/gl/gl_renderer.h"
#include "src/gl/headless_context.h"

namespace rsl::gl {

class HeadlessGlRenderer final : public VertexRenderer {
public:
    HeadlessGlRenderer(const Scene& scene, EnvironmentLights environment_lights, PartFields fields,
                       const RenderOptions& options)
        : renderer_(scene, std::move(environment_lights), std::move(fields), options) {}
    // The renderer's GL objects are deleted in this context (members are
    // destroyed after the body runs).
    ~HeadlessGlRenderer() override { context_.make_current(); }
    HeadlessGlRenderer(const HeadlessGlRenderer&) = delete;
    HeadlessGlRenderer& operator=(const HeadlessGlRenderer&) = delete;

    std::string backend() const override { return "gl"; }
    // "GPU: EGL surfaceless: OpenGL 4.5 (Core Profile) Mesa … on llvmpipe …"
    std::string device() const override { return "GPU: " + context_.description(); }
    const Scene& scene() const override { return renderer_.scene(); }

    void set_time(float t) override { renderer_.set_time(t); }
    void set_view(float t, const Vec3& camera, const Mat3& rotation) override { renderer_.set_view(t, camera, rotation); }
    float time() const override { return renderer_.time(); }
    // Edits only touch the library; the upload happens in shade().
    MaterialLibrary& materials() override { return renderer_.materials(); }
    const MaterialLibrary& materials() const override { return renderer_.materials(); }
    void set_environment_lights(EnvironmentLights lights) override {
        renderer_.set_environment_lights(std::move(lights));
    }
    const EnvironmentLights& environment_lights() const override { return renderer_.environment_lights(); }
    void set_local_lights(std::vector<LocalLight> lights) override { renderer_.set_local_lights(std::move(lights)); }
    const std::vector<LocalLight>& local_lights() const override { return renderer_.local_lights(); }
    VertexColors make_output() const override { return renderer_.make_output(); }
    void shade(VertexColors& out) override {
        context_.make_current();
        renderer_.shade(out);
    }
    using VertexRenderer::shade;
    std::optional<Image> device_image(const PinholeCamera& camera) override {
        context_.make_current();
        return renderer_.form_image(camera);
    }
    const RenderStats& stats() const override { return renderer_.stats(); }
    std::string pass_times() const override { return renderer_.pass_times(); }

    const GlRenderer& renderer() const { return renderer_; }

private:
    HeadlessContext context_;  // first: current before the renderer is built
    GlRenderer renderer_;
};

}  // namespace rsl::gl
