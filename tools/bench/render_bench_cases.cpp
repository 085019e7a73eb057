#include "tools/rsl/progress_display.h"
#include "tools/bench/render_bench_cases.h"
#include "src/formats/environment_file.h"
#include "src/formats/scene_file.h"
#include "src/lightfit/scene_lights.h"

#include <chrono>
#include <cstdio>

#include "src/lightfit/reconstruct.h"
#include "src/render/render_setup.h"
#include "src/image/error_metrics.h"
#include "src/trace/ground_truth.h"

namespace rsl {

namespace fs = std::filesystem;

namespace {

double since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// Every part Lambertian (albedo 0.6): the "diffuse" rows.
void make_diffuse(Scene& scene) {
    MaterialDesc lambert;
    lambert.name = "diffuse";
    lambert.model = "lambert";
    lambert.params["albedo"] = {0.6f, 0.6f, 0.6f};
    scene.materials = {lambert};
    for (Part& part : scene.parts) part.material = 0;
}

// The four environments of the table as cube maps of the scenes' resolution.
struct NamedEnvironment {
    std::string name;
    CubeMap map;
};
std::vector<NamedEnvironment> table_environments(const bench::BenchOptions& assets, int n, bool quick) {
    std::vector<NamedEnvironment> result;
    for (const char* probe : {"grace", "ennis", "uffizi"}) {
        const fs::path path = assets.shared_assets / "probes" / (std::string(probe) + ".hdr");
        if (fs::exists(path)) result.push_back({probe, load_environment(path, n)});
        if (quick) return result;
    }
    // The project's generated sun and sky (assets/generated, made by `rsl assets`).
    const fs::path sunsky = assets.generated_assets / "sunsky.exr";
    if (fs::exists(sunsky)) result.push_back({"sunsky", load_environment(sunsky, n)});
    return result;
}

}  // namespace

PrecomputeSettings bench_precompute() {
    PrecomputeSettings p;
    p.svdf_resolution = 16, p.svdf_clusters = 64, p.svdf_vectors = 6, p.svdf_supersampling = 2;
    p.ovdf_shells = 13, p.ovdf_inner_radius = 0.0f, p.ovdf_outer_radius = 20.0f;  // inner: per mesh, the default
    p.ovdf_cube_resolution = 16, p.ovdf_vdt_resolution = 16, p.ovdf_vectors = 6;
    return p;
}

std::vector<RenderBenchCase> render_speed_cases(bool quick) {
    if (quick) return {{"robot 30 RSLs", "robot.json", false, 30, 0.5f}};
    return {{"bunny on plane 30 RSLs", "../external/bunny.json", true, 30, 0.0f},
            {"robot 30 RSLs", "robot.json", false, 30, 0.5f},
            {"kitchen 30 RSLs", "kitchen.json", false, 30, 1.0f}};
}

std::shared_ptr<Scene> load_bench_scene(const RenderBenchCase& c, const bench::BenchOptions& assets) {
    if (c.needs_shared && !fs::exists(assets.shared_assets)) return nullptr;
    auto scene = std::make_shared<Scene>(load_scene(assets.scenes / c.scene_file));
    scene->precompute = bench_precompute();
    return scene;
}

namespace {

struct SceneCase {
    std::string name, file;
    std::vector<float> times;
    bool needs_shared = false;
    bool scene_settings = false;  // the scene file's own precompute settings, not bench_precompute()
    bool glossy_only = false;
    std::string only_environment;  // empty: all of them
};

std::vector<AccuracyRow> accuracy_rows(const std::vector<SceneCase>& scenes, const std::vector<int>& light_counts,
                                       const bench::BenchOptions& assets, bool quick, bool progress) {
    std::vector<AccuracyRow> rows;
    for (const SceneCase& sc : scenes) {
        if (sc.needs_shared && !fs::exists(assets.shared_assets)) continue;
        for (const bool glossy : {true, false}) {
            if ((quick || sc.glossy_only) && !glossy) continue;
            auto scene = std::make_shared<Scene>(load_scene(assets.scenes / sc.file));
            if (!sc.scene_settings) scene->precompute = bench_precompute();
            if (!glossy) make_diffuse(*scene);
            // Fields depend on geometry only: bake once per scene and material set.
            RenderOptions bake_options;
            bake_options.environment = false;
            const RenderSetup setup = prepare_render(scene, bake_options,
                                                     {.progress = cli::drawn_progress(progress), .field_cache = assets.field_cache});
            for (const NamedEnvironment& env : table_environments(assets, scene->environment.resolution, quick)) {
                if (!sc.only_environment.empty() && env.name != sc.only_environment) continue;
                for (float t : sc.times) {
                    auto start = std::chrono::steady_clock::now();
                    GroundTruth truth(*scene, env.map, t);
                    const VertexColors reference = truth.shade_vertices();
                    const double truth_seconds = since(start);
                    for (int k : light_counts) {
                        AccuracyRow row;
                        row.scene = sc.name, row.environment = env.name, row.material = glossy ? "glossy" : "diffuse";
                        row.time = t, row.lights = k;
                        row.settings = sc.scene_settings ? "scene" : "bench";
                        const RslSet rsls = fit_environment_lights(env.map, k);
                        RenderOptions options;
                        CpuRenderer renderer(*scene, rsls, setup.fields, options);
                        renderer.set_time(t);
                        start = std::chrono::steady_clock::now();
                        const VertexColors colors = renderer.shade();
                        row.render_seconds = since(start);
                        row.truth_seconds = truth_seconds;
                        row.vertices = colors.vertex_count();
                        const VertexErrorReport error = compare_vertex_colors(colors, reference);
                        const ObjectErrorReport objects = object_errors(error);
                        row.error = error.total.relative_l2();
                        row.objects_error = objects.objects.relative_l2();
                        row.worst_part = objects.worst_part, row.worst_part_error = objects.worst;
                        RenderOptions no_occluders;
                        no_occluders.occluders = false;
                        CpuRenderer self_only(*scene, rsls, setup.fields, no_occluders);
                        self_only.set_time(t);
                        row.no_occluder_error = compare_vertex_colors(self_only.shade(), reference).total.relative_l2();
                        // The light approximation alone: the exact integral
                        // under the map the RSLs stand for (one more ground
                        // truth per row, so only for the glossy robot under grace).
                        row.light_error = -1;
                        if (sc.name == "robot" && glossy && env.name == "grace") {
                            GroundTruth light_only(*scene, lightfit::reconstruct(rsls, env.map.resolution()), t);
                            row.light_error =
                                compare_vertex_colors(light_only.shade_vertices(), reference).total.relative_l2();
                        }
                        if (progress)
                            std::fprintf(stderr,
                                         "%s t=%.2f %s %s K=%d: %.4f, objects %.4f, worst %s %.4f (light %.4f, no "
                                         "occluders %.4f)\n",
                                         row.scene.c_str(), t, row.environment.c_str(), row.material.c_str(), k,
                                         row.error, row.objects_error, row.worst_part.c_str(), row.worst_part_error,
                                         row.light_error, row.no_occluder_error);
                        rows.push_back(row);
                    }
                }
            }
        }
    }
    return rows;
}

}  // namespace

std::vector<AccuracyRow> render_accuracy_table(const bench::BenchOptions& assets, bool quick, bool progress) {
    std::vector<SceneCase> scenes(3);
    scenes[0].name = "robot", scenes[0].file = "robot.json", scenes[0].times = {0.0f, 0.5f, 1.0f};
    scenes[1].name = "kitchen", scenes[1].file = "kitchen.json", scenes[1].times = {1.0f};
    scenes[2].name = "bunny", scenes[2].file = "../external/bunny.json", scenes[2].times = {0.0f}, scenes[2].needs_shared = true;
    std::vector<int> light_counts = {10, 30, 60, 100};
    if (quick) {
        scenes.resize(1);
        scenes[0].times = {0.0f};
        light_counts = {10, 30};
    }
    return accuracy_rows(scenes, light_counts, assets, quick, progress);
}

std::vector<AccuracyRow> render_accuracy_goal_rows(const bench::BenchOptions& assets, bool quick, bool progress) {
    SceneCase robot;
    robot.name = "robot", robot.file = "robot.json", robot.times = {0.0f, 0.5f, 1.0f};
    robot.scene_settings = true, robot.glossy_only = true, robot.only_environment = "grace";
    robot.needs_shared = true;  // grace is one of the shared probes
    if (quick) robot.times = {0.0f};
    return accuracy_rows({robot}, quick ? std::vector<int>{30} : std::vector<int>{10, 30, 60, 100}, assets,
                         false, progress);
}

nlohmann::json accuracy_row_json(const AccuracyRow& row) {
    return {{"bench", "render-accuracy"},
            {"scene", row.scene},
            {"precompute", row.settings},
            {"time", row.time},
            {"environment", row.environment},
            {"material", row.material},
            {"lights", row.lights},
            {"vertices", row.vertices},
            {"relative_l2", row.error},
            {"objects_relative_l2", row.objects_error},
            {"worst_part", row.worst_part},
            {"worst_part_relative_l2", row.worst_part_error},
            {"relative_l2_light_only", row.light_error},
            {"relative_l2_without_occluders", row.no_occluder_error},
            {"truth_seconds", row.truth_seconds},
            {"render_seconds", row.render_seconds}};
}

}  // namespace rsl
