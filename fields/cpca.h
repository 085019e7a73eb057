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
