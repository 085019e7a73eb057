#include "src/fields/svdf.h"

#include <chrono>

#include "src/core/error.h"
#include "src/rays/ray_scene.h"

namespace rsl {
namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

std::vector<float> trace_svdf_tables(const TriangleMesh& mesh, const SvdfParams& params,
                                     const std::function<void(double)>& progress) {
    // A vertex on the seam where one piece of the mesh stands on another
    // sees the open half of its hemisphere, as the truth's vertices do
    // (docs/design/TRUTH.md, "Vertices on another part's surface").
    RayScene scene(/*origins_outside_surfaces=*/true);
    scene.add_instance(scene.add_mesh(mesh), Mat4(1.0f));
    scene.commit();
    VisibilityMapOptions options;
    options.resolution = params.resolution;
    options.supersampling = params.supersampling;
    options.coarse_to_fine = params.coarse_to_fine;
    options.below_horizon = params.below_horizon;
    options.mode = params.mode;
    return trace_vertex_vdts(scene, mesh, options, [&](size_t done, size_t total) {
        if (progress) progress(double(done) / double(total));
    });
}

Svdf compress_svdf(const std::vector<float>& tables, const SvdfParams& params, SvdfBakeStats* stats) {
    const int dims = params.resolution * params.resolution;
    RSL_CHECK_EQ(tables.size() % size_t(dims), size_t(0));
    const int vertices = int(tables.size() / size_t(dims));
    CpcaOptions options;
    options.clusters = params.effective_clusters(size_t(vertices));
    options.vectors = params.vectors;
    options.refine_iterations = params.refine_iterations;
    options.half_precision_tables = params.half_precision_tables;
    options.seed = params.seed;
    const auto start = std::chrono::steady_clock::now();
    Svdf svdf;
    svdf.params = params;
    svdf.model = fit_cpca(tables.data(), vertices, dims, options);
    if (stats) {
        stats->compress_seconds = seconds_since(start);
        stats->compression = measure_cpca(tables.data(), svdf.model, params.half_precision_tables);
    }
    return svdf;
}

Svdf bake_svdf(const TriangleMesh& mesh, const SvdfParams& params, SvdfBakeStats* stats,
               const std::function<void(double)>& progress) {
    // Tracing dominates; compression is reported as the last 15%.
    const auto start = std::chrono::steady_clock::now();
    const std::vector<float> tables =
        trace_svdf_tables(mesh, params, [&](double f) { if (progress) progress(0.85 * f); });
    SvdfBakeStats local;
    local.trace_seconds = seconds_since(start);
    Svdf svdf = compress_svdf(tables, params, &local);
    if (progress) progress(1.0);
    if (stats) *stats = local;
    return svdf;
}

std::vector<uint8_t> Svdf::enclosed_vertices() const {
    constexpr float kEnclosedDistance = -2.0f;  // the plane's width: no square of it sees the texel
    const int texels = params.resolution * params.resolution;
    std::vector<uint8_t> enclosed(size_t(vertex_count()), 0);
    for (int v = 0; v < vertex_count(); ++v) {
        // Most vertices see the sky around their normal, the centre texel: test it first.
        bool open = model.reconstruct(v, texels / 2 + params.resolution / 2) > kEnclosedDistance;
        for (int t = 0; t < texels && !open; ++t) open = model.reconstruct(v, t) > kEnclosedDistance;
        enclosed[size_t(v)] = open ? 0 : 1;
    }
    return enclosed;
}

void Svdf::visible_fraction_batch(int first_vertex, const int* vertex, const float* x, const float* y, const float* h,
                                  int count, float* out) const {
    for (int i = 0; i < count; ++i) out[i] = visible_fraction(first_vertex + vertex[i], Vec2(x[i], y[i]), h[i]);
}

}  // namespace rsl
