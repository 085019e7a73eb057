#include "src/fields/cpca.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include <Eigen/Dense>
#include <Imath/half.h>
#include <tbb/parallel_for.h>

#include "src/core/error.h"

namespace rsl {
namespace {

using RowMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using Matrix = Eigen::MatrixXf;

Matrix orthonormal_columns(const Matrix& y) {
    Eigen::HouseholderQR<Matrix> qr(y);
    return qr.householderQ() * Matrix::Identity(y.rows(), y.cols());
}

// Top-k principal directions (D × k, orthonormal columns) of the rows of the
// centered matrix x, by a randomized range finder with one power iteration
// (Halko, Martinsson & Tropp 2011). Exact when rank(x) ≤ k + oversampling.
// Columns beyond the data's rank are zero.
Matrix top_principal_directions(const RowMatrix& x, int k, uint64_t seed) {
    const int n = int(x.rows()), d = int(x.cols());
    Matrix basis = Matrix::Zero(d, k);
    const int l = std::min({k + 8, n, d});
    if (l == 0) return basis;
    std::mt19937_64 rng(seed);
    std::normal_distribution<float> gauss;
    Matrix omega(d, l);
    for (int c = 0; c < l; ++c)
        for (int r = 0; r < d; ++r) omega(r, c) = gauss(rng);
    Matrix q = orthonormal_columns(x * omega);                       // n × l
    q = orthonormal_columns(x * orthonormal_columns(x.transpose() * q));  // one power iteration
    const Matrix b = q.transpose() * x;                                 // l × d
    // SVD of the small b through its l × l Gram matrix, in double.
    const Eigen::MatrixXd gram = (b * b.transpose()).cast<double>();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram);
    const double largest = std::max(eigen.eigenvalues()(l - 1), 1e-30);
    for (int i = 0; i < std::min(k, l); ++i) {
        const double lambda = eigen.eigenvalues()(l - 1 - i);
        if (lambda <= largest * 1e-12) break;  // beyond the numerical rank
        const Eigen::VectorXf u = eigen.eigenvectors().col(l - 1 - i).cast<float>();
        Eigen::VectorXf v = b.transpose() * u;
        v /= v.norm();
        basis.col(i) = v;
    }
    // Re-orthonormalize the non-zero columns (float round-off).
    for (int i = 0; i < k; ++i) {
        Eigen::VectorXf v = basis.col(i);
        if (v.squaredNorm() == 0) continue;
        for (int j = 0; j < i; ++j) v -= basis.col(j).dot(v) * basis.col(j);
        basis.col(i) = v / v.norm();
    }
    return basis;
}

// Squared distances from every row of z to every row of centers.
Matrix pairwise_sq_distances(const RowMatrix& z, const RowMatrix& centers) {
    Matrix dist = -2.0f * (z * centers.transpose());
    const Eigen::VectorXf zn = z.rowwise().squaredNorm(), cn = centers.rowwise().squaredNorm();
    dist.colwise() += zn;
    dist.rowwise() += cn.transpose();
    return dist;
}

// Lloyd's k-means with k-means++ seeding on low-dimensional points z.
std::vector<int32_t> kmeans(const RowMatrix& z, int k, int iterations, uint64_t seed) {
    const int n = int(z.rows());
    std::mt19937_64 rng(seed);
    RowMatrix centers(k, z.cols());
    std::vector<float> nearest(n, std::numeric_limits<float>::infinity());
    int chosen = int(std::uniform_int_distribution<int>(0, n - 1)(rng));
    for (int c = 0; c < k; ++c) {
        centers.row(c) = z.row(chosen);
        double total = 0;
        for (int s = 0; s < n; ++s) {
            nearest[s] = std::min(nearest[s], (z.row(s) - centers.row(c)).squaredNorm());
            total += nearest[s];
        }
        if (c + 1 == k) break;
        // D² sampling; when every point coincides with a center, take any.
        double target = std::uniform_real_distribution<double>(0, total)(rng);
        chosen = int(std::uniform_int_distribution<int>(0, n - 1)(rng));
        for (int s = 0; s < n && total > 0; ++s) {
            target -= nearest[s];
            if (target <= 0) { chosen = s; break; }
        }
    }
    std::vector<int32_t> assignment(n, 0);
    for (int it = 0; it < iterations; ++it) {
        const Matrix dist = pairwise_sq_distances(z, centers);
        tbb::parallel_for(0, n, [&](int s) {
            Eigen::Index best;
            dist.row(s).minCoeff(&best);
            assignment[s] = int32_t(best);
        });
        RowMatrix sums = RowMatrix::Zero(k, z.cols());
        std::vector<int> counts(k, 0);
        for (int s = 0; s < n; ++s) {
            sums.row(assignment[s]) += z.row(s);
            ++counts[assignment[s]];
        }
        for (int c = 0; c < k; ++c)
            if (counts[c] > 0) centers.row(c) = sums.row(c) / float(counts[c]);
    }
    return assignment;
}

RowMatrix gather_rows(const float* data, int dims, const std::vector<int>& rows) {
    RowMatrix x(rows.size(), dims);
    for (size_t r = 0; r < rows.size(); ++r)
        x.row(r) = Eigen::Map<const Eigen::RowVectorXf>(data + size_t(rows[r]) * dims, dims);
    return x;
}

// Squared reconstruction error of sample x against cluster c, and its coefficients.
float residual_and_coefficients(const CpcaModel& model, int cluster, const float* x, float* w) {
    const int k = model.vectors;
    std::fill(w, w + k, 0.0f);
    float norm2 = 0;
    for (int t = 0; t < model.dims; ++t) {
        const float* r = model.row(cluster, t);
        const float d = x[t] - r[0];
        norm2 += d * d;
        for (int i = 0; i < k; ++i) w[i] += d * r[i + 1];
    }
    float captured = 0;
    for (int i = 0; i < k; ++i) captured += w[i] * w[i];
    return std::max(norm2 - captured, 0.0f);
}

void refit_clusters(const float* data, int samples, int dims, const CpcaOptions& options, CpcaModel& model) {
    std::vector<std::vector<int>> members(model.clusters);
    for (int s = 0; s < samples; ++s) members[model.assignment[s]].push_back(s);
    // Drop empty clusters and renumber.
    std::vector<int32_t> renumber(model.clusters, -1);
    int kept = 0;
    for (int c = 0; c < model.clusters; ++c)
        if (!members[c].empty()) renumber[c] = kept++;
    for (int s = 0; s < samples; ++s) model.assignment[s] = renumber[model.assignment[s]];
    members.erase(std::remove_if(members.begin(), members.end(), [](auto& m) { return m.empty(); }), members.end());
    CpcaModel fitted;
    fitted.dims = dims;
    fitted.vectors = options.vectors;
    fitted.tables.resize(size_t(kept) * dims * (options.vectors + 1));
    fitted.clusters = kept;
    tbb::parallel_for(0, kept, [&](int c) {
        CpcaModel one;
        one.dims = dims;
        one.vectors = options.vectors;
        fit_pca_cluster(data, dims, members[c], options.vectors, options.seed + 7919u * uint64_t(c),
                        options.half_precision_tables, one);
        std::copy(one.tables.begin(), one.tables.end(),
                  fitted.tables.begin() + size_t(c) * dims * (options.vectors + 1));
    });
    model.tables = std::move(fitted.tables);
    model.clusters = kept;
}

}  // namespace

float round_to_half(float value) { return float(Imath::half(value)); }

void CpcaModel::reconstruct(int sample, float* out) const {
    for (int t = 0; t < dims; ++t) out[t] = reconstruct(sample, t);
}

size_t CpcaModel::stored_bytes(bool half_tables) const {
    const size_t index_bytes = clusters <= 65536 ? 2 : 4;
    return tables.size() * (half_tables ? 2 : 4) + assignment.size() * index_bytes + coefficients.size() * 4;
}

void fit_pca_cluster(const float* data, int dims, const std::vector<int>& members, int vectors, uint64_t seed,
                     bool half_precision, CpcaModel& model) {
    RSL_CHECK(!members.empty());
    RowMatrix x = gather_rows(data, dims, members);
    const Eigen::RowVectorXf mean = x.colwise().mean();
    x.rowwise() -= mean;
    const Matrix basis = top_principal_directions(x, vectors, seed);
    const size_t base = model.tables.size();
    model.tables.resize(base + size_t(dims) * (vectors + 1));
    float* out = model.tables.data() + base;
    for (int t = 0; t < dims; ++t) {
        out[t * (vectors + 1)] = mean(t);
        for (int i = 0; i < vectors; ++i) out[t * (vectors + 1) + 1 + i] = basis(t, i);
    }
    if (half_precision)
        for (size_t i = base; i < model.tables.size(); ++i) model.tables[i] = round_to_half(model.tables[i]);
    ++model.clusters;
}

void project_coefficients(const float* data, CpcaModel& model) {
    const int n = model.samples();
    model.coefficients.assign(size_t(n) * model.vectors, 0.0f);
    tbb::parallel_for(0, n, [&](int s) {
        residual_and_coefficients(model, model.assignment[s], data + size_t(s) * model.dims,
                                  model.coefficients.data() + size_t(s) * model.vectors);
    });
}

CpcaModel fit_cpca(const float* data, int samples, int dims, const CpcaOptions& options,
                   const std::function<void(double)>& progress) {
    RSL_CHECK_GT(samples, 0);
    RSL_CHECK_GT(options.clusters, 0);
    RSL_CHECK_GE(options.vectors, 0);
    auto report = [&](double f) { if (progress) progress(f); };
    const int k = std::min(options.clusters, samples);
    const Eigen::Map<const RowMatrix> all(data, samples, dims);

    // 1. Reduced coordinates for k-means: the top global principal components,
    //    found on a fixed random subset (cheap) and applied to every sample.
    const int m = std::min({options.kmeans_dimensions, dims, samples});
    std::vector<int> subset(samples);
    std::iota(subset.begin(), subset.end(), 0);
    std::mt19937_64 rng(options.seed);
    if (samples > 4096) {
        std::shuffle(subset.begin(), subset.end(), rng);
        subset.resize(4096);
    }
    RowMatrix sub = gather_rows(data, dims, subset);
    const Eigen::RowVectorXf global_mean = sub.colwise().mean();
    sub.rowwise() -= global_mean;
    const Matrix global_basis = top_principal_directions(sub, m, options.seed ^ 0x5eedull);
    RowMatrix reduced(samples, m);
    tbb::parallel_for(0, samples, 256, [&](int s) {
        const int end = std::min(s + 256, samples);
        reduced.middleRows(s, end - s) = (all.middleRows(s, end - s).rowwise() - global_mean) * global_basis;
    });
    report(0.15);

    // 2. k-means in the reduced space, then per-cluster PCA in full.
    CpcaModel model;
    model.dims = dims;
    model.vectors = options.vectors;
    model.clusters = k;
    model.assignment = kmeans(reduced, k, options.kmeans_iterations, options.seed);
    refit_clusters(data, samples, dims, options, model);
    report(0.45);

    // 3. CPCA refinement: move each sample to the candidate cluster that
    //    reconstructs it best, then refit.
    for (int pass = 0; pass < options.refine_iterations && model.clusters > 1; ++pass) {
        RowMatrix centers = RowMatrix::Zero(model.clusters, m);
        std::vector<int> counts(model.clusters, 0);
        for (int s = 0; s < samples; ++s) {
            centers.row(model.assignment[s]) += reduced.row(s);
            ++counts[model.assignment[s]];
        }
        for (int c = 0; c < model.clusters; ++c) centers.row(c) /= float(std::max(counts[c], 1));
        const int candidates = std::min(options.reassign_candidates, model.clusters);
        std::vector<int32_t> next(samples);
        tbb::parallel_for(0, samples, 512, [&](int start) {
            const int end = std::min(start + 512, samples);
            const Matrix dist = pairwise_sq_distances(reduced.middleRows(start, end - start), centers);
            std::vector<float> w(model.vectors);
            std::vector<int> order(model.clusters);
            for (int s = start; s < end; ++s) {
                std::iota(order.begin(), order.end(), 0);
                std::partial_sort(order.begin(), order.begin() + candidates, order.end(),
                                  [&](int a, int b) { return dist(s - start, a) < dist(s - start, b); });
                int best = model.assignment[s];
                float best_error =
                    residual_and_coefficients(model, best, data + size_t(s) * dims, w.data());
                for (int c = 0; c < candidates; ++c) {
                    if (order[c] == model.assignment[s]) continue;
                    const float e = residual_and_coefficients(model, order[c], data + size_t(s) * dims, w.data());
                    if (e < best_error) { best_error = e; best = order[c]; }
                }
                next[s] = best;
            }
        });
        model.assignment = std::move(next);
        refit_clusters(data, samples, dims, options, model);
        report(0.45 + 0.45 * double(pass + 1) / options.refine_iterations);
    }
    project_coefficients(data, model);
    report(1.0);
    return model;
}

CpcaReport measure_cpca(const float* data, const CpcaModel& model, bool half_tables) {
    CpcaReport report;
    const int n = model.samples();
    std::vector<double> sum2(n), max_error(n);
    tbb::parallel_for(0, n, [&](int s) {
        for (int t = 0; t < model.dims; ++t) {
            const double e = double(model.reconstruct(s, t)) - data[size_t(s) * model.dims + t];
            sum2[s] += e * e;
            max_error[s] = std::max(max_error[s], std::abs(e));
        }
    });
    double total = 0;
    for (int s = 0; s < n; ++s) {
        total += sum2[s];
        report.max_error = std::max(report.max_error, max_error[s]);
    }
    report.rms_error = std::sqrt(total / (double(n) * model.dims));
    report.raw_bytes = size_t(n) * model.dims * sizeof(float);
    report.stored_bytes = model.stored_bytes(half_tables);
    return report;
}

}  // namespace rsl
