// The experiment behind `rsl baselines` (docs/BASELINES.md): one static frame
// of a scene with every method against the ground truth. SH PRT, Haar PRT,
// eigentransport and the RSL renderer share the truth's vertices, camera and image formation;
// images are compared with compare_images (src/image/error_metrics.h), the
// same definition `rsl compare` uses.
#include "tools/rsl/progress_display.h"
#include "tools/bench/baselines_experiment.h"
#include "src/formats/environment_file.h"
#include "src/formats/image_file.h"
#include "src/formats/scene_file.h"
#include "src/lightfit/scene_lights.h"

#include "tools/bench/experiment_support.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <unistd.h>
#include <fmt/core.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "tools/baselines/eigentransport.h"
#include "tools/baselines/prt.h"
#include "tools/baselines/raster.h"
#include "tools/baselines/triple.h"
#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/image/error_metrics.h"
#include "src/image/image_formation.h"
#include "src/render/ovdf_occluder.h"
#include "src/render/render_setup.h"
#include "src/formats/scene_environment.h"

namespace rsl {
namespace {

using Clock = ExperimentClock;

// The parts that are a ground under the objects: left out of the objects'
// error, and removed by --no-ground (a ground biases eigentransport's basis).
const std::vector<std::string> kGroundParts = {"ground", "floor"};

struct MethodResult {
    std::string method;  // "truth", "sh", "haar", "eigen", "rsl"
    int terms = 0;
    double vertex_error = 0, objects_error = 0, image_error = 0, image_h1 = 0;
    std::string worst_part;  // the object part with the largest relative L2, and that error
    double worst_error = 0;
    double frame_ms = 0, precompute_s = 0;
    size_t bytes = 0;
    Image image;
    std::string label() const { return method == "truth" ? "TRUTH" : fmt::format("{} {}", method, terms); }
};

size_t field_bytes(const PartFields& fields) {
    size_t bytes = 0;
    for (const auto& svdf : fields.self)
        if (svdf) bytes += svdf->model.stored_bytes(false);
    for (const auto& occluder : fields.occluder)
        if (auto* ovdf = dynamic_cast<const OvdfOccluder*>(occluder.get())) bytes += ovdf->field().model.stored_bytes(false);
    return bytes;
}

struct Diagnostics {
    std::vector<std::pair<int, double>> haar, rsl;  // unshadowed (terms, vertex error)
    std::vector<std::pair<int, double>> triple_exact;  // triple product with exact BRDF slices, vs the truth
    nlohmann::json eigen;    // the eigentransport precompute, results.json "eigen"
    std::string eigen_note;  // the same as a line under the table
};

// The files every run writes, beside each method's image.
const std::vector<std::string> kFixedOutputs{"results.json", "table.md", "sheet.png", "error_plot.png"};

// A method's image file name, without its extension.
std::string image_stem(const MethodResult& r) {
    return r.method == "truth" ? "truth" : fmt::format("{}_{}", r.method, r.terms);
}

// Output phase: results.json, table.md and every method's EXR and PNG; returns the table.
std::string write_results(const BaselinesExperiment& args, const Scene& scene, const std::vector<MethodResult>& results,
                          const PrtPrecompute& prt, double texel_sum_error, const Diagnostics& unshadowed) {
    const std::filesystem::path dir(args.output);
    nlohmann::json json = {{"scene", scene.name}, {"source", scene.source.string()},
                           {"environment", scene.environment.file.filename().string()},
                           {"materials", args.diffuse ? "diffuse" : "scene"}, {"time", args.time},
                           {"cube_resolution", scene.environment.resolution}, {"vertices", prt.layout.total()},
                           {"shadow_rays", prt.rays}, {"transport_vs_truth_error", texel_sum_error},
                           {"no_ground", args.no_ground}, {"methods", nlohmann::json::array()}};
    std::string table = fmt::format(
        "Scene `{}`{}, environment `{}`, {} materials, t = {}, {} vertices, cube 6×{}². "
        "Objects: every part but {}.\n\n"
        "| method | terms | vertex rel. L2 | objects rel. L2 | worst part | image rel. L2 | image H1 | ms / frame | "
        "precompute s | memory MB |\n| --- | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: |\n",
        scene.name, args.no_ground ? " without its ground" : "", scene.environment.file.filename().string(),
        args.diffuse ? "diffuse" : "scene (glossy)", args.time, prt.layout.total(), scene.environment.resolution,
        fmt::join(kGroundParts, ", "));
    for (const MethodResult& r : results) {
        json["methods"].push_back({{"method", r.method}, {"terms", r.terms}, {"vertex_error", r.vertex_error},
                                   {"objects_error", r.objects_error}, {"worst_part", r.worst_part},
                                   {"worst_part_error", r.worst_error}, {"image_error", r.image_error},
                                   {"image_h1_error", r.image_h1}, {"frame_ms", r.frame_ms},
                                   {"precompute_seconds", r.precompute_s}, {"bytes", r.bytes}});
        const std::string worst = r.worst_part.empty() ? "–" : fmt::format("{} {:.4f}", r.worst_part, r.worst_error);
        table += fmt::format("| {} | {} | {:.4f} | {:.4f} | {} | {:.4f} | {:.4f} | {:.2f} | {:.1f} | {:.1f} |\n", r.method,
                             r.terms, r.vertex_error, r.objects_error, worst, r.image_error, r.image_h1, r.frame_ms,
                             r.precompute_s, double(r.bytes) / 1e6);
        write_exr_and_png(dir / (image_stem(r) + ".exr"), r.image, ToneMap{0.0f, true});
    }
    if (!unshadowed.eigen.is_null()) json["eigen"] = unshadowed.eigen;
    table += unshadowed.eigen_note;
    table += "\nWithout visibility (V = 1; RSL with SVDF and OVDF off) against the unshadowed truth, vertex rel. L2:\n";
    for (const auto& [name, rows] : {std::pair{"haar", &unshadowed.haar}, std::pair{"rsl", &unshadowed.rsl}}) {
        if (rows->empty()) continue;
        json[fmt::format("{}_unshadowed_vertex_error", name)] = nlohmann::json::object();
        table += fmt::format("- {}:", name);
        for (const auto& [terms, error] : *rows) {
            table += fmt::format(" {} → {:.4f};", terms, error);
            json[fmt::format("{}_unshadowed_vertex_error", name)][std::to_string(terms)] = error;
        }
        table += "\n";
    }
    if (!unshadowed.triple_exact.empty()) {
        table += "\nTriple product with exact BRDF slices (no tables), vertex rel. L2:";
        for (const auto& [terms, error] : unshadowed.triple_exact) {
            table += fmt::format(" {} → {:.4f};", terms, error);
            json["triple_exact_vertex_error"][std::to_string(terms)] = error;
        }
        table += "\n";
    }
    write_file_atomically(dir / "results.json", json.dump(2) + "\n");
    write_file_atomically(dir / "table.md", table);
    return table;
}

// Output phase: sheet.png, side by side: one exposure for all, from the truth's 99th luminance percentile.
void write_contact_sheet(const std::filesystem::path& dir, const std::vector<MethodResult>& results) {
    std::vector<float> lum;
    const Image& truth = results.front().image;
    for (int y = 0; y < truth.height; ++y)
        for (int x = 0; x < truth.width; ++x) lum.push_back(luminance(truth.rgb(x, y)));
    std::nth_element(lum.begin(), lum.begin() + lum.size() * 99 / 100, lum.end());
    const float gain = 0.9f / std::max(lum[lum.size() * 99 / 100], 1e-6f);
    std::vector<Image> tiles;
    std::vector<std::string> labels;
    for (const MethodResult& r : results) {
        tiles.push_back(r.image);
        labels.push_back(r.method == "truth" ? "TRUTH"
                                             : fmt::format("{} {}  {:.1f}%", r.method, r.terms, 100 * r.image_error));
    }
    write_png(dir / "sheet.png", raster::contact_sheet(tiles, labels, 4, gain));
}

// Output phase: error_plot.png, the image error against the terms, one curve per method.
void write_error_plot(const std::filesystem::path& dir, const std::vector<MethodResult>& results) {
    std::vector<raster::Series> series = {{"SH", Color(0.85f, 0.2f, 0.1f), {}, {}, {}},
                                          {"HAAR", Color(0.1f, 0.45f, 0.85f), {}, {}, {}},
                                          {"EIGEN", Color(0.6f, 0.3f, 0.75f), {}, {}, {}},
                                          {"TRIPLE", Color(0.85f, 0.55f, 0.1f), {}, {}, {}},
                                          {"RSL", Color(0.1f, 0.6f, 0.2f), {}, {}, {}}};
    const std::vector<std::string> methods = {"sh", "haar", "eigen", "triple", "rsl"};  // the series' order
    for (const MethodResult& r : results) {
        const int s = int(std::find(methods.begin(), methods.end(), r.method) - methods.begin());
        if (s == int(methods.size())) continue;
        series[s].x.push_back(r.terms);
        series[s].y.push_back(std::max(r.image_error, 1e-6));
    }
    std::erase_if(series, [](const raster::Series& s) { return s.x.empty(); });
    write_png(dir / "error_plot.png",
              raster::line_plot(series, "TERMS (SH COEFFICIENTS, HAAR/TRIPLE TERMS, EIGENTRANSPORTS, RSLS)",
                                 "IMAGE REL. L2 ERROR"));
}

// Every output file of the experiment, then the table on stdout.
void write_outputs(const BaselinesExperiment& args, const Scene& scene, const std::vector<MethodResult>& results,
                   const PrtPrecompute& prt, double texel_sum_error,
                   const Diagnostics& unshadowed) {
    const std::filesystem::path dir(args.output);
    std::vector<std::string> stems;
    for (const MethodResult& r : results) stems.push_back(image_stem(r));
    check_experiment_outputs(scene, dir, stems, kFixedOutputs);
    const std::string table = write_results(args, scene, results, prt, texel_sum_error, unshadowed);
    write_contact_sheet(dir, results);
    write_error_plot(dir, results);
    fmt::print("{}\nwrote {}/table.md, results.json, sheet.png, error_plot.png\n", table, dir.string());
}

// Prints one progress line to stderr unless the run is quiet.
void say(const BaselinesExperiment& args, const std::string& line) {
    if (!args.quiet) fmt::print(stderr, "{}\n", line);
}

// Every part's vertex colours as one list, parts in order.
std::vector<Color> flatten(const VertexColors& colors) {
    std::vector<Color> flat;
    for (const auto& part : colors.parts) flat.insert(flat.end(), part.begin(), part.end());
    return flat;
}

// The frame every method is measured in and the rows measured so far, the
// truth's first: each method's colours become a row against the truth.
struct Measurements {
    Measurements(const BaselinesExperiment& args, const Scene& scene, float t)
        : args(args), scene(scene), t(t), posed(scene, t),
          camera(PinholeCamera::at_time(scene.camera, t, args.width, args.height)), layout(scene) {}

    const BaselinesExperiment& args;
    const Scene& scene;
    const float t;
    PosedScene posed;
    const PinholeCamera camera;
    const VertexLayout layout;
    VertexColors truth_colors;
    std::vector<Color> truth_flat;
    std::vector<MethodResult> results;

    // Adds one method's row: errors of its vertex colours and image against the truth's, and its costs.
    void add_result(const std::string& method, int terms, const std::vector<Color>& flat, double frame_ms,
                    double precompute_s, size_t bytes) {
        MethodResult r;
        r.method = method, r.terms = terms;
        r.vertex_error = relative_l2(flat, truth_flat);
        const VertexColors colors = layout.to_colors(scene, flat, method, t);
        const ObjectErrorReport objects = object_errors(compare_vertex_colors(colors, truth_colors), kGroundParts);
        r.objects_error = objects.objects.relative_l2();
        r.worst_part = objects.worst_part, r.worst_error = objects.worst;
        r.image = form_image(posed, camera, colors);
        const ImageErrorReport errors = compare_images(r.image, results.front().image);
        r.image_error = errors.pixels.relative_l2(), r.image_h1 = errors.relative_h1();
        r.frame_ms = frame_ms, r.precompute_s = precompute_s, r.bytes = bytes;
        say(args, fmt::format("{} {}: vertex error {:.4f} (objects {:.4f}), image error {:.4f} (H1 {:.4f}), {:.2f} ms",
                              method, terms, r.vertex_error, r.objects_error, r.image_error, r.image_h1, frame_ms));
        results.push_back(std::move(r));
    }
};

// Phase: the scene's environment map at the scene's resolution, timed.
CubeMap load_environment(const BaselinesExperiment& args, const Scene& scene) {
    const auto load_start = Clock::now();
    CubeMap environment = scene_environment_map(scene, scene.environment.resolution);
    say(args, fmt::format("environment {} as 6x{}^2 ({:.1f} s)", describe_environment(scene.environment),
                          environment.resolution(), seconds_since(load_start)));
    return environment;
}

// Phase: the ground truth's vertex colours and image, the first row.
void measure_truth(const GroundTruth& truth, Measurements& m) {
    MethodResult reference;
    reference.method = "truth";
    auto truth_start = Clock::now();
    // At unit texture, as every PRT row is (their transport has no texture):
    // a textured part's image is then compared like for like.
    m.truth_colors = truth.shade_vertices().at_unit_texture();
    reference.frame_ms = 1e3 * seconds_since(truth_start);
    reference.image = form_image(m.posed, m.camera, m.truth_colors);
    m.truth_flat = flatten(m.truth_colors);
    say(m.args, fmt::format("ground truth: {:.1f} s", reference.frame_ms / 1e3));
    m.results.push_back(reference);
}

// The shadowed PRT transport and how far its texel sum is from the truth.
struct ShadowedPrt {
    PrtPrecompute prt;
    double texel_sum_error = 0;
};

// Phase: SH and Haar transport from one shared pass of shadow rays.
ShadowedPrt precompute_shadowed_prt(const GroundTruth& truth, const CubeMap& environment, const Measurements& m) {
    const BaselinesExperiment& args = m.args;
    PrtOptions prt_options;
    prt_options.sh_order = *std::max_element(args.sh_orders.begin(), args.sh_orders.end());
    prt_options.haar_drop = args.haar_drop;
    prt_options.check_lighting = &environment;
    say(args, "PRT precompute (SH + Haar transport)...");
    ShadowedPrt shadowed{precompute_prt(truth, environment, prt_options)};
    const PrtPrecompute& prt = shadowed.prt;
    shadowed.texel_sum_error = relative_l2(prt.texel_sum, m.truth_flat);
    say(args, fmt::format("  {:.1f} s wall; CPU s: rays {:.1f}, SH {:.1f}, Haar {:.1f}; transport vs truth {:.2e}",
                          prt.wall_seconds, prt.trace_cpu_seconds, prt.sh_cpu_seconds, prt.haar_cpu_seconds,
                          shadowed.texel_sum_error));
    return shadowed;
}

// Phase: one row per SH order and per Haar term count, rendered from the
// shadowed transport into `flat`.
void measure_prt_methods(const PrtPrecompute& prt, const CubeMap& environment, Measurements& m,
                         std::vector<Color>& flat) {
    const BaselinesExperiment& args = m.args;
    const Mat3 rotation = m.scene.environment.rotation_at(m.t);
    {
        const ShRenderer sh_renderer(prt, environment);
        for (int order : args.sh_orders) {
            const double ms = median_ms(args.repeats, [&] { sh_renderer.render(order, rotation, flat); });
            const size_t bytes = prt.layout.total() * sh::coefficient_count(order) * 3 * sizeof(float);
            m.add_result("sh", order * order, flat, ms, prt.trace_cpu_seconds + prt.sh_cpu_seconds, bytes);
        }
    }
    {
        HaarRenderer haar_renderer(prt);
        for (int terms : args.haar_terms) {
            const double ms = median_ms(args.repeats, [&] { haar_renderer.render(environment, terms, flat); });
            m.add_result("haar", terms, flat, ms, prt.trace_cpu_seconds + prt.haar_cpu_seconds, prt.haar.bytes());
        }
    }
}

// Eigentransport holds the whole transport matrix (3V × texels, float) in
// memory: a scene or cube too large for it is refused before the truth's
// minutes are spent, not by the allocator halfway.
void require_eigentransport_fits(const BaselinesExperiment& args, const Scene& scene, const CubeMap& environment) {
    if (args.eigen_terms.empty()) return;
    const double matrix_bytes = 3.0 * double(VertexLayout(scene).total()) * environment.texel_count() * sizeof(float);
    const double machine_bytes = double(::sysconf(_SC_PHYS_PAGES)) * double(::sysconf(_SC_PAGE_SIZE));
    if (machine_bytes > 0 && matrix_bytes > 0.6 * machine_bytes)
        throw_file_error(scene.source,
                         "eigentransport needs a {:.1f} GB transport matrix ({} vertices × 3 × {} texels), more "
                         "than 60% of this machine's {:.1f} GB: lower --resolution, or leave it out with "
                         "--eigen-terms \"\"",
                         matrix_bytes / 1e9, VertexLayout(scene).total(), environment.texel_count(), machine_bytes / 1e9);
}

// Phase: eigentransport rows, one per d, all from one basis of the largest
// d, on their own pass of shadow rays (the dense transport matrix is built
// and released inside the precompute).
void measure_eigentransport(const GroundTruth& truth, const CubeMap& environment, Measurements& m,
                            std::vector<Color>& flat, Diagnostics& notes) {
    const BaselinesExperiment& args = m.args;
    if (args.eigen_terms.empty()) return;
    EigenOptions options;
    options.max_terms = *std::max_element(args.eigen_terms.begin(), args.eigen_terms.end());
    if (args.eigen_objects_basis)
        for (const Part& part : m.scene.parts)
            options.basis_parts.push_back(std::find(kGroundParts.begin(), kGroundParts.end(), part.name) ==
                                          kGroundParts.end());
    say(args, fmt::format("eigentransport precompute ({} x {} transport matrix, {:.1f} GB, d = {})...",
                          3 * m.layout.total(), environment.texel_count(),
                          3e-9 * double(m.layout.total()) * environment.texel_count() * sizeof(float), options.max_terms));
    const EigenTransport eigen = precompute_eigentransport(truth, environment, options);
    const double precompute_s = eigen.trace_cpu_seconds + eigen.pca_cpu_seconds;
    const std::string solver = eigen.randomized ? "randomized" : "dense";
    say(args, fmt::format("  {:.1f} s wall; CPU s: rays {:.1f}, PCA {:.1f} ({} eigensolver)", eigen.wall_seconds,
                          eigen.trace_cpu_seconds, eigen.pca_cpu_seconds, solver));
    notes.eigen = {{"max_terms", eigen.max_terms()}, {"solver", solver},
                   {"basis", args.eigen_objects_basis ? "objects" : "all"}, {"rays_cpu_seconds", eigen.trace_cpu_seconds},
                   {"pca_cpu_seconds", eigen.pca_cpu_seconds}, {"wall_seconds", eigen.wall_seconds},
                   {"captured_variance", nlohmann::json::object()}};
    notes.eigen_note = fmt::format("\nEigentransport: one basis of d = {} fitted to {} ({} eigensolver; CPU s: rays "
                                   "{:.1f}, PCA {:.1f}; {:.1f} s wall); transport variance captured:",
                                   eigen.max_terms(), args.eigen_objects_basis ? "the objects' vertices" : "every vertex",
                                   solver, eigen.trace_cpu_seconds, eigen.pca_cpu_seconds, eigen.wall_seconds);
    EigenRenderer renderer(eigen);
    const Mat3 rotation = m.scene.environment.rotation_at(m.t);
    for (int requested : args.eigen_terms) {
        const int terms = std::min(requested, eigen.max_terms());  // at most the texel count
        const double ms = median_ms(args.repeats, [&] { renderer.render(environment, rotation, terms, flat); });
        m.add_result("eigen", terms, flat, ms, precompute_s, eigen.bytes(terms));
        notes.eigen["captured_variance"][std::to_string(terms)] = eigen.captured_variance(terms);
        notes.eigen_note += fmt::format(" {} → {:.4f};", terms, eigen.captured_variance(terms));
    }
    notes.eigen_note += "\n";
}

// Phase: the wavelet triple product's rows: per-vertex visibility and the BRDF
// tables precomputed once, one row per lighting term count; and, once per
// count, the exact-slice mode's error (what the tables cost in accuracy).
void measure_triple(const GroundTruth& truth, const CubeMap& environment, Measurements& m, std::vector<Color>& flat,
                    Diagnostics& diagnostics) {
    const BaselinesExperiment& args = m.args;
    if (args.triple_terms.empty()) return;
    TripleOptions options;
    options.visibility_drop = args.haar_drop;
    options.normal_resolution = args.triple_normals, options.view_resolution = args.triple_views;
    options.brdf_terms = args.triple_brdf_terms;
    options.lookup = args.triple_lookup;
    say(args, "Triple product precompute (visibility + BRDF tables)...");
    const TriplePrecompute pre = precompute_triple_visibility(truth, environment, options);
    const TripleBrdfTables tables = tabulate_part_brdfs(truth, pre, options);
    const double precompute_s = pre.trace_cpu_seconds + pre.transform_cpu_seconds + tables.cpu_seconds();
    say(args, fmt::format("  {:.1f} s wall; CPU s: rays {:.1f}, Haar {:.1f}, BRDF tables {:.1f}; {:.1f} MB visibility, "
                          "{:.1f} MB tables",
                          pre.wall_seconds, pre.trace_cpu_seconds, pre.transform_cpu_seconds, tables.cpu_seconds(),
                          double(pre.visibility.bytes()) / 1e6, double(tables.bytes()) / 1e6));
    TripleRenderer renderer(pre, truth, &tables);
    for (int terms : args.triple_terms) {
        const double ms = median_ms(args.repeats, [&] { renderer.render(environment, terms, truth.camera_position(), flat); });
        const size_t lighting_bytes = size_t(terms) * (sizeof(int32_t) + sizeof(Color));
        m.add_result("triple", terms, flat, ms, precompute_s, pre.visibility.bytes() + tables.bytes() + lighting_bytes);
    }
    TripleRenderer exact(pre, truth, nullptr);
    for (int terms : args.triple_terms) {
        exact.render(environment, terms, truth.camera_position(), flat);
        diagnostics.triple_exact.push_back({terms, relative_l2(flat, m.truth_flat)});
    }
}

// Phase: the transport without visibility (V = 1), and the Haar rows'
// errors from it against its own unshadowed texel sum.
PrtPrecompute measure_unshadowed_haar(const BaselinesExperiment& args, const GroundTruth& truth,
                                      const CubeMap& environment, std::vector<Color>& flat,
                                      Diagnostics& unshadowed_errors) {
    PrtOptions unshadowed_options;
    unshadowed_options.sh = false;
    unshadowed_options.haar_drop = args.haar_drop;
    unshadowed_options.visibility = false;
    unshadowed_options.check_lighting = &environment;
    PrtPrecompute unshadowed = precompute_prt(truth, environment, unshadowed_options);
    {
        HaarRenderer haar_renderer(unshadowed);
        for (int terms : args.haar_terms) {
            haar_renderer.render(environment, terms, flat);
            unshadowed_errors.haar.push_back({terms, relative_l2(flat, unshadowed.texel_sum)});
        }
    }
    return unshadowed;
}

// Phase: RSL rows, one per light count (fields baked once), each also shaded
// with every visibility factor off against the unshadowed truth.
void measure_rsl(const std::shared_ptr<Scene>& scene_ptr, const PrtPrecompute& unshadowed, Measurements& m,
                 Diagnostics& unshadowed_errors) {
    const BaselinesExperiment& args = m.args;
    Scene& scene = *scene_ptr;
    const float t = m.t;
    RenderOptions options;
    options.local_lights = false;
    options.environment_light_count = args.rsl_lights.front();
    say(args, "RSL: fitting lights and baking visibility fields...");
    RenderSetup setup = prepare_render(scene_ptr, options, {.progress = cli::drawn_progress(!args.quiet), .field_cache = {}});
    const size_t bytes = field_bytes(setup.fields);
    for (int lights : args.rsl_lights) {
        const auto fit_start = Clock::now();
        RslSet set = lights == options.environment_light_count ? setup.environment_lights.first
                                                            : fit_scene_lights(*setup.scene, setup.environment, lights);
        const double fit_s = lights == options.environment_light_count ? setup.fit_seconds : seconds_since(fit_start);
        options.environment_light_count = lights;
        CpuRenderer renderer(scene, std::move(set), setup.fields, options);
        renderer.set_time(t);
        VertexColors colors = renderer.make_output();
        const double ms = median_ms(args.repeats, [&] { renderer.shade(colors); });
        m.add_result("rsl", lights, flatten(colors.at_unit_texture()), ms, setup.bake_seconds + fit_s, bytes);
        // The same lights with every visibility factor off, against the
        // unshadowed truth: the lighting + BRDF part of RSL's error.
        RenderOptions no_shadows = options;
        no_shadows.self_visibility = false, no_shadows.occluders = false;
        CpuRenderer light_only(scene, renderer.environment_lights(), setup.fields, no_shadows);
        light_only.set_time(t);
        light_only.shade(colors);
        unshadowed_errors.rsl.push_back({lights, relative_l2(flatten(colors.at_unit_texture()), unshadowed.texel_sum)});
    }
}

// --no-ground: the scene without its ground or floor parts, so that every
// method (and eigentransport's basis) sees the objects alone.
void remove_ground_parts(Scene& scene) {
    std::vector<std::string> names;
    for (const Part& part : scene.parts) names.push_back(part.name);
    const size_t removed = std::erase_if(scene.parts, [](const Part& part) {
        return std::any_of(kGroundParts.begin(), kGroundParts.end(),
                           [&](const std::string& ground) { return is_receiver(part.name, ground); });
    });
    if (removed == 0)
        throw_file_error(scene.source, "--no-ground: no part is named {} (the parts: {})",
                         fmt::join(kGroundParts, " or "), fmt::join(names, ", "));
    if (scene.parts.empty()) throw_file_error(scene.source, "--no-ground: every part is a ground, nothing is left");
}

}  // namespace

void run_baselines_experiment(const BaselinesExperiment& args) {
    auto scene_ptr = std::make_shared<Scene>(load_scene(args.scene));
    Scene& scene = *scene_ptr;
    if (args.no_ground) remove_ground_parts(scene);
    adapt_scene(scene, args.environment, args.resolution, args.diffuse);
    check_experiment_outputs(scene, args.output, {"truth"}, kFixedOutputs);  // before the hours of work
    const float t = args.time;
    const CubeMap environment = load_environment(args, scene);
    require_eigentransport_fits(args, scene, environment);

    GroundTruthOptions truth_options;
    truth_options.local_lights = false;
    // The PRT transports sample each texel at its centre (tools/baselines/transport.h):
    // they and every row here are measured against that same sum.
    truth_options.max_sample_share = 0.0f;
    const GroundTruth truth(scene, environment, t, truth_options);
    Measurements m(args, scene, t);
    measure_truth(truth, m);

    // SH and Haar share one pass of shadow rays.
    ShadowedPrt shadowed = precompute_shadowed_prt(truth, environment, m);
    std::vector<Color> flat;
    measure_prt_methods(shadowed.prt, environment, m, flat);
    // The shadowed Haar transport is released first (it can be large), then
    // eigentransport's dense transport matrix comes and goes.
    shadowed.prt.haar = {};
    Diagnostics unshadowed_errors;
    measure_eigentransport(truth, environment, m, flat, unshadowed_errors);
    measure_triple(truth, environment, m, flat, unshadowed_errors);
    // Without visibility (V = 1 in the transport, fields off in RSL), against
    // the unshadowed truth: the lighting approximations alone, like for like.
    const PrtPrecompute unshadowed = measure_unshadowed_haar(args, truth, environment, flat, unshadowed_errors);
    if (!args.no_rsl) measure_rsl(scene_ptr, unshadowed, m, unshadowed_errors);
    write_outputs(args, scene, m.results, shadowed.prt, shadowed.texel_sum_error, unshadowed_errors);
}

}  // namespace rsl
