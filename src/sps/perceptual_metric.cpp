#include "sps/perceptual_metric.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>

namespace sps {

std::optional<std::string> metric_matrix_problem(const Eigen::MatrixXd& metric, Eigen::Index dims) {
  if (metric.size() == 0) return std::nullopt;
  if (metric.rows() != dims || metric.cols() != dims) {
    return "needs " + std::to_string(dims) + " x " + std::to_string(dims) + " entries, got " +
           std::to_string(metric.rows()) + " x " + std::to_string(metric.cols());
  }
  if (!metric.allFinite()) return "holds a non-finite entry";
  const Eigen::VectorXd diagonal = metric.diagonal();
  if ((diagonal.array() < 1e-18).any() || (diagonal.array() > 1e18).any()) {
    return "needs every diagonal entry in [1e-18, 1e18]";
  }
  if ((metric - metric.transpose()).cwiseAbs().maxCoeff() > 1e-9 * metric.cwiseAbs().maxCoeff()) {
    return "is not symmetric";
  }
  // Relative to the diagonal, so that the check does not depend on the units.
  const Eigen::VectorXd inv_sqrt = diagonal.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd normalised = inv_sqrt.asDiagonal() * metric * inv_sqrt.asDiagonal();
  const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (normalised + normalised.transpose()));
  if (llt.info() != Eigen::Success || llt.matrixLLT().diagonal().minCoeff() < 1e-6) {
    return "is not positive definite (two directions look the same)";
  }
  return std::nullopt;
}

void validate_metric_matrix(const Eigen::MatrixXd& metric, Eigen::Index dims,
                            const std::string& what) {
  if (const auto problem = metric_matrix_problem(metric, dims)) {
    throw std::invalid_argument(what + " " + *problem);
  }
}

PerceptualMetric::PerceptualMetric(const Eigen::VectorXd& scale)
    : PerceptualMetric(scale, Eigen::MatrixXd()) {}

PerceptualMetric::PerceptualMetric(const Eigen::VectorXd& scale, const Eigen::MatrixXd& metric)
    : scale_(scale) {
  if (scale.size() == 0 || !scale.allFinite() || (scale.array() <= 0.0).any()) {
    throw std::invalid_argument("the perceptual scale needs positive finite entries");
  }
  validate_metric_matrix(metric, scale.size(), "the perceptual metric");
  if (metric.size() > 0) {
    matrix_ = metric;
    upper_ = Eigen::LLT<Eigen::MatrixXd>(0.5 * (metric + metric.transpose())).matrixU();
  }
}

double PerceptualMetric::length(const Eigen::VectorXd& x) const {
  return seen(x).norm();
}

Eigen::VectorXd PerceptualMetric::weighted(const Eigen::VectorXd& x) const {
  if (!full()) return scale_.cwiseAbs2().cwiseProduct(x);
  return matrix_ * x;
}

Eigen::VectorXd PerceptualMetric::seen(const Eigen::VectorXd& x) const {
  if (!full()) return x.cwiseProduct(scale_);
  return upper_.triangularView<Eigen::Upper>() * x;
}

Eigen::VectorXd PerceptualMetric::unseen(const Eigen::VectorXd& y) const {
  if (!full()) return y.cwiseQuotient(scale_);
  return upper_.triangularView<Eigen::Upper>().solve(y);
}

Eigen::MatrixXd PerceptualMetric::seen_covariance(const Eigen::MatrixXd& covariance) const {
  if (!full()) return scale_.asDiagonal() * covariance * scale_.asDiagonal();
  const Eigen::MatrixXd r = upper_.triangularView<Eigen::Upper>();
  return r * covariance * r.transpose();
}

}  // namespace sps
