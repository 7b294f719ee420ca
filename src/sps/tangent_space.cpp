#include "sps/tangent_space.hpp"

#include <algorithm>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

namespace sps {

namespace {

// N^T (N N^T)^+ N: the orthogonal projector onto the span of the normals (zero for none).
Eigen::MatrixXd normal_projector(const Eigen::MatrixXd& normals, Eigen::Index dims) {
  if (normals.rows() == 0 || normals.cols() != dims) return Eigen::MatrixXd::Zero(dims, dims);
  const Eigen::MatrixXd nnt = normals * normals.transpose();
  const Eigen::MatrixXd inv = nnt.completeOrthogonalDecomposition().pseudoInverse();
  return normals.transpose() * inv * normals;
}

}  // namespace

Eigen::MatrixXd tangent_projector(const Eigen::MatrixXd& normals, Eigen::Index dims) {
  return Eigen::MatrixXd::Identity(dims, dims) - normal_projector(normals, dims);
}

Eigen::MatrixXd most_visible_tangent_directions(const Eigen::MatrixXd& projector,
                                                const Eigen::VectorXd& scale, int k) {
  const Eigen::Index d = projector.rows();
  const Eigen::VectorXd s2 =
      scale.size() == d ? Eigen::VectorXd(scale.cwiseProduct(scale)) : Eigen::VectorXd::Ones(d);
  const Eigen::MatrixXd m = projector * s2.asDiagonal() * projector;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(0.5 * (m + m.transpose()));
  const int count = static_cast<int>(std::min<Eigen::Index>(k, d));
  Eigen::MatrixXd dirs(d, count);
  for (int i = 0; i < count; ++i) {
    Eigen::VectorXd e = eigen.eigenvalues()(d - 1 - i) > 1e-12 * std::max(1.0, m.trace())
                            ? Eigen::VectorXd(eigen.eigenvectors().col(d - 1 - i))
                            : Eigen::VectorXd::Zero(d);
    // A fixed sign (the largest entry positive), so the plane does not depend on the solver.
    Eigen::Index largest = 0;
    e.cwiseAbs().maxCoeff(&largest);
    if (e(largest) < 0.0) e = -e;
    dirs.col(i) = e;
  }
  return dirs;
}

TangentSpace::TangentSpace(const Eigen::MatrixXd& normals, Eigen::Index dims) {
  if (normals.rows() == 0 || normals.cols() != dims) return;
  normals_ = normals;
  normal_projector_ = normal_projector(normals, dims);
}

Eigen::VectorXd TangentSpace::project(const Eigen::VectorXd& d) const {
  // d less its normal part (not P d): exactly d where the normals do not reach.
  if (normal_projector_.size() > 0) {
    const Eigen::VectorXd tangent = d - normal_projector_ * d;
    // The coordinates taken out stay exactly unchanged, not to rounding: a point on a face of
    // the box has no room at all for a move of 1e-17 across it, and such a move had left a
    // held plane at the box's edge without any direction (nine identical cells).
    return mask_.size() > 0 ? Eigen::VectorXd(tangent.cwiseProduct(mask_)) : tangent;
  }
  if (mask_.size() > 0) return d.cwiseProduct(mask_);
  return d;
}

Eigen::VectorXd TangentSpace::through(const Eigen::VectorXd& origin,
                                      const Eigen::VectorXd& y) const {
  if (whole()) return y;
  if (normal_projector_.size() == 0) {
    return y - (y - origin).cwiseProduct(Eigen::VectorXd::Ones(y.size()) - mask_);
  }
  Eigen::VectorXd nearest = y - normal_projector_ * (y - origin);
  for (Eigen::Index k = 0; k < mask_.size(); ++k) {
    if (mask_(k) <= 0.0) nearest(k) = origin(k);  // exactly, as in project
  }
  return nearest;
}

Eigen::MatrixXd TangentSpace::projector(Eigen::Index dims) const {
  Eigen::MatrixXd p(dims, dims);
  for (Eigen::Index k = 0; k < dims; ++k) p.col(k) = project(Eigen::VectorXd::Unit(dims, k));
  return p;
}

TangentSpace TangentSpace::without_coordinates(const Eigen::VectorXd& keep) const {
  TangentSpace space;
  space.mask_ = mask_.size() == keep.size() ? Eigen::VectorXd(mask_.cwiseProduct(keep)) : keep;
  if (normals_.rows() == 0) return space;  // a mask of coordinates, applied exactly
  // The held normals and a unit normal for every coordinate taken out.
  const Eigen::Index d = keep.size();
  const auto removed = static_cast<Eigen::Index>((space.mask_.array() <= 0.0).count());
  Eigen::MatrixXd normals(normals_.rows() + removed, d);
  normals.topRows(normals_.rows()) = normals_;
  Eigen::Index row = normals_.rows();
  for (Eigen::Index k = 0; k < d; ++k) {
    if (space.mask_(k) <= 0.0) normals.row(row++) = Eigen::RowVectorXd::Unit(d, k);
  }
  space.normals_ = normals_;
  space.normal_projector_ = normal_projector(normals, d);
  return space;
}

}  // namespace sps
