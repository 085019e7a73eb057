// `rsl bench fields`: SVDF/OVDF bake times, compression ratios and errors,
// lookups per second, and the compression/error trade-off (docs/design/FIELDS.md).
#include <chrono>
#include <filesystem>
#include <random>

#include "src/fields/ovdf.h"
#include "src/fields/svdf.h"
#include "tools/bench/bench.h"
#include "src/core/scene.h"
#include "src/formats/obj_loader.h"
#include "src/formats/scene_file.h"
#include "src/rays/ray_scene.h"

namespace rsl::bench {
namespace {
namespace fs = std::filesystem;

// Random vectors drawn one component per statement, so that every compiler
// draws the same cases (a call's arguments are evaluated in an unspecified
// order); last component first, the order GCC gave the measured benchmarks.
template <typename Distribution>
Vec2 draw_vec2(Distribution& distribution, std::mt19937& rng) {
    const float y = distribution(rng);
    const float x = distribution(rng);
    return Vec2(x, y);
}

template <typename Distribution>
Vec3 draw_vec3(Distribution& distribution, std::mt19937& rng) {
    const float z = distribution(rng);
    const Vec2 xy = draw_vec2(distribution, rng);
    return Vec3(xy, z);
}

// Mean |fraction − reference| over random squares at random vertices, where the
// reference reads the uncompressed tables with the same VDT rule (isolates the
// compression error from the VDT approximation).
double fraction_error_vs_raw(const Svdf& svdf, const std::vector<float>& raw, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-0.7f, 0.7f), h(0.03f, 0.3f);
    const int n = svdf.resolution(), nn = n * n;
    std::uniform_int_distribution<int> vertex(0, svdf.vertex_count() - 1);
    double sum = 0;
    const int samples = 20000;
    for (int k = 0; k < samples; ++k) {
        const int v = vertex(rng);
        const Vec2 c = draw_vec2(u, rng);
        const float he = h(rng);
        sum += std::abs(svdf.visible_fraction(v, c, he) - vdt_visible_fraction(n, raw.data() + size_t(v) * nn, c, he));
    }
    return sum / samples;
}

void bench_svdf(const BenchOptions& options) {
    const fs::path bunny = options.shared_assets / "meshes/stanford-bunny.obj";
    const fs::path suzanne = options.shared_assets / "meshes/suzanne.obj";
    const fs::path path = options.quick ? suzanne : bunny;
    if (!fs::exists(path)) {
        bench_emit({{"bench", "fields"}, {"case", "svdf bake"}, {"skipped", "missing " + path.string()}});
        return;
    }
    const TriangleMesh mesh = load_obj(path);  // validated, normals and tangents complete
    SvdfParams params;
    // Wall time depends on what else runs; CPU time (all threads) / 2 is the
    // time on two dedicated cores.
    const double cpu_start = process_cpu_seconds();
    auto start = BenchClock::now();
    const std::vector<float> raw = trace_svdf_tables(mesh, params);
    const double trace_seconds = seconds_since(start);
    const double trace_cpu = process_cpu_seconds() - cpu_start;
    SvdfBakeStats stats;
    const Svdf svdf = compress_svdf(raw, params, &stats);
    const double total_cpu = process_cpu_seconds() - cpu_start;
    const size_t rays_lower_bound = mesh.vertex_count() * HemisphereSampling(params.resolution, 1).traced_texels().size();
    bench_emit({{"bench", "fields"},
                {"case", "svdf bake " + path.filename().string()},
                {"vertices", mesh.vertex_count()},
                {"resolution", params.resolution},
                {"supersampling", params.supersampling},
                {"clusters", svdf.model.clusters},
                {"vectors", params.vectors},
                {"trace_seconds", trace_seconds},
                {"compress_seconds", stats.compress_seconds},
                {"total_seconds", trace_seconds + stats.compress_seconds},
                {"trace_cpu_seconds", trace_cpu},
                {"total_cpu_seconds", total_cpu},
                {"center_rays_per_second", double(rays_lower_bound) / trace_seconds},
                {"raw_bytes", stats.compression.raw_bytes},
                {"stored_bytes", stats.compression.stored_bytes},
                {"compression_ratio", stats.compression.compression_ratio()},
                {"rms_error_plane_units", stats.compression.rms_error},
                {"mean_fraction_error_vs_raw", fraction_error_vs_raw(svdf, raw, 3)}});

    // Lookups per second (single thread, random vertices and squares).
    {
        std::mt19937 rng(1);
        std::uniform_real_distribution<float> u(-0.8f, 0.8f);
        std::uniform_int_distribution<int> vertex(0, svdf.vertex_count() - 1);
        const int count = 2'000'000;
        std::vector<int> vs(4096);
        std::vector<Vec2> cs(4096);
        for (int k = 0; k < 4096; ++k) vs[k] = vertex(rng), cs[k] = draw_vec2(u, rng);
        float sink = 0;
        start = BenchClock::now();
        for (int k = 0; k < count; ++k) sink += svdf.visible_fraction(vs[k & 4095], cs[k & 4095], 0.1f);
        const double s = seconds_since(start);
        bench_emit({{"bench", "fields"}, {"case", "svdf lookup"}, {"lookups_per_second", count / s},
                    {"threads", 1}, {"checksum", sink}});
    }

    // Compression / error trade-off (paper Fig. 11 style).
    struct Setting { int clusters, vectors; };
    const std::vector<Setting> settings = options.quick ? std::vector<Setting>{{64, 4}, {32, 8}}
                                                        : std::vector<Setting>{{256, 16}, {256, 8}, {128, 8}, {64, 4}};
    for (const Setting& s : settings) {
        SvdfParams p = params;
        p.clusters = s.clusters;
        p.vectors = s.vectors;
        SvdfBakeStats st;
        const Svdf compressed = compress_svdf(raw, p, &st);
        bench_emit({{"bench", "fields"},
                    {"case", "svdf tradeoff " + path.filename().string()},
                    {"clusters", compressed.model.clusters},
                    {"vectors", s.vectors},
                    {"compress_seconds", st.compress_seconds},
                    {"compression_ratio", st.compression.compression_ratio()},
                    {"stored_megabytes", st.compression.stored_bytes / 1e6},
                    {"rms_error_plane_units", st.compression.rms_error},
                    {"mean_fraction_error_vs_raw", fraction_error_vs_raw(compressed, raw, 3)}});
    }
}

void bench_ovdf(const BenchOptions& options) {
    const fs::path robot = options.generated_assets / "robot.glb";
    if (!fs::exists(robot)) {
        bench_emit({{"bench", "fields"}, {"case", "ovdf bake"}, {"skipped", "missing " + robot.string()}});
        return;
    }
    const Scene scene = load_scene(robot);
    // The largest part: the worst case of a scene's per-part bakes.
    size_t part = 0;
    for (size_t i = 0; i < scene.parts.size(); ++i)
        if (scene.parts[i].mesh.triangle_count() > scene.parts[part].mesh.triangle_count()) part = i;
    const TriangleMesh& mesh = scene.parts[part].mesh;
    OvdfParams params;
    if (options.quick) params.cube_resolution = 8;
    OvdfBakeStats stats;
    const double cpu_start = process_cpu_seconds();
    const Ovdf ovdf = bake_ovdf(mesh, params, &stats);
    const double cpu = process_cpu_seconds() - cpu_start;
    bench_emit({{"bench", "fields"},
                {"case", "ovdf bake robot part '" + scene.parts[part].name + "'"},
                {"triangles", mesh.triangle_count()},
                {"shells", params.shells},
                {"cube_resolution", params.cube_resolution},
                {"vectors", params.vectors},
                {"segments", params.segment_count()},
                {"seconds", stats.seconds},
                {"cpu_seconds", cpu},
                {"raw_bytes", stats.compression.raw_bytes},
                {"stored_bytes", stats.compression.stored_bytes},
                {"compression_ratio", stats.compression.compression_ratio()},
                {"rms_error_plane_units", stats.compression.rms_error}});
    // Lookups per second for each blend (single thread), receivers around the part.
    std::mt19937 rng(2);
    std::normal_distribution<float> g;
    std::uniform_real_distribution<float> u(0, 1);
    std::vector<Vec3> points(4096), lights(4096);
    for (int k = 0; k < 4096; ++k) {
        const Vec3 dir = glm::normalize(draw_vec3(g, rng));
        points[k] = ovdf.center + ovdf.radius * (0.8f + 4.0f * u(rng)) * dir;
        lights[k] = glm::normalize(-dir + 0.5f * draw_vec3(g, rng));
    }
    const char* names[3] = {"aligned coefficients", "aligned samples", "sample frames"};
    for (int b = 0; b < 3; ++b) {
        const int count = options.quick ? 100000 : 1000000;
        float sink = 0;
        const auto start = BenchClock::now();
        for (int k = 0; k < count; ++k) sink += ovdf.visible_fraction(points[k & 4095], lights[k & 4095], 0.1f, OvdfBlend(b));
        bench_emit({{"bench", "fields"}, {"case", std::string("ovdf lookup ") + names[b]},
                    {"lookups_per_second", count / seconds_since(start)}, {"threads", 1}, {"checksum", sink}});
    }
    // Trade-off: vectors per segment.
    for (int vectors : {4, 16}) {
        OvdfParams p = params;
        p.vectors = vectors;
        if (!options.quick) p.cube_resolution = 16;  // keeps the sweep short; ratios scale with it
        OvdfBakeStats st;
        bake_ovdf(mesh, p, &st);
        bench_emit({{"bench", "fields"}, {"case", "ovdf tradeoff"}, {"cube_resolution", p.cube_resolution},
                    {"vectors", vectors}, {"compression_ratio", st.compression.compression_ratio()},
                    {"stored_megabytes", st.compression.stored_bytes / 1e6},
                    {"rms_error_plane_units", st.compression.rms_error}, {"seconds", st.seconds}});
    }
}

// Choices measured against rays: below-horizon value and VDT mode. For each
// variant, VDTs of a vertex subset; squares with their visible fraction over
// the above-horizon part of the square (what the shading integral weighs: ρ·cos
// is zero below) traced with 24×24 rays.
void bench_choices(const BenchOptions& options) {
    const fs::path path = options.shared_assets / (options.quick ? "meshes/suzanne.obj" : "meshes/stanford-bunny.obj");
    if (!fs::exists(path)) return;
    const TriangleMesh mesh = load_obj(path);  // validated, normals and tangents complete
    RayScene scene;
    scene.add_instance(scene.add_mesh(mesh), Mat4(1.0f));
    scene.commit();
    const RayOffset offset{scene.world_diagonal()};
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0, 1);
    std::vector<uint32_t> subset;
    for (int k = 0; k < (options.quick ? 100 : 400); ++k) subset.push_back(uint32_t(u(rng) * mesh.vertex_count()));
    struct Square { int k; Vec2 c; float h; double want; bool horizon; };
    std::vector<Square> squares;
    for (int k = 0; k < int(subset.size()); ++k) {
        const Frame frame = vertex_frame(mesh, subset[k]);
        const Vec3 origin = offset.origin(mesh.positions[subset[k]], frame.z);
        for (int q = 0; q < 8; ++q) {
            const bool horizon = q < 4;
            const float h = 0.04f + 0.16f * u(rng), angle = 6.2831853f * u(rng);
            const float r = horizon ? 0.9f + 0.15f * u(rng) : 0.8f * u(rng);
            const Vec2 c = r * Vec2(std::cos(angle), std::sin(angle));
            int visible = 0, total = 0;
            for (int b = 0; b < 24; ++b)
                for (int a = 0; a < 24; ++a) {
                    const Vec2 p = c + h * Vec2(-1 + (2 * a + 1.0f) / 24, -1 + (2 * b + 1.0f) / 24);
                    if (glm::dot(p, p) >= 1.0f) continue;
                    ++total;
                    visible += !scene.occluded(origin, frame.to_world(plane_to_hemisphere(p)), 0.0f, 1e30f);
                }
            if (total > 0) squares.push_back({k, c, h, double(visible) / total, horizon});
        }
    }
    struct Variant { const char* name; BelowHorizon below; VdtMode mode; int supersampling; };
    const Variant variants[] = {{"extend, coverage-aware, 2x2", BelowHorizon::Extend, VdtMode::CoverageAware, 2},
                                {"blocked, coverage-aware, 2x2", BelowHorizon::Blocked, VdtMode::CoverageAware, 2},
                                {"visible, coverage-aware, 2x2", BelowHorizon::Visible, VdtMode::CoverageAware, 2},
                                {"extend, binary, 1x1", BelowHorizon::Extend, VdtMode::Binary, 1},
                                {"extend, coverage-aware, 4x4", BelowHorizon::Extend, VdtMode::CoverageAware, 4}};
    for (const Variant& v : variants) {
        VisibilityMapOptions o;
        o.below_horizon = v.below;
        o.mode = v.mode;
        o.supersampling = v.supersampling;
        const std::vector<float> vdts = trace_vertex_vdts(scene, mesh, o, {}, &subset);
        double err[2] = {0, 0};
        int count[2] = {0, 0};
        for (const Square& s : squares) {
            const float got = vdt_visible_fraction(32, vdts.data() + size_t(s.k) * 1024, s.c, s.h);
            err[s.horizon] += std::abs(got - s.want);
            ++count[s.horizon];
        }
        bench_emit({{"bench", "fields"}, {"case", std::string("vdt choice ") + v.name}, {"mesh", path.filename().string()},
                    {"mean_error_inside_disk", err[0] / std::max(count[0], 1)},
                    {"mean_error_at_horizon", err[1] / std::max(count[1], 1)}, {"squares", squares.size()}});
    }
}

RegisterBenchmark fields_benchmark({"fields",
    "SVDF/OVDF bake time, compression ratio and error, lookups per second, trade-off",
    [](const BenchOptions& options) {
        bench_choices(options);
        bench_svdf(options);
        bench_ovdf(options);
    }});

}  // namespace
}  // namespace rsl::bench
