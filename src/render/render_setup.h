#pragma once
// Everything a renderer needs before its first frame, from a scene file:
// the scene, its environment as a cube map (two when the scene blends two
// maps, `second_file`), the environment's RSL sets (one per map) and the
// parts' visibility fields (from the scene's field cache, <scene folder>/
// .rsl-cache, baking only what is missing, reporting progress to a callback).
// Shared by `rsl render`, `rsl bench render` and the error tables.
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "src/core/envmap.h"
#include "src/render/cpu_renderer.h"

namespace rsl {

struct RenderSetup {
    std::shared_ptr<Scene> scene;  // shared: renderers keep a reference to it
    CubeMap environment;           // resolution 0 when the scene has none
    CubeMap second_environment;    // environment.second_file; resolution 0 without a blend
    // One RSL set per map (fitted on its own map; frame_setup.h blends them).
    EnvironmentLights environment_lights;
    // The map the ground truth integrates at time t: (1 − w)·first + w·second
    // (EnvironmentDesc::blend_weight_at), or the first map without a blend.
    CubeMap environment_at(float t) const;
    PartFields fields;
    double fit_seconds = 0, bake_seconds = 0;  // bake_seconds: loading and baking fields
    int fields_loaded = 0, fields_baked = 0;    // field files reused from / written to the cache
};

// How prepare_render reports and where it keeps the fields.
struct SetupOptions {
    // Hears (what, fraction) of the fit ("fit", once done) and of every field
    // bake, from worker threads (FieldBakeOptions::progress).
    std::function<void(const std::string& what, double fraction)> progress;
    // Field cache folder; empty: beside the scene file (a scene in memory
    // without one is baked in memory).
    std::filesystem::path field_cache;
    // The largest image the run forms, for the memory estimate (a side of 0: the scene camera's).
    int image_width = 0, image_height = 0;
};

// Loads the scene and its environment, fits options.environment_light_count RSLs,
// bakes the fields the options switch on.
RenderSetup prepare_render(const std::filesystem::path& scene_path, const RenderOptions& options,
                           const SetupOptions& setup = {});
// The same for a scene already in memory (its environment file is still read).
RenderSetup prepare_render(std::shared_ptr<Scene> scene, const RenderOptions& options, const SetupOptions& setup = {});
// "sunsky.exr: 30 RSLs fitted in 0.12 s": the fit, as a tool prints it, and
// on a second line a note where a source is smaller than a texel (fit_limits.h).
std::string describe_fit(const RenderSetup& setup);

}  // namespace rsl
