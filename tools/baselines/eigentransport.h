#pragma once
// Eigentransport (Nowrouzezahrai et al., "Eigentransport for Efficient and
// Accurate All-Frequency Relighting"): a PCA basis of the scene's own
// per-vertex transport, for *static* scenes like the other PRT baselines.
//
// The transport matrix G has one row per (vertex, RGB channel), row 3v + c,
// and one column per cube texel k: g_k = f_k Ω_k with f from the ground
// truth's rays (transport.h), so that a vertex channel's colour under
// lighting L is the dot product g · L. With μ the mean row and B the top d
// eigenvectors of the covariance Σ_rows (g − μ)(g − μ)ᵀ (decreasing
// eigenvalue; a smaller d is a prefix):
//
//   colour(v, c) = μ · L_c + Σ_{i<d} c_{3v+c, i} l_{c, i},
//   c_{row, i} = (g_row − μ) · B_i,   l_{c, i} = L_c · B_i.
//
// This is the paper's reconstruction T ≈ T_L B + T̃ (its eq. 2) dotted with
// the lighting, the mean kept whole; the paper's eq. 10 folds the mean into
// the coefficients through its projection, which drops the mean's part
// outside the basis. Both are exact at d = the texel count.
//
// A turned environment is resampled into the precompute frame (rsl::rotate)
// and projected again, the paper's brute-force rotation.
#include <cstdint>

#include <Eigen/Core>

#include "tools/baselines/transport.h"

namespace rsl {

using RowMatrixXf = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The dense transport matrix (3V × texels, float) and what sampling it cost.
struct TransportMatrix {
    RowMatrixXf rows;  // row 3v + c: vertex v (flat, VertexLayout), channel c
    uint64_t rays = 0;
    // Summed over threads: the rays (TransportSampler::sample, as
    // PrtPrecompute times them) and writing g = f Ω into the rows.
    double trace_cpu_seconds = 0, fill_cpu_seconds = 0;
};

// Samples every vertex's g = f Ω on `environment`'s texels, directions
// turned by `environment_rotation` (as precompute_prt samples them).
TransportMatrix sample_transport_matrix(const GroundTruth& truth, const CubeMap& environment,
                                        const Mat3& environment_rotation, bool visibility = true);

enum class EigenSolver {
    Automatic,   // Dense up to kDenseSolverTexels texels, Randomized above
    Dense,       // every eigenpair of the texels × texels covariance
    Randomized,  // a randomized range finder with power iterations (top d only)
};
inline constexpr int kDenseSolverTexels = 2048;

struct EigenOptions {
    int max_terms = 128;  // d_max (capped at the texel count); smaller d are its prefixes
    EigenSolver solver = EigenSolver::Automatic;
    int power_iterations = 4, oversampling = 16;  // Randomized only
    uint64_t seed = 44;                           // Randomized only: the Gaussian test matrix
    bool visibility = true;                       // false: V = 1, no rays
    // The parts whose rows the mean and the basis are fitted to (per part;
    // empty: all). The other parts' rows are projected onto that basis, which
    // separates a ground's bias on the basis from its effect on the truth.
    std::vector<bool> basis_parts;
};

struct EigenTransport {
    explicit EigenTransport(VertexLayout vertex_layout) : layout(std::move(vertex_layout)) {}
    VertexLayout layout;
    float time = 0;
    Mat3 environment_rotation{1.0f};  // the rotation the transport was sampled under
    Eigen::VectorXf mean;             // μ: the mean row (texels)
    Eigen::MatrixXf basis;            // texels × d_max, orthonormal columns B_i
    RowMatrixXf coefficients;         // 3V × d_max: (g_row − μ) · B_i
    Eigen::VectorXd eigenvalues;      // d_max, decreasing: Σ over the basis rows of ((g − μ) · B_i)²
    double total_variance = 0;        // Σ_rows ‖g − μ‖² over the basis rows, the squared error at d = 0
    bool randomized = false;          // which solver ran
    uint64_t rays = 0;
    // Thread-seconds (summed over threads) of the rays and of the PCA
    // (filling the matrix, mean, covariance, eigenvectors, coefficients);
    // wall time of both.
    double trace_cpu_seconds = 0, pca_cpu_seconds = 0, wall_seconds = 0;

    int texels() const { return int(mean.size()); }
    int max_terms() const { return int(basis.cols()); }
    // Fraction of Σ_rows ‖g − μ‖² that the first `terms` eigentransports keep.
    double captured_variance(int terms) const;
    // What rendering with `terms` needs: coefficients, basis columns and mean (float).
    size_t bytes(int terms) const;
};

// The transport matrix of `truth`'s scene at its time, its PCA and its
// coefficients; the matrix is released before returning.
EigenTransport precompute_eigentransport(const GroundTruth& truth, const CubeMap& environment,
                                         const EigenOptions& options);
// The same from a matrix already sampled (its rows are centred in place).
EigenTransport eigentransport_from_matrix(TransportMatrix& matrix, VertexLayout layout, const EigenOptions& options);

class EigenRenderer {
public:
    explicit EigenRenderer(const EigenTransport& eigen) : eigen_(eigen) {}
    // Vertex colours with the first `terms` eigentransports; `environment` is
    // in the precompute frame (an environment that turned is resampled first).
    void render(const CubeMap& environment, int terms, std::vector<Color>& out);
    // The same with the environment turned by `rotation` (world): resampled
    // with rsl::rotate unless it is the precompute rotation, then projected.
    void render(const CubeMap& environment, const Mat3& rotation, int terms, std::vector<Color>& out);

private:
    void project(const CubeMap& environment, int terms);
    const EigenTransport& eigen_;
    Eigen::Matrix<float, Eigen::Dynamic, 3> lighting_;  // l_{c, i}: terms × RGB
    Eigen::RowVector3f mean_lighting_;                  // μ · L_c
};

}  // namespace rsl
