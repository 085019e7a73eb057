// Robot (RSL paper Figure 13): the 12-part walking robot on the ground under
// the sun/sky map, which turns about the vertical axis, seen from a camera
// moving on a path. The sun's sharp shadow on the ground and on the robot
// itself moves with the limbs: the OVDFs of the parts (others' shadows) and
// the SVDFs (self-shadows) are looked up every frame.
#include <chrono>

#include <fmt/format.h>

#include "tools/rsl/progress_display.h"
#include "demos/demo_runners.h"
#include "demos/demo_support.h"

namespace rsl::demos {

DemoResult run_robot_demo(const DemoOptions& options) {
    DemoResult result;
    result.name = "robot";
    const auto start = std::chrono::steady_clock::now();
    std::shared_ptr<Scene> scene = load_demo_scene(options, "robot/scene.json");
    RenderOptions render;
    if (options.quick) render.environment_light_count = kQuickLights;
    RenderSession session(scene, render, Backend::Cpu,
                          {.progress = cli::drawn_progress(options.progress), .field_cache = options.field_cache});
    result.setup_seconds = seconds_between(start, std::chrono::steady_clock::now());

    SequenceSpec spec;
    spec.name = result.name;
    render_sequence(spec, options, session, result);
    result.notes.push_back(fmt::format("{} vertices, {} square lights, sun/sky turning {:.0f} deg/s",
                                       scene->vertex_count(), session.renderer().stats().lights,
                                       scene->environment.rotation_degrees_per_second));
    return result;
}

}  // namespace rsl::demos
