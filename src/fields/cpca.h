#pragma once
// Clustered principal component analysis (Sloan et al. 2003), the compression
// of the SVDF (RSL paper §5.1); with one fixed cluster per segment it is also
// the OVDF's per-segment PCA.
//
// Each sample x (a D-vector: one VDT) is stored as a cluster index c and k
// coefficients w, and reconstructed as x ≈ μ_c + Σ_i w_i b_{c,i}. The cluster
// tables are texel-major — for texel t the k + 1 floats [μ_c[t], b_{c,0}[t], …]
// are contiguous — so that a lookup reconstructing four bilinear taps touches
// four short rows and never the whole table.
#include <cstdint>
#include <functional>
#include <vector>

namespace rsl {

struct CpcaOptions {
    int clusters = 256;
    int vectors = 8;
    int kmeans_iterations = 8;
    int refine_iterations = 2;  // CPCA passes: reassign by reconstruction error, refit
    int kmeans_dimensions = 32;  // k-means runs on the data's top global principal components
    int reassign_candidates = 4;  // clusters tried per sample in a refine pass (nearest means)
    uint64_t seed = 1;
    // Round the means and basis vectors to IEEE half precision (what the field
    // file stores and the GPU samples); coefficients stay float.
    bool half_precision_tables = true;
};

// Σ_t w_t·(mean_weight·row_t[0] + Σ_m c_m·row_t[m+1]) over four rows of
// `vectors` + 1 floats: the bilinear blend of the rows first, then one dot
// product (fewer operations than four reconstructions, and the loops unroll
// for a compile-time V; V = 0 takes `vectors`).
template <int V>
inline float blend_rows_dot(const float* const rows[4], const float w[4], float mean_weight, const float* c,
                            int vectors) {
    constexpr int kMaxStride = 33;
    const int n = V > 0 ? V : vectors;
    float blended[kMaxStride];
    blended[0] = w[0] * rows[0][0] + w[1] * rows[1][0] + w[2] * rows[2][0] + w[3] * rows[3][0];
    for (int m = 1; m <= n; ++m) blended[m] = w[0] * rows[0][m] + w[1] * rows[1][m] + w[2] * rows[2][m] + w[3] * rows[3][m];
    float value = mean_weight * blended[0];
    for (int m = 0; m < n; ++m) value += c[m] * blended[m + 1];
    return value;
}

// blend_rows_dot with the usual vector counts unrolled.
inline float blend_rows_dot_any(const float* const rows[4], const float w[4], float mean_weight, const float* c,
                                int vectors) {
    switch (vectors) {
        case 4: return blend_rows_dot<4>(rows, w, mean_weight, c, vectors);
        case 6: return blend_rows_dot<6>(rows, w, mean_weight, c, vectors);
        case 8: return blend_rows_dot<8>(rows, w, mean_weight, c, vectors);
        default: return blend_rows_dot<0>(rows, w, mean_weight, c, vectors);
    }
}

struct CpcaModel {
    int dims = 0, vectors = 0, clusters = 0;
    std::vector<float> tables;        // clusters × dims × (vectors + 1), texel-major
    std::vector<int32_t> assignment;  // per sample
    std::vector<float> coefficients;  // samples × vectors

    int samples() const { return int(assignment.size()); }
    const float* row(int cluster, int dim) const {
        return tables.data() + (size_t(cluster) * dims + dim) * (vectors + 1);
    }
    const float* coefficients_of(int sample) const { return coefficients.data() + size_t(sample) * vectors; }

    float reconstruct(int sample, int dim) const {
        const float* r = row(assignment[sample], dim);
        const float* w = coefficients_of(sample);
        float value = r[0];
        for (int i = 0; i < vectors; ++i) value += w[i] * r[i + 1];
        return value;
    }
    void reconstruct(int sample, float* out) const;
    // Σ_t weight_t · reconstruct(sample, index_t), as lookups need it.
    float reconstruct_bilinear(int sample, const int index[4], const float weight[4]) const {
        if (vectors > 32) {
            float value = 0;
            for (int t = 0; t < 4; ++t) value += weight[t] * reconstruct(sample, index[t]);
            return value;
        }
        const int cluster = assignment[sample];
        const float* const rows[4] = {row(cluster, index[0]), row(cluster, index[1]), row(cluster, index[2]),
                                      row(cluster, index[3])};
        return blend_rows_dot_any(rows, weight, 1.0f, coefficients_of(sample), vectors);
    }

    // Bytes as stored in a field file (tables as half or float, one uint16 or
    // int32 cluster index and float coefficients per sample).
    size_t stored_bytes(bool half_tables) const;
};

struct CpcaReport {
    double rms_error = 0;  // over all samples and dims
    double max_error = 0;
    size_t raw_bytes = 0, stored_bytes = 0;
    double compression_ratio() const { return stored_bytes ? double(raw_bytes) / double(stored_bytes) : 0; }
};

// data: samples × dims, row-major. progress(fraction) is called from the
// calling thread between phases.
CpcaModel fit_cpca(const float* data, int samples, int dims, const CpcaOptions& options,
                   const std::function<void(double)>& progress = {});

// Plain PCA of a set of samples (one cluster): mean + top-k basis vectors,
// appended to `model` as a new cluster whose members are `members` (indices
// into data). Used per OVDF segment.
void fit_pca_cluster(const float* data, int dims, const std::vector<int>& members, int vectors, uint64_t seed,
                     bool half_precision, CpcaModel& model);

// Coefficients of every sample against its assigned cluster (model.assignment
// must be set; resizes model.coefficients).
void project_coefficients(const float* data, CpcaModel& model);

CpcaReport measure_cpca(const float* data, const CpcaModel& model, bool half_tables);

float round_to_half(float value);

}  // namespace rsl
