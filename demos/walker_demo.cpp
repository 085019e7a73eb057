// Walker: the project's skinned, textured character (tools/assets/walker.h)
// walks a circle round a steel orb beside a glazed teapot under the turning
// sun/sky map. Its skin is split into eight rigid segments whose fields move
// with their joints (docs/design/SKINNING.md); its cloth, skin and metal belt
// come from a base colour and a metallic-roughness texture
// (docs/design/BRDF.md "Textured roughness and metallic").
#include <chrono>

#include <fmt/format.h>

#include "tools/rsl/progress_display.h"
#include "demos/demo_runners.h"
#include "demos/demo_support.h"

namespace rsl::demos {

DemoResult run_walker_demo(const DemoOptions& options) {
    DemoResult result;
    result.name = "walker";
    const auto start = std::chrono::steady_clock::now();
    std::shared_ptr<Scene> scene = load_demo_scene(options, "walker/scene.json");
    RenderOptions render;
    if (options.quick) render.environment_light_count = kQuickLights;
    RenderSession session(scene, render, Backend::Cpu,
                          {.progress = cli::drawn_progress(options.progress), .field_cache = options.field_cache});
    result.setup_seconds = seconds_between(start, std::chrono::steady_clock::now());

    SequenceSpec spec;
    spec.name = result.name;
    render_sequence(spec, options, session, result);
    result.notes.push_back(fmt::format("{} vertices ({} skin segments), {} square lights, sun/sky turning {:.0f} deg/s",
                                       scene->vertex_count(), scene->skins.empty() ? 0 : scene->skins[0].joints.size(),
                                       session.renderer().stats().lights,
                                       scene->environment.rotation_degrees_per_second));
    return result;
}

}  // namespace rsl::demos
