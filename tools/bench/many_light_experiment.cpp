// The experiment behind `rsl baselines --many-light` (docs/BASELINES.md,
// "Many lights"). Every row shades the same static frame with the same RSL
// set (rows of K other than baseline_lights fit their own), so the rows
// differ in the visibility factor alone; errors are against the ground
// truth under the scene's own environment.
#include "tools/rsl/progress_display.h"
#include "tools/bench/many_light_experiment.h"
#include "src/formats/image_file.h"
#include "src/formats/scene_file.h"
#include "src/lightfit/scene_lights.h"

#include <algorithm>
#include <cmath>
#include <fmt/core.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "tools/baselines/raster.h"
#include "tools/bench/experiment_support.h"
#include "src/backend/make_renderer.h"
#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/image/error_metrics.h"
#include "src/image/image_formation.h"
#include "src/render/render_setup.h"
#include "src/trace/environment_rays.h"
#include "src/trace/ground_truth.h"
#ifdef RSL_HAVE_GL
#include "src/gl/gl_renderer.h"
#endif

namespace rsl {
namespace {

struct Row {
    std::string method;   // "rsl", "rsl-gl", "rays", "rays-gl", "rays-budget", "shadow-map", "env-rays"
    int setting = 0;      // K, S, the map's resolution or env-rays' N
    int lights = 0;       // K shaded (0: env-rays, which shades the map itself)
    double frame_ms = 0;  // median shading time of one frame (GL: colours read back)
    double gpu_pass_ms = 0;  // GL: median of the vertex pass's time (timer queries; the clock on llvmpipe)
    bool gpu_clock = false;  // ... measured by the clock around glFinish
    uint64_t rays = 0;    // shadow rays per frame (ray-traced rows)
    double vertex_error = 0, objects_error = 0, worst_error = 0, image_error = 0;
    std::string worst_part;
    Image image;
    std::string label() const {
        if (method == "rsl" || method == "rsl-gl") return fmt::format("{} K={}", method, setting);
        if (method == "rays" || method == "rays-gl") return fmt::format("{} S={}", method, setting);
        if (method == "rays-budget") return fmt::format("rays budget S={}", setting);
        if (method == "env-rays") return fmt::format("env-rays N={}", setting);
        return fmt::format("shadow map {}", setting);
    }
};

Row make_row(const std::string& method, int setting, int lights) {
    Row row;
    row.method = method, row.setting = setting, row.lights = lights;
    return row;
}

// The side S whose S² rays per (vertex, light) pair fit `budget` rays for
// `pairs` pairs; at least 1 (a budget below one ray a pair is exceeded).
int samples_for_budget(uint64_t budget, uint64_t pairs) {
    if (pairs == 0) return 1;
    const double per_pair = double(budget) / double(pairs);
    return std::clamp(int(std::floor(std::sqrt(per_pair))), 1, RenderOptions::kMaxRaySamples);
}

// The GL renderer's last vertex pass time (timer queries, or the clock
// where they measure nothing: `clock`); 0 for the CPU renderer.
double gpu_pass_ms(const VertexRenderer& renderer, bool& clock) {
#ifdef RSL_HAVE_GL
    if (const auto* gl_renderer = dynamic_cast<const gl::GlRenderer*>(&renderer)) {
        const gl::PassTimings timings = gl_renderer->timings();
        clock = timings.clock;
        return timings.shade_ms;
    }
#endif
    return 0.0;
}

// Output phase: results.json, table.md and every row's and the truth's EXR and PNG; returns the table.
std::string write_results(const ManyLightExperiment& args, const Scene& scene, size_t vertices, const Image& truth_image,
                          double truth_ms, const std::vector<Row>& rows, const std::string& gl_device) {
    const std::filesystem::path dir(args.output);
    nlohmann::json json = {{"scene", scene.name},
                           {"source", scene.source.string()},
                           {"environment", scene.environment.file.filename().string()},
                           {"time", args.time},
                           {"vertices", vertices},
                           {"truth_ms", truth_ms},
                           {"receivers", args.receivers},
                           {"gl_device", gl_device},
                           {"methods", nlohmann::json::array()}};
    std::string table = fmt::format(
        "Scene `{}`, environment `{}`, t = {}, {} vertices; truth {:.0f} ms. Errors: relative L2 against the "
        "truth (objects: all parts but {}). GL rows: {}.\n\n"
        "| method | K | ms / frame | GPU pass ms | rays / frame | vertices | objects | worst part | image |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: |\n",
        scene.name, scene.environment.file.filename().string(), args.time, vertices, truth_ms,
        fmt::format("{}", fmt::join(args.receivers, ", ")), gl_device);
    for (const Row& r : rows) {
        json["methods"].push_back({{"method", r.method}, {"setting", r.setting}, {"lights", r.lights},
                                   {"frame_ms", r.frame_ms}, {"gpu_pass_ms", r.gpu_pass_ms}, {"gpu_pass_clock", r.gpu_clock},
                                   {"rays", r.rays}, {"vertex_error", r.vertex_error},
                                   {"objects_error", r.objects_error}, {"worst_part", r.worst_part},
                                   {"worst_part_error", r.worst_error}, {"image_error", r.image_error}});
        const std::string gpu_ms =
            r.gpu_pass_ms > 0 ? fmt::format("{:.1f}{}", r.gpu_pass_ms, r.gpu_clock ? " (clock)" : "") : std::string("–");
        table += fmt::format("| {} | {} | {:.1f} | {} | {} | {:.4f} | {:.4f} | {} {:.4f} | {:.4f} |\n", r.label(),
                             r.lights ? fmt::format("{}", r.lights) : std::string("–"),
                             r.frame_ms, gpu_ms, r.rays ? fmt::format("{:.2f} M", double(r.rays) / 1e6) : std::string("–"),
                             r.vertex_error, r.objects_error, r.worst_part, r.worst_error, r.image_error);
        write_exr_and_png(dir / (r.label() + ".exr"), r.image, ToneMap{0.0f, true});
    }
    write_exr_and_png(dir / "truth.exr", truth_image, ToneMap{0.0f, true});
    write_file_atomically(dir / "results.json", json.dump(2) + "\n");
    write_file_atomically(dir / "table.md", table);
    return table;
}

// Output phase: sheet.png, the truth and every row at one exposure, from the truth's 99th luminance percentile.
void write_contact_sheet(const std::filesystem::path& dir, const Image& truth_image, const std::vector<Row>& rows) {
    std::vector<float> lum;
    for (int y = 0; y < truth_image.height; ++y)
        for (int x = 0; x < truth_image.width; ++x) lum.push_back(luminance(truth_image.rgb(x, y)));
    std::nth_element(lum.begin(), lum.begin() + lum.size() * 99 / 100, lum.end());
    const float gain = 0.9f / std::max(lum[lum.size() * 99 / 100], 1e-6f);
    std::vector<Image> tiles{truth_image};
    std::vector<std::string> labels{"TRUTH"};
    for (const Row& r : rows) {
        tiles.push_back(r.image);
        labels.push_back(fmt::format("{}  {:.0f} MS  {:.1f}%", r.label(), r.frame_ms, 100 * r.objects_error));
    }
    write_png(dir / "sheet.png", raster::contact_sheet(tiles, labels, 4, gain));
}

// Output phase: pareto.png, the objects' error against frame time, one curve per method.
void write_pareto_plot(const std::filesystem::path& dir, const Scene& scene, const std::vector<Row>& rows) {
    const std::vector<std::pair<std::string, Color>> families = {{"rsl", Color(0.1f, 0.6f, 0.2f)},
                                                                 {"rsl-gl", Color(0.5f, 0.8f, 0.2f)},
                                                                 {"rays", Color(0.85f, 0.2f, 0.1f)},
                                                                 {"rays-gl", Color(0.95f, 0.45f, 0.6f)},
                                                                 {"rays-budget", Color(0.9f, 0.6f, 0.1f)},
                                                                 {"shadow-map", Color(0.1f, 0.45f, 0.85f)},
                                                                 {"env-rays", Color(0.55f, 0.25f, 0.75f)}};
    std::vector<raster::Series> series;
    for (const auto& [family, color] : families) {
        raster::Series s{family, color, {}, {}, {}};
        for (const Row& r : rows)
            if (r.method == family) {
                s.x.push_back(std::max(r.frame_ms, 1e-3)), s.y.push_back(std::max(r.objects_error, 1e-6));
                const char* prefix = family.starts_with("rsl")    ? "K"
                                     : family.starts_with("rays") ? "S"
                                     : family == "env-rays"       ? "N"
                                                                  : "";
                s.labels.push_back(fmt::format("{}{}", prefix, r.setting));
            }
        if (!s.x.empty()) series.push_back(std::move(s));
    }
    write_png(dir / "pareto.png", raster::line_plot(series, fmt::format("MS PER FRAME ({})", scene.name),
                                                    "OBJECTS REL. L2 ERROR", 640, 420, true));
}

// The files every run writes, beside each row's image and the truth's.
const std::vector<std::string> kFixedOutputs{"results.json", "table.md", "sheet.png", "pareto.png"};

// Every output file of the experiment, then the table on stdout.
void write_outputs(const ManyLightExperiment& args, const Scene& scene, size_t vertices, const Image& truth_image,
                   double truth_ms, const std::vector<Row>& rows, const std::string& gl_device) {
    const std::filesystem::path dir(args.output);
    std::vector<std::string> stems{"truth"};
    for (const Row& r : rows) stems.push_back(r.label());
    check_experiment_outputs(scene, dir, stems, kFixedOutputs);
    const std::string table = write_results(args, scene, vertices, truth_image, truth_ms, rows, gl_device);
    write_contact_sheet(dir, truth_image, rows);
    write_pareto_plot(dir, scene, rows);
    fmt::print("{}\nwrote {}/table.md, results.json, pareto.png, sheet.png\n", table, dir.string());
}

// Prints one progress line to stderr unless the run is quiet.
void say(const ManyLightExperiment& args, const std::string& line) {
    if (!args.quiet) fmt::print(stderr, "{}\n", line);
}

// Phase: the scene at the experiment's environment and resolution.
std::shared_ptr<Scene> load_experiment_scene(const ManyLightExperiment& args) {
    auto scene_ptr = std::make_shared<Scene>(load_scene(args.scene));
    Scene& scene = *scene_ptr;
    adapt_scene(scene, args.environment, args.resolution, false);
    // One map: every row shades one RSL set (lights_for), so the truth must
    // not blend in a second map the rows do not see.
    scene.environment.second_file.clear();
    return scene_ptr;
}

// The ground truth's vertex colours and the time they took.
struct TruthColors {
    VertexColors colors;
    double ms = 0;
};

// Phase: the ground truth's vertex colours under the environment at t, timed.
TruthColors shade_truth(const ManyLightExperiment& args, const Scene& scene, const RenderSetup& setup) {
    const float t = args.time;
    GroundTruthOptions truth_options;
    truth_options.local_lights = false;
    const GroundTruth truth(scene, setup.environment_at(t), t, truth_options);
    const auto truth_start = ExperimentClock::now();
    TruthColors result{truth.shade_vertices()};
    result.ms = 1e3 * seconds_since(truth_start);
    return result;
}

// What every row is measured against (the truth, its frame and image) and
// the rows measured so far.
struct RowMeasurer {
    RowMeasurer(const ManyLightExperiment& args, Scene& scene, const RenderSetup& setup, const RenderOptions& options,
                TruthColors truth)
        : args(args), scene(scene), setup(setup), options(options), t(args.time), truth_colors(std::move(truth.colors)),
          truth_ms(truth.ms), posed(scene, t), camera(PinholeCamera::at_time(scene.camera, t, args.width, args.height)),
          truth_image(form_image(posed, camera, truth_colors)) {}

    const ManyLightExperiment& args;
    Scene& scene;
    const RenderSetup& setup;
    const RenderOptions& options;
    const float t;
    const VertexColors truth_colors;
    const double truth_ms;
    const PosedScene posed;
    const PinholeCamera camera;
    const Image truth_image;
    std::vector<Row> rows;

    // The RSL set of k lights: the baseline's as fitted by the setup, other k fitted here.
    RslSet lights_for(int k) const {
        return k == args.baseline_lights ? setup.environment_lights.first
                                         : fit_scene_lights(*setup.scene, setup.environment, k, options.cross_face_lights);
    }

    // Times `repeats` frames of a renderer posed at t and measures its colours.
    void measure(Row row, VertexRenderer& renderer) {
        renderer.set_time(t);
        VertexColors colors = renderer.make_output();
        renderer.shade(colors);  // warm-up: per-thread scratch, GL programs and textures
        // set_time in the frame: what a moving scene pays each frame (the
        // occluder lists; the shadow maps are redrawn only after it).
        std::vector<double> gpu_ms;
        row.frame_ms = median_ms(args.repeats, [&] {
            renderer.set_time(t);
            renderer.shade(colors);
            gpu_ms.push_back(gpu_pass_ms(renderer, row.gpu_clock));
        });
        std::sort(gpu_ms.begin(), gpu_ms.end());
        row.gpu_pass_ms = gpu_ms[gpu_ms.size() / 2];
        row.rays = renderer.stats().shadow_rays;
        add_row(std::move(row), colors);
    }

    // Measures a row's colours against the truth (vertices, objects, worst
    // part, the image they form) and keeps it.
    void add_row(Row row, const VertexColors& colors) {
        const VertexErrorReport report = compare_vertex_colors(colors, truth_colors);
        const ObjectErrorReport objects = object_errors(report, args.receivers);
        row.vertex_error = report.total.relative_l2();
        row.objects_error = objects.objects.relative_l2();
        row.worst_part = objects.worst_part, row.worst_error = objects.worst;
        row.image = form_image(posed, camera, colors);
        row.image_error = compare_images(row.image, truth_image).pixels.relative_l2();
        say(args, fmt::format("{}: {:.1f} ms{}, error: vertices {:.4f}, objects {:.4f}, worst {} {:.4f}, image {:.4f}",
                              row.label(), row.frame_ms, row.rays ? fmt::format(", {} rays", row.rays) : std::string(),
                              row.vertex_error, row.objects_error, row.worst_part, row.worst_error, row.image_error));
        rows.push_back(std::move(row));
    }

    // env-rays at N samples per vertex: the map and the BRDF importance
    // sampled (src/trace/environment_rays.h); a frame is shade_vertices.
    void measure_env_ray_row(int samples) {
        EnvironmentRaysOptions o;
        o.samples = samples;
        o.local_lights = false;  // as the truth's and every row's
        const EnvironmentRays env_rays(scene, setup.environment_at(t), t, o);
        VertexColors colors = env_rays.shade_vertices();  // warm-up
        const uint64_t rays_before = env_rays.rays_traced();
        Row row = make_row("env-rays", samples, 0);
        row.frame_ms = median_ms(args.repeats, [&] { colors = env_rays.shade_vertices(); });
        row.rays = (env_rays.rays_traced() - rays_before) / uint64_t(std::max(args.repeats, 1));
        add_row(std::move(row), colors);
    }

    // Ray-traced many-light, the rays backend: the fields unused, every
    // visibility factor by rays of `samples`² per pair; returns the row's
    // rays per frame.
    uint64_t measure_ray_row(const std::string& method, int samples) {
        RenderOptions o = options;
        o.ray_samples = samples;
        const auto renderer = make_renderer(Backend::Rays, scene, lights_for(args.baseline_lights), PartFields{}, o);
        measure(make_row(method, samples, args.baseline_lights), *renderer);
        return rows.back().rays;
    }
};

// Phase: one CPU RSL row per K of rsl_lights.
void measure_rsl_rows(RowMeasurer& m) {
    for (int k : m.args.rsl_lights) {
        RenderOptions o = m.options;
        o.environment_light_count = k;
        CpuRenderer renderer(m.scene, m.lights_for(k), m.setup.fields, o);
        m.measure(make_row("rsl", k, k), renderer);
    }
}

// Phase: the ray-traced rows, one per S of ray_samples, then the one whose S
// fits the ray budget.
void measure_ray_rows(RowMeasurer& m) {
    const ManyLightExperiment& args = m.args;
    uint64_t rays_at_one = 0;
    for (int samples : args.ray_samples) {
        const uint64_t rays = m.measure_ray_row("rays", samples);
        if (samples == 1) rays_at_one = rays;
    }
    if (args.ray_budget > 0) {
        if (rays_at_one == 0) {  // the pairs that need rays, from one frame at S = 1
            RenderOptions o = m.options;
            o.ray_samples = 1;
            const auto probe = make_renderer(Backend::Rays, m.scene, m.lights_for(args.baseline_lights), PartFields{}, o);
            probe->set_time(m.t);
            probe->shade();
            rays_at_one = probe->stats().shadow_rays;
        }
        const int samples = samples_for_budget(args.ray_budget, rays_at_one);
        say(args, fmt::format("ray budget {}: {} pairs need rays, so S = {}", args.ray_budget, rays_at_one, samples));
        m.measure_ray_row("rays-budget", samples);
    }
}

// Phase: the GL rows, the fields' sum on the GPU path, the ray-traced rows'
// rays traced on the GPU, and shadow maps; returns the GL device, or why
// the rows were skipped.
std::string measure_gl_rows(RowMeasurer& m) {
    const ManyLightExperiment& args = m.args;
    std::string gl_device = "none asked for";
    if (!args.gl_lights.empty() || !args.gl_ray_samples.empty() || !args.shadow_map_resolutions.empty()) {
        try {
            for (int k : args.gl_lights) {
                RenderOptions o = m.options;
                o.environment_light_count = k;
                const auto renderer = make_renderer(Backend::Gl, m.scene, m.lights_for(k), m.setup.fields, o);
                gl_device = renderer->device();
                m.measure(make_row("rsl-gl", k, k), *renderer);
            }
            for (int samples : args.gl_ray_samples) {
                RenderOptions o = m.options;
                o.gpu_rays.enabled = true;
                o.gpu_rays.samples_per_side = samples;
                const auto renderer =
                    make_renderer(Backend::Gl, m.scene, m.lights_for(args.baseline_lights), PartFields{}, o);
                gl_device = renderer->device();
                m.measure(make_row("rays-gl", samples, args.baseline_lights), *renderer);
            }
            for (int resolution : args.shadow_map_resolutions) {
                RenderOptions o = m.options;
                o.shadow_maps.enabled = true;
                o.shadow_maps.resolution = resolution;
                o.shadow_maps.filter = ShadowFilter::Pcss;
                const auto renderer =
                    make_renderer(Backend::Gl, m.scene, m.lights_for(args.baseline_lights), m.setup.fields, o);
                gl_device = renderer->device();
                m.measure(make_row("shadow-map", resolution, args.baseline_lights), *renderer);
            }
        } catch (const Error& e) {
            gl_device = fmt::format("skipped ({})", e.what());
            say(args, "GL rows " + gl_device);
        }
    }
    return gl_device;
}

}  // namespace

void run_many_light_experiment(const ManyLightExperiment& args) {
    const std::shared_ptr<Scene> scene_ptr = load_experiment_scene(args);
    Scene& scene = *scene_ptr;
    check_experiment_outputs(scene, args.output, {"truth"}, kFixedOutputs);  // before the hours of work
    RenderOptions options;
    options.local_lights = false;
    options.environment_light_count = args.baseline_lights;
    say(args, "fitting lights and baking visibility fields...");
    RenderSetup setup = prepare_render(scene_ptr, options, {.progress = cli::drawn_progress(!args.quiet), .field_cache = {}});

    RowMeasurer m(args, scene, setup, options, shade_truth(args, scene, setup));
    say(args, fmt::format("ground truth: {:.1f} s", m.truth_ms / 1e3));
    measure_rsl_rows(m);
    measure_ray_rows(m);
    for (int samples : args.env_ray_samples) m.measure_env_ray_row(samples);
    const std::string gl_device = measure_gl_rows(m);
    write_outputs(args, scene, m.truth_colors.vertex_count(), m.truth_image, m.truth_ms, m.rows, gl_device);
}

}  // namespace rsl
