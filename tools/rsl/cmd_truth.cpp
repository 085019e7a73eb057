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
#include "tools/rsl/frame_output.h"
#include "tools/rsl/image_args.h"
#include "src/core/atomic_file.h"
#include "src/core/envmap.h"
#include "src/core/error.h"
#include "src/core/image.h"
#include "tools/rsl/progress_display.h"
#include "src/core/scene.h"
#include "src/formats/scene_environment.h"
#include "src/formats/scene_file.h"
#include "src/trace/ground_truth.h"
#include "src/image/image_formation.h"

namespace rsl::cli {
namespace {

struct TruthArgs {
    std::string scene;
    float time = 0;
    std::string frames;
    std::string output = "truth.exr";
    std::string vertex_output;
    bool per_pixel = false;
    int resolution = 0;
    std::optional<int> width, height;  // absent: the scene camera's
    int samples = 1;
    int subdivision = 1;
    std::vector<std::string> background;
    std::string animation;
    float exposure = 0;
    bool no_lights = false, no_shadows = false, quiet = false;
};

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Checking phase: every flag before the scene loads.
void check_truth_args(const TruthArgs& args) {
    check_image_output(args.output);
    check_image_size(args.width, args.height, args.samples);
    check_time("--time", args.time);
    check_exposure(args.exposure);
    if (!args.frames.empty()) parse_frames(args.frames);
    if (args.resolution != 0 && (args.resolution < 1 || args.resolution > kMaxCubeResolution))
        throw_error("--resolution {}: expected 1 to {} texels per cube-face edge (leave it out for the scene's)",
                    args.resolution, kMaxCubeResolution);
    if (args.subdivision < 1 || args.subdivision > 16)
        throw_error("--subdivision {}: expected 1 to 16", args.subdivision);
    parse_background(fmt::format("{}", fmt::join(args.background, " ")));
}

// One frame at time t: the truth's vertex colours and image, written, and its summary line.
void truth_frame(const TruthArgs& args, const Scene& scene, float t, size_t frame, FrameOutput& output,
                 const std::filesystem::path& vertex_path, const EnvironmentBackdrop* backdrop) {
    const bool want_vertices = !vertex_path.empty();
    const int resolution = args.resolution > 0 ? args.resolution : scene.environment.resolution;
    const CubeMap environment = scene_environment_at(scene, resolution, t);
    GroundTruthOptions options;
    options.texel_subdivision = args.subdivision;
    options.local_lights = !args.no_lights;
    options.shadows = !args.no_shadows;

    const auto start = Clock::now();
    const GroundTruth truth(scene, environment, t, options);
    const double setup_seconds = seconds_since(start);
    if (!args.quiet && frame == 0)
        fmt::print(stderr, "truth: scene '{}' at t = {} s: {} parts, {} vertices, {} lit texel samples (6×{}²), "
                   "{} lights; BVHs in {:.2f} s\n", scene.name, t, scene.parts.size(), scene.vertex_count(),
                   truth.environment_sample_count(), resolution, options.local_lights ? scene.lights.size() : 0,
                   setup_seconds);
    if (!args.quiet && !scene.environment.second_file.empty())
        fmt::print(stderr, "truth: environment {} blended with {}, weight of the second {:.3f}\n",
                   scene.environment.file.filename().string(), scene.environment.second_file.filename().string(),
                   scene.environment.blend_weight_at(t));

    const int width = args.width.value_or(scene.camera.width);
    const int height = args.height.value_or(scene.camera.height);
    const PinholeCamera camera = PinholeCamera::at_time(scene.camera, t, width, height);
    ImageFormationOptions formation;
    formation.samples_per_side = args.samples;
    const Background background = parse_background(fmt::format("{}", fmt::join(args.background, " ")));
    formation.opaque_background = background.kind == Background::Kind::Color;
    formation.background = background.color;

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
    if (backdrop) backdrop->fill(image, camera, args.samples, t);
    const double shade_seconds = seconds_since(shade_start);

    output.write(frame, image);
    if (want_vertices) write_vertex_colors(vertex_path, vertices);

    if (args.quiet) return;
    const uint64_t rays = truth.rays_traced();
    fmt::print("truth: {}{} ({}×{}{}), {}{:.2f} s, {} shadow rays ({:.1f} M/s)\n",
               output.frames() > 1 ? fmt::format("t={:.3f}: ", t) : "", output.image_path(frame).string(), width,
               height, args.per_pixel ? ", per pixel" : "", want_vertices ? vertex_path.string() + ", " : "",
               shade_seconds, rays, double(rays) / std::max(shade_seconds, 1e-9) * 1e-6);
    if (frame == 0 && output.sequence_exposure())
        fmt::print("exposure: {:+.3f} stops for every frame{}\n", *output.sequence_exposure(),
                   args.exposure == 0.0f ? " (the first frame's; --exposure sets another)" : "");
}

void run_truth(const TruthArgs& args) {
    check_truth_args(args);
    const std::vector<float> times = args.frames.empty() ? std::vector<float>{args.time} : parse_frames(args.frames);
    FrameOutput output(args.output, times.size(), times.size() > 1 ? double(times[1]) - double(times[0]) : 1.0,
                       args.exposure, args.animation);
    const Scene scene = load_scene(args.scene);
    check_truth_memory(scene, args.width.value_or(scene.camera.width), args.height.value_or(scene.camera.height));
    // Per frame, the vertex file (empty: none).
    std::vector<std::filesystem::path> vertex_paths(times.size());
    if (!args.per_pixel || !args.vertex_output.empty()) {
        std::filesystem::path vertex_path = args.vertex_output;
        if (vertex_path.empty()) vertex_path = std::filesystem::path(args.output).replace_extension(".rslv");
        for (size_t f = 0; f < times.size(); ++f) vertex_paths[f] = times.size() > 1 ? numbered(vertex_path, int(f)) : vertex_path;
    }
    std::vector<std::filesystem::path> outputs = output.files();
    outputs.insert(outputs.end(), vertex_paths.begin(), vertex_paths.end());
    check_outputs_apart(outputs, scene.input_files);
    std::optional<EnvironmentBackdrop> backdrop;
    if (parse_background(fmt::format("{}", fmt::join(args.background, " "))).kind == Background::Kind::Environment)
        backdrop.emplace(scene);
    for (size_t f = 0; f < times.size(); ++f)
        truth_frame(args, scene, times[f], f, output, vertex_paths[f], backdrop ? &*backdrop : nullptr);
    if (const std::filesystem::path animation = output.finish(); !animation.empty() && !args.quiet)
        fmt::print("animation: {} ({} frames)\n", animation.string(), times.size());
}

RegisterCommand truth_command({"truth",
    "Embree ground truth: exact direct lighting per vertex (every cube-map texel and local light, "
    "with shadow rays) → .rslv, and its image → EXR (alpha = coverage) + PNG",
    40, [](CLI::App& app) {
        auto args = std::make_shared<TruthArgs>();
        app.add_option("scene", args->scene, "Scene file (.json, .gltf/.glb or .obj)")->required();
        auto* time = app.add_option("--time,-t", args->time, "Time in seconds (parts, environment, lights, camera posed at t)")
            ->capture_default_str();
        auto* frames = app.add_option("--frames", args->frames,
            "START:END:STEP: numbered frames OUT.NNNN.exr and OUT.NNNN.rslv, as rsl render --frames names them, "
            "all with the first frame's exposure unless --exposure is given");
        time->excludes(frames);
        app.add_option("-o,--output", args->output,
                       "Output image: .exr (a tone-mapped .png is written beside it) or .png (the tone-mapped image "
                       "alone)")
            ->capture_default_str();
        app.add_option("--vertex-out", args->vertex_output,
                       "Per-vertex values (.rslv, for rsl compare); default: the output with extension .rslv");
        app.add_option("--animation", args->animation,
                       "With --frames: also join the frames into FILE.png (an animated PNG) or FILE.mp4 (needs "
                       "ffmpeg)")->needs(frames);
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
        app.add_option("--background", args->background,
                       "What shows where no part covers a pixel: environment (the scene's environment map), or an "
                       "opaque colour R,G,B or R G B (default: black, alpha 0)")
            ->expected(1, 3);
        app.add_option("--exposure", args->exposure,
                       "PNG exposure in stops (default: automatic; a sequence takes its first frame's for every frame)");
        app.add_flag("--no-lights", args->no_lights, "Leave out the scene's local lights");
        app.add_flag("--no-shadows", args->no_shadows,
                     "The unshadowed integral: every direction above the shading horizon counts as visible (no shadow rays)");
        app.add_flag("--quiet,-q", args->quiet, "No progress or summary line (errors and warnings still go to stderr)");
        app.callback([args] { run_truth(*args); });
    }});

}  // namespace
}  // namespace rsl::cli
