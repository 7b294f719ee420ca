#include "pca.hpp"

#include <algorithm>

#include <Eigen/QR>
#include <Eigen/SVD>

namespace default_model {

PcaResult factored_pca(const Eigen::MatrixXd& theta, const Eigen::MatrixXd& basis, int keep) {
  const Eigen::Index n = theta.rows(), p = theta.cols();
  PcaResult r;
  const Eigen::VectorXd theta_mean = theta.colwise().mean().transpose();
  r.mean = basis * theta_mean;
  const Eigen::MatrixXd centred = theta.rowwise() - theta_mean.transpose();
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(basis);
  const Eigen::MatrixXd R = qr.matrixQR().topRows(p).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(basis.rows(), p);
  const Eigen::MatrixXd M = centred * R.transpose();  // n x p
  Eigen::BDCSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeThinV);
  keep = static_cast<int>(std::min<Eigen::Index>(keep, svd.singularValues().size()));
  r.directions = Q * svd.matrixV().leftCols(keep);
  r.variances = svd.singularValues().head(keep).array().square() / double(n - 1);
  r.total_variance = svd.singularValues().squaredNorm() / double(n - 1);
  return r;
}

PcaResult explicit_pca(const Eigen::MatrixXd& rows, int keep) {
  const Eigen::Index n = rows.rows();
  PcaResult r;
  r.mean = rows.colwise().mean().transpose();
  const Eigen::MatrixXd centred = rows.rowwise() - r.mean.transpose();
  Eigen::BDCSVD<Eigen::MatrixXd> svd(centred, Eigen::ComputeThinV);
  keep = static_cast<int>(std::min<Eigen::Index>(keep, svd.singularValues().size()));
  r.directions = svd.matrixV().leftCols(keep);
  r.variances = svd.singularValues().head(keep).array().square() / double(n - 1);
  r.total_variance = svd.singularValues().squaredNorm() / double(n - 1);
  return r;
}

}  // namespace default_model
