// Kitchen (RSL paper Figure 16): five parts, the teapot and the cup moving on
// the counter, the lighting changing from one environment map to another,
// and one small sphere light moving through the scene so that the parts cast
// sharp shadows on the counter and on each other.
//
// The environment change: the CPU renderer takes one RSL set, so the demo
// fits both maps and cross-fades them. Light transport is linear in the
// lighting, so shading once with each map and blending the vertex colours
// with weights (1 − w, w) is exactly the cross-fade of the two maps' RSL
// radiance; both renderers include the local light, and as the weights sum to
// 1 it is counted once. A renderer whose weight is 0 is skipped.
#include <chrono>

#include <fmt/format.h>
#include <cmath>

#include "demos/demo_runners.h"
#include "demos/demo_support.h"
#include "src/core/error.h"
#include "src/render/render_setup.h"

namespace rsl::demos {

float environment_blend_weight(const EnvironmentDesc& environment, float t) {
    if (environment.second_file.empty() || !(environment.blend_period_seconds > 0)) return 0.0f;
    // 0 at t = 0, the second map alone at half the period, back at a full period.
    return 0.5f - 0.5f * std::cos(2.0f * kPi * t / environment.blend_period_seconds);
}

DemoResult run_kitchen_demo(const DemoOptions& options) {
    DemoResult result;
    result.name = "kitchen";
    const auto start = std::chrono::steady_clock::now();
    std::shared_ptr<Scene> scene = load_demo_scene(options, "kitchen/scene.json");
    if (scene->environment.second_file.empty())
        throw_file_error(scene->source, "the kitchen demo needs environment.second_file (the map it changes to)");
    RenderOptions render;
    if (options.quick) render.environment_lights = kQuickLights;
    const RenderSetup setup = prepare_render(scene, render, options.progress);
    const CubeMap second_map = load_environment(scene->environment.second_file, scene->environment.resolution);
    Renderer first(*scene, setup.environment_lights, setup.fields, render);
    Renderer second(*scene, fit_environment_lights(second_map, render.environment_lights), setup.fields, render);
    result.setup_seconds = seconds_between(start, std::chrono::steady_clock::now());

    VertexColors first_colors = first.make_output(), second_colors = second.make_output();
    SequenceSpec spec;
    spec.name = result.name;
    spec.shade = [&](int, float t, VertexColors& colors, FrameTiming& timing) {
        const auto begin = std::chrono::steady_clock::now();
        const float w = environment_blend_weight(scene->environment, t);
        std::vector<const VertexColors*> inputs;
        std::vector<float> weights;
        if (w < 1.0f) {
            first.set_time(t);
            first.shade(first_colors);
            inputs.push_back(&first_colors), weights.push_back(1.0f - w);
        }
        if (w > 0.0f) {
            second.set_time(t);
            second.shade(second_colors);
            inputs.push_back(&second_colors), weights.push_back(w);
        }
        weighted_sum(colors, inputs, weights);
        timing.shade_seconds = seconds_between(begin, std::chrono::steady_clock::now());
    };
    spec.label = [&](int, float t) {
        return fmt::format("t={:.2f}s mix={:.0f}%", t, 100.0f * environment_blend_weight(scene->environment, t));
    };
    render_sequence(spec, options, *scene, first.make_output(), result);
    result.notes.push_back(fmt::format(
        "{} vertices; {} and {} ({} RSLs each) cross-faded over {} s; {} local light(s)", scene->vertex_count(),
        scene->environment.file.filename().string(), scene->environment.second_file.filename().string(),
        render.environment_lights, scene->environment.blend_period_seconds, scene->lights.size()));
    return result;
}

}  // namespace rsl::demos
