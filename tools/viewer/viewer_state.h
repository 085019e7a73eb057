#pragma once
// The viewer's state between frames and its ImGui panel (viewer_panel.cpp).
#include <future>
#include <memory>
#include <vector>

#include "src/brdf/material_library.h"
#include "src/core/envmap.h"
#include "src/core/scene.h"
#include "src/gl/gl_renderer.h"
#include "tools/viewer/viewer.h"

namespace rsl::gl {

struct OrbitCamera {
    Vec3 target{0};
    float distance = 3, yaw = 0, pitch = 0.3f;  // radians
    float fov_y_degrees = 40;
    Vec3 eye() const {
        return target + distance * Vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
    }
};

struct ViewerState {
    Scene* scene = nullptr;
    const CubeMap* environment = nullptr;
    const CubeMap* second_environment = nullptr;  // the blend's second map; null without one
    GlRenderer* renderer = nullptr;  // its materials() is what the panel edits
    // The ray-traced reference (made at the first frame that shows it): the
    // renderer's materials, lights and toggles, with GPU rays for visibility.
    std::unique_ptr<GlRenderer> reference;
    ViewMode mode = ViewMode::Rsl;
    int reference_rays = 2;
    OrbitCamera camera;
    float time = 0, environment_degrees = 0, exposure = 0;
    bool playing = true, panel = true;
    RenderOptions toggles;
    int rsl_count = 30;
    std::future<EnvironmentLights> refit;  // the background fit, when one runs
    int refit_count = 0;
    bool lights_dirty = false;  // the scene's first light moved: hand the lights to the renderer
    double frame_ms = 0, fps = 0;
};

// Draws the panel and applies what changed (materials, toggles, RSL count);
// with the reference shown, the two renderers' frame times on screen (view_overlay).
void viewer_panel(ViewerState& state);
void view_overlay(const ViewerState& state);
// Applies finished background work (new RSL sets) and moved lights.
void apply_pending(ViewerState& state);

}  // namespace rsl::gl
