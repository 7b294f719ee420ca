// Bodies that meet typed measurements: "1.80 m, about 85 kg".
//
// The measurement functions m(x) of a body model are piecewise smooth in the shape
// coordinates x in [0,1]^K (beta = 6x - 3): height, volume and the joint lengths are smooth;
// girths and the crotch come from slices and ray hits that move from one triangle to the next.
// Jacobians are taken by central differences with a step of 0.01 in x (0.06 standard
// deviations), far wider than the triangle-to-triangle kinks, so the Gauss-Newton steps see
// the smooth trend.
//
// The solve is a constrained least-squares problem: the point nearest to a start point (the
// smallest change of the betas) whose measurements are within tolerance of the targets, inside
// the search box. Each step is the minimum-norm Gauss-Newton step towards the start point
// under the linearized constraints, on the coordinates not pinned at a bound (an active set),
// with a backtracking line search on the residual. When the targets cannot all be met inside
// the box the same iteration ends at the least-squares point (the nearest reachable values),
// and the result says so.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "body/body_model.hpp"
#include "body/measurements.hpp"

namespace body {

struct MeasurementTarget {
  const MeasurementKind* kind = nullptr;
  double value = 0.0;  // SI (metres, kg, kg/m^2)
};

// "height=1.80" or "mass=85kg" -> a target; throws std::invalid_argument naming the problem
// (unknown name: the list of names; bad value: see parse_measurement_value). `value_required`
// false accepts a bare "height" (value NaN: the caller fills in the start body's value).
MeasurementTarget parse_target(const std::string& text, bool value_required = true);

// `targets` followed by the held values that are not targets too: the body a target solve
// finds must keep what is held. A target on a held measurement must agree with the hold
// (within its tolerance): throws std::invalid_argument naming both otherwise. Holds without a
// value (NaN) are skipped.
std::vector<MeasurementTarget> targets_with_holds(std::vector<MeasurementTarget> targets,
                                                  const std::vector<MeasurementTarget>& holds);

struct SolveResult {
  Eigen::VectorXd x;           // in [0,1]^K
  bool reached = false;        // every target within its tolerance
  std::vector<double> values;  // the targets' measurements at x, in the targets' order
  int iterations = 0;
  int evaluations = 0;  // bodies measured
  // For the user: what was reached, or which targets could not be met and the nearest
  // reachable values ("height 2.60 m is out of reach in the search range (+-3 SD); nearest
  // reachable: height 2.07 m").
  std::string message;
};

class MeasurementConstraints {
 public:
  // Throws std::invalid_argument when a target is NaN, named twice, not measurable on this
  // model (e.g. shoulder_width without shoulder joints), or when height, mass and bmi are all
  // given with values that disagree (BMI is mass / height^2: no body meets all three).
  // `tolerance_share` scales each kind's hold tolerance (1 cm, 1.5 kg...) into the tolerance a
  // solve aims for.
  MeasurementConstraints(std::shared_ptr<const Model> model, std::vector<MeasurementTarget> targets,
                         double tolerance_share = 0.5);

  const std::vector<MeasurementTarget>& targets() const { return targets_; }
  int dims() const { return model_->component_count(); }
  bool empty() const { return targets_.empty(); }

  // The targets' measurements of the body at x (NaN where the landmark is missing).
  Eigen::VectorXd values(const Eigen::VectorXd& x) const;
  // d values / d x (rows: targets), central differences (one-sided at the box's faces).
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& x) const;
  // The columns of `dirs` projected onto the directions that leave every target's measurement
  // unchanged to first order at x (the null space of jacobian(x)).
  Eigen::MatrixXd tangent(const Eigen::VectorXd& x, const Eigen::MatrixXd& dirs) const;
  // The same with the Jacobian given (rows: targets).
  static Eigen::MatrixXd tangent(const Eigen::MatrixXd& jacobian, const Eigen::MatrixXd& dirs);

  // The point nearest to `start` (in x, inside the box) meeting the targets. With
  // `jacobian_hint` the iteration reuses that Jacobian (e.g. the plane centre's for the nine
  // cells of a grid) and takes a fresh one only when a step fails to reduce the residual.
  SolveResult solve(const Eigen::VectorXd& start, int max_iterations = 30,
                    const Eigen::MatrixXd* jacobian_hint = nullptr) const;

 private:
  Eigen::VectorXd scaled_residual(const Eigen::VectorXd& values) const;

  std::shared_ptr<const Model> model_;
  std::vector<MeasurementTarget> targets_;
  Eigen::VectorXd tolerance_;  // per target
  bool girths_ = false;        // some target needs the slices
  unsigned bands_ = 0;         // and which (measure()'s GirthBand)
};

}  // namespace body
