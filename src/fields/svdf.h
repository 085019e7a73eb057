#pragma once
// Self-visibility distance field (RSL paper §4.3.1, §5.1): one VDT per vertex
// in the vertex's local frame, compressed with clustered PCA. A lookup
// reconstructs only the four bilinear taps it needs.
#include <cstdint>
#include <functional>

#include "src/fields/cpca.h"
#include "src/fields/visibility_map.h"
#include "src/core/mesh.h"

namespace rsl {

struct SvdfParams {
    int resolution = 32;
    int supersampling = 2;  // adaptive: k×k rays in boundary texels
    bool coarse_to_fine = true;  // see src/fields/visibility_map.h
    int clusters = 256;     // scaled down to vertices / 16 for small meshes
    int vectors = 8;
    int refine_iterations = 2;
    VdtMode mode = VdtMode::CoverageAware;
    BelowHorizon below_horizon = BelowHorizon::Extend;
    bool half_precision_tables = true;
    uint64_t seed = 1;

    int effective_clusters(size_t vertices) const {
        return int(std::max<size_t>(1, std::min<size_t>(size_t(clusters), vertices / 16)));
    }
};

struct SvdfBakeStats {
    double trace_seconds = 0, compress_seconds = 0;
    CpcaReport compression;  // rms error in plane units, sizes in bytes
};

class Svdf {
public:
    SvdfParams params;
    CpcaModel model;  // samples = vertices, dims = resolution²

    int vertex_count() const { return model.samples(); }
    int resolution() const { return params.resolution; }

    // Reconstructed signed distance at plane point p.
    float distance(int vertex, const Vec2& p) const {
        const BilinearTaps taps = bilinear_taps(params.resolution, p);
        return model.reconstruct_bilinear(vertex, &taps.index[0], &taps.weight[0]);
    }
    // Visible fraction of the axis-aligned square (center, half-edge) of the
    // vertex's local plane.
    float visible_fraction(int vertex, const Vec2& center, float half_edge) const {
        return visible_fraction_from_distance(distance(vertex, center), half_edge);
    }
    // visible_fraction for `count` squares: vertex first_vertex + vertex[i],
    // center (x[i], y[i]), half-edge h[i] → out[i] (the renderer's batch; a
    // loop of its own so that the lookup inlines into it).
    void visible_fraction_batch(int first_vertex, const int* vertex, const float* x, const float* y, const float* h,
                                int count, float* out) const;
    // Same for a local direction (unit, vertex frame) and half-edge.
    float visible_fraction(int vertex, const Vec3& local_direction, float half_edge) const {
        return visible_fraction(vertex, lookup_plane_point(local_direction), half_edge);
    }
    // Per vertex, 1 where the vertex is enclosed by its own part: every
    // texel's distance is at most −2, so no square that fits the plane
    // (half-edge ≤ 2) sees any of it. Such a vertex lies inside the part's
    // other pieces (a lens set into a body); a pixel that sees its triangle
    // lies outside them, and the vertex says nothing of its light.
    std::vector<uint8_t> enclosed_vertices() const;
};

// Traces and compresses the SVDF of one part (self-shadowing only).
// progress(fraction) is called with the fraction of the whole bake.
Svdf bake_svdf(const TriangleMesh& mesh, const SvdfParams& params, SvdfBakeStats* stats = nullptr,
               const std::function<void(double)>& progress = {});

// The uncompressed VDTs (vertices × resolution²), for tests and benchmarks.
std::vector<float> trace_svdf_tables(const TriangleMesh& mesh, const SvdfParams& params,
                                     const std::function<void(double)>& progress = {});

// Compression alone (from uncompressed tables).
Svdf compress_svdf(const std::vector<float>& tables, const SvdfParams& params, SvdfBakeStats* stats = nullptr);

}  // namespace rsl
