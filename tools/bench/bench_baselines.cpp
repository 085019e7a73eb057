// `rsl bench baselines`: the PRT baselines' building blocks, and a small
// static scene end to end with SH, Haar, eigentransport and the triple
// product (precompute, frame time, error against the ground truth). The full
// comparison with RSL on real scenes is `rsl baselines`.
#include <chrono>
#include <cmath>
#include <fmt/core.h>

#include "src/image/error_metrics.h"
#include "tools/baselines/eigentransport.h"
#include "tools/baselines/prt.h"
#include "tools/baselines/triple.h"
#include "tools/bench/bench.h"

namespace rsl::bench {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

template <typename F>
double best_seconds(int repeats, const F& f) {
    double best = 1e30;
    for (int r = 0; r < repeats; ++r) {
        const auto start = Clock::now();
        f();
        best = std::min(best, seconds_since(start));
    }
    return best;
}

CubeMap make_sky(int n) {
    CubeMap map(n);
    const Vec3 sun = glm::normalize(Vec3(0.3f, 0.9f, 0.2f));
    for (int k = 0; k < map.texel_count(); ++k) {
        const Vec3 d = map.texel_direction(k);
        const float sky = d.y > 0 ? 0.4f + 0.6f * d.y : 0.1f;
        const float glow = glm::dot(d, sun) > 0.97f ? 40.0f : 0.0f;
        map.radiance(k) = Color(sky + glow, sky + 0.9f * glow, 1.2f * sky + 0.7f * glow);
    }
    return map;
}

// A UV sphere floating over a ground grid: self- and cast shadows.
Scene make_scene(int detail) {
    Scene scene;
    scene.name = "sphere-over-plane";
    scene.source = "bench";
    MaterialDesc glossy;
    glossy.name = "glossy";
    glossy.model = "blinn_phong";
    glossy.params = {{"kd", {0.4f, 0.4f, 0.4f}}, {"ks", {0.4f, 0.4f, 0.4f}}, {"exponent", {30}}};
    scene.materials.push_back(glossy);
    auto add = [&](TriangleMesh mesh) {
        SceneNode node;
        node.name = mesh.name;
        scene.nodes.push_back(node);
        Part part;
        part.name = mesh.name;
        part.node = int(scene.nodes.size()) - 1;
        part.mesh = std::move(mesh);
        scene.parts.push_back(std::move(part));
    };
    TriangleMesh ground;
    ground.name = "ground";
    for (int j = 0; j <= detail; ++j)
        for (int i = 0; i <= detail; ++i) {
            ground.positions.emplace_back(4.0f * (float(i) / detail - 0.5f), 0.0f, 4.0f * (float(j) / detail - 0.5f));
            ground.normals.emplace_back(0, 1, 0);
            ground.tangents.emplace_back(1, 0, 0, 1);
        }
    for (int j = 0; j < detail; ++j)
        for (int i = 0; i < detail; ++i) {
            const uint32_t a = j * (detail + 1) + i, b = a + 1, c = a + detail + 1, d = c + 1;
            for (uint32_t index : {a, c, b, b, c, d}) ground.indices.push_back(index);
        }
    add(std::move(ground));
    TriangleMesh sphere;
    sphere.name = "sphere";
    for (int j = 0; j <= detail; ++j)
        for (int i = 0; i <= 2 * detail; ++i) {
            const float theta = kPi * float(j) / detail, phi = kPi * float(i) / detail;
            const Vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            sphere.positions.push_back(Vec3(0, 0.8f, 0) + 0.5f * n);
            sphere.normals.push_back(n);
            sphere.tangents.emplace_back(Frame::from_normal(n).x, 1.0f);
        }
    for (int j = 0; j < detail; ++j)
        for (int i = 0; i < 2 * detail; ++i) {
            const uint32_t a = j * (2 * detail + 1) + i, b = a + 1, c = a + 2 * detail + 1, d = c + 1;
            for (uint32_t index : {a, b, c, b, d, c}) sphere.indices.push_back(index);
        }
    add(std::move(sphere));
    scene.camera.position = Vec3(1.5f, 2.5f, 3.0f);
    scene.camera.target = Vec3(0, 0.4f, 0);
    return scene;
}

// End to end on a small static scene: every precompute once, then each
// method's frame time and vertex error against the truth.
void bench_small_scene(const BenchOptions& options, const CubeMap& sky, int repeats) {
    const int n = sky.resolution();
    const Scene scene = make_scene(options.quick ? 12 : 40);
    GroundTruthOptions truth_options;
    truth_options.local_lights = false;
    truth_options.max_sample_share = 0.0f;  // the texel-centre sum the transports sample
    const GroundTruth truth(scene, sky, 0.0f, truth_options);
    auto start = Clock::now();
    const VertexColors truth_colors = truth.shade_vertices();
    const double truth_s = seconds_since(start);
    std::vector<Color> reference;
    for (const auto& part : truth_colors.parts) reference.insert(reference.end(), part.begin(), part.end());
    PrtOptions prt_options;
    const PrtPrecompute prt = precompute_prt(truth, sky, prt_options);
    bench_emit({{"bench", "baselines"}, {"case", fmt::format("{} precompute", scene.name)},
                {"vertices", prt.layout.total()}, {"cube", n}, {"wall_seconds", prt.wall_seconds},
                {"truth_seconds", truth_s}, {"ray_cpu_seconds", prt.trace_cpu_seconds},
                {"sh_cpu_seconds", prt.sh_cpu_seconds}, {"haar_cpu_seconds", prt.haar_cpu_seconds},
                {"haar_entries", prt.haar.entries()}, {"haar_bytes", prt.haar.bytes()},
                {"sh_bytes", prt.sh.bytes()}});
    std::vector<Color> out;
    auto emit_frame = [&](const std::string& method, int terms, double s) {
        bench_emit({{"bench", "baselines"}, {"case", fmt::format("{} {} {}", scene.name, method, terms)},
                    {"frame_seconds", s}, {"vertex_error", relative_l2(out, reference)}});
    };
    const ShRenderer sh_renderer(prt, sky);
    for (int order : {3, 5, 10})
        emit_frame("sh", order * order, best_seconds(repeats, [&] { sh_renderer.render(order, Mat3(1.0f), out); }));
    HaarRenderer haar_renderer(prt);
    for (int terms : {20, 30, 60, 100})
        emit_frame("haar", terms, best_seconds(repeats, [&] { haar_renderer.render(sky, terms, out); }));

    const EigenTransport eigen = precompute_eigentransport(truth, sky, EigenOptions{});
    bench_emit({{"bench", "baselines"}, {"case", fmt::format("{} eigentransport precompute", scene.name)},
                {"wall_seconds", eigen.wall_seconds}, {"ray_cpu_seconds", eigen.trace_cpu_seconds},
                {"pca_cpu_seconds", eigen.pca_cpu_seconds}, {"bytes_128", eigen.bytes(eigen.max_terms())}});
    EigenRenderer eigen_renderer(eigen);
    for (int terms : {16, 48, 128})
        emit_frame("eigen", terms, best_seconds(repeats, [&] { eigen_renderer.render(sky, terms, out); }));

    const TripleOptions triple_options;
    const TriplePrecompute triple = precompute_triple_visibility(truth, sky, triple_options);
    const TripleBrdfTables tables = tabulate_part_brdfs(truth, triple, triple_options);
    bench_emit({{"bench", "baselines"}, {"case", fmt::format("{} triple product precompute", scene.name)},
                {"wall_seconds", triple.wall_seconds}, {"ray_cpu_seconds", triple.trace_cpu_seconds},
                {"table_cpu_seconds", tables.cpu_seconds()}, {"visibility_bytes", triple.visibility.bytes()},
                {"table_bytes", tables.bytes()}});
    TripleRenderer triple_renderer(triple, truth, &tables);
    for (int terms : {80, 320})
        emit_frame("triple", terms, best_seconds(repeats, [&] {
                       triple_renderer.render(sky, terms, truth.camera_position(), out);
                   }));
}

void run(const BenchOptions& options) {
    const int repeats = options.quick ? 2 : 5;
    {  // SH evaluation and rotation
        const int count = options.quick ? 20000 : 200000;
        std::vector<double> y(100);
        double sink = 0;
        const double s = best_seconds(repeats, [&] {
            for (int i = 0; i < count; ++i) {
                const double z = -1.0 + 2.0 * (i + 0.5) / count, r = std::sqrt(1 - z * z);
                sh::evaluate(10, DVec3(r * std::cos(i * 2.4), r * std::sin(i * 2.4), z), y.data());
                sink += y[57];
            }
        });
        bench_emit({{"bench", "baselines"}, {"case", "sh evaluate order 10"}, {"seconds", s},
                    {"evaluations_per_second", count / s}, {"checksum", sink}});
        const glm::dmat3 R = glm::mat3_cast(glm::angleAxis(0.7, glm::normalize(glm::dvec3(1, 2, 3))));
        const double rot = best_seconds(repeats, [&] { sh::Rotation(10, R); });
        bench_emit({{"bench", "baselines"}, {"case", "sh rotation matrices order 10"}, {"seconds", rot}});
    }
    const int n = options.quick ? 16 : 32;
    const CubeMap sky = make_sky(n);
    {  // lighting approximations per frame
        haar::LightingApproximation approximation(n);
        haar::SparseLighting lighting;
        const double haar_s = best_seconds(repeats, [&] { approximation.approximate(sky, 100, lighting); });
        const sh::TexelBasis basis(n, 10);
        const double sh_s = best_seconds(repeats, [&] { sh::project_cube(sky, basis); });
        bench_emit({{"bench", "baselines"}, {"case", fmt::format("lighting 6x{}^2: haar transform + 100 terms", n)},
                    {"seconds", haar_s}});
        bench_emit({{"bench", "baselines"}, {"case", fmt::format("lighting 6x{}^2: sh projection order 10", n)},
                    {"seconds", sh_s}});
    }
    bench_small_scene(options, sky, repeats);
}

RegisterBenchmark baselines_benchmark({"baselines",
    "PRT baselines: SH evaluation/rotation, lighting approximation; SH, Haar, eigentransport and the triple product on a small scene end to end", run});

}  // namespace
}  // namespace rsl::bench
