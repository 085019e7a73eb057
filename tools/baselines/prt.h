#pragma once
// Precomputed radiance transfer baselines for *static* scenes (their limit):
//
//   SH PRT (Sloan et al. 2002): per vertex, the transport projected onto real
//   SH up to order 10, T_i = Σ_k f_k A_ki (A: exact texel integrals of Y_i);
//   at run time the lighting's SH coefficients (rotated by SH rotation
//   matrices when the environment turns) are dotted with T. Orders 3 and 5
//   are prefixes of order 10, so one precomputation serves 9, 25 and 100
//   coefficients.
//
//   Haar PRT (Ng et al. 2003): per vertex, g_k = f_k Ω_k wavelet-transformed
//   per face and stored sparsely (float; coefficients below `haar_drop` × the
//   vertex's largest are dropped). Ng's layout: for each wavelet coefficient,
//   the list of vertices with a nonzero transport there, in blocks of
//   vertices; a frame walks only the rows of the N kept lighting terms.
//
// Both take f_k from the same rays as the ground truth (transport.h), at the
// camera position of the precompute time (glossy transport is view-fixed).
#include <cstdint>
#include <vector>

#include "tools/baselines/haar.h"
#include "tools/baselines/sh.h"
#include "tools/baselines/transport.h"

namespace rsl {

struct PrtOptions {
    bool sh = true;
    int sh_order = sh::kMaxOrder;
    bool haar = true;
    float haar_drop = 1e-3f;  // relative to the vertex's largest |coefficient|
    int block_vertices = 256;
    // Also keep Σ_k L_k f_k Ω_k per vertex with this lighting (a check that the
    // transport reproduces the ground truth); null to skip.
    const CubeMap* check_lighting = nullptr;
    bool visibility = true;  // false: V = 1, no rays (unshadowed transport)
};

struct ShTransfer {
    int order = 0;
    std::vector<float> rgb;  // [vertex][order²][3]
    size_t bytes() const { return rgb.size() * sizeof(float); }
};

struct HaarBlock {
    size_t first_vertex = 0;
    int vertex_count = 0;
    std::vector<uint32_t> row_start;  // per wavelet index, then the end
    std::vector<uint16_t> vertex;     // within the block
    std::vector<Color> value;
};

struct HaarTransport {
    int resolution = 0;
    std::vector<HaarBlock> blocks;
    size_t entries() const;
    size_t bytes() const;  // vertex ids, values and row offsets
};

struct PrtPrecompute {
    explicit PrtPrecompute(VertexLayout vertex_layout) : layout(std::move(vertex_layout)) {}
    VertexLayout layout;
    float time = 0;
    Mat3 environment_rotation{1.0f};  // the rotation the transport was sampled under
    ShTransfer sh;
    HaarTransport haar;
    std::vector<Color> texel_sum;  // Σ_k L_k f_k Ω_k (when PrtOptions::check_lighting)
    uint64_t rays = 0;
    // Thread-seconds spent per stage, summed over threads (the stages share
    // one pass over the vertices, so wall time cannot be split).
    double trace_cpu_seconds = 0, sh_cpu_seconds = 0, haar_cpu_seconds = 0;
    double wall_seconds = 0;
};

// Samples every vertex's transport on `environment`'s texel grid (its
// resolution must be a power of two for Haar) and projects it.
PrtPrecompute precompute_prt(const GroundTruth& truth, const CubeMap& environment, const PrtOptions& options);

// SH rendering: per vertex Σ_{i < order²} T_i · l_i with the lighting's SH
// coefficients in the frame the transport was sampled in.
class ShRenderer {
public:
    ShRenderer(const PrtPrecompute& prt, const CubeMap& environment);
    // Vertex colours with `order` ≤ the precomputed order, the environment
    // turned by `rotation` (world) relative to the precompute rotation.
    void render(int order, const Mat3& rotation, std::vector<Color>& out) const;
    const sh::ShColor& lighting() const { return lighting_; }

private:
    const PrtPrecompute& prt_;
    sh::ShColor lighting_;  // projected at the precompute rotation
};

class HaarRenderer {
public:
    HaarRenderer(const PrtPrecompute& prt);
    // Vertex colours with the `terms` largest area-weighted lighting
    // coefficients of `environment` (already in the precompute frame: an
    // environment that turned is resampled with rsl::rotate first, as Ng 2003).
    void render(const CubeMap& environment, int terms, std::vector<Color>& out);
    const haar::SparseLighting& lighting() const { return lighting_; }

private:
    const PrtPrecompute& prt_;
    haar::LightingApproximation approximation_;
    haar::SparseLighting lighting_;
};

}  // namespace rsl
