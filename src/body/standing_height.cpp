#include "body/standing_height.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace body {

StandingHeights::StandingHeights(const Model& model) {
  const Eigen::Index v = model.vertex_count();
  if (v == 0 || model.shapedirs.rows() != 3 * v || model.v_template.rows() != v) {
    throw std::invalid_argument("standing heights: the model '" + model.name +
                                "' has no vertices or mismatched shape directions");
  }
  const Eigen::Index k = model.shapedirs.cols();
  template_y_ = model.v_template.col(1);
  unit_dirs_y_.resize(v, k);
  // beta = 6x - 3: the template plus -3 of every kept direction is the body at x = 0.
  for (Eigen::Index i = 0; i < v; ++i) {
    unit_dirs_y_.row(i) = 6.0f * model.shapedirs.row(3 * i + 1);
    template_y_[i] -= 3.0f * model.shapedirs.row(3 * i + 1).sum();
  }
}

double StandingHeights::height_m(const Eigen::VectorXd& x) const {
  if (x.size() != dims()) {
    throw std::invalid_argument("standing heights: a search point has " + std::to_string(x.size()) +
                                " entries, the model " + std::to_string(dims()));
  }
  const Eigen::VectorXf y = template_y_ + unit_dirs_y_ * x.cast<float>();
  return static_cast<double>(y.maxCoeff() - y.minCoeff());
}

double StandingHeights::tallest_m(const std::vector<Eigen::VectorXd>& xs) const {
  double tallest = 0.0;
  for (const auto& x : xs) tallest = std::max(tallest, height_m(x));
  return tallest;
}

}  // namespace body
