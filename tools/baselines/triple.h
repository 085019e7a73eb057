#pragma once
// The wavelet triple-product baseline (Ng, Ramamoorthi, Hanrahan 2004; the
// BRDF tabulated per normal and local view as Ma et al. 2006): unlike Haar
// PRT's fixed-view transport, the BRDF is a third factor, so the view can
// change and a BRDF can be swapped without tracing again.
//
//   B(x, ω_o) = Σ_k L_k · (V_k(x) Ω_k) · ρ̃_k(n, ω_o),  ρ̃_k = ρ(ω_k, ω_o) max(0, n·ω_k)
//
// - L: the environment's N largest area-weighted Haar terms (haar.h), per frame.
// - VΩ: per vertex, the visibility (TransportSampler::sample_visibility, the
//   truth's rays and horizon rules) times the texel solid angles,
//   Haar-transformed and stored sparsely (coefficients below `visibility_drop`
//   × the vertex's largest dropped). Sampled once; view independent.
// - ρ̃: per material, not per vertex. For each normal of a coarse global cube
//   (the texel centres of 6×R_n²) and each view of an R_v×R_v grid on the
//   hemisphere in a frame built from that normal, the slice over the 6×N²
//   environment texels, Haar-transformed and cut to its M largest
//   area-weighted terms. A vertex blends the slices of its 2×2 nearest
//   normals on the cube's face grid and, in each of those normals' frames,
//   its 2×2 nearest views, bilinearly (Ma 2006 interpolates the coefficients
//   of nearby tabulated functions); the triple sum is linear in ρ̃, so the
//   blend is the weighted sum of up to 16 sparse slices. `lookup = nearest`
//   takes the single nearest slice instead (Ng 2004). A view-independent
//   (Lambertian) BRDF gets one view per normal. The exact mode instead evaluates ρ̃ per vertex
//   per frame for its own shading frame and view with every term: the
//   accuracy reference (with every lighting term it is the truth's sum).
//
// The tabulated frame is built from the normal alone (Frame::from_normal), so
// an anisotropic BRDF's tangent is not followed; the exact mode follows it.
#include <cstdint>
#include <memory>
#include <vector>

#include "tools/baselines/haar.h"
#include "tools/baselines/transport.h"

namespace rsl {

class Brdf;

// How a vertex finds its BRDF slice in the tables.
enum class TripleLookup { nearest, bilinear };

struct TripleOptions {
    float visibility_drop = 1e-3f;  // relative to the vertex's largest |VΩ coefficient|
    int normal_resolution = 8;      // R_n: 6·R_n² tabulated normals
    int view_resolution = 8;        // R_v: R_v² views per normal (1 for a Lambertian BRDF)
    int brdf_terms = 256;           // M: kept terms per slice
    TripleLookup lookup = TripleLookup::bilinear;
    int block_vertices = 256;
    bool visibility = true;  // false: V = 1 above the horizons, no rays
};

// Per vertex (flat index), its VΩ Haar coefficients: rows start[v] .. start[v + 1].
struct SparseVisibility {
    int resolution = 0;
    std::vector<uint64_t> start;
    std::vector<uint32_t> index;
    std::vector<float> value;
    size_t entries() const { return index.size(); }
    size_t bytes() const;
};

struct TriplePrecompute {
    explicit TriplePrecompute(VertexLayout vertex_layout) : layout(std::move(vertex_layout)) {}
    VertexLayout layout;
    Mat3 environment_rotation{1.0f};
    std::vector<Vec3> directions;  // the texels' directions, turned as the truth's
    SparseVisibility visibility;
    uint64_t rays = 0;
    // Thread-seconds, summed over threads (as PrtPrecompute).
    double trace_cpu_seconds = 0, transform_cpu_seconds = 0, wall_seconds = 0;
};

// Samples every vertex's visibility on `environment`'s texels (a power-of-two resolution).
TriplePrecompute precompute_triple_visibility(const GroundTruth& truth, const CubeMap& environment,
                                              const TripleOptions& options);

// A vertex's slices and their weights (summing to 1): 2×2 normals × 2×2
// views at most; zero weights are left out.
struct SliceWeights {
    static constexpr int kMax = 16;
    int count = 0;
    int slice[kMax];
    float weight[kMax];
};

// One BRDF's slices: normal × view, each at most M (index, RGB) terms.
class BrdfSlices {
public:
    BrdfSlices(const Brdf& brdf, const std::vector<Vec3>& directions, int resolution, const TripleOptions& options);

    int views_per_side() const { return views_; }
    int slice_count() const { return int(count_.size()); }
    // The slice of the tabulated normal nearest `normal` and, in its frame,
    // the tabulated view nearest `view` (both world, unit).
    int slice_of(const Vec3& normal, const Vec3& view) const;
    // The slices blended for a vertex of `normal` seen along `view` (world,
    // unit), by the table's lookup mode. No allocation.
    void weights(const Vec3& normal, const Vec3& view, SliceWeights& out) const;
    TripleLookup lookup() const { return lookup_; }
    // Adds Σ weight · slice to `dense` (6N² Haar coefficients) and appends each
    // index it touches for the first time (`touched[i]` 0 → 1) to `list`;
    // returns the list's new length. The caller clears all three. No allocation.
    size_t accumulate(const SliceWeights& weights, Color* dense, uint8_t* touched, int32_t* list, size_t listed) const;
    // The tabulated normal and view (world) of a slice.
    Vec3 normal(int slice) const;
    Vec3 view(int slice) const;
    const int32_t* index(int slice) const { return &index_[size_t(slice) * terms_]; }
    const Color* value(int slice) const { return &value_[size_t(slice) * terms_]; }
    int count(int slice) const { return count_[size_t(slice)]; }
    size_t bytes() const;
    double cpu_seconds() const { return cpu_seconds_; }

private:
    CubeMap normals_;  // its texel centres are the tabulated normals
    int views_, terms_;
    TripleLookup lookup_;
    std::vector<int32_t> index_;  // slice · M + t
    std::vector<Color> value_;
    std::vector<int32_t> count_;
    double cpu_seconds_ = 0;
};

// ρ̃ of one normal's frame and local view over every texel (dense, texel
// domain): ρ(frame.to_local(ω_k), view_local) · max(0, ω_k·n).
void brdf_slice(const Brdf& brdf, const Frame& frame, const Vec3& view_local, const std::vector<Vec3>& directions,
                Color* out);

// The slice tables of every part (one per distinct BRDF).
struct TripleBrdfTables {
    std::vector<std::shared_ptr<const BrdfSlices>> part;
    size_t bytes() const;
    double cpu_seconds() const;
};
TripleBrdfTables tabulate_part_brdfs(const GroundTruth& truth, const TriplePrecompute& precompute,
                                     const TripleOptions& options);

class TripleRenderer {
public:
    // `tables` null: the exact mode (ρ̃ per vertex per frame, all terms).
    TripleRenderer(const TriplePrecompute& precompute, const GroundTruth& truth, const TripleBrdfTables* tables);
    ~TripleRenderer();
    // Vertex colours with the `terms` largest lighting coefficients of
    // `environment` (in the precompute frame, as HaarRenderer) seen from `camera`.
    void render(const CubeMap& environment, int terms, const Vec3& camera, std::vector<Color>& out);

private:
    struct State;
    const TriplePrecompute& precompute_;
    const GroundTruth& truth_;
    const TripleBrdfTables* tables_;
    std::unique_ptr<State> state_;
};

}  // namespace rsl
