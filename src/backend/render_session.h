#pragma once
// One scene made ready to render and rendered frame by frame: the scene
// loaded, the environment fitted, the fields loaded or baked
// (prepare_render), a renderer of the chosen backend (make_renderer), and per
// frame the pose, the shade and the image. `rsl render`, the C++ and Python
// API, the demos and the benchmarks all start here, so a scene renders the
// same way whoever asks (docs/design/RENDERER.md, "The renderer base").
#include <filesystem>
#include <memory>

#include "src/backend/make_renderer.h"
#include "src/render/render_setup.h"

namespace rsl {

class RenderSession {
public:
    // Loads the scene file, fits options.environment_light_count RSLs, loads or
    // bakes the fields the options switch on (none for a backend without
    // BackendCapabilities::fields), makes the backend's renderer.
    RenderSession(const std::filesystem::path& scene_path, const RenderOptions& options,
                  Backend backend = Backend::Cpu, const SetupOptions& setup = {});
    // The same for a scene in memory; the session shares it with the caller,
    // who may edit it between frames as the API does (the renderer reads it).
    RenderSession(std::shared_ptr<Scene> scene, const RenderOptions& options, Backend backend = Backend::Cpu,
                  const SetupOptions& setup = {});

    const RenderSetup& setup() const { return setup_; }
    Scene& scene() { return *setup_.scene; }
    const Scene& scene() const { return *setup_.scene; }
    Backend backend() const { return backend_; }
    VertexRenderer& renderer() { return *renderer_; }
    const VertexRenderer& renderer() const { return *renderer_; }

    // Poses the scene at time t (after edits to the scene, too).
    void set_time(float t) { renderer_->set_time(t); }
    // Shades every vertex at the renderer's time; with `for_image`, also
    // keeps what image() needs (the per-pixel terms).
    const VertexColors& shade(bool for_image = true);
    // set_time(t), then shade(for_image).
    const VertexColors& shade(float t, bool for_image = true);
    // The last shade()'s vertex colours (black before the first).
    const VertexColors& colors() const { return colors_; }
    // The scene's camera at the renderer's time, width × height (0: the camera's own).
    PinholeCamera camera(int width = 0, int height = 0) const;
    // The image of the last shade(for_image = true) through `camera`, formed
    // by the renderer: the same picture on every backend.
    Image image(const PinholeCamera& camera, const ImageFormationOptions& formation = {});

private:
    RenderSetup setup_;
    Backend backend_;
    std::unique_ptr<VertexRenderer> renderer_;
    VertexColors colors_;
};

}  // namespace rsl
