// Bounded quasi-Newton maximization (L-BFGS-B from LBFGS++) that never throws and never loses
// the best point seen: line-search failures near a flat optimum are normal here, and then the
// best evaluated point is the answer.
#pragma once

#include <functional>

#include <Eigen/Core>

namespace sps {

// f(x, grad) returns the value at x and writes the gradient (to be MAXIMIZED).
using Objective = std::function<double(const Eigen::VectorXd& x, Eigen::VectorXd& grad)>;

struct MaximizeResult {
  Eigen::VectorXd x;
  double value = 0.0;
  int evaluations = 0;
};

MaximizeResult maximize_bounded(const Objective& f, const Eigen::VectorXd& x0,
                                const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                int max_iterations, double gradient_tolerance = 1e-6);

}  // namespace sps
