// rsl view SCENE: the interactive GPU viewer (tools/viewer/viewer.h).
#ifdef RSL_HAVE_GL
#include <memory>

#include "tools/rsl/progress_display.h"
#include "tools/rsl/command.h"
#include "tools/rsl/render_args.h"
#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/core/scene.h"
#include "tools/viewer/viewer.h"
#include "src/formats/scene_file.h"
#include "src/render/render_setup.h"

namespace rsl::cli {
namespace {

struct ViewArgs {
    std::string scene, screenshot, view = "rsl";
    int lights = 30, frames = 0, width = 1280, height = 720, reference_rays = 2;
    float time = 0, exposure = 0;
    bool quick = false, no_panel = false;
    std::vector<std::string> materials;
};

RegisterCommand view_command({"view",
    "Open a window on a scene, rendered on the GPU: orbit, turn the environment, swap and edit BRDFs, move a light.",
    35, [](CLI::App& app) {
        auto args = std::make_shared<ViewArgs>();
        app.add_option("scene", args->scene, "Scene file (.json, .gltf/.glb, .obj)")->required()->check(CLI::ExistingFile);
        app.add_option("--lights,-k", args->lights, "Number of environment RSLs at start")->capture_default_str();
        app.add_option("--time,-t", args->time, "Start time in seconds")->capture_default_str();
        auto* exposure = app.add_option("--exposure", args->exposure, "Exposure in stops (default: automatic)");
        auto* width = app.add_option("--width", args->width,
                                     "Window width (a screenshot on software OpenGL: 480 unless --width or --height is given)")
                          ->capture_default_str();
        auto* height = app.add_option("--height", args->height, "Window height")->capture_default_str();
        app.add_option("--material", args->materials, "PART=MATERIAL: shade a part with another scene material");
        app.add_flag("--quick-fields", args->quick,
                     "Bake small visibility fields (seconds instead of minutes; coarser shadows)");
        app.add_flag("--no-panel", args->no_panel, "Hide the control panel (H toggles it)");
        app.add_option("--view", args->view,
                       "What the window shows (R cycles): rsl, rays (the ray-traced reference: SxS shadow rays per "
                       "vertex and light traced on the GPU) or split (RSL left, rays right, each with its time)")
            ->check(CLI::IsMember({"rsl", "rays", "split"}))
            ->capture_default_str();
        app.add_option("--reference-rays", args->reference_rays, "S of the ray-traced reference, 1..16")
            ->check(CLI::Range(1, GpuRayOptions::kMaxSamplesPerSide))
            ->capture_default_str();
        app.add_option("--screenshot", args->screenshot,
                       "Write the last frame to this PNG and exit (with --frames). On software OpenGL (llvmpipe) "
                       "without --width/--height: 480 pixels wide, no panel, no per-pixel passes");
        app.add_option("--frames", args->frames, "Render N frames (playing the animation), print each one's time, then exit");
        app.callback([args, exposure, width, height] {
            if (args->lights < 1) throw_error("--lights {}: expected at least 1", args->lights);
            if (!args->screenshot.empty() && args->frames < 1) throw_error("--screenshot needs --frames N (N ≥ 1)");
            if (!args->screenshot.empty()) check_outputs_apart({args->screenshot}, load_scene(args->scene).input_files);
            gl::ViewerOptions options;
            options.scene = args->scene;
            options.render.environment_light_count = args->lights;
            options.render.material_override = parse_material_overrides(args->materials);
            options.quick_fields = args->quick;
            options.start_time = args->time;
            options.exposure = args->exposure;
            options.auto_exposure = exposure->count() == 0;
            options.width = args->width;
            options.height = args->height;
            options.panel = !args->no_panel;
            options.view = gl::parse_view_mode(args->view);
            options.reference_rays = args->reference_rays;
            options.screenshot = args->screenshot;
            options.frames = args->frames;
            // A GPU's default window, shrunk on a software renderer unless a size was asked for.
            options.software_fallback = width->count() == 0 && height->count() == 0;
            ProgressDisplay display;
            options.progress = [&display](const std::string& what, double fraction) { display(what, fraction); };
            options.notice = [&display](const std::string& line) { display.note(line); };
            options.software_fallback_applied = [&display](int w, int h) {
                display.note(fmt::format("software OpenGL: frames at {}×{} without the panel and the per-pixel "
                                         "passes, seconds each, not tens (--width/--height: the full setting)", w, h));
            };
            options.frame_done = [&display](int frame, int frames, double seconds) {
                display.note(fmt::format("frame {}/{}: {:.2f} s", frame, frames, seconds));
            };
            gl::run_viewer(options);
        });
    }});

}  // namespace
}  // namespace rsl::cli
#endif  // RSL_HAVE_GL
