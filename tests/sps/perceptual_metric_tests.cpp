// The full perceptual metric (sps/perceptual_metric.hpp): what it measures, that a diagonal
// one is the per-coordinate scale, and that broken matrices are refused with a message.
#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <catch2/catch.hpp>

#include "sps/perceptual_metric.hpp"
#include "test_support.hpp"

namespace {

using sps_test::overlapping_metric;

Eigen::Vector3d sqrt_diagonal(const Eigen::Matrix3d& m) {
  return m.diagonal().cwiseSqrt();
}

}  // namespace

TEST_CASE("a diagonal perceptual metric is the scale per coordinate", "[metric]") {
  const Eigen::Vector3d scale(30.0, 60.0, 20.0);
  const sps::PerceptualMetric metric(scale);
  CHECK_FALSE(metric.full());
  const Eigen::Vector3d x(0.1, -0.2, 0.3);
  CHECK(metric.length(x) == Approx(x.cwiseProduct(scale).norm()));
  CHECK((metric.unseen(metric.seen(x)) - x).norm() < 1e-12);
  CHECK((metric.weighted(x) - scale.cwiseAbs2().cwiseProduct(x)).norm() < 1e-9);
  CHECK((metric.scale() - scale).norm() == 0.0);
  const Eigen::Matrix3d cov = Eigen::Vector3d(0.01, 0.02, 0.03).asDiagonal();
  CHECK((metric.seen_covariance(cov) -
         Eigen::Matrix3d(
             (scale.cwiseAbs2().cwiseProduct(Eigen::Vector3d(0.01, 0.02, 0.03))).asDiagonal()))
            .norm() < 1e-9);
}

TEST_CASE("a full perceptual metric measures sqrt(x^T M x) and sees overlapping directions",
          "[metric]") {
  const Eigen::Matrix3d m = overlapping_metric();
  const sps::PerceptualMetric metric(sqrt_diagonal(m), m);
  CHECK(metric.full());
  CHECK(metric.dims() == 3);
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(0.1, -0.2, 0.3), Eigen::Vector3d(1, 0, 0),
                                   Eigen::Vector3d(0.5, -0.5, 0.0)}) {
    CHECK(metric.length(x) == Approx(std::sqrt(x.dot(m * x))));
    CHECK((metric.unseen(metric.seen(x)) - x).norm() < 1e-12);
    // M x, the gradient of half the squared length: the same as seen through R^T R.
    CHECK((metric.weighted(x) - m * x).norm() < 1e-9 * (m * x).norm() + 1e-12);
    const Eigen::Vector3d seen_back =
        Eigen::Matrix3d(m.llt().matrixU()).transpose() * metric.seen(x);
    CHECK((metric.weighted(x) - seen_back).norm() < 1e-9 * (m * x).norm() + 1e-12);
  }
  // Moving the first two directions against each other shows far less than the diagonal
  // alone would say (they move the same vertices the same way).
  const Eigen::Vector3d against(0.5, -0.5, 0.0);
  CHECK(metric.length(against) < 0.6 * sps::PerceptualMetric(sqrt_diagonal(m)).length(against));
  // What is seen of x with covariance C spreads as much as x^T M x on average: trace(M C).
  const Eigen::Matrix3d cov = Eigen::Vector3d(0.02, 0.01, 0.03).asDiagonal();
  const Eigen::MatrixXd seen = metric.seen_covariance(cov);
  CHECK((seen - seen.transpose()).norm() < 1e-9);
  CHECK(seen.trace() == Approx((m * cov).trace()));
}

TEST_CASE("a malformed perceptual metric is refused with a message", "[metric]") {
  const Eigen::Matrix3d good = overlapping_metric();
  CHECK_NOTHROW(sps::validate_metric_matrix(good, 3, "the metric"));
  CHECK_NOTHROW(sps::validate_metric_matrix(Eigen::MatrixXd(), 3, "the metric"));
  CHECK_THROWS_WITH(sps::validate_metric_matrix(good, 4, "the metric"),
                    Catch::Contains("the metric needs 4 x 4"));
  Eigen::Matrix3d bad = good;
  bad(0, 1) += 100.0;
  CHECK_THROWS_WITH(sps::validate_metric_matrix(bad, 3, "the metric"),
                    Catch::Contains("not symmetric"));
  bad = good;
  bad(2, 2) = std::nan("");
  CHECK_THROWS_WITH(sps::validate_metric_matrix(bad, 3, "the metric"),
                    Catch::Contains("non-finite"));
  // Two directions that look exactly alike.
  Eigen::Matrix3d a;
  a << 1, 2, 0, 1, 2, 0, 0, 0, 3;
  CHECK_THROWS_WITH(sps::validate_metric_matrix(a.transpose() * a, 3, "the metric"),
                    Catch::Contains("positive definite"));
  bad = good;
  bad(1, 1) = -5.0;
  CHECK_THROWS_AS(sps::validate_metric_matrix(bad, 3, "the metric"), std::invalid_argument);
  // The same rule, without an exception, for callers that fall back on the scale alone.
  CHECK_FALSE(sps::metric_matrix_problem(good, 3).has_value());
  CHECK(sps::metric_matrix_problem(bad, 3).value_or("").find("diagonal") != std::string::npos);
  CHECK(sps::metric_matrix_problem(good, 2).has_value());
  CHECK_THROWS_AS(sps::PerceptualMetric(Eigen::Vector3d(1.0, 0.0, 1.0)), std::invalid_argument);
  CHECK_THROWS_AS(sps::PerceptualMetric(Eigen::Vector2d(1.0, 1.0), good), std::invalid_argument);
}
