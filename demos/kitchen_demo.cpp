// Kitchen (RSL paper Figure 16): five parts, the teapot and the cup moving on
// the counter, the lighting changing from one environment map to another,
// and one small sphere light moving through the scene so that the parts cast
// sharp shadows on the counter and on each other.
//
// The environment change is the renderer core's (src/render/frame_setup.h):
// the scene file's second map and period, both maps fitted with their own
// RSLs, shaded in one pass with weights (1 − w(t), w(t)); at w = 0 or 1 only
// one set is shaded.
#include <chrono>

#include <fmt/format.h>
#include <cmath>

#include "tools/rsl/progress_display.h"
#include "demos/demo_runners.h"
#include "demos/demo_support.h"
#include "src/core/error.h"

namespace rsl::demos {

DemoResult run_kitchen_demo(const DemoOptions& options) {
    DemoResult result;
    result.name = "kitchen";
    const auto start = std::chrono::steady_clock::now();
    std::shared_ptr<Scene> scene = load_demo_scene(options, "kitchen/scene.json");
    if (scene->environment.second_file.empty())
        throw_file_error(scene->source, "the kitchen demo needs environment.second_file (the map it changes to)");
    RenderOptions render;
    if (options.quick) render.environment_light_count = kQuickLights;
    RenderSession session(scene, render, Backend::Cpu,
                          {.progress = cli::drawn_progress(options.progress), .field_cache = options.field_cache});
    result.setup_seconds = seconds_between(start, std::chrono::steady_clock::now());

    SequenceSpec spec;
    spec.name = result.name;
    spec.label = [&](int, float t) {
        return fmt::format("t={:.2f}s mix={:.0f}%", t, 100.0f * scene->environment.blend_weight_at(t));
    };
    render_sequence(spec, options, session, result);
    result.notes.push_back(fmt::format(
        "{} vertices; {} and {} ({} RSLs each) blended by the renderer over a {} s period; {} local light(s)", scene->vertex_count(),
        scene->environment.file.filename().string(), scene->environment.second_file.filename().string(),
        render.environment_light_count, scene->environment.blend_period_seconds, scene->lights.size()));
    return result;
}

}  // namespace rsl::demos
