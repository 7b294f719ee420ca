// PCA of a population given as X = Theta * B^T (bodies as rows, parameters Theta, basis B):
// X_c = Theta_c B^T = (Theta_c R^T) Q^T with B = Q R, so the SVD of the small matrix
// Theta_c R^T (Eigen BDCSVD) gives the singular values of X_c and its principal directions Q W
// exactly, without forming the N x 3V matrix.
#pragma once

#include <Eigen/Core>

namespace default_model {

struct PcaResult {
  Eigen::VectorXd mean;        // 3V
  Eigen::MatrixXd directions;  // 3V x K, orthonormal columns
  Eigen::VectorXd variances;   // K eigenvalues of the covariance (divisor N - 1)
  double total_variance = 0;   // trace of the covariance
};

PcaResult factored_pca(const Eigen::MatrixXd& theta, const Eigen::MatrixXd& basis, int keep);

// Plain PCA of explicit rows (for checking the factored one on small populations).
PcaResult explicit_pca(const Eigen::MatrixXd& rows, int keep);

}  // namespace default_model
