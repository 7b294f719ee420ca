// How tall the bodies of some search points stand (top of the head above the soles), for
// framing a grid of them: bodies are linear in the betas, so each height is one product with
// the vertical rows of the shape directions and a min/max over the vertices.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "body/body_model.hpp"

namespace body {

class StandingHeights {
 public:
  // Uses the model's kept components (search points x in [0, 1], beta = 6x - 3). Throws
  // std::invalid_argument for a model without vertices or with mismatched shape directions.
  explicit StandingHeights(const Model& model);
  int dims() const { return static_cast<int>(unit_dirs_y_.cols()); }
  // Metres from the lowest to the highest vertex of the body of x (a standing body's height).
  // Throws std::invalid_argument when x has the wrong size.
  double height_m(const Eigen::VectorXd& x) const;
  // The largest height_m of the points (0 for none).
  double tallest_m(const std::vector<Eigen::VectorXd>& xs) const;

 private:
  Eigen::VectorXf template_y_;   // V: the template's heights at beta = 0
  Eigen::MatrixXf unit_dirs_y_;  // V x K: d y / d x (6 * the shape directions' vertical rows)
};

}  // namespace body
