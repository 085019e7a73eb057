// `rsl truth SCENE --time T -o out.exr`: the Embree ground truth
// (docs/design/TRUTH.md). Per-vertex exact direct lighting, written as .rslv, and the
// image formed from it exactly as the RSL renderer forms its image (or, with
// --per-pixel, the same integral at every pixel's hit point), as EXR + PNG.
#include <algorithm>
#include <chrono>
#include <optional>

#include <fmt/core.h>
#include <fmt/format.h>

#include "tools/rsl/command.h"
#include "tools/rsl/image_args.h"
#include "src/core/atomic_file.h"
#include "src/core/envmap.h"
#include "src/core/error.h"
#include "src/core/image.h"
#include "tools/rsl/progress_display.h"
#include "src/core/scene.h"
#include "src/core/scene_environment.h"
#include "src/trace/ground_truth.h"
#include "src/frame/image_formation.h"

namespace rsl::cli {
namespace {

struct TruthArgs {
    std::string scene;
    float time = 0;
    std::string output = "truth.exr";
    std::string vertex_output;
    bool per_pixel = false;
    int resolution = 0;
    std::optional<int> width, height;  // absent: the scene camera's
    int samples = 1;
    int subdivision = 1;
    std::vector<float> background;
    float exposure = 0;
    bool no_lights = false, no_shadows = false, quiet = false;
};

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// The environment at time t: with `second_file`, the blend (1 − w)·first +
// w·second of the scene format (EnvironmentDesc::blend_weight_at), which the
// RSL renderer applies to its two RSL sets.
CubeMap load_scene_environment(const Scene& scene, int resolution, float t) {
    const CubeMap first = scene_environment_map(scene, resolution);  // black without one: lights only
    if (scene.environment.second_file.empty()) return first;
    return blend_environments(first, scene_environment_map(scene, resolution, true), scene.environment.blend_weight_at(t));
}

void run_truth(const TruthArgs& args) {
    const std::filesystem::path output(args.output);
    if (output.extension() != ".exr")
        throw_error("-o {}: expected an .exr path (a .png preview is written beside it)", args.output);
    check_image_size(args.width, args.height, args.samples);
    check_time("--time", args.time);
    check_exposure(args.exposure);
    if (args.resolution != 0 && (args.resolution < 1 || args.resolution > kMaxCubeResolution))
        throw_error("--resolution {}: expected 1 to {} texels per cube-face edge (leave it out for the scene's)",
                    args.resolution, kMaxCubeResolution);
    if (args.subdivision < 1 || args.subdivision > 16)
        throw_error("--subdivision {}: expected 1 to 16", args.subdivision);
    if (!args.background.empty() && args.background.size() != 3)
        throw_error("--background: expected three values R G B, got {}", args.background.size());
    for (const float value : args.background)  // a NaN background is a NaN in every uncovered pixel
        if (!(value >= 0 && value <= kMaxRadiance))
            throw_error("--background {}: expected radiances from 0 to {:g} (finite)", fmt::join(args.background, " "),
                        kMaxRadiance);

    const Scene scene = load_scene(args.scene);
    const bool want_vertices = !args.per_pixel || !args.vertex_output.empty();
    std::filesystem::path vertex_path = args.vertex_output;
    if (vertex_path.empty()) vertex_path = std::filesystem::path(output).replace_extension(".rslv");
    check_outputs_apart({output, std::filesystem::path(output).replace_extension(".png"),
                         want_vertices ? vertex_path : std::filesystem::path()},
                        scene.input_files);
    const int resolution = args.resolution > 0 ? args.resolution : scene.environment.resolution;
    const CubeMap environment = load_scene_environment(scene, resolution, args.time);
    GroundTruthOptions options;
    options.texel_subdivision = args.subdivision;
    options.local_lights = !args.no_lights;
    options.shadows = !args.no_shadows;

    const auto start = Clock::now();
    const GroundTruth truth(scene, environment, args.time, options);
    const double setup_seconds = seconds_since(start);
    if (!args.quiet)
        fmt::print(stderr, "truth: scene '{}' at t = {} s: {} parts, {} vertices, {} lit texel samples (6×{}²), "
                   "{} lights; BVHs in {:.2f} s\n", scene.name, args.time, scene.parts.size(), scene.vertex_count(),
                   truth.environment_sample_count(), resolution, options.local_lights ? scene.lights.size() : 0,
                   setup_seconds);
    if (!args.quiet && !scene.environment.second_file.empty())
        fmt::print(stderr, "truth: environment {} blended with {}, weight of the second {:.3f}\n",
                   scene.environment.file.filename().string(), scene.environment.second_file.filename().string(),
                   scene.environment.blend_weight_at(args.time));

    const int width = args.width.value_or(scene.camera.width);
    const int height = args.height.value_or(scene.camera.height);
    const PinholeCamera camera = PinholeCamera::at_time(scene.camera, args.time, width, height);
    ImageFormationOptions formation;
    formation.samples_per_side = args.samples;
    if (!args.background.empty()) {
        formation.opaque_background = true;
        formation.background = Color(args.background[0], args.background[1], args.background[2]);
    }

    const auto shade_start = Clock::now();
    VertexColors vertices;
    ProgressDisplay display(!args.quiet);
    // A ProgressCallback (done of total) drawn as job `what`.
    const auto job = [&display](const std::string& what) {
        return [&display, what](size_t done, size_t total) { display(what, double(done) / double(std::max<size_t>(total, 1))); };
    };
    if (want_vertices) {
        vertices = truth.shade_vertices(job("truth: vertices"));
        display("truth: vertices", 1.0);
    }
    Image image;
    if (args.per_pixel) {
        const PosedScene& posed = truth.posed();
        image = trace_image(posed, camera, formation,
                            [&](const RayHit& hit, const Vec3& dir) { return truth.shade_hit(hit, dir); },
                            job("truth: pixels"));
        display("truth: pixels", 1.0);
    } else {
        image = form_image(truth.posed(), camera, vertices, formation);
    }
    const double shade_seconds = seconds_since(shade_start);

    write_exr_and_png(output, image, ToneMap{args.exposure, args.exposure == 0.0f});
    if (want_vertices) write_vertex_colors(vertex_path, vertices);

    if (args.quiet) return;
    const uint64_t rays = truth.rays_traced();
    fmt::print("truth: {} ({}×{}{}), {}{:.2f} s, {} shadow rays ({:.1f} M/s)\n", output.string(), width, height,
               args.per_pixel ? ", per pixel" : "", want_vertices ? vertex_path.string() + ", " : "", shade_seconds,
               rays, double(rays) / std::max(shade_seconds, 1e-9) * 1e-6);
}

RegisterCommand truth_command({"truth",
    "Embree ground truth: exact direct lighting per vertex (every cube-map texel and local light, "
    "with shadow rays) → .rslv, and its image → EXR (alpha = coverage) + PNG",
    40, [](CLI::App& app) {
        auto args = std::make_shared<TruthArgs>();
        app.add_option("scene", args->scene, "Scene file (.json, .gltf/.glb or .obj)")->required();
        app.add_option("--time,-t", args->time, "Time in seconds (parts, environment, lights, camera posed at t)")
            ->capture_default_str();
        app.add_option("-o,--output", args->output, "Output image (.exr; a tone-mapped .png is written beside it)")
            ->capture_default_str();
        app.add_option("--vertex-out", args->vertex_output,
                       "Per-vertex values (.rslv, for rsl compare); default: the output with extension .rslv");
        app.add_flag("--per-pixel", args->per_pixel,
                     "Shade every pixel's hit point exactly instead of interpolating vertex values (slow)");
        app.add_option("--resolution", args->resolution, "Cube-map resolution N (6×N×N texels); default: the scene's");
        app.add_option("--width", args->width, "Image width (default: the scene camera's)");
        app.add_option("--height", args->height, "Image height (default: the scene camera's)");
        app.add_option("--samples", args->samples, "S×S primary rays per pixel")->capture_default_str();
        app.add_option("--subdivision", args->subdivision,
                       "At least S×S shadow rays per texel on a sub-grid with exact sub-texel solid angles (bright "
                       "texels are cut finer anyway, up to 32×32: a sun casts its texel's penumbra)")
            ->capture_default_str();
        app.add_option("--background", args->background, "Opaque background colour R G B (default: black, alpha 0)")
            ->expected(3);
        app.add_option("--exposure", args->exposure, "PNG exposure in stops (default: automatic)");
        app.add_flag("--no-lights", args->no_lights, "Leave out the scene's local lights");
        app.add_flag("--no-shadows", args->no_shadows,
                     "The unshadowed integral: every direction above the shading horizon counts as visible (no shadow rays)");
        app.add_flag("--quiet,-q", args->quiet, "No progress or summary line (errors and warnings still go to stderr)");
        app.callback([args] { run_truth(*args); });
    }});

}  // namespace
}  // namespace rsl::cli
