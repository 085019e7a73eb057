#include "src/render/render_setup.h"

#include "src/formats/scene_file.h"
#include "src/lightfit/fit_limits.h"

#include "src/lightfit/scene_lights.h"
#include "src/render/memory_estimate.h"

#include <chrono>

#include <fmt/format.h>
#include "src/core/error.h"
#include "src/formats/scene_environment.h"

namespace rsl {

namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

CubeMap RenderSetup::environment_at(float t) const {
    if (second_environment.resolution() == 0) return environment;
    return blend_environments(environment, second_environment, scene->environment.blend_weight_at(t));
}

RenderSetup prepare_render(const std::filesystem::path& scene_path, const RenderOptions& options,
                           const SetupOptions& how) {
    return prepare_render(std::make_shared<Scene>(load_scene(scene_path)), options, how);
}

RenderSetup prepare_render(std::shared_ptr<Scene> scene, const RenderOptions& options, const SetupOptions& how) {
    RenderSetup setup;
    setup.scene = std::move(scene);
    const Scene& s = *setup.scene;
    check_render_memory(s, options.self_visibility, options.occluders, how.image_width, how.image_height);
    if (s.environment.present() && options.environment) {
        auto start = std::chrono::steady_clock::now();
        setup.environment = scene_environment_map(s, s.environment.resolution);
        setup.environment_lights.first =
            fit_scene_lights(s, setup.environment, options.environment_light_count, options.cross_face_lights);
        if (!s.environment.second_file.empty()) {
            setup.second_environment = scene_environment_map(s, s.environment.resolution, true);
            setup.environment_lights.second =  // the suns in both, so the blend keeps them whole
                fit_scene_lights(s, setup.second_environment, options.environment_light_count, options.cross_face_lights);
        }
        setup.fit_seconds = seconds_since(start);
        // Too few lights for a bright source: an error the truth will show (docs/design/LIGHTFIT.md).
        const std::string crowded = crowded_light_warning(
            describe_environment(s.environment), options.environment_light_count,
            find_crowded_light(setup.environment, setup.environment_lights.first));
        if (!crowded.empty()) warn("{}", crowded);
        if (how.progress) how.progress("fit", 1.0);
    }
    FieldBakeOptions bake;
    bake.self_visibility = options.self_visibility;
    bake.occluders = options.occluders;
    bake.cache_directory = how.field_cache;
    bake.progress = how.progress;
    const auto start = std::chrono::steady_clock::now();
    if (!s.source.empty() || !how.field_cache.empty()) {
        // The scene's field cache: reuse what `rsl bake` (or an earlier run)
        // wrote, bake only what is missing.
        FieldLoadReport report;
        setup.fields = load_part_fields(s, bake, &report);
        setup.fields_loaded = report.loaded, setup.fields_baked = report.baked;
    } else {
        setup.fields = bake_part_fields(s, bake);
    }
    setup.bake_seconds = seconds_since(start);
    return setup;
}

std::string describe_fit(const RenderSetup& setup) {
    const Scene& s = *setup.scene;
    if (setup.environment.resolution() == 0) return "no environment lights";
    const std::string fit =
        fmt::format("{}: {} RSLs fitted in {:.2f} s{}", describe_environment(s.environment),
                    setup.environment_lights.first.lights.size(), setup.fit_seconds,
                    s.environment.second_file.empty() ? "" : " (and as many for the blend's second map)");
    // A source smaller than a texel is the map's limit, not an error against the truth, which sees the same map.
    const std::string point_like = point_like_note("note: " + describe_environment(s.environment), setup.environment,
                                                   find_point_like_source(setup.environment));
    return point_like.empty() ? fit : fit + "\n" + point_like;
}

}  // namespace rsl
