#include <cstdio>
#include <random>
#include <set>
#include <vector>

#include <catch2/catch.hpp>

#include "src/fields/cpca.h"

using namespace rsl;

namespace {

// Samples drawn as cluster mean + a combination of `rank` random directions.
struct Synthetic {
    std::vector<float> data;
    std::vector<int> truth;  // generating cluster per sample
};
Synthetic low_rank_clusters(int clusters, int per_cluster, int dims, int rank, float mean_scale, uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> g;
    Synthetic s;
    for (int c = 0; c < clusters; ++c) {
        std::vector<float> mean(dims), basis(size_t(rank) * dims);
        for (float& v : mean) v = mean_scale * g(rng);
        for (float& v : basis) v = g(rng) / std::sqrt(float(dims));
        for (int k = 0; k < per_cluster; ++k) {
            std::vector<float> w(rank);
            for (float& v : w) v = g(rng);
            for (int t = 0; t < dims; ++t) {
                float x = mean[t];
                for (int r = 0; r < rank; ++r) x += w[r] * basis[size_t(r) * dims + t];
                s.data.push_back(x);
            }
            s.truth.push_back(c);
        }
    }
    return s;
}

}  // namespace

TEST_CASE("CPCA reproduces cluster means + rank-8 data exactly", "[cpca]") {
    const int clusters = 6, per = 120, dims = 256;
    const Synthetic s = low_rank_clusters(clusters, per, dims, 8, 3.0f, 17);
    CpcaOptions options;
    options.clusters = clusters;
    options.vectors = 8;
    options.half_precision_tables = false;
    const CpcaModel model = fit_cpca(s.data.data(), clusters * per, dims, options);
    REQUIRE(model.clusters == clusters);
    // Each fitted cluster holds the samples of exactly one generating cluster.
    std::vector<std::set<int>> sources(model.clusters);
    for (int i = 0; i < clusters * per; ++i) sources[model.assignment[i]].insert(s.truth[i]);
    for (auto& src : sources) CHECK(src.size() == 1);
    const CpcaReport r = measure_cpca(s.data.data(), model, false);
    std::printf("CPCA synthetic rank 8: rms %.2e, max %.2e\n", r.rms_error, r.max_error);
    CHECK(r.rms_error < 2e-5);
    CHECK(r.max_error < 2e-4);
}

TEST_CASE("PCA of one cluster: exact for rank ≤ k, and the error of truncation", "[cpca]") {
    const int dims = 64, n = 200;
    const Synthetic s = low_rank_clusters(1, n, dims, 5, 1.0f, 3);
    std::vector<int> members(n);
    for (int i = 0; i < n; ++i) members[i] = i;
    for (int vectors : {5, 8}) {
        CpcaModel model;
        model.dims = dims;
        model.vectors = vectors;
        fit_pca_cluster(s.data.data(), dims, members, vectors, 1, false, model);
        model.assignment.assign(n, 0);
        project_coefficients(s.data.data(), model);
        CHECK(measure_cpca(s.data.data(), model, false).max_error < 1e-4);
    }
    // Rank 5 data with 2 vectors: the residual equals the energy in the three
    // smallest principal directions, which is far from zero.
    CpcaModel model;
    model.dims = dims;
    model.vectors = 2;
    fit_pca_cluster(s.data.data(), dims, members, 2, 1, false, model);
    model.assignment.assign(n, 0);
    project_coefficients(s.data.data(), model);
    CHECK(measure_cpca(s.data.data(), model, false).rms_error > 0.05);
}

TEST_CASE("half-precision tables cost about 1e-3 relative", "[cpca]") {
    const Synthetic s = low_rank_clusters(4, 80, 128, 8, 2.0f, 5);
    CpcaOptions options;
    options.clusters = 4;
    options.vectors = 8;
    options.half_precision_tables = true;
    const CpcaModel model = fit_cpca(s.data.data(), 320, 128, options);
    const CpcaReport r = measure_cpca(s.data.data(), model, true);
    // |x| ≲ 8 here; half has an 11-bit significand: 8 · 2⁻¹¹ ≈ 4e-3 worst case.
    CHECK(r.rms_error < 3e-3);
    CHECK(r.rms_error > 1e-6);  // the rounding really happened
    CHECK(r.stored_bytes < model.stored_bytes(false));
}

TEST_CASE("CPCA refinement fixes clusters that k-means splits wrongly", "[cpca]") {
    // Two clusters with the same mean but different 2D subspaces, wide spread:
    // k-means on distances cannot separate them, reassigning by reconstruction
    // error can.
    const int dims = 48, per = 300;
    std::mt19937 rng(8);
    std::normal_distribution<float> g;
    std::vector<float> data;
    std::vector<std::vector<float>> bases(2, std::vector<float>(2 * dims));
    for (auto& b : bases)
        for (float& v : b) v = g(rng) / std::sqrt(float(dims));
    for (int c = 0; c < 2; ++c)
        for (int k = 0; k < per; ++k) {
            const float w0 = 4 * g(rng), w1 = 4 * g(rng);
            for (int t = 0; t < dims; ++t) data.push_back(w0 * bases[c][t] + w1 * bases[c][dims + t]);
        }
    CpcaOptions options;
    options.clusters = 2;
    options.vectors = 2;
    options.half_precision_tables = false;
    options.refine_iterations = 0;
    const double plain = measure_cpca(data.data(), fit_cpca(data.data(), 2 * per, dims, options), false).rms_error;
    options.refine_iterations = 6;
    const double refined = measure_cpca(data.data(), fit_cpca(data.data(), 2 * per, dims, options), false).rms_error;
    std::printf("CPCA refinement: rms %.4f → %.4f\n", plain, refined);
    CHECK(refined < 0.5 * plain);
    CHECK(refined < 1e-3);
}
