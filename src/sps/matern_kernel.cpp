#include "sps/matern_kernel.hpp"

#include <cmath>
#include <utility>

namespace sps {

namespace {

constexpr double kSqrt5 = 2.23606797749978969641;

// Shape of the kernel as a function of r (without the amplitude).
double matern52(double r) {
  return (1.0 + kSqrt5 * r + (5.0 / 3.0) * r * r) * std::exp(-kSqrt5 * r);
}

// (d matern52 / dr) / r, finite at r = 0: -(5/3)(1 + sqrt5 r) exp(-sqrt5 r).
double matern52_dr_over_r(double r) {
  return -(5.0 / 3.0) * (1.0 + kSqrt5 * r) * std::exp(-kSqrt5 * r);
}

}  // namespace

Eigen::VectorXd KernelParams::to_log() const {
  Eigen::VectorXd out(length_scales.size() + 1);
  out(0) = std::log(amplitude);
  out.tail(length_scales.size()) = length_scales.array().log();
  return out;
}

KernelParams KernelParams::from_log(const Eigen::VectorXd& log_params) {
  KernelParams p;
  p.amplitude = std::exp(log_params(0));
  p.length_scales = log_params.tail(log_params.size() - 1).array().exp();
  return p;
}

MaternKernel::MaternKernel(KernelParams params) : params_(std::move(params)) {
  inv_sq_lengths_ = params_.length_scales.array().square().inverse();
}

double MaternKernel::operator()(const Eigen::VectorXd& x, const Eigen::VectorXd& y) const {
  const double r2 = ((x - y).array().square() * inv_sq_lengths_.array()).sum();
  return variance() * matern52(std::sqrt(r2));
}

Eigen::MatrixXd MaternKernel::gram(const Eigen::MatrixXd& points) const {
  const Eigen::Index n = points.cols();
  Eigen::MatrixXd k(n, n);
  const double var = variance();
  for (Eigen::Index j = 0; j < n; ++j) {
    k(j, j) = var;
    for (Eigen::Index i = j + 1; i < n; ++i) {
      const double r2 =
          ((points.col(i) - points.col(j)).array().square() * inv_sq_lengths_.array()).sum();
      k(i, j) = k(j, i) = var * matern52(std::sqrt(r2));
    }
  }
  return k;
}

Eigen::VectorXd MaternKernel::cross(const Eigen::MatrixXd& points, const Eigen::VectorXd& x) const {
  const Eigen::Index n = points.cols();
  Eigen::VectorXd k(n);
  const double var = variance();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double r2 = ((points.col(i) - x).array().square() * inv_sq_lengths_.array()).sum();
    k(i) = var * matern52(std::sqrt(r2));
  }
  return k;
}

void MaternKernel::cross_batch(const Eigen::MatrixXd& points, const Eigen::MatrixXd& xs,
                               Eigen::MatrixXd& k, Eigen::MatrixXd& q) const {
  // Squared scaled distances through one matrix product (|a|^2 + |b|^2 - 2 a.b), then the
  // kernel with vectorized exp: this is the optimizer's innermost loop.
  const Eigen::VectorXd inv_l = inv_sq_lengths_.cwiseSqrt();
  const Eigen::MatrixXd ps = inv_l.asDiagonal() * points;
  const Eigen::MatrixXd qs = inv_l.asDiagonal() * xs;
  Eigen::MatrixXd r2 = -2.0 * (ps.transpose() * qs);
  r2.colwise() += ps.colwise().squaredNorm().transpose();
  r2.rowwise() += qs.colwise().squaredNorm();
  const Eigen::ArrayXXd r = r2.array().max(0.0).sqrt();
  const Eigen::ArrayXXd e = variance() * (-kSqrt5 * r).exp();
  k = (e * (1.0 + kSqrt5 * r + (5.0 / 3.0) * r.square())).matrix();
  q = (e * (-(5.0 / 3.0)) * (1.0 + kSqrt5 * r)).matrix();
}

Eigen::VectorXd MaternKernel::contract_log_gradients(const Eigen::MatrixXd& points,
                                                     const Eigen::MatrixXd& m) const {
  const Eigen::Index n = points.cols();
  const Eigen::Index d = points.rows();
  Eigen::VectorXd g = Eigen::VectorXd::Zero(d + 1);
  const double var = variance();
  Eigen::ArrayXd length_acc = Eigen::ArrayXd::Zero(d);
  double amp_acc = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) {
    amp_acc += m(j, j) * var;  // diagonal: k = a^2, no length-scale dependence
    for (Eigen::Index i = j + 1; i < n; ++i) {
      const Eigen::ArrayXd sq =
          (points.col(i) - points.col(j)).array().square() * inv_sq_lengths_.array();
      const double r = std::sqrt(sq.sum());
      const double mij = m(i, j) + m(j, i);  // both triangle halves
      amp_acc += mij * var * matern52(r);
      // dr/dlog l_k = -sq_k / r, so dk/dlog l_k = -a^2 (dm/dr / r) sq_k.
      length_acc += (mij * -var * matern52_dr_over_r(r)) * sq;
    }
  }
  g(0) = 2.0 * amp_acc;  // dk/dlog a = 2k
  g.tail(d) = length_acc.matrix();
  return g;
}

}  // namespace sps
