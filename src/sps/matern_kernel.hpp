// ARD Matern 5/2 kernel k(x, y) = a^2 (1 + sqrt5 r + 5/3 r^2) exp(-sqrt5 r),
// r^2 = sum_k (x_k - y_k)^2 / l_k^2 (Snoek et al. 2012), with the derivatives the preference
// model and the acquisition optimizers need.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace sps {

struct KernelParams {
  double amplitude = 0.2;         // a (the signal standard deviation)
  Eigen::VectorXd length_scales;  // l, one per dimension

  // Hyperparameters in log space, as the MAP estimation optimizes them: [log a, log l...].
  Eigen::VectorXd to_log() const;
  static KernelParams from_log(const Eigen::VectorXd& log_params);
};

class MaternKernel {
 public:
  explicit MaternKernel(KernelParams params);

  const KernelParams& params() const { return params_; }
  double variance() const { return params_.amplitude * params_.amplitude; }

  double operator()(const Eigen::VectorXd& x, const Eigen::VectorXd& y) const;

  // Gram matrix of the columns of `points` (d x N).
  Eigen::MatrixXd gram(const Eigen::MatrixXd& points) const;
  // Cross-covariances k(points_i, x) (N).
  Eigen::VectorXd cross(const Eigen::MatrixXd& points, const Eigen::VectorXd& x) const;

  // For many query points at once (columns of `xs`): k(i, j) = k(points_i, xs_j) and the
  // factor q(i, j) with d k(points_i, x) / dx at xs_j = q(i, j) * (xs_j - points_i) / l^2.
  void cross_batch(const Eigen::MatrixXd& points, const Eigen::MatrixXd& xs, Eigen::MatrixXd& k,
                   Eigen::MatrixXd& q) const;
  const Eigen::VectorXd& inverse_squared_lengths() const { return inv_sq_lengths_; }

  // g_j = sum_il M_il * d Gram_il / d log(hyperparameter j) for a symmetric M, where j = 0 is
  // the amplitude and 1 + k the length scale k. Contracting on the fly avoids storing d + 1
  // N x N derivative matrices.
  Eigen::VectorXd contract_log_gradients(const Eigen::MatrixXd& points,
                                         const Eigen::MatrixXd& m) const;

 private:
  KernelParams params_;
  Eigen::VectorXd inv_sq_lengths_;  // 1 / l_k^2
};

}  // namespace sps
