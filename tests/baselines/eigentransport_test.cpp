// Eigentransport against brute force: the transport sum Σ_k L_k f_k Ω_k and
// a dense SVD of the same transport matrix, on the small shadow scene.
#include <cmath>

#include <Eigen/SVD>
#include <catch2/catch.hpp>

#include "src/image/error_metrics.h"
#include "tests/baselines/baseline_scenes.h"
#include "tools/baselines/eigentransport.h"
#include "tools/baselines/prt.h"

using namespace rsl;
using namespace rsl::test;

namespace {

// Σ_k L_k f_k Ω_k per vertex (double), the transport sum under `lighting`.
std::vector<Color> transport_sum(const GroundTruth& truth, const CubeMap& grid, const CubeMap& lighting) {
    PrtOptions options;
    options.sh = options.haar = false;
    options.check_lighting = &lighting;
    return precompute_prt(truth, grid, options).texel_sum;
}

GroundTruthOptions environment_only() {
    GroundTruthOptions options;
    options.local_lights = false;
    options.max_sample_share = 0.0f;  // the texel-centre sum the transports sample
    return options;
}

}  // namespace

TEST_CASE("Eigentransport with every term is the transport sum; fewer terms are not") {
    for (bool glossy : {false, true}) {
        for (EigenSolver solver : {EigenSolver::Dense, EigenSolver::Randomized}) {
            INFO("glossy " << glossy << ", randomized " << (solver == EigenSolver::Randomized));
            const Scene scene = make_shadow_scene(glossy);
            const CubeMap sky = make_sky(4);  // 96 texels, fewer than the 270 rows
            const GroundTruth truth(scene, sky, 0.0f, environment_only());
            const std::vector<Color> reference = transport_sum(truth, sky, sky);
            EigenOptions options;
            options.max_terms = sky.texel_count();
            options.solver = solver;
            const EigenTransport eigen = precompute_eigentransport(truth, sky, options);
            REQUIRE(eigen.max_terms() == sky.texel_count());
            CHECK(eigen.randomized == (solver == EigenSolver::Randomized));
            CHECK(eigen.rays > 0);
            EigenRenderer renderer(eigen);
            std::vector<Color> out;
            renderer.render(sky, eigen.max_terms(), out);
            CHECK(relative_l2(out, reference) < 1e-5);
            CHECK(eigen.captured_variance(eigen.max_terms()) == Approx(1.0).epsilon(1e-5));
            // A few terms approximate: the check above can tell.
            renderer.render(sky, 4, out);
            CHECK(relative_l2(out, reference) > 1e-3);
        }
    }
}

TEST_CASE("Eigentransport's basis is orthonormal and truncating it loses the discarded eigenvalues (Eckart-Young)") {
    const Scene scene = make_shadow_scene(false);
    const CubeMap sky = make_sky(8);
    const GroundTruth truth(scene, sky, 0.0f, environment_only());
    TransportMatrix matrix = sample_transport_matrix(truth, sky, Mat3(1.0f));
    const Eigen::MatrixXd g = matrix.rows.cast<double>();
    const Eigen::RowVectorXd mean = g.colwise().mean();
    const Eigen::MatrixXd centred = g.rowwise() - mean;
    const Eigen::VectorXd singular = Eigen::BDCSVD<Eigen::MatrixXd>(centred).singularValues();  // decreasing
    const Eigen::VectorXd eigenvalues = singular.array().square();

    EigenOptions options;
    options.max_terms = 48;
    options.solver = EigenSolver::Dense;
    const EigenTransport eigen = eigentransport_from_matrix(matrix, VertexLayout(scene), options);
    CHECK((eigen.mean.cast<double>() - mean.transpose()).cwiseAbs().maxCoeff() < 1e-6 * mean.cwiseAbs().maxCoeff());
    const Eigen::MatrixXd basis = eigen.basis.cast<double>();
    CHECK((basis.transpose() * basis - Eigen::MatrixXd::Identity(48, 48)).cwiseAbs().maxCoeff() < 1e-5);

    const double total = eigenvalues.sum();
    CHECK(eigen.total_variance == Approx(total).epsilon(1e-5));
    for (int d : {1, 4, 16, 48}) {
        INFO("d = " << d);
        const Eigen::MatrixXd coefficients = eigen.coefficients.leftCols(d).cast<double>();
        const double error = (centred - coefficients * basis.leftCols(d).transpose()).squaredNorm();
        const double discarded = eigenvalues.tail(eigenvalues.size() - d).sum();
        CHECK(std::abs(error - discarded) <= 1e-6 * total + 1e-4 * discarded);
        CHECK(eigen.captured_variance(d) == Approx(1.0 - discarded / total).epsilon(1e-5));
        CHECK(eigen.eigenvalues[d - 1] == Approx(eigenvalues[d - 1]).epsilon(1e-4));
    }
    CHECK(eigenvalues[47] > 1e-4 * total);  // the tail is not trivially empty
}

TEST_CASE("Eigentransport fitted to some parts is the PCA of their rows alone; the others are projected onto it") {
    const Scene scene = make_shadow_scene(false);  // parts: ground (81 vertices), roof (9)
    const CubeMap sky = make_sky(4);
    const GroundTruth truth(scene, sky, 0.0f, environment_only());
    const VertexLayout layout(scene);
    TransportMatrix matrix = sample_transport_matrix(truth, sky, Mat3(1.0f));
    const Eigen::MatrixXd g = matrix.rows.cast<double>();
    // The ground's rows (shadowed by the roof: a rich basis); the roof's are projected.
    const Eigen::MatrixXd ground_rows = g.topRows(Eigen::Index(3 * layout.first(1)));
    const Eigen::RowVectorXd ground_mean = ground_rows.colwise().mean();
    const Eigen::MatrixXd ground_centred = ground_rows.rowwise() - ground_mean;
    const Eigen::VectorXd eigenvalues = Eigen::BDCSVD<Eigen::MatrixXd>(ground_centred).singularValues().array().square();

    EigenOptions options;
    options.max_terms = 8;
    options.solver = EigenSolver::Dense;
    options.basis_parts = {true, false};  // the ground only
    const EigenTransport eigen = eigentransport_from_matrix(matrix, layout, options);
    CHECK((eigen.mean.cast<double>() - ground_mean.transpose()).cwiseAbs().maxCoeff() <
          1e-6 * ground_mean.cwiseAbs().maxCoeff());
    CHECK(eigen.total_variance == Approx(eigenvalues.sum()).epsilon(1e-5));
    for (int d : {1, 4, 8}) {
        INFO("d = " << d);
        CHECK(eigen.eigenvalues[d - 1] == Approx(eigenvalues[d - 1]).epsilon(1e-4));
        CHECK(eigen.captured_variance(d) == Approx(eigenvalues.head(d).sum() / eigenvalues.sum()).epsilon(1e-5));
    }
    CHECK(eigenvalues[7] > 1e-4 * eigenvalues.sum());  // eight real directions
    // Every row, the roof's too, has the coefficients of its projection on the ground's basis.
    const Eigen::MatrixXd basis = eigen.basis.cast<double>();
    const Eigen::MatrixXd expected = (g.rowwise() - ground_mean) * basis;
    CHECK((eigen.coefficients.cast<double>() - expected).cwiseAbs().maxCoeff() < 1e-5 * expected.cwiseAbs().maxCoeff());
    // The roof's own mean differs: the selection is not ignored.
    options.basis_parts = {false, true};
    options.max_terms = 1;
    TransportMatrix again = sample_transport_matrix(truth, sky, Mat3(1.0f));
    const EigenTransport roof = eigentransport_from_matrix(again, layout, options);
    CHECK((roof.mean - eigen.mean).cwiseAbs().maxCoeff() > 1e-3 * eigen.mean.cwiseAbs().maxCoeff());
}

TEST_CASE("Eigentransport's randomized solver keeps the variance of the exact top eigenvectors") {
    const Scene scene = make_shadow_scene(false);
    const CubeMap sky = make_sky(8);  // 384 texels
    const GroundTruth truth(scene, sky, 0.0f, environment_only());
    EigenOptions options;
    options.max_terms = 16;
    options.solver = EigenSolver::Dense;
    const EigenTransport dense = precompute_eigentransport(truth, sky, options);
    options.solver = EigenSolver::Randomized;
    const EigenTransport randomized = precompute_eigentransport(truth, sky, options);
    REQUIRE(randomized.randomized);
    const Eigen::MatrixXd basis = randomized.basis.cast<double>();
    CHECK((basis.transpose() * basis - Eigen::MatrixXd::Identity(16, 16)).cwiseAbs().maxCoeff() < 1e-5);
    for (int d : {1, 4, 16}) {
        INFO("d = " << d);
        // Never above the optimum (Eckart-Young), and within 0.1% of its loss.
        CHECK(randomized.captured_variance(d) <= dense.captured_variance(d) + 1e-6);
        CHECK(1.0 - randomized.captured_variance(d) <= (1.0 - dense.captured_variance(d)) * 1.001 + 1e-6);
    }
    CHECK(dense.captured_variance(16) < 0.999);  // a real truncation
}

TEST_CASE("Eigentransport with a turned environment is the transport sum of the resampled map") {
    const Scene scene = make_shadow_scene(false);
    const CubeMap sky = make_sky(4);
    const GroundTruth truth(scene, sky, 0.0f, environment_only());
    EigenOptions options;
    options.max_terms = sky.texel_count();
    const EigenTransport eigen = precompute_eigentransport(truth, sky, options);
    const Mat3 turn = glm::mat3_cast(glm::angleAxis(0.7f, glm::normalize(Vec3(1.0f, 0.3f, 0.2f))));
    const std::vector<Color> reference = transport_sum(truth, sky, rotate(sky, turn));
    EigenRenderer renderer(eigen);
    std::vector<Color> out;
    renderer.render(sky, turn, eigen.max_terms(), out);
    CHECK(relative_l2(out, reference) < 1e-5);
    // Turning the other way is visibly different: the check can fail.
    renderer.render(sky, glm::transpose(turn), eigen.max_terms(), out);
    CHECK(relative_l2(out, reference) > 0.05);
    // At the precompute rotation nothing is resampled.
    std::vector<Color> unturned;
    renderer.render(sky, eigen.environment_rotation, 8, out);
    renderer.render(sky, 8, unturned);
    CHECK(relative_l2(out, unturned) == 0.0);
}
