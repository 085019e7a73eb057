// `rsl bench truth`: ground-truth throughput. Shadow rays per second in the
// per-vertex case (coherent 16-ray packets from one origin, all cores), the
// same rays one at a time for comparison, and the time of the robot scene's
// full ground truth at 6×32×32 texels.
// `rsl bench image`: primary rays per second of image formation (form_image,
// tiles of coherent packets) against the same rays traced one at a time.
#include <chrono>
#include <filesystem>

#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "tools/assets/primitives.h"
#include "tools/bench/bench.h"
#include "src/core/envmap.h"
#include "src/core/scene.h"
#include "src/formats/scene_file.h"
#include "src/trace/ground_truth.h"
#include "src/image/image_formation.h"
#include "src/formats/scene_environment.h"

namespace rsl::bench {
namespace {
namespace fs = std::filesystem;

// Rays per CPU-second (process_cpu_seconds) say what the code does when it
// gets the cores of a shared machine.

// A floor with spheres standing on it: the shape of the project's scenes
// (receivers under occluders) without needing the generated assets.
Scene synthetic_scene(bool quick) {
    Scene scene;
    scene.name = "bench-spheres";
    MaterialDesc white;
    white.params["albedo"] = {0.8f, 0.8f, 0.8f};
    scene.materials.push_back(white);
    auto add = [&](TriangleMesh mesh, Vec3 at) {
        SceneNode node;
        node.name = mesh.name;
        node.rest.translation = at;
        scene.nodes.push_back(node);
        Part part;
        part.name = mesh.name;
        part.mesh = std::move(mesh);
        part.node = int(scene.nodes.size()) - 1;
        scene.parts.push_back(std::move(part));
    };
    const int cells = quick ? 24 : 96;
    TriangleMesh floor = assets::grid_plane(6, 6, cells, cells);
    floor.name = "floor";
    add(std::move(floor), Vec3(0));
    for (int k = 0; k < 5; ++k) {
        TriangleMesh ball = assets::sphere(0.45f, quick ? 0.12f : 0.04f);
        ball.name = "ball" + std::to_string(k);
        add(std::move(ball), Vec3(-2.0f + k, 0.45f + 0.1f * k, 0.3f * (k % 2)));
    }
    scene.camera.position = Vec3(0, 4, 6);
    return scene;
}

void emit_truth(const std::string& case_name, const Scene& scene, const CubeMap& map, float t) {
    const auto build_start = BenchClock::now();
    const GroundTruth truth(scene, map, t);
    const double build_seconds = seconds_since(build_start);
    const auto start = BenchClock::now();
    const double cpu_start = process_cpu_seconds();
    const VertexColors colors = truth.shade_vertices();
    const double seconds = seconds_since(start), cpu = process_cpu_seconds() - cpu_start;
    const uint64_t rays = truth.rays_traced();
    bench_emit({{"bench", "truth"},
                {"case", case_name},
                {"parts", scene.parts.size()},
                {"vertices", scene.vertex_count()},
                {"texels", map.texel_count()},
                {"lit_texel_samples", truth.environment_sample_count()},
                {"lights", scene.lights.size()},
                {"bvh_seconds", build_seconds},
                {"seconds", seconds},
                {"shadow_rays", rays},
                {"rays_per_vertex", double(rays) / double(std::max<size_t>(scene.vertex_count(), 1))},
                {"cpu_seconds", cpu},
                {"shadow_rays_per_second", double(rays) / seconds},
                {"shadow_rays_per_cpu_second", double(rays) / cpu}});
}

// The same per-vertex rays (upper hemisphere of a 6×N×N map) traced as
// 16-ray packets and as single rays, over a sample of vertices.
void emit_packet_comparison(const std::string& case_name, const Scene& scene, int resolution) {
    const PosedScene posed(scene, 0.0f);
    const CubeMap map(resolution);
    std::vector<Vec3> dirs(map.texel_count());
    for (int k = 0; k < map.texel_count(); ++k) dirs[k] = map.texel_direction(k);
    std::vector<std::pair<int, int>> vertices;
    for (size_t p = 0; p < scene.parts.size(); ++p)
        for (size_t v = 0; v < scene.parts[p].mesh.vertex_count(); v += 7) vertices.emplace_back(int(p), int(v));
    for (bool packets : {true, false}) {
        const auto start = BenchClock::now();
        const double cpu_start = process_cpu_seconds();
        const uint64_t rays = tbb::parallel_reduce(
            tbb::blocked_range<size_t>(0, vertices.size(), 16), uint64_t(0),
            [&](const tbb::blocked_range<size_t>& range, uint64_t count) {
                std::vector<Vec3> batch(dirs.size());
                std::vector<uint8_t> visible(dirs.size());
                for (size_t i = range.begin(); i != range.end(); ++i) {
                    const SurfacePoint x = posed.vertex(vertices[i].first, vertices[i].second);
                    const Vec3 origin = x.ray_origin();
                    int n = 0;
                    for (const Vec3& d : dirs)
                        if (glm::dot(d, x.offset_normal) > 0.0f) batch[n++] = d;
                    if (packets) {
                        posed.rays().occluded_batch(origin, batch.data(), n, 0.0f, 1e30f, visible.data());
                    } else {
                        for (int k = 0; k < n; ++k)
                            visible[k] = !posed.rays().occluded(origin, batch[k], 0.0f, 1e30f);
                    }
                    count += uint64_t(n);
                }
                return count;
            },
            std::plus<uint64_t>());
        const double seconds = seconds_since(start), cpu = process_cpu_seconds() - cpu_start;
        bench_emit({{"bench", "truth"},
                    {"case", case_name + (packets ? " packets of 16" : " single rays")},
                    {"vertices", vertices.size()},
                    {"seconds", seconds},
                    {"cpu_seconds", cpu},
                    {"shadow_rays", rays},
                    {"shadow_rays_per_second", double(rays) / seconds},
                    {"shadow_rays_per_cpu_second", double(rays) / cpu}});
    }
}

CubeMap white_cube(int n) {
    CubeMap map(n);
    for (Color& c : map.radiances()) c = Color(1);
    return map;
}

RegisterBenchmark truth_benchmark({"truth",
    "Ground truth: shadow rays per second (per-vertex packets vs single rays) and the robot scene at 6×32×32",
    [](const BenchOptions& options) {
        const Scene spheres = synthetic_scene(options.quick);
        const int n = options.quick ? 8 : 32;
        emit_truth(fmt::format("spheres, white 6x{}x{}", n, n), spheres, white_cube(n), 0.0f);
        emit_packet_comparison(fmt::format("spheres, hemisphere of 6x{}x{}", n, n), spheres, n);

        const fs::path robot_path = options.scenes / "robot.json";
        if (!fs::exists(robot_path) || !fs::exists(options.generated_assets / "robot.glb")) {
            bench_emit({{"bench", "truth"}, {"case", "robot"}, {"skipped", "run `rsl assets` first: missing " + robot_path.string()}});
            return;
        }
        const Scene robot = load_scene(robot_path);
        const int robot_n = options.quick ? 8 : 32;
        const CubeMap environment = scene_environment_map(robot, robot_n);
        emit_truth(fmt::format("robot t=0, its environment 6x{}x{}", robot_n, robot_n), robot, environment, 0.0f);
        if (!options.quick) emit_truth("robot t=0, white 6x32x32", robot, white_cube(32), 0.0f);
    }});

void emit_image(const std::string& case_name, const Scene& scene, int width, int height, bool quick) {
    PosedScene posed(scene, 0.0f);
    // Posing the parts at a new time (transforms, top-level commit): what
    // `rsl render` adds to each frame's image time besides form_image.
    const double pose_seconds = best_seconds(quick ? 3 : 15, [&] {
        posed.set_time(0.5f);
        posed.set_time(0.0f);
    }) / 2;
    const PinholeCamera camera = PinholeCamera::at_time(scene.camera, 0.0f, width, height);
    VertexColors colors;
    colors.scene_name = scene.name;
    for (const Part& part : scene.parts) {
        colors.add_part(part.name, part.mesh.vertex_count());
        for (size_t v = 0; v < part.mesh.vertex_count(); ++v)
            colors.parts.back()[v] = Color(0.5f) + 0.5f * glm::sin(part.mesh.positions[v] * 7.0f);
    }
    const int repeats = quick ? 3 : 15;
    for (int s : {1, 2}) {
        ImageFormationOptions options;
        options.samples_per_side = s;
        Image packets, single;
        double best[2], cpu[2];
        for (int variant = 0; variant < 2; ++variant) {
            Image& out = variant == 0 ? packets : single;
            best[variant] = 1e30;
            cpu[variant] = 1e30;
            for (int r = 0; r < repeats; ++r) {
                const auto start = BenchClock::now();
                const double cpu_start = process_cpu_seconds();
                const auto shade = [&](const RayHit& hit, const Vec3&) {
                    return interpolate_vertex_colors(posed.scene(), colors, hit);
                };
                out = variant == 0 ? form_image(posed, camera, colors, options)
                                   : trace_image_one_ray_at_a_time(posed, camera, options, shade);
                best[variant] = std::min(best[variant], seconds_since(start));
                cpu[variant] = std::min(cpu[variant], process_cpu_seconds() - cpu_start);
            }
        }
        double max_difference = 0;
        for (size_t i = 0; i < packets.pixels.size(); ++i)
            max_difference = std::max(max_difference, double(std::abs(packets.pixels[i] - single.pixels[i])));
        const double rays = double(width) * height * s * s;
        bench_emit({{"bench", "image"},
                    {"case", fmt::format("{} {}x{}, {}x{} samples per pixel", case_name, width, height, s, s)},
                    {"parts", scene.parts.size()},
                    {"primary_rays", rays},
                    {"seconds", best[0]},
                    {"cpu_seconds", cpu[0]},
                    {"primary_rays_per_second", rays / best[0]},
                    {"primary_rays_per_cpu_second", rays / cpu[0]},
                    {"single_ray_seconds", best[1]},
                    {"single_ray_cpu_seconds", cpu[1]},
                    {"single_rays_per_second", rays / best[1]},
                    {"speedup", best[1] / best[0]},
                    {"max_pixel_difference", max_difference},
                    {"pose_seconds", pose_seconds}});
    }
}

RegisterBenchmark image_benchmark({"image",
    "Image formation: primary rays per second (tiles of packets vs single rays), robot and spheres at 640x480",
    [](const BenchOptions& options) {
        const int width = options.quick ? 160 : 640, height = options.quick ? 120 : 480;
        emit_image("spheres", synthetic_scene(options.quick), width, height, options.quick);
        const fs::path robot_path = options.scenes / "robot.json";
        if (!fs::exists(robot_path) || !fs::exists(options.generated_assets / "robot.glb")) {
            bench_emit({{"bench", "image"}, {"case", "robot"}, {"skipped", "run `rsl assets` first: missing " + robot_path.string()}});
            return;
        }
        emit_image("robot", load_scene(robot_path), width, height, options.quick);
    }});

}  // namespace
}  // namespace rsl::bench
