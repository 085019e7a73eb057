#pragma once
// `rsl view SCENE`: the interactive viewer (GLFW window, Dear ImGui panel) on
// top of the GPU renderer. Mouse: left-drag orbits, right-drag turns the
// environment, wheel zooms, shift + left-drag moves the local light in the
// view plane. Keys: space play/pause, ←/→ turn the environment, R cycles
// RSL / the GPU ray-traced reference / both side by side, H hides the
// panel, Esc quits. The panel swaps each part's BRDF, edits material
// parameters (the table is rebuilt and uploaded the same frame), re-fits the
// environment with another number of RSLs in a background thread, switches
// each visibility factor, and shows fps and the GPU time of each pass.
#include <filesystem>
#include <functional>
#include <string>

#include "src/core/scene.h"
#include "src/render/render_options.h"

namespace rsl::gl {

// What the window shows: the RSL renderer, the ray-traced reference
// (RenderOptions::gpu_rays: the CPU ray rows' rays on the GPU), or both side
// by side, RSL on the left, each with its frame time.
enum class ViewMode { Rsl, Rays, Split };
// "rsl", "rays" or "split"; others throw rsl::Error.
ViewMode parse_view_mode(const std::string& name);

struct ViewerOptions {
    std::filesystem::path scene;
    RenderOptions render;
    bool quick_fields = false;         // small precompute settings: seconds instead of minutes
    float start_time = 0;
    float exposure = 0;                // stops
    bool auto_exposure = true;         // set `exposure` from the first frame's vertex colours
    int width = 1280, height = 720;
    bool panel = true;
    ViewMode view = ViewMode::Rsl;
    int reference_rays = 2;            // S of the ray-traced reference: S×S rays per vertex and light
    // Screenshot mode: render `frames` frames (playing), save the last to
    // `screenshot` (PNG) and exit. frames = 0: interactive.
    std::filesystem::path screenshot;
    int frames = 0;
    // Screenshot mode on a software renderer (is_software_renderer: seconds
    // a frame): render at most kSoftwareWidth pixels wide, without the panel
    // (it would cover the small image) and without the per-pixel passes
    // (RenderOptions::pixel_shadows, pixel_highlights: two thirds of
    // llvmpipe's frame), so that a dozen frames take seconds, not minutes
    // (docs/GPU.md).
    bool software_fallback = false;
    static constexpr int kSoftwareWidth = 480;
    // Hears the fit's and the field bakes' progress (SetupOptions::progress).
    std::function<void(const std::string& what, double fraction)> progress;
    // Hears the context's description (context_description) once it is made.
    std::function<void(const std::string& line)> notice;
    // Hears that the software fallback applies, with the size it renders at.
    std::function<void(int width, int height)> software_fallback_applied;
    // In screenshot mode, hears each frame's end: its number (1..frames) and
    // the seconds it took.
    std::function<void(int frame, int frames, double seconds)> frame_done;
};

// Runs the viewer until the window closes (or the screenshot is written).
// Throws rsl::Error when no window or GL 4.3 core context can be had.
void run_viewer(const ViewerOptions& options);

// Precompute settings small enough to bake a scene's fields in seconds.
void use_quick_fields(PrecomputeSettings& settings);

}  // namespace rsl::gl
