// How far apart two points of the search box look to a person, in the design space's visible
// units (mm of vertex displacement for a body): |x| = sqrt(x^T M x). A space whose coordinates
// change what is seen independently has a diagonal M, one scale per coordinate; a body model
// whose components are not orthogonal in vertex space (components turned so that one carries
// stature and one mass) has a full M, the Gram matrix of its directions' vertex displacements,
// and a diagonal would mistake two components that move the same vertices the same way for
// two independent changes.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

namespace sps {

// What is wrong with `metric` ("is not symmetric", ...), or nothing when it is empty or a
// dims x dims matrix that is finite, symmetric (to 1e-9 of its largest entry) and positive
// definite, with every diagonal entry in [1e-18, 1e18]. For callers that fall back on a
// diagonal metric rather than refuse.
std::optional<std::string> metric_matrix_problem(const Eigen::MatrixXd& metric, Eigen::Index dims);

// Throws std::invalid_argument "<what> <problem>" where metric_matrix_problem finds one.
void validate_metric_matrix(const Eigen::MatrixXd& metric, Eigen::Index dims,
                            const std::string& what);

class PerceptualMetric {
 public:
  // One scale per coordinate: M = diag(scale^2). Throws std::invalid_argument unless every
  // entry is positive and finite.
  explicit PerceptualMetric(const Eigen::VectorXd& scale);
  // The full metric when `metric` is not empty (validated as above, the same size as
  // `scale`); otherwise diag(scale^2).
  PerceptualMetric(const Eigen::VectorXd& scale, const Eigen::MatrixXd& metric);

  Eigen::Index dims() const { return scale_.size(); }
  bool full() const { return upper_.size() > 0; }
  // The visible change per unit of each coordinate on its own: the square root of M's diagonal.
  const Eigen::VectorXd& scale() const { return scale_; }

  // M x: the gradient of half the squared length at x.
  Eigen::VectorXd weighted(const Eigen::VectorXd& x) const;

  // sqrt(x^T M x).
  double length(const Eigen::VectorXd& x) const;
  // R x, with M = R^T R (R upper triangular, or diag(scale)): x as a person sees it, where
  // lengths and angles are the plain Euclidean ones.
  Eigen::VectorXd seen(const Eigen::VectorXd& x) const;
  // The inverse of seen(): the box direction that looks like y.
  Eigen::VectorXd unseen(const Eigen::VectorXd& y) const;
  // R C R^T: the covariance of seen(x) when x has covariance C.
  Eigen::MatrixXd seen_covariance(const Eigen::MatrixXd& covariance) const;

 private:
  Eigen::VectorXd scale_;
  Eigen::MatrixXd matrix_;  // the full metric M as given; empty for a diagonal one
  Eigen::MatrixXd upper_;   // R of the full metric; empty for a diagonal one
};

}  // namespace sps
