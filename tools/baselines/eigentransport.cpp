// Eigentransport: the dense transport matrix from the ground truth's rays,
// its PCA (the texels × texels covariance from float tiles summed in double,
// then its top eigenvectors), per-row coefficients, and rendering as one
// projection of the lighting plus a dot product per vertex channel.
#include "tools/baselines/eigentransport.h"

#include <algorithm>
#include <chrono>
#include <mutex>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "src/core/error.h"
#include "tools/baselines/thread_seconds.h"

namespace rsl {

namespace {

using baselines_timing::Clock;
using baselines_timing::seconds_since;
using baselines_timing::ThreadSeconds;

using Eigen::Index;

// Row ranges [begin, end) of the transport matrix that the basis is fitted to.
using RowRanges = std::vector<std::pair<Index, Index>>;

// The rows of the parts `options.basis_parts` selects (every row when it is empty).
RowRanges basis_rows(const VertexLayout& layout, const EigenOptions& options) {
    if (options.basis_parts.empty()) return {{0, Index(3 * layout.total())}};
    RSL_CHECK_EQ(int(options.basis_parts.size()), layout.parts());
    RowRanges ranges;
    for (int p = 0; p < layout.parts(); ++p)
        if (options.basis_parts[p] && layout.first(p + 1) > layout.first(p))
            ranges.emplace_back(Index(3 * layout.first(p)), Index(3 * layout.first(p + 1)));
    if (ranges.empty()) throw_error("eigentransport: the basis parts have no vertices");
    return ranges;
}

Index row_count(const RowRanges& ranges) {
    Index count = 0;
    for (const auto& [begin, end] : ranges) count += end - begin;
    return count;
}

// μ: the mean of the basis rows, summed in double column strip by column strip.
Eigen::VectorXd mean_row(const RowMatrixXf& g, const RowRanges& ranges, ThreadSeconds& seconds) {
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(g.cols());
    tbb::parallel_for(tbb::blocked_range<Index>(0, g.cols(), 256), [&](const tbb::blocked_range<Index>& columns) {
        seconds.time([&] {
            for (const auto& [begin, end] : ranges)
                for (Index row = begin; row < end; ++row)
                    for (Index k = columns.begin(); k != columns.end(); ++k) sum[k] += g(row, k);
        });
    });
    return sum / double(std::max<Index>(row_count(ranges), 1));
}

void subtract_row(RowMatrixXf& g, const Eigen::VectorXf& mean, ThreadSeconds& seconds) {
    tbb::parallel_for(tbb::blocked_range<Index>(0, g.rows(), 1024), [&](const tbb::blocked_range<Index>& rows) {
        seconds.time([&] { g.middleRows(rows.begin(), rows.size()).rowwise() -= mean.transpose(); });
    });
}

// Σ_rows g gᵀ of the centred rows. Each task owns one tile of the lower
// triangle and sums float products of row chunks into double, so no
// per-thread copy of the texels² matrix is needed and the result does not
// depend on the thread count.
Eigen::MatrixXd covariance(const RowMatrixXf& centred, const RowRanges& ranges, ThreadSeconds& seconds) {
    constexpr Index kTile = 256, kChunk = 4096;
    const Index texels = centred.cols();
    std::vector<std::pair<Index, Index>> tiles;
    for (Index i = 0; i < texels; i += kTile)
        for (Index j = 0; j <= i; j += kTile) tiles.emplace_back(i, j);
    Eigen::MatrixXd sum(texels, texels);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
        seconds.time([&] {
            Eigen::MatrixXf product;
            Eigen::MatrixXd tile;
            for (size_t t = range.begin(); t != range.end(); ++t) {
                const auto [i, j] = tiles[t];
                const Index ni = std::min(kTile, texels - i), nj = std::min(kTile, texels - j);
                tile.setZero(ni, nj);
                for (const auto& [begin, end] : ranges)
                    for (Index r = begin; r < end; r += kChunk) {
                        const Index nr = std::min(kChunk, end - r);
                        product.noalias() = centred.block(r, i, nr, ni).transpose() * centred.block(r, j, nr, nj);
                        tile += product.cast<double>();
                    }
                sum.block(i, j, ni, nj) = tile;
                sum.block(j, i, nj, ni) = tile.transpose();
            }
        });
    });
    return sum;
}

struct Eigenpairs {
    Eigen::MatrixXd vectors;  // columns, by decreasing eigenvalue
};

// Every eigenpair of the covariance, the largest `terms` kept.
Eigenpairs top_eigenpairs_dense(const Eigen::MatrixXd& covariance, Index terms) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance);
    RSL_CHECK(solver.info() == Eigen::Success);
    return {solver.eigenvectors().rightCols(terms).rowwise().reverse()};  // ascending → decreasing
}

Eigen::MatrixXd orthonormal_columns(const Eigen::MatrixXd& y) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(y);
    return qr.householderQ() * Eigen::MatrixXd::Identity(y.rows(), y.cols());
}

// a · b with the rows of a shared among threads.
Eigen::MatrixXd multiply(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, ThreadSeconds& seconds) {
    Eigen::MatrixXd product(a.rows(), b.cols());
    tbb::parallel_for(tbb::blocked_range<Index>(0, a.rows(), 128), [&](const tbb::blocked_range<Index>& rows) {
        seconds.time([&] { product.middleRows(rows.begin(), rows.size()).noalias() = a.middleRows(rows.begin(), rows.size()) * b; });
    });
    return product;
}

// The top `terms` eigenvectors by a randomized range finder with power
// iterations (Halko, Martinsson & Tropp 2011): the full solver is cubic in
// the texels (6144 at N = 32), this one is linear.
Eigenpairs top_eigenpairs_randomized(const Eigen::MatrixXd& covariance, Index terms, const EigenOptions& options,
                                     ThreadSeconds& seconds) {
    const Index texels = covariance.rows();
    const Index width = std::min(texels, terms + Index(std::max(options.oversampling, 0)));
    std::mt19937_64 random(options.seed);
    std::normal_distribution<double> normal;
    Eigen::MatrixXd test(texels, width);
    for (Index j = 0; j < width; ++j)
        for (Index i = 0; i < texels; ++i) test(i, j) = normal(random);
    Eigen::MatrixXd range = orthonormal_columns(multiply(covariance, test, seconds));
    for (int iteration = 0; iteration < options.power_iterations; ++iteration)
        range = orthonormal_columns(multiply(covariance, range, seconds));
    const Eigen::MatrixXd small = range.transpose() * multiply(covariance, range, seconds);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(small);
    RSL_CHECK(solver.info() == Eigen::Success);
    return {range * solver.eigenvectors().rightCols(terms).rowwise().reverse()};
}

// c = (g − μ) · B for every centred row.
RowMatrixXf project_rows(const RowMatrixXf& centred, const Eigen::MatrixXf& basis, ThreadSeconds& seconds) {
    RowMatrixXf coefficients(centred.rows(), basis.cols());
    tbb::parallel_for(tbb::blocked_range<Index>(0, centred.rows(), 2048), [&](const tbb::blocked_range<Index>& rows) {
        seconds.time([&] {
            coefficients.middleRows(rows.begin(), rows.size()).noalias() =
                centred.middleRows(rows.begin(), rows.size()) * basis;
        });
    });
    return coefficients;
}

bool use_randomized_solver(const EigenOptions& options, Index texels, Index terms) {
    if (options.solver != EigenSolver::Automatic) return options.solver == EigenSolver::Randomized;
    return texels > kDenseSolverTexels && terms + options.oversampling < texels / 2;
}

}  // namespace

TransportMatrix sample_transport_matrix(const GroundTruth& truth, const CubeMap& environment,
                                        const Mat3& environment_rotation, bool visibility) {
    const VertexLayout layout(truth.posed().scene());
    const TransportSampler sampler(truth, environment, environment_rotation, visibility);
    const int texels = sampler.texel_count();
    const size_t vertices = layout.total();
    TransportMatrix matrix;
    matrix.rows.resize(Index(3 * vertices), texels);
    std::mutex totals_mutex;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, vertices, 64), [&](const tbb::blocked_range<size_t>& range) {
        TransportSampler::Scratch scratch = sampler.make_scratch();
        std::vector<Color> f(static_cast<size_t>(texels));
        uint64_t rays = 0;
        double trace_s = 0, fill_s = 0;
        for (size_t v = range.begin(); v != range.end(); ++v) {
            auto start = Clock::now();
            const auto [part, vertex] = layout.locate(v);
            rays += sampler.sample(part, vertex, f.data(), scratch);
            trace_s += seconds_since(start);
            start = Clock::now();
            for (int c = 0; c < 3; ++c) {
                float* row = matrix.rows.row(Index(3 * v + c)).data();
                for (int k = 0; k < texels; ++k) row[k] = f[k][c] * environment.solid_angle(k);
            }
            fill_s += seconds_since(start);
        }
        std::lock_guard<std::mutex> lock(totals_mutex);
        matrix.rays += rays;
        matrix.trace_cpu_seconds += trace_s;
        matrix.fill_cpu_seconds += fill_s;
    });
    return matrix;
}

EigenTransport eigentransport_from_matrix(TransportMatrix& matrix, VertexLayout layout, const EigenOptions& options) {
    RSL_CHECK_GE(options.max_terms, 1);
    RSL_CHECK_EQ(size_t(matrix.rows.rows()), 3 * layout.total());
    EigenTransport eigen(std::move(layout));
    eigen.rays = matrix.rays;
    eigen.trace_cpu_seconds = matrix.trace_cpu_seconds;
    RowMatrixXf& g = matrix.rows;
    const Index terms = std::min<Index>(options.max_terms, g.cols());
    ThreadSeconds pca;
    const RowRanges fitted = basis_rows(eigen.layout, options);
    eigen.mean = mean_row(g, fitted, pca).cast<float>();
    subtract_row(g, eigen.mean, pca);
    const Eigen::MatrixXd spread = covariance(g, fitted, pca);
    eigen.total_variance = spread.trace();
    eigen.randomized = use_randomized_solver(options, g.cols(), terms);
    Eigenpairs pairs;
    if (eigen.randomized) {
        pairs = top_eigenpairs_randomized(spread, terms, options, pca);
    } else {
        pca.time([&] { pairs = top_eigenpairs_dense(spread, terms); });
    }
    eigen.basis = pairs.vectors.cast<float>();
    eigen.coefficients = project_rows(g, eigen.basis, pca);
    // The variance of the basis rows each basis vector keeps, from the
    // coefficients themselves (for either solver the basis actually stored).
    pca.time([&] {
        eigen.eigenvalues = Eigen::VectorXd::Zero(terms);
        for (const auto& [begin, end] : fitted)
            eigen.eigenvalues +=
                eigen.coefficients.middleRows(begin, end - begin).cast<double>().colwise().squaredNorm().transpose();
    });
    eigen.pca_cpu_seconds = matrix.fill_cpu_seconds + pca.total();
    return eigen;
}

EigenTransport precompute_eigentransport(const GroundTruth& truth, const CubeMap& environment,
                                         const EigenOptions& options) {
    const auto wall_start = Clock::now();
    const Scene& scene = truth.posed().scene();
    const Mat3 rotation = scene.environment.rotation_at(truth.time());
    EigenTransport eigen = [&] {
        TransportMatrix matrix = sample_transport_matrix(truth, environment, rotation, options.visibility);
        return eigentransport_from_matrix(matrix, VertexLayout(scene), options);
    }();  // the dense matrix is released here
    eigen.time = truth.time();
    eigen.environment_rotation = rotation;
    eigen.wall_seconds = seconds_since(wall_start);
    return eigen;
}

double EigenTransport::captured_variance(int terms) const {
    RSL_CHECK_LE(terms, max_terms());
    if (!(total_variance > 0)) return 1.0;
    return eigenvalues.head(terms).sum() / total_variance;
}

size_t EigenTransport::bytes(int terms) const {
    return (size_t(coefficients.rows()) * terms + size_t(texels()) * (size_t(terms) + 1)) * sizeof(float);
}

// ---------------------------------------------------------------- rendering

void EigenRenderer::project(const CubeMap& environment, int terms) {
    RSL_CHECK_EQ(environment.texel_count(), eigen_.texels());
    static_assert(sizeof(Color) == 3 * sizeof(float));
    const Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>> radiance(
        reinterpret_cast<const float*>(environment.radiances().data()), environment.texel_count(), 3);
    lighting_.noalias() = eigen_.basis.leftCols(terms).transpose() * radiance;
    mean_lighting_.noalias() = eigen_.mean.transpose() * radiance;
}

void EigenRenderer::render(const CubeMap& environment, int terms, std::vector<Color>& out) {
    RSL_CHECK_GE(terms, 0);
    RSL_CHECK_LE(terms, eigen_.max_terms());
    project(environment, terms);
    const size_t vertices = eigen_.layout.total();
    out.resize(vertices);
    const Index stride = eigen_.coefficients.cols();
    using ChannelRows = Eigen::Map<const RowMatrixXf, 0, Eigen::OuterStride<>>;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, vertices, 1024), [&](const tbb::blocked_range<size_t>& range) {
        Eigen::VectorXf channel[3];
        for (int c = 0; c < 3; ++c) {
            // The rows of channel c are every third row of the coefficients.
            const ChannelRows rows(eigen_.coefficients.data() + (3 * range.begin() + c) * stride, Index(range.size()),
                                   terms, Eigen::OuterStride<>(3 * stride));
            channel[c].noalias() = rows * lighting_.col(c);
        }
        for (size_t v = range.begin(); v != range.end(); ++v) {
            const Index i = Index(v - range.begin());
            out[v] = Color(mean_lighting_[0] + channel[0][i], mean_lighting_[1] + channel[1][i],
                           mean_lighting_[2] + channel[2][i]);
        }
    });
}

void EigenRenderer::render(const CubeMap& environment, const Mat3& rotation, int terms, std::vector<Color>& out) {
    if (rotation == eigen_.environment_rotation) return render(environment, terms, out);
    // Lighting in the transport's frame: turned by R0⁻¹ R (R0: precompute rotation).
    render(rotate(environment, glm::transpose(eigen_.environment_rotation) * rotation), terms, out);
}

}  // namespace rsl
