// `rsl render SCENE --time T -o out.exr`: the CPU runtime renderer
// (docs/design/RENDERER.md), with --backend rays its sum with ray-traced
// visibility (docs/BASELINES.md), with --backend gl the GPU one (docs/GPU.md).
// Per-vertex colours from the RSL sum and the image the renderer forms of
// them (VertexRenderer::form_image: the same picture on either backend),
// written as EXR + PNG or PNG (tools/rsl/frame_output.h), and optionally as
// per-vertex .rslv for `rsl compare`.
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>

#include <fmt/core.h>

#include "src/backend/render_session.h"
#include "tools/rsl/command.h"
#include "tools/rsl/frame_output.h"
#include "tools/rsl/image_args.h"
#include "tools/rsl/progress_display.h"
#include "tools/rsl/render_args.h"
#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/scene_file.h"
#include "src/image/image_formation.h"
#include "src/render/render_setup.h"

namespace rsl::cli {
namespace {

struct RenderArgs {
    std::string scene;
    float time = 0;
    std::string frames;
    int lights = 30;
    bool same_face = false;
    std::string backend = "cpu";
    bool no_self = false, no_occluders = false, no_culling = false, exact_shapes = true;
    bool exact_diffuse_light = true;
    std::string pixel_shadows = "planes";
    bool pixel_highlights = true;
    std::vector<std::string> materials;
    std::string output;
    std::string vertex_output;
    std::string background;
    std::string animation;
    std::optional<int> width, height;  // absent: the scene camera's
    int samples = 1;
    float exposure = 0;
    bool quiet = false;
    int shadow_maps = 0;  // 0: off; else the resolution (GL only)
    std::string shadow_filter = "pcss";
    int gpu_rays = 0;  // 0: off; else S (GL only)
    int ray_samples = 0;  // 0: not given; else S (backends with BackendCapabilities::ray_samples)
};

// Checking phase: the light count, image size, samples, time, exposure and
// the output's extension and the background, before the scene loads; returns the output path.
std::filesystem::path check_render_args(const RenderArgs& args) {
    if (args.lights < 1) throw_error("--lights {}: expected at least 1", args.lights);
    check_image_size(args.width, args.height, args.samples);
    check_time("--time", args.time);
    check_exposure(args.exposure);
    if (!args.frames.empty()) parse_frames(args.frames);
    check_image_output(args.output);
    parse_background(args.background);
    return args.output;
}

// The backends `rsl render` offers that have `capability`, as "--backend gl"
// (or "--backend a or --backend b"), for an error that says what to add.
std::string backends_offering(bool BackendCapabilities::*capability) {
    std::string text;
    for (const std::string& name : backends_with(capability))
        if (backend_capabilities(parse_backend(name)).standalone)
            text += (text.empty() ? "--backend " : " or --backend ") + name;
    return text.empty() ? "a backend this rsl was built without" : text;
}

// Options phase: the renderer's options from the arguments, shadow maps checked before the fit and the bake.
RenderOptions render_options(const RenderArgs& args, Backend backend) {
    RenderOptions options;
    options.environment_light_count = args.lights;
    options.cross_face_lights = !args.same_face;
    options.self_visibility = !args.no_self;
    options.occluders = !args.no_occluders;
    options.occluder_culling = !args.no_culling;
    options.exact_shapes = args.exact_shapes;
    options.exact_diffuse_light = args.exact_diffuse_light;
    options.pixel_shadows = parse_pixel_shadows(args.pixel_shadows);
    options.pixel_highlights = args.pixel_highlights;
    options.material_override = parse_material_overrides(args.materials);
    const BackendCapabilities can = backend_capabilities(backend);
    if (!can.fields && (args.no_self || args.no_occluders))
        throw_error("{}: the {} backend shades with no fields (its rays find every part's shadows)",
                    args.no_self ? "--no-self" : "--no-occluders", backend_name(backend));
    if (args.ray_samples != 0) {
        if (args.ray_samples < 1 || args.ray_samples > RenderOptions::kMaxRaySamples)
            throw_error("--ray-samples {}: expected S of 1..{} (SxS rays per vertex and light)", args.ray_samples,
                        RenderOptions::kMaxRaySamples);
        if (!can.ray_samples)
            throw_error("--ray-samples: the {} backend traces no rays (add {})", backend_name(backend),
                        backends_offering(&BackendCapabilities::ray_samples));
        options.ray_samples = args.ray_samples;
    }
    if (args.shadow_maps != 0) {  // before the fit and the bake: a bad value costs nothing
        if (args.shadow_maps < ShadowMapOptions::kMinResolution || args.shadow_maps > ShadowMapOptions::kMaxResolution)
            throw_error("--shadow-maps {}: expected a resolution of {}..{} texels", args.shadow_maps,
                        ShadowMapOptions::kMinResolution, ShadowMapOptions::kMaxResolution);
        if (!can.shadow_maps)
            throw_error("--shadow-maps: shadow-mapped visibility is a GPU baseline (add {})",
                        backends_offering(&BackendCapabilities::shadow_maps));
        options.shadow_maps.enabled = true;
        options.shadow_maps.resolution = args.shadow_maps;
        options.shadow_maps.filter = args.shadow_filter == "pcf" ? ShadowFilter::Pcf : ShadowFilter::Pcss;
    }
    if (args.gpu_rays != 0) {
        if (args.gpu_rays < 1 || args.gpu_rays > GpuRayOptions::kMaxSamplesPerSide)
            throw_error("--gpu-rays {}: expected S of 1..{} (SxS rays per vertex and light)", args.gpu_rays,
                        GpuRayOptions::kMaxSamplesPerSide);
        if (!can.gpu_rays)
            throw_error("--gpu-rays: GPU ray-traced visibility is a GPU baseline (add {})",
                        backends_offering(&BackendCapabilities::gpu_rays));
        if (args.shadow_maps != 0) throw_error("--gpu-rays and --shadow-maps: pick one visibility baseline");
        options.gpu_rays.enabled = true;
        options.gpu_rays.samples_per_side = args.gpu_rays;
    }
    return options;
}

// Report phase: the renderer's device (backends on one) and the environment's blend, unless quiet.
void report_renderer(const RenderArgs& args, Backend backend, const RenderSetup& setup, const VertexRenderer& renderer) {
    const Scene& scene = *setup.scene;
    if (!args.quiet && backend_capabilities(backend).device) fmt::print(stderr, "{}\n", renderer.device());
    if (!args.quiet && setup.environment_lights.blends())
        fmt::print(stderr, "environment: {} blended with {} over a {} s period (docs/SCENE_FORMAT.md)\n",
                   scene.environment.file.filename().string(), scene.environment.second_file.filename().string(),
                   scene.environment.blend_period_seconds);
}

// Frame phase: shades and forms every frame, writes its image (and vertex
// colours), and prints one line of timings per frame.
void render_frames(const RenderArgs& args, RenderSession& session, FrameOutput& output) {
    const Scene& scene = session.scene();
    const std::vector<float> times = args.frames.empty() ? std::vector<float>{args.time} : parse_frames(args.frames);
    ImageFormationOptions formation;
    formation.samples_per_side = args.samples;
    const Background background = parse_background(args.background);
    formation.opaque_background = background.kind == Background::Kind::Color;
    formation.background = background.color;
    std::optional<EnvironmentBackdrop> backdrop;
    if (background.kind == Background::Kind::Environment) backdrop.emplace(scene);
    for (size_t f = 0; f < times.size(); ++f) {
        const float t = times[f];
        const auto start = std::chrono::steady_clock::now();
        const VertexColors& colors = session.shade(t);
        const auto shaded = std::chrono::steady_clock::now();
        const PinholeCamera camera = session.camera(args.width.value_or(0), args.height.value_or(0));
        Image image = session.image(camera, formation);
        if (backdrop) backdrop->fill(image, camera, args.samples, t);
        const auto formed = std::chrono::steady_clock::now();
        const std::filesystem::path exr = output.image_path(f);
        output.write(f, image);
        if (!args.vertex_output.empty())
            write_vertex_colors(times.size() > 1 ? numbered(args.vertex_output, int(f)) : std::filesystem::path(args.vertex_output), colors);
        const double shading_ms = 1e3 * std::chrono::duration<double>(shaded - start).count();
        const double image_ms = 1e3 * std::chrono::duration<double>(formed - shaded).count();
        const VertexRenderer& renderer = session.renderer();
        const RenderStats& stats = renderer.stats();
        const std::string blend = session.setup().environment_lights.blends()
                                      ? fmt::format(", second map {:.0f}%", 100.0f * scene.environment.blend_weight_at(t))
                                      : "";
        const std::string rays = backend_capabilities(session.backend()).ray_samples
                                     ? fmt::format(" ({:.2f} M shadow rays)", double(stats.shadow_rays) / 1e6)
                                     : "";
        if (args.quiet) continue;
        fmt::print("t={:.3f}: {} vertices x {} lights{}, {} shading {:.1f} ms{}, image {:.1f} ms; occluder pairs {} "
                   "({} culled) -> {}\n",
                   t, colors.vertex_count(), stats.lights, blend, renderer.backend(), shading_ms, rays, image_ms,
                   stats.occluder_pairs, stats.occluder_pairs_culled, exr.string());
        if (const std::string passes = renderer.pass_times(); !passes.empty()) fmt::print("  GPU passes: {}\n", passes);
        if (f == 0 && output.sequence_exposure())
            fmt::print("exposure: {:+.3f} stops for every frame{}\n", *output.sequence_exposure(),
                       args.exposure == 0.0f ? " (the first frame's; --exposure sets another)" : "");
    }
    if (const std::filesystem::path animation = output.finish(); !animation.empty() && !args.quiet)
        fmt::print("animation: {} ({} frames)\n", animation.string(), times.size());
}

// The frames' spacing in scene time (the animation's delay per frame).
double frame_seconds(const std::vector<float>& times) {
    return times.size() > 1 ? double(times[1]) - double(times[0]) : 1.0;
}

// Every file a run writes: each frame's image, its vertex colours and the animation.
std::vector<std::filesystem::path> render_outputs(const RenderArgs& args, const FrameOutput& output) {
    std::vector<std::filesystem::path> outputs = output.files();
    for (size_t f = 0; f < output.frames() && !args.vertex_output.empty(); ++f)
        outputs.push_back(output.frames() > 1 ? numbered(args.vertex_output, int(f)) : std::filesystem::path(args.vertex_output));
    return outputs;
}

void run_render(const RenderArgs& args) {
    const Backend backend = parse_backend(args.backend);
    const std::filesystem::path output_path = check_render_args(args);
    const RenderOptions options = render_options(args, backend);
    const std::vector<float> times = args.frames.empty() ? std::vector<float>{args.time} : parse_frames(args.frames);
    FrameOutput output(output_path, times.size(), frame_seconds(times), args.exposure, args.animation);
    auto scene = std::make_shared<Scene>(load_scene(args.scene));
    check_outputs_apart(render_outputs(args, output), scene->input_files);  // before the fit and the bake

    ProgressDisplay display(!args.quiet);
    SetupOptions how;
    how.progress = [&display](const std::string& what, double fraction) { display(what, fraction); };
    how.image_width = args.width.value_or(0), how.image_height = args.height.value_or(0);
    // Every backend shades the same per-vertex sum and forms the same image.
    RenderSession session(scene, options, backend, how);
    const RenderSetup& setup = session.setup();
    if (!args.quiet && setup.environment.resolution() > 0) display.note(describe_fit(setup));
    display.note(fmt::format("fields: {} loaded from the cache, {} baked ({:.1f} s)", setup.fields_loaded,
                             setup.fields_baked, setup.bake_seconds));
    report_renderer(args, backend, setup, session.renderer());
    render_frames(args, session, output);
}

RegisterCommand render_command({"render",
    "Render a scene with the RSL runtime (multi-product shading of moving parts, local lights).", 30,
    [](CLI::App& app) {
        auto args = std::make_shared<RenderArgs>();
        app.add_option("scene", args->scene, "Scene file (.json, .gltf/.glb, .obj)")->required()->check(CLI::ExistingFile);
        auto* time = app.add_option("--time,-t", args->time, "Time in seconds (within ±1e6)")->capture_default_str();
        auto* frames = app.add_option("--frames", args->frames,
            "START:END:STEP: numbered frames OUT.NNNN.exr (or .png; at most 100000), all with the first "
            "frame's exposure unless --exposure is given");
        time->excludes(frames);
        app.add_option("--lights,-k", args->lights, "Number of environment RSLs fitted to the map (each glTF sun adds one of its own)")->capture_default_str();
        app.add_option("--backend", args->backend,
                       "cpu (the fields' sum), rays (the same sum with every light's visibility from shadow rays "
                       "traced by Embree, no fields: the ray-traced baseline; --ray-samples), or gl (the GPU "
                       "renderer, where this rsl has it)")
            ->check(CLI::IsMember(backends_with(&BackendCapabilities::standalone)))->capture_default_str();
        app.add_flag("--same-face", args->same_face, "Fit light regions within one cube face only (the paper's rule)");
        app.add_flag("--no-self", args->no_self, "Switch self-visibility (SVDF) off");
        app.add_flag("--no-occluders", args->no_occluders, "Switch the other parts' shadows (OVDF) off");
        app.add_flag("--no-culling", args->no_culling, "Look every occluder up (for checking the culling)");
        app.add_flag("--exact-shapes,!--no-exact-shapes", args->exact_shapes,
                     "Parts that are one flat rectangle (a ground) or one box shadow the others from their shape, "
                     "not their OVDF: exact near contacts, about 5% slower (default on; docs/design/RENDERER.md)");
        app.add_flag("--exact-diffuse-light,!--no-exact-diffuse-light", args->exact_diffuse_light,
                     "Shade each material's diffuse term with the environment's exact irradiance, the squares "
                     "giving only its shadows: the diffuse light's error no longer depends on K (default on; "
                     "off: the RSL paper's sum; docs/design/RENDERER.md)");
        app.add_option("--pixel-shadows", args->pixel_shadows,
                       "Which parts take the other parts' shadows per pixel in the image, where a shadow edge "
                       "crosses a triangle (sharp shadows on coarse receivers; per-vertex colours unchanged; "
                       "either backend): planes (flat rectangles: grounds, floors), all "
                       "(the gl backend: as planes), or off")
            ->check(CLI::IsMember({"planes", "all", "off"}))->capture_default_str();
        app.add_flag("--pixel-highlights,!--no-pixel-highlights", args->pixel_highlights,
                     "Glossy parts take each light's BRDF average at every pixel's own normal and view in the "
                     "image, so that highlights between vertices show (default on; per-vertex colours unchanged; "
                     "either backend)");
        app.add_option("--material", args->materials, "PART=MATERIAL: shade a part with another scene material");
        app.add_option("-o,--output", args->output,
                       "Image to write: .exr (a tone-mapped .png preview is written beside it) or .png (the "
                       "tone-mapped image alone)")->required();
        app.add_option("--background", args->background,
                       "What shows where no part covers a pixel: environment (the scene's environment map), or a "
                       "colour R,G,B, each 0 to 1e15 (default: black, alpha 0)");
        app.add_option("--animation", args->animation,
                       "With --frames: also join the frames into FILE.png (an animated PNG, playing at the frames' "
                       "spacing in scene time) or FILE.mp4 (needs ffmpeg)")->needs(frames);
        app.add_option("--vertex-out", args->vertex_output, "Per-vertex colours (.rslv) for `rsl compare`");
        app.add_option("--width", args->width, "Image width, 1..16384 (default: the scene camera's)");
        app.add_option("--height", args->height, "Image height, 1..16384 (default: the scene camera's)");
        app.add_option("--samples", args->samples, "S: SxS primary rays per pixel, 1..16")->capture_default_str();
        app.add_option("--exposure", args->exposure, "PNG exposure in stops, -64..64 (default 0: automatic, as rsl truth; a sequence takes its first "
                       "frame's for every frame)")->capture_default_str();
        auto* shadow_maps = app.add_option("--shadow-maps", args->shadow_maps,
            "RES: the shadow-mapped baseline (gl backend): environment lights' visibility from one RESxRES "
            "depth map each (16..8192) instead of the SVDF/OVDF fields (docs/GPU.md)");
        app.add_option("--shadow-filter", args->shadow_filter,
                       "With --shadow-maps: pcss (blocker search; default) or pcf (fixed occluder distance, "
                       "0.1 x the scene's radius)")
            ->check(CLI::IsMember({"pcf", "pcss"}))->needs(shadow_maps)->capture_default_str();
        app.add_option("--gpu-rays", args->gpu_rays,
            "S: the ray-traced baseline (gl backend): every light's visibility from SxS jittered shadow rays per "
            "vertex, traced on the GPU through a BVH of the posed parts, instead of the fields (1..16; docs/GPU.md)");
        app.add_option("--ray-samples", args->ray_samples,
            "S: with --backend rays, SxS jittered shadow rays per vertex and light (1..16; default 1; "
            "docs/BASELINES.md)");
        app.add_flag("--quiet,-q", args->quiet, "No progress or per-frame lines (errors and warnings still go to stderr)");
        app.callback([args] { run_render(*args); });
    }});

}  // namespace
}  // namespace rsl::cli
