// Materials (RSL paper Figure 15): the same object four times in a row, in
// steel (Phong), bronze (Cook-Torrance), metal (isotropic Ward) and brushed
// steel (anisotropic Ward). A scripted edit sweeps their glossiness over the
// frames; every frame the BRDF tables are rebuilt from the edited materials,
// and nothing else: the visibility fields stay, since the BRDF is a separate
// factor of the product (RSL paper §4.2).
//
// The CPU renderer builds its tables in its constructor (MaterialTables), so
// the edit rebuilds the renderer around the same fields and RSLs; its cost is
// the table rebuild, reported per frame as the "update" time.
#include <algorithm>
#include <chrono>

#include <fmt/format.h>
#include <cmath>

#include "tools/rsl/progress_display.h"
#include "demos/demo_runners.h"
#include "demos/demo_support.h"
#include "src/core/error.h"

namespace rsl::demos {

void set_glossiness(MaterialDesc& material, float roughness) {
    const float r = std::clamp(roughness, 0.02f, 1.0f);
    if (material.model == "phong" || material.model == "blinn_phong")
        material.params["exponent"] = {2.0f / (r * r) - 2.0f};
    else if (material.model == "cook_torrance_beckmann" || material.model == "cook_torrance_ggx")
        material.params["roughness"] = {r};
    else if (material.model == "ward")
        material.params["alpha"] = {r};
    else if (material.model == "ward_anisotropic")
        material.params["alpha_x"] = {r}, material.params["alpha_y"] = {std::max(0.02f, 0.25f * r)};
    else
        throw_error("material '{}' ({}): no glossiness parameter to sweep", material.name, material.model);
}

float sweep_roughness(int frame, int frames) {
    const float s = frames > 1 ? float(frame) / float(frames - 1) : 0.0f;
    return 0.06f + (0.5f - 0.06f) * s;
}

DemoResult run_materials_demo(const DemoOptions& options) {
    DemoResult result;
    result.name = "materials";
    const auto start = std::chrono::steady_clock::now();
    std::shared_ptr<Scene> scene = load_demo_scene(options, "materials/scene.json");
    // Every material a part named orb_* uses is swept; the floor is not.
    std::vector<int> swept;
    for (const Part& part : scene->parts)
        if (part.name.rfind("orb", 0) == 0 &&
            std::find(swept.begin(), swept.end(), part.material) == swept.end())
            swept.push_back(part.material);
    if (swept.empty()) throw_file_error(scene->source, "no part named orb*: nothing to sweep");
    RenderOptions render;
    if (options.quick) render.environment_light_count = kQuickLights;
    RenderSession session(scene, render, Backend::Cpu,
                          {.progress = cli::drawn_progress(options.progress), .field_cache = options.field_cache});
    result.setup_seconds = seconds_between(start, std::chrono::steady_clock::now());

    const int frames = options.frames > 0 ? options.frames : 12;
    MaterialLibrary& library = session.renderer().materials();
    SequenceSpec spec;
    spec.name = result.name;
    spec.default_width = 480, spec.default_height = 180;  // a row of four
    int edits = 0;
    spec.update = [&](int frame, float) {
        for (int m : swept) {
            MaterialDesc desc = library.desc(m);
            set_glossiness(desc, sweep_roughness(frame, frames));
            library.replace(m, std::move(desc));  // rebuilds this material's table only
            ++edits;
        }
    };
    spec.label = [&](int f, float) { return fmt::format("roughness {:.2f}", sweep_roughness(f, frames)); };
    render_sequence(spec, options, session, result);
    double rebuild = 0;
    for (const FrameTiming& timing : result.timings) rebuild += timing.update_seconds;
    result.metrics["table_rebuild_seconds"] = rebuild / double(result.timings.size());
    result.metrics["edit_seconds"] = rebuild / double(std::max(edits, 1));
    result.notes.push_back(fmt::format("{} materials swept (roughness {:.2f} -> {:.2f}); edits {:.1f} ms per frame, "
                                       "{:.1f} ms per material edit, on average ({} BRDF tables, {}x{} texels; "
                                       "the renderer is not rebuilt)",
                                       swept.size(), sweep_roughness(0, frames), sweep_roughness(frames - 1, frames),
                                       1e3 * rebuild / double(result.timings.size()),
                                       1e3 * rebuild / double(std::max(edits, 1)), library.distinct_table_count(),
                                       render.brdf_table.resolution, render.brdf_table.resolution));
    return result;
}

}  // namespace rsl::demos
