// `rsl bench render-factors`: the error budget of the RSL renderer against the
// ground truth, per scene and probe. One truth per frame (shadowed and
// unshadowed), then the renderer with one approximation at a time replaced by
// its exact value: visibility by rays over each square
// (src/render/exact_visibility.h); the light split into the BRDF tables' error
// (the truth's integral with ρ·cos read from the tables) and the squares'
// (the renderer's against that). docs/RESULTS.md carries its table ("Error budget").
#include <cstdio>
#include <filesystem>
#include <functional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "src/backend/make_renderer.h"
#include "src/brdf/material_library.h"
#include "src/core/hemisphere.h"
#include "src/formats/environment_file.h"
#include "src/formats/scene_file.h"
#include "src/rays/posed_scene.h"
#include "src/shading/squares.h"
#include "src/formats/scene_environment.h"
#include "src/image/error_metrics.h"
#include "src/lightfit/scene_lights.h"
#include "src/render/exact_visibility.h"
#include "src/render/render_setup.h"
#include "src/trace/ground_truth.h"
#include "tools/bench/bench.h"
#include "tools/bench/render_bench_cases.h"

namespace rsl::bench {
namespace {
namespace fs = std::filesystem;

struct BudgetCase {
    std::string scene, file;
    std::string environment;  // "scene": the scene's own map; else a probe under the shared assets
    float time = 0;
    bool needs_shared = false;
};

std::vector<BudgetCase> budget_cases(bool quick) {
    if (quick) return {{"robot", "robot.json", "scene", 0.0f}};
    return {{"robot", "robot.json", "scene", 0.0f},       {"robot", "robot.json", "grace", 0.0f, true},
            {"bunny", "../external/bunny.json", "scene", 0.0f, true}, {"kitchen", "kitchen.json", "scene", 1.0f},
            {"kitchen", "kitchen.json", "sunsky", 1.0f}};
}

// A probe by name: the project's generated map (sunsky, studio) or a shared probe (grace, uffizi).
fs::path named_probe(const BenchOptions& options, const std::string& name) {
    const fs::path generated = options.generated_assets / (name + ".exr");
    return fs::exists(generated) ? generated : options.shared_assets / "probes" / (name + ".hdr");
}

// The renderer's vertex colours at t with the RSLs `rsls` and the options `edit` sets.
VertexColors render(const Scene& scene, const RslSet& rsls, const PartFields& fields, float t,
                    const std::function<void(RenderOptions&)>& edit) {
    RenderOptions options;
    options.environment_light_count = int(rsls.lights.size());
    edit(options);
    const std::unique_ptr<VertexRenderer> renderer = make_renderer(Backend::Cpu, scene, rsls, fields, options);
    renderer->set_time(t);
    return renderer->shade();
}

// The exact unshadowed integral times the renderer's shadowed-to-unshadowed
// ratio, per vertex and channel: what the renderer would give if its light
// (squares and BRDF tables) were exact and only its visibility approximate.
VertexColors ratio_with_exact_unshadowed(const VertexColors& shaded, const VertexColors& unshadowed,
                                         const VertexColors& exact_unshadowed) {
    VertexColors out = exact_unshadowed;
    for (size_t p = 0; p < out.parts.size(); ++p)
        for (size_t v = 0; v < out.parts[p].size(); ++v) {
            const Color& s = shaded.parts[p][v];
            const Color& u = unshadowed.parts[p][v];
            Color& c = out.parts[p][v];
            c.r = u.r > 0.0f ? c.r * s.r / u.r : 0.0f;
            c.g = u.g > 0.0f ? c.g * s.g / u.g : 0.0f;
            c.b = u.b > 0.0f ? c.b * s.b / u.b : 0.0f;
        }
    return out;
}

// The unshadowed integral over every (sub-)texel of the truth, with each
// part's ρ·cos read from its BRDF table as the renderer reads a square
// narrower than a texel: the tables' own error, against the unshadowed truth.
VertexColors unshadowed_with_tables(const Scene& scene, const CubeMap& map, float t) {
    const MaterialLibrary library = MaterialLibrary::from_scene(scene);
    const PosedScene posed(scene, t);
    const EnvironmentSamples samples = EnvironmentSamples::from_cube(
        map, scene.environment.rotation_at(t), 1, GroundTruthOptions::kDefaultMaxSampleShare);
    const Vec3 camera = scene.camera.position_at(t);
    VertexColors colors;
    colors.scene_name = scene.name;
    for (size_t p = 0; p < scene.parts.size(); ++p) colors.add_part(scene.parts[p].name, scene.parts[p].mesh.vertex_count());
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const BrdfTable& table = library.part_table(int(p));
        tbb::parallel_for(tbb::blocked_range<size_t>(0, scene.parts[p].mesh.vertex_count(), 16),
                          [&](const tbb::blocked_range<size_t>& range) {
            std::vector<float> cx, cy, vx, vy, vz, r, g, b;
            std::vector<Color> weight;
            for (size_t v = range.begin(); v != range.end(); ++v) {
                const SurfacePoint x = posed.vertex(int(p), int(v));
                const Vec3 wo = x.frame.to_local(glm::normalize(camera - x.position));
                if (!(wo.z > 0.0f)) continue;
                const Vec2 alignment = shading::view_alignment(wo);
                cx.clear(), cy.clear(), weight.clear();
                for (size_t k = 0; k < samples.size(); ++k) {
                    const Vec3 wi = x.frame.to_local(samples.directions[k]);
                    if (!(wi.z > 0.0f)) continue;
                    const Vec2 plane = hemisphere_to_plane(wi);
                    const Vec2 at = table.isotropic() ? shading::to_view_aligned(plane, alignment) : plane;
                    cx.push_back(at.x), cy.push_back(at.y), weight.push_back(samples.radiance_weights[k]);
                }
                const size_t m = cx.size();
                vx.assign(m, wo.x), vy.assign(m, wo.y), vz.assign(m, wo.z), r.resize(m), g.resize(m), b.resize(m);
                SquareQueries queries;
                queries.center_x = cx.data(), queries.center_y = cy.data();
                queries.uniform_half_edge = 1e-6f;  // read one texel wide, as a sub-texel square
                queries.view_x = vx.data(), queries.view_y = vy.data(), queries.view_z = vz.data();
                queries.count = m;
                table.square_average_batch(queries, ColorOutputs{r.data(), g.data(), b.data()});
                DVec3 sum(0.0);
                for (size_t i = 0; i < m; ++i) sum += DVec3(weight[i]) * DVec3(r[i], g[i], b[i]);
                colors.parts[p][v] = Color(sum);
            }
        });
    }
    return colors;
}

void bench_factors(const BenchOptions& options) {
    const std::vector<int> light_counts = options.quick ? std::vector<int>{30} : std::vector<int>{30, 100};
    for (const BudgetCase& c : budget_cases(options.quick)) {
        if (c.needs_shared && !fs::exists(options.shared_assets)) {
            bench_emit({{"bench", "render-factors"}, {"case", c.scene + " " + c.environment},
                        {"skipped", "needs the shared assets (--shared-assets)"}});
            continue;
        }
        auto scene = std::make_shared<Scene>(load_scene(options.scenes / c.file));
        if (options.quick) scene->precompute = bench_precompute();  // fields in seconds
        scene->environment.second_file.clear();                     // one map, as every row's RSLs
        const std::string env_name =
            c.environment == "scene" ? scene->environment.file.stem().string() : c.environment;
        const CubeMap map = c.environment == "scene"
                                ? scene_environment_map(*scene, scene->environment.resolution)
                                : load_environment(named_probe(options, c.environment), scene->environment.resolution);
        RenderOptions bake;
        bake.environment = false;  // the fields only; every row fits its own RSLs
        const RenderSetup setup = prepare_render(scene, bake, {.progress = {}, .field_cache = options.field_cache});
        const float t = c.time;
        GroundTruthOptions no_lights;
        no_lights.local_lights = false;  // the budget of the environment's light
        const VertexColors reference = GroundTruth(*scene, map, t, no_lights).shade_vertices();
        GroundTruthOptions unshadowed_options = no_lights;
        unshadowed_options.shadows = false;
        const VertexColors unshadowed_reference = GroundTruth(*scene, map, t, unshadowed_options).shade_vertices();

        const VertexColors tables = unshadowed_with_tables(*scene, map, t);
        for (int k : light_counts) {
            const RslSet rsls = fit_environment_lights(map, k);
            auto emit = [&](const std::string& variant, const VertexColors& colors, const VertexColors& against) {
                const VertexErrorReport error = compare_vertex_colors(colors, against);
                const ObjectErrorReport objects = object_errors(error);
                bench_emit({{"bench", "render-factors"}, {"scene", c.scene}, {"environment", env_name},
                            {"time", t}, {"lights", k}, {"precompute", options.quick ? "bench" : "scene"},
                            {"variant", variant}, {"relative_l2", error.total.relative_l2()},
                            {"objects_relative_l2", objects.objects.relative_l2()}, {"worst_part", objects.worst_part},
                            {"worst_part_relative_l2", objects.worst}});
                std::fprintf(stderr, "%s %s t=%.2f K=%d %s: %.4f, objects %.4f, worst %s %.4f\n", c.scene.c_str(),
                             env_name.c_str(), t, k, variant.c_str(), error.total.relative_l2(),
                             objects.objects.relative_l2(), objects.worst_part.c_str(), objects.worst);
            };
            auto no_local = [](RenderOptions& o) { o.local_lights = false; };
            const VertexColors shaded = render(*scene, rsls, setup.fields, t, no_local);
            emit("renderer", shaded, reference);
            // The light alone: the squares and the BRDF tables, no visibility on either side.
            const VertexColors unshadowed = render(*scene, rsls, setup.fields, t, [&](RenderOptions& o) {
                no_local(o), o.self_visibility = false, o.occluders = false;
            });
            emit("unshadowed", unshadowed, unshadowed_reference);
            emit("tables", tables, unshadowed_reference);
            emit("squares", unshadowed, tables);
            emit("ratio_oracle", ratio_with_exact_unshadowed(shaded, unshadowed, unshadowed_reference), reference);
            for (const auto& [variant, mode] : {std::pair{"exact_self", ExactVisibilityMode::Self},
                                                std::pair{"exact_others", ExactVisibilityMode::Others},
                                                std::pair{"exact_visibility", ExactVisibilityMode::All}}) {
                const auto exact = std::make_shared<const ExactVisibility>(*scene, t, mode);
                emit(variant, render(*scene, rsls, setup.fields, t, [&](RenderOptions& o) {
                         no_local(o), o.exact_visibility = exact;
                     }),
                     reference);
            }
        }
    }
}

RegisterBenchmark render_factors_benchmark(
    {"render-factors",
     "The renderer's error budget per scene and probe: each approximation replaced by its exact value (slow)",
     bench_factors});

}  // namespace
}  // namespace rsl::bench
