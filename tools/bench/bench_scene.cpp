// `rsl bench scene`: loading speed of OBJ meshes, glTF files and scene files
// (parse + validation + normals/tangents), and of evaluating the animated
// node hierarchy.
#include <chrono>
#include <filesystem>

#include "tools/bench/bench.h"
#include "src/core/scene.h"
#include "src/formats/scene_file.h"

namespace rsl::bench {
namespace {
namespace fs = std::filesystem;

void bench_load(const fs::path& path, int repeats) {
    const std::string name = path.filename().string();
    if (!fs::exists(path)) {
        bench_emit({{"bench", "scene"}, {"case", "load " + name}, {"skipped", "missing " + path.string()}});
        return;
    }
    Scene scene;
    const double seconds = best_seconds(repeats, [&] { scene = load_scene(path); });
    size_t triangles = 0;
    for (const Part& p : scene.parts) triangles += p.mesh.triangle_count();
    const double megabytes = double(fs::file_size(path)) / (1 << 20);
    bench_emit({{"bench", "scene"},
                {"case", "load " + name},
                {"seconds", seconds},
                {"parts", scene.parts.size()},
                {"vertices", scene.vertex_count()},
                {"triangles", triangles},
                {"file_megabytes", megabytes},
                {"vertices_per_second", scene.vertex_count() / seconds}});
}

// Part transforms for every frame: what a renderer does per frame.
void bench_hierarchy(const fs::path& path, bool quick) {
    if (!fs::exists(path)) {
        bench_emit({{"bench", "scene"}, {"case", "part transforms"}, {"skipped", "missing " + path.string()}});
        return;
    }
    const Scene scene = load_scene(path);
    const int evaluations = quick ? 1000 : 20000;
    float checksum = 0;
    const auto start = BenchClock::now();
    for (int e = 0; e < evaluations; ++e) {
        const float t = scene.animation.start + (scene.animation.end - scene.animation.start) * float(e) / evaluations;
        for (size_t p = 0; p < scene.parts.size(); ++p) checksum += scene.part_transform_at(int(p), t)[3][1];
    }
    const double seconds = seconds_since(start);
    bench_emit({{"bench", "scene"},
                {"case", "part transforms " + path.filename().string()},
                {"parts", scene.parts.size()},
                {"frames", evaluations},
                {"seconds", seconds},
                {"microseconds_per_frame", 1e6 * seconds / evaluations},
                {"checksum", checksum}});
}

void run(const BenchOptions& options) {
    const int repeats = options.quick ? 1 : 3;
    bench_load(options.shared_assets / (options.quick ? "meshes/suzanne.obj" : "meshes/stanford-bunny.obj"), repeats);
    bench_load(options.generated_assets / "robot.glb", repeats);
    if (!options.quick) bench_load(options.generated_assets / "kitchen.glb", repeats);
    bench_hierarchy(options.generated_assets / "robot.glb", options.quick);
}

RegisterBenchmark scene_benchmark({"scene", "OBJ/glTF/scene loading and part-transform evaluation", run});

}  // namespace
}  // namespace rsl::bench
