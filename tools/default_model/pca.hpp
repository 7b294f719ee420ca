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

// The components of the built-in models. Survey measures (measures, N x M: each body's draw)
// are weighed in beside the vertices, each standardised and all of them together given
// `measure_weight` times the vertices' total variance, so that the first components carry
// what the survey measures vary in, not only what moves most vertices most. From the PCA of
// vertices and measures together, the k-th component is the vertices' regression on the k-th
// unit-variance score (betas stay uncorrelated with unit variance over the population). The
// first `searched` components are then turned among themselves (the population is the same
// N(0, I) in any orthogonal turn): component j takes all of the block's rise of lead j
// (leads, N x L: e.g. stature, then mass), the later components none of it; the free ones
// after the leads are the vertices' principal axes of the rest, and any of them that moves
// the vertices by less than `visible_share` of the total variance takes some of the largest.
// The components beyond `searched` are turned to their vertex axes. Directions are unit
// columns, not orthogonal; variances are their vertex variances.
struct SurveyPcaOptions {
  double measure_weight = 1.0;
  int searched = 10;
  double visible_share = 0.015;
};
PcaResult survey_pca(const Eigen::MatrixXd& theta, const Eigen::MatrixXd& basis,
                     const Eigen::MatrixXd& measures, const Eigen::MatrixXd& leads, int keep,
                     const SurveyPcaOptions& options);

// Plain PCA of explicit rows (for checking the factored one on small populations).
PcaResult explicit_pca(const Eigen::MatrixXd& rows, int keep);

}  // namespace default_model
