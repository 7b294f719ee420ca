#include "sps/bounded_maximizer.hpp"

#include <cmath>
#include <exception>
#include <limits>

#include <LBFGSB.h>

namespace sps {

MaximizeResult maximize_bounded(const Objective& f, const Eigen::VectorXd& x0,
                                const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                int max_iterations, double gradient_tolerance) {
  MaximizeResult best;
  best.x = x0.cwiseMax(lower).cwiseMin(upper);
  best.value = -std::numeric_limits<double>::infinity();

  // LBFGS++ minimizes; track the best point ourselves since a failed line search throws.
  auto negated = [&](const Eigen::VectorXd& x, Eigen::VectorXd& grad) {
    const double value = f(x, grad);
    ++best.evaluations;
    if (!std::isfinite(value) || !grad.allFinite()) {
      grad.setZero();
      return std::numeric_limits<double>::max();
    }
    if (value > best.value) {
      best.value = value;
      best.x = x;
    }
    grad = -grad;
    return -value;
  };

  LBFGSpp::LBFGSBParam<double> param;
  param.epsilon = gradient_tolerance;
  param.epsilon_rel = 0.0;
  param.max_iterations = max_iterations;
  param.max_linesearch = 30;
  param.past = 3;
  param.delta = 1e-10;
  LBFGSpp::LBFGSBSolver<double> solver(param);
  Eigen::VectorXd x = best.x;
  double fx = 0.0;
  try {
    solver.minimize(negated, x, fx, lower, upper);
  } catch (const std::exception&) {
    // Keep the best point evaluated so far.
  }
  if (!std::isfinite(best.value)) {
    Eigen::VectorXd grad(x0.size());
    best.value = f(best.x, grad);
  }
  return best;
}

}  // namespace sps
