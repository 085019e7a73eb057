// `rsl bench render`: frames per second of the CPU RSL renderer — shading
// alone and with image formation — and its speed-up over the ground truth on
// the same frame, measured in the same run; plus the error against it.
// `rsl bench render-accuracy`: the error table of docs/RESULTS.md.
#include <algorithm>
#include <chrono>
#include <filesystem>

#include <fmt/core.h>

#include "tools/bench/bench.h"
#include "tools/bench/render_bench_cases.h"
#include "src/backend/render_session.h"
#include "src/formats/scene_file.h"
#include "src/render/render_setup.h"
#include "src/image/error_metrics.h"
#include "src/trace/ground_truth.h"
#include "src/image/image_formation.h"

namespace rsl::bench {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

template <class F>
double median_seconds(int repeats, F&& f) {
    std::vector<double> times;
    for (int i = 0; i < repeats; ++i) {
        const auto start = Clock::now();
        f();
        times.push_back(since(start));
    }
    std::sort(times.begin(), times.end());
    return times[times.size() / 2];
}

// What one case measures, in seconds: the renderer's frame, its variants' and the truth's.
struct CaseTimings {
    double shade = 0, image = 0, shade_pixel_terms = 0, image_per_pixel = 0;
    int width = 0, height = 0;
    double field_lookups = 0, self_only = 0, brdf_only = 0;
    double truth = 0;
};

// Timing phase: shading, image formation, and `rsl render`'s image (shading
// that keeps the per-pixel terms, then the image with them); `colors` ends as
// the frame as measured first.
CaseTimings time_renderer(VertexRenderer& renderer, const Scene& scene, const RenderBenchCase& c, int repeats,
                          bool quick, VertexColors& colors) {
    CaseTimings timings;
    timings.shade = median_seconds(repeats, [&] {
        renderer.set_time(c.time);
        renderer.shade(colors);
    });
    timings.width = quick ? 160 : scene.camera.width, timings.height = quick ? 120 : scene.camera.height;
    PosedScene posed(scene, c.time);
    const PinholeCamera camera = PinholeCamera::at_time(scene.camera, c.time, timings.width, timings.height);
    Image image;
    timings.image = median_seconds(repeats, [&] { image = form_image(posed, camera, colors); });
    // `rsl render`'s image: shading that keeps the per-pixel terms, then the
    // image with per-pixel shadows and highlights (docs/design/RENDERER.md).
    renderer.keep_image_terms(true);
    renderer.shade(colors);
    timings.shade_pixel_terms = median_seconds(repeats, [&] {
        renderer.set_time(c.time);
        renderer.shade(colors);
    });
    renderer.form_image(colors, camera);  // warm-up: the posed scene's ray structure is built at the first image
    timings.image_per_pixel = median_seconds(repeats, [&] { renderer.form_image(colors, camera); });
    renderer.keep_image_terms(false);
    renderer.shade(colors);  // the colours and stats of the frame as measured first
    return timings;
}

// Timing phase: the same frame with parts of the work switched off or done
// the slower way, in the same run: where the time goes, and the split OVDF
// lookup's gain over the field's own lookup (src/fields/ovdf.h).
void time_variants(const Scene& scene, const RenderSetup& setup, const RenderOptions& render_options,
                   const RenderBenchCase& c, int repeats, CaseTimings& timings) {
    auto variant_seconds = [&](auto&& configure) {
        RenderOptions o = render_options;
        configure(o);
        const std::unique_ptr<VertexRenderer> r = make_renderer(Backend::Cpu, scene, setup.environment_lights, setup.fields, o);
        VertexColors out = r->make_output();
        r->set_time(c.time);
        r->shade(out);
        return median_seconds(repeats, [&] { r->shade(out); });
    };
    timings.field_lookups = variant_seconds([](RenderOptions& o) { o.fast_occluder_lookups = false; });
    timings.self_only = variant_seconds([](RenderOptions& o) { o.occluders = false; });
    timings.brdf_only = variant_seconds([](RenderOptions& o) { o.occluders = o.self_visibility = false; });
}

// Report phase: the case's one line of the benchmark's output.
void emit_case(const RenderBenchCase& c, const Scene& scene, const RenderSetup& setup, const RenderStats& stats,
               const CaseTimings& timings, const VertexErrorReport& error, const ObjectErrorReport& objects) {
    const double shade_seconds = timings.shade, image_seconds = timings.image, truth_seconds = timings.truth;
    bench_emit({{"bench", "render"},
                {"case", c.name},
                {"vertices", stats.vertices},
                {"parts", scene.parts.size()},
                {"lights", stats.lights},
                {"second_map_weight", setup.environment_lights.blends() ? scene.environment.blend_weight_at(c.time) : 0.0f},
                {"lookups", stats.lookups},
                {"occluder_pairs", stats.occluder_pairs},
                {"occluder_pairs_culled", stats.occluder_pairs_culled},
                {"block_occluders_culled", stats.block_occluders_culled},
                {"occluder_lookups", stats.occluder_lookups},
                {"shade_seconds_field_lookups", timings.field_lookups},
                {"shade_seconds_self_only", timings.self_only},
                {"shade_seconds_brdf_only", timings.brdf_only},
                {"bake_seconds", setup.bake_seconds},
                {"fields_loaded", setup.fields_loaded},
                {"fields_baked", setup.fields_baked},
                {"fit_seconds", setup.fit_seconds},
                {"shade_seconds", shade_seconds},
                {"fps_shading", 1.0 / shade_seconds},
                {"image_seconds", image_seconds},
                {"image", fmt::format("{}x{}", timings.width, timings.height)},
                {"fps_with_image", 1.0 / (shade_seconds + image_seconds)},
                {"shade_seconds_pixel_terms", timings.shade_pixel_terms},
                {"image_seconds_per_pixel", timings.image_per_pixel},
                {"truth_seconds", truth_seconds},
                {"speedup_shading", truth_seconds / shade_seconds},
                {"speedup_with_image", (truth_seconds + image_seconds) / (shade_seconds + image_seconds)},
                {"relative_l2_vs_truth", error.total.relative_l2()},
                {"objects_relative_l2_vs_truth", objects.objects.relative_l2()},
                {"worst_part", objects.worst_part},
                {"worst_part_relative_l2_vs_truth", objects.worst}});
}

void bench_case(const RenderBenchCase& c, const BenchOptions& options) {
    const auto scene = load_bench_scene(c, options);
    if (!scene) {
        bench_emit({{"bench", "render"}, {"case", c.name}, {"skipped", "missing shared assets"}});
        return;
    }
    RenderOptions render_options;
    render_options.environment_light_count = c.lights;
    RenderSession session(scene, render_options, Backend::Cpu, {.progress = {}, .field_cache = options.field_cache});
    const RenderSetup& setup = session.setup();
    VertexRenderer& renderer = session.renderer();
    VertexColors colors = session.shade(c.time, false);  // warm-up: thread-local scratch, caches
    const int repeats = options.quick ? 2 : 5;
    CaseTimings timings = time_renderer(renderer, *scene, c, repeats, options.quick, colors);
    time_variants(*scene, setup, render_options, c, repeats, timings);

    // The map the renderer's RSLs stand for at c.time (blended when the scene blends two).
    GroundTruth truth(*scene, setup.environment_at(c.time), c.time);
    auto start = Clock::now();
    const VertexColors reference = truth.shade_vertices();
    timings.truth = since(start);
    const VertexErrorReport error = compare_vertex_colors(colors, reference);
    const ObjectErrorReport objects = object_errors(error);
    emit_case(c, *scene, setup, renderer.stats(), timings, error, objects);
}

// The cost of roughness and metallic varying per point (src/brdf/pbr_basis.h):
// assets/scenes/pbr.json as it is, and with every gltf_pbr material given a
// 1×1 white metallic-roughness texture (the same values, shaded from the
// basis tables), timed alternately in one run.
void bench_pbr_texture_cost(const BenchOptions& options) {
    const fs::path file = options.scenes / "pbr.json";
    if (!fs::exists(file)) return;
    auto plain = std::make_shared<Scene>(load_scene(file));
    plain->precompute = bench_precompute();
    auto textured = std::make_shared<Scene>(*plain);
    auto white = std::make_shared<Texture>();
    white->name = "white";
    white->image = Image(1, 1, 3);
    white->image.set_rgb(0, 0, Color(1.0f));
    int varying = 0;
    for (MaterialDesc& m : textured->materials)
        if (m.model == "gltf_pbr") m.metallic_roughness_texture = white, ++varying;
    for (Part& part : textured->parts)
        if (part.mesh.texcoords.size() != part.mesh.vertex_count())
            part.mesh.texcoords.assign(part.mesh.vertex_count(), Vec2(0.5f));
    RenderOptions render_options;
    RenderSession a(plain, render_options, Backend::Cpu, {.progress = {}, .field_cache = options.field_cache});
    RenderSession b(textured, render_options, Backend::Cpu, {.progress = {}, .field_cache = options.field_cache});
    VertexColors ca = a.shade(0.0f, false), cb = b.shade(0.0f, false);  // warm-up
    std::vector<double> plain_times, textured_times;
    for (int i = 0; i < (options.quick ? 2 : 7); ++i) {
        auto start = Clock::now();
        a.renderer().shade(ca);
        plain_times.push_back(since(start));
        start = Clock::now();
        b.renderer().shade(cb);
        textured_times.push_back(since(start));
    }
    std::sort(plain_times.begin(), plain_times.end());
    std::sort(textured_times.begin(), textured_times.end());
    const double plain_seconds = plain_times[plain_times.size() / 2];
    const double textured_seconds = textured_times[textured_times.size() / 2];
    bench_emit({{"bench", "render"},
                {"case", "pbr: metallic-roughness textures"},
                {"vertices", a.renderer().stats().vertices},
                {"varying_materials", varying},
                {"shade_seconds_plain", plain_seconds},
                {"shade_seconds_textured", textured_seconds},
                {"textured_over_plain", textured_seconds / plain_seconds},
                {"lookups_plain", a.renderer().stats().lookups},
                {"lookups_textured", b.renderer().stats().lookups},
                {"relative_l2_textured_vs_plain", compare_vertex_colors(cb.at_unit_texture(), ca.at_unit_texture())
                                                      .total.relative_l2()}});
}

void bench_render(const BenchOptions& options) {
    for (const RenderBenchCase& c : render_speed_cases(options.quick)) bench_case(c, options);
}

RegisterBenchmark render_benchmark({"render",
    "CPU RSL renderer: fps (shading, with image formation) and speed-up over the ground truth", bench_render});

void bench_render_accuracy(const BenchOptions& options) {
    for (const AccuracyRow& row : render_accuracy_table(options, options.quick))
        bench_emit(accuracy_row_json(row));
}

RegisterBenchmark pbr_texture_benchmark({"render-pbr-texture",
    "CPU shading with metallic-roughness textures (the basis tables) against the same materials untextured, pbr.json",
    bench_pbr_texture_cost});

RegisterBenchmark render_accuracy_benchmark({"render-accuracy",
    "Per-vertex relative L2 error of the RSL renderer vs the ground truth (docs/RESULTS.md); slow",
    bench_render_accuracy});

void bench_render_accuracy_goal(const BenchOptions& options) {
    for (const AccuracyRow& row : render_accuracy_goal_rows(options, options.quick))
        bench_emit(accuracy_row_json(row));
}

RegisterBenchmark render_goal_benchmark({"render-goal",
    "The accuracy goal rows: glossy robot under grace, t = 0/0.5/1, K = 10-100, the scene's own field settings",
    bench_render_accuracy_goal});

}  // namespace
}  // namespace rsl::bench
