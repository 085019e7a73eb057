// `rsl bench render-factors`: which approximation of the RSL renderer is to
// blame for its error against the ground truth. One ground truth per frame,
// then the renderer with one factor at a time replaced by its exact value
// (ray-traced visibility over each square, src/render/exact_visibility.h; the
// exact integral under the RSLs' own map) or with other field settings
// (OVDF outer radius and shells, cube resolution). docs/RESULTS.md.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>

#include "src/lightfit/scene_lights.h"
#include "src/lightfit/reconstruct.h"
#include "tools/bench/bench.h"
#include "src/backend/make_renderer.h"
#include "src/render/exact_visibility.h"
#include "tools/bench/render_bench_cases.h"
#include "src/render/render_setup.h"
#include "src/frame/error_metrics.h"
#include "src/trace/ground_truth.h"
#include "src/core/scene_environment.h"

namespace rsl::bench {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct Variant {
    std::string name;
    std::function<void(PrecomputeSettings&)> fields;  // field settings (null: the bench's)
    std::function<void(RenderOptions&, const Scene&, float)> options;
};

std::vector<Variant> variants(bool quick) {
    auto exact = [](ExactVisibilityMode mode) {
        return [mode](RenderOptions& o, const Scene& scene, float t) {
            o.exact_visibility = std::make_shared<const ExactVisibility>(scene, t, mode);
        };
    };
    std::vector<Variant> v = {
        {"renderer", nullptr, nullptr},
        {"no OVDF", nullptr, [](RenderOptions& o, const Scene&, float) { o.occluders = false; }},
        {"exact visibility (rays over each square)", nullptr, exact(ExactVisibilityMode::All)},
        {"exact self-visibility, OVDF", nullptr, exact(ExactVisibilityMode::Self)},
        {"SVDF, exact others' visibility", nullptr, exact(ExactVisibilityMode::Others)},
        {"SVDF, exact others' visibility per part, multiplied", nullptr, exact(ExactVisibilityMode::OthersProduct)},
        {"exact self × exact others' visibility, averaged apart", nullptr, exact(ExactVisibilityMode::SelfTimesOthers)},
        {"OVDF outer 6R, 8 shells", [](PrecomputeSettings& p) { p.ovdf_outer_radius = 6.0f, p.ovdf_shells = 8; },
         nullptr},
        {"OVDF outer 12R, 11 shells", [](PrecomputeSettings& p) { p.ovdf_outer_radius = 12.0f, p.ovdf_shells = 11; },
         nullptr},
        {"OVDF outer 20R, 13 shells", [](PrecomputeSettings& p) { p.ovdf_outer_radius = 20.0f, p.ovdf_shells = 13; },
         nullptr},
    };
    if (!quick) {
        v.push_back({"OVDF outer 20R, 26 shells", [](PrecomputeSettings& p) {
                         p.ovdf_outer_radius = 20.0f, p.ovdf_shells = 26;
                     }, nullptr});
        v.push_back({"OVDF outer 20R, 13 shells, 32² cube", [](PrecomputeSettings& p) {
                         p.ovdf_outer_radius = 20.0f, p.ovdf_shells = 13, p.ovdf_cube_resolution = 32;
                     }, nullptr});
        v.push_back({"OVDF outer 20R, 13 shells, 32² VDTs, 12 vectors", [](PrecomputeSettings& p) {
                         p.ovdf_outer_radius = 20.0f, p.ovdf_shells = 13, p.ovdf_vdt_resolution = 32, p.ovdf_vectors = 12;
                     }, nullptr});
    }
    return v;
}

void bench_factors(const BenchOptions& options) {
    struct Frame {
        std::string environment;  // "scene": the scene's own map; else a probe under shared assets
        float time;
    };
    // The scene's own sun and sky at mid-stride, then, with the shared probes,
    // the small bright window of ennis and the broad grace.
    std::vector<Frame> frames = {{"scene", 0.5f}};
    if (!options.quick)
        for (const Frame& probe : {Frame{"ennis", 0.5f}, Frame{"grace", 0.0f}})
            if (fs::exists(options.shared_assets / "probes" / (probe.environment + ".hdr"))) frames.push_back(probe);
    const std::vector<int> light_counts = options.quick ? std::vector<int>{30} : std::vector<int>{30, 100};
    const RenderBenchCase robot{"robot", "robot.json", false, 30, 0.5f};
    for (const Frame& frame : frames) {
        const auto base = load_bench_scene(robot, options);
        const std::string env_name =
            frame.environment == "scene" ? base->environment.file.stem().string() : frame.environment;
        const CubeMap map = frame.environment == "scene"
                                ? scene_environment_map(*base, base->environment.resolution)
                                : load_environment(options.shared_assets / "probes" / (frame.environment + ".hdr"),
                                                   base->environment.resolution);
        auto start = Clock::now();
        const VertexColors reference = GroundTruth(*base, map, frame.time).shade_vertices();
        const double truth_seconds = since(start);
        for (int k : light_counts) {
            const RslSet rsls = fit_environment_lights(map, k);
            // All vertices, the objects (every part but the ground) and the worst part.
            auto emit = [&](const std::string& variant, const VertexColors& colors, double seconds) {
                const VertexErrorReport error = compare_vertex_colors(colors, reference);
                const ObjectErrorReport objects = object_errors(error);
                bench_emit({{"bench", "render-factors"}, {"scene", "robot"}, {"environment", env_name},
                            {"time", frame.time}, {"lights", k}, {"variant", variant},
                            {"relative_l2", error.total.relative_l2()},
                            {"objects_relative_l2", objects.objects.relative_l2()}, {"worst_part", objects.worst_part},
                            {"worst_part_relative_l2", objects.worst}, {"seconds", seconds},
                            {"truth_seconds", truth_seconds}});
                std::fprintf(stderr, "robot %s t=%.2f K=%d %s: %.4f, objects %.4f, worst %s %.4f (%.1f s)\n",
                             env_name.c_str(), frame.time, k, variant.c_str(), error.total.relative_l2(),
                             objects.objects.relative_l2(), objects.worst_part.c_str(), objects.worst, seconds);
            };
            // The square-vs-region light approximation alone: the exact
            // integral under the map the RSLs stand for.
            start = Clock::now();
            const VertexColors light_only =
                GroundTruth(*base, lightfit::reconstruct(rsls, map.resolution()), frame.time).shade_vertices();
            emit("light only (truth under the RSLs' map)", light_only, since(start));
            for (const Variant& v : variants(options.quick)) {
                auto scene = std::make_shared<Scene>(*base);
                if (v.fields) v.fields(scene->precompute);
                RenderOptions render_options;
                render_options.environment_lights = k;
                render_options.environment = false;  // fields only; the RSLs are `rsls`
                const RenderSetup setup = prepare_render(scene, render_options);
                render_options.environment = true;
                start = Clock::now();
                if (v.options) v.options(render_options, *scene, frame.time);
                const std::unique_ptr<VertexRenderer> renderer =
                    make_renderer(Backend::Cpu, *scene, rsls, setup.fields, render_options);
                renderer->set_time(frame.time);
                const VertexColors colors = renderer->shade();
                emit(v.name, colors, since(start));
            }
        }
    }
}

RegisterBenchmark render_factors_benchmark({"render-factors",
    "RSL renderer error vs truth with each approximation replaced by its exact value (slow)", bench_factors});

}  // namespace
}  // namespace rsl::bench
