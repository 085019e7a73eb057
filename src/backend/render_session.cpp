#include "src/backend/render_session.h"
#include "src/formats/scene_file.h"

#include <utility>

namespace rsl {

RenderSession::RenderSession(const std::filesystem::path& scene_path, const RenderOptions& options, Backend backend,
                             const SetupOptions& setup)
    : RenderSession(std::make_shared<Scene>(load_scene(scene_path)), options, backend, setup) {}

namespace {

// What prepare_render makes for `backend`: no fields for a backend that does
// not shade with them (BackendCapabilities::fields).
RenderOptions setup_options(const RenderOptions& options, Backend backend) {
    RenderOptions o = options;
    if (!backend_capabilities(backend).fields) o.self_visibility = o.occluders = false;
    return o;
}

}  // namespace

RenderSession::RenderSession(std::shared_ptr<Scene> scene, const RenderOptions& options, Backend backend,
                             const SetupOptions& setup)
    : setup_(prepare_render(std::move(scene), setup_options(options, backend), setup)),
      backend_(backend),
      renderer_(make_renderer(backend, *setup_.scene, setup_.environment_lights, setup_.fields, options)),
      colors_(renderer_->make_output()) {}

const VertexColors& RenderSession::shade(bool for_image) {
    renderer_->keep_image_terms(for_image);
    renderer_->shade(colors_);
    return colors_;
}

const VertexColors& RenderSession::shade(float t, bool for_image) {
    set_time(t);
    return shade(for_image);
}

PinholeCamera RenderSession::camera(int width, int height) const {
    const Camera& desc = scene().camera;
    return PinholeCamera::at_time(desc, renderer_->time(), width > 0 ? width : desc.width,
                                  height > 0 ? height : desc.height);
}

Image RenderSession::image(const PinholeCamera& camera, const ImageFormationOptions& formation) {
    return renderer_->form_image(colors_, camera, formation);
}

}  // namespace rsl
