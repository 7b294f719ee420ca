// The body population of the default model: anthropometric factors drawn from a correlated
// distribution per sex (ANSUR II summary statistics, see docs/default-model.md), mapped to a
// deformation of the template mesh. The deformation of a vertex is a blend, by smooth
// per-bone weights, of per-bone affine maps (bone moved to its new joint, scaled along and
// across the bone) plus a breast/pectoral displacement and a vertical shift that keeps the
// soles on y = 0. It is linear in the per-body parameter vector theta, so every body is
// B * theta for one fixed basis B (3V x P); PCA can use that without materialising all bodies.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "mannequin_shape.hpp"

namespace default_model {

struct Anthropometry {
  bool female = false;
  double stature_cm = 0, weight_kg = 0, chest_cm = 0, waist_cm = 0, hip_cm = 0;
  double biacromial_cm = 0, chest_depth_cm = 0, neck_cm = 0, head_cm = 0;
  double leg_ratio_z = 0, arm_z = 0, muscle_z = 0;  // standardised, within sex
};

// Deterministic: the same seed gives the same population on every platform with IEEE doubles.
std::vector<Anthropometry> sample_population(int count, std::uint64_t seed);

// The mean person (average of the female and male means), the template's proportions.
Anthropometry mean_person();

class DeformationModel {
 public:
  DeformationModel(const std::vector<Vec3>& template_vertices, const Skeleton& skeleton,
                   const Eigen::MatrixXd& weights);

  int parameter_count() const { return static_cast<int>(basis_.cols()); }
  const Eigen::MatrixXd& basis() const { return basis_; }  // 3V x P
  Eigen::VectorXd parameters(const Anthropometry& a) const;
  Eigen::VectorXd rest_parameters() const;  // reproduces the template exactly
  Eigen::VectorXd vertices(const Eigen::VectorXd& theta) const { return basis_ * theta; }

 private:
  Eigen::MatrixXd basis_;
  Skeleton skeleton_;
  std::array<Eigen::Matrix3d, kJointCount> frames_;  // columns: along, u, v
  std::vector<int> sole_vertices_;
  std::vector<Vec3> vertices_;
  Eigen::MatrixXd weights_;
};

}  // namespace default_model
