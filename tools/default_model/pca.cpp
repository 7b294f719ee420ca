#include "pca.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>

namespace default_model {

namespace {

// The population's vertices X = Theta B^T in the QR coordinates of the basis (B = QR): the
// centred vertices are coords Q^T, so every vertex statistic comes from the small n x p
// matrix `coords` without forming the n x 3V one.
struct FactoredPopulation {
  Eigen::VectorXd mean;    // 3V: the mean body's vertices
  Eigen::MatrixXd q;       // 3V x p, orthonormal columns
  Eigen::MatrixXd coords;  // n x p: Theta_c R^T
};

FactoredPopulation factor_population(const Eigen::MatrixXd& theta, const Eigen::MatrixXd& basis) {
  const Eigen::Index p = theta.cols();
  const Eigen::VectorXd theta_mean = theta.colwise().mean().transpose();
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(basis);
  const Eigen::MatrixXd r = qr.matrixQR().topRows(p).triangularView<Eigen::Upper>();
  return {basis * theta_mean, qr.householderQ() * Eigen::MatrixXd::Identity(basis.rows(), p),
          (theta.rowwise() - theta_mean.transpose()) * r.transpose()};
}

}  // namespace

PcaResult factored_pca(const Eigen::MatrixXd& theta, const Eigen::MatrixXd& basis, int keep) {
  const Eigen::Index n = theta.rows();
  PcaResult r;
  const FactoredPopulation f = factor_population(theta, basis);
  r.mean = f.mean;
  Eigen::BDCSVD<Eigen::MatrixXd> svd(f.coords, Eigen::ComputeThinV);
  keep = static_cast<int>(std::min<Eigen::Index>(keep, svd.singularValues().size()));
  r.directions = f.q * svd.matrixV().leftCols(keep);
  r.variances = svd.singularValues().head(keep).array().square() / double(n - 1);
  r.total_variance = svd.singularValues().squaredNorm() / double(n - 1);
  return r;
}

namespace {

// Turns the columns of `axes` (the vertices' regressions on unit-variance scores) among
// themselves, which keeps the scores uncorrelated with unit variance: to the vertices' own
// principal axes of their span, largest first.
void turn_to_vertex_axes(Eigen::Ref<Eigen::MatrixXd> axes) {
  if (axes.cols() == 0) return;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(axes.transpose() * axes);
  axes = axes * eig.eigenvectors().rowwise().reverse();
}

}  // namespace

PcaResult survey_pca(const Eigen::MatrixXd& theta, const Eigen::MatrixXd& basis,
                     const Eigen::MatrixXd& measures, const Eigen::MatrixXd& leads, int keep,
                     const SurveyPcaOptions& options) {
  const Eigen::Index n = theta.rows(), p = theta.cols(), m = measures.cols();
  PcaResult r;
  const FactoredPopulation f = factor_population(theta, basis);
  r.mean = f.mean;
  Eigen::MatrixXd joint(n, p + m);
  joint.leftCols(p) = f.coords;
  r.total_variance = joint.leftCols(p).squaredNorm() / double(n - 1);
  const double per_measure = std::sqrt(options.measure_weight * r.total_variance / double(m));
  for (Eigen::Index j = 0; j < m; ++j) {
    const Eigen::VectorXd c = measures.col(j).array() - measures.col(j).mean();
    const double sd = std::sqrt(c.squaredNorm() / double(n - 1));
    joint.col(p + j) = sd > 0 ? Eigen::VectorXd(c * (per_measure / sd)) : Eigen::VectorXd::Zero(n);
  }
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(joint, Eigen::ComputeThinU | Eigen::ComputeThinV);
  keep = static_cast<int>(std::min<Eigen::Index>(keep, svd.singularValues().size()));
  const double root_n = std::sqrt(double(n - 1));
  // The vertices' regression on each unit-variance score z_k = sqrt(n - 1) u_k, in the QR's
  // coordinates, and the unit scores' directions (U's columns).
  Eigen::MatrixXd axes = svd.matrixV().topLeftCorner(p, keep) *
                         (svd.singularValues().head(keep) / root_n).asDiagonal();
  Eigen::MatrixXd scores = svd.matrixU().leftCols(keep);
  const int searched = std::min(keep, options.searched);
  const int led = std::min<int>(static_cast<int>(leads.cols()), searched);
  // Each lead in turn, within the searched block's columns not yet taken: a reflection that
  // puts all of its rise there on one axis (the others then leave it alone, so that a corner
  // of the box is no taller, say, than that axis alone at +-3).
  for (int j = 0; j < led; ++j) {
    const Eigen::VectorXd c = leads.col(j).array() - leads.col(j).mean();
    const Eigen::VectorXd l =
        scores.middleCols(j, searched - j).transpose() * c / root_n;  // per unit score
    Eigen::VectorXd v = l;
    v[0] -= l.norm();  // H l = |l| e_0 with H = I - 2 v v^T / v^T v
    if (v.squaredNorm() <= 1e-24 * std::max(1.0, l.squaredNorm())) continue;
    const Eigen::MatrixXd H = Eigen::MatrixXd::Identity(searched - j, searched - j) -
                              2.0 * v * v.transpose() / v.squaredNorm();
    axes.middleCols(j, searched - j) = axes.middleCols(j, searched - j) * H;
    // The scores turn with the axes (the next lead's rise is read from them).
    scores.middleCols(j, searched - j) = scores.middleCols(j, searched - j) * H;
  }
  // The rest of the searched block, and the components beyond it, each turned to the
  // vertices' principal axes (neither turn mixes the two blocks, so the first `searched`
  // components span the same space as before).
  turn_to_vertex_axes(axes.middleCols(led, searched - led));
  turn_to_vertex_axes(axes.rightCols(keep - searched));
  // A free component (not a lead's) of the searched block that the measures need but the
  // eye can hardly see takes some of the largest free one (a turn in the plane of the two,
  // which are orthogonal in vertex space) until it moves the vertices by `visible_share` of
  // the total variance; never more than 0.9 of the free components' average, so that there
  // is always a donor (the neutral model's stature axis carries most of its variance, the
  // sexes' difference included). Then the free ones largest first again (a reordering keeps
  // the block's span).
  const int free = searched - led;
  if (free > 0) {
    auto free_axes = axes.middleCols(led, free);
    const double floor = std::min(options.visible_share * r.total_variance,
                                  0.9 * free_axes.squaredNorm() / double(free));
    for (int j = 0; j < free; ++j) {
      Eigen::Index big = 0;
      free_axes.colwise().squaredNorm().maxCoeff(&big);
      const double a = free_axes.col(big).squaredNorm(), b = free_axes.col(j).squaredNorm();
      if (b >= floor || a <= floor || big == j) continue;
      const double s = std::sqrt((floor - b) / (a - b)), c = std::sqrt(1 - s * s);
      const Eigen::VectorXd largest = free_axes.col(big), weak = free_axes.col(j);
      free_axes.col(big) = c * largest - s * weak;
      free_axes.col(j) = s * largest + c * weak;
    }
    std::vector<int> order(free);
    for (int k = 0; k < free; ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](int x, int y) {
      return free_axes.col(x).squaredNorm() > free_axes.col(y).squaredNorm();
    });
    const Eigen::MatrixXd unsorted = free_axes;
    for (int k = 0; k < free; ++k) free_axes.col(k) = unsorted.col(order[k]);
  }
  r.directions.resize(basis.rows(), keep);
  r.variances.resize(keep);
  for (int k = 0; k < keep; ++k) {
    const Eigen::VectorXd axis = f.q * axes.col(k);
    r.variances[k] = axis.squaredNorm();
    r.directions.col(k) = axis / std::sqrt(r.variances[k]);
  }
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
