#include "spaces/body_holds.hpp"

#include <cmath>
#include <utility>

#include "body/measurement_solve.hpp"

namespace spaces {

namespace {

// The held measurements: points solved onto them by Gauss-Newton steps (the cells of a plane
// reusing the Jacobian at its centre), normals their Jacobian (central differences,
// body/measurement_solve.hpp).
class BodyHolds : public app::ConstraintProjector {
 public:
  explicit BodyHolds(std::shared_ptr<const body::MeasurementConstraints> constraints)
      : constraints_(std::move(constraints)) {}
  Eigen::VectorXd project(const Eigen::VectorXd& x) const override {
    return constraints_->solve(x).x;
  }
  Eigen::MatrixXd normals(const Eigen::VectorXd& x) const override {
    return constraints_->jacobian(x);
  }
  // A cell stops as soon as it is inside the tolerance, so a few steps from the centre's
  // Jacobian do (a new Jacobian per cell would cost a measurement per coordinate).
  Eigen::VectorXd project_near(const Eigen::VectorXd& x,
                               const Eigen::MatrixXd& nearby_normals) const override {
    return constraints_->solve(x, 10, &nearby_normals).x;
  }
  std::string description() const override {
    std::string text;
    for (const auto& t : constraints_->targets()) {
      text += (text.empty() ? "" : ", ") + std::string(t.kind->name) + " " +
              body::format_measurement(t.kind->quantity, t.value, body::Units::kMetric);
    }
    return text;
  }
  std::vector<app::HeldValue> held_values() const override {
    std::vector<app::HeldValue> held;
    for (const auto& t : constraints_->targets()) held.push_back({t.kind->name, t.value});
    return held;
  }

 private:
  std::shared_ptr<const body::MeasurementConstraints> constraints_;
};

}  // namespace

std::shared_ptr<const app::ConstraintProjector> make_body_holds(
    std::shared_ptr<const body::Model> model, const std::vector<std::string>& holds,
    const Eigen::VectorXd& reference) {
  std::vector<body::MeasurementTarget> targets;
  for (const auto& text : holds) targets.push_back(body::parse_target(text, false));
  if (targets.empty()) return nullptr;
  const body::Measurements at = body::measure(*model, body::betas_from_unit(reference));
  for (auto& t : targets) {
    if (std::isnan(t.value)) t.value = at.*(t.kind->field);
  }
  // A hold no body in the search range meets (height 0.5 m, BMI 60, or height, mass and BMI
  // that disagree) would show nine copies of the nearest body and end every plane at once:
  // refuse it as a target is refused, with the nearest reachable values.
  {
    const body::MeasurementConstraints check(model, targets);
    const body::SolveResult reachable = check.solve(reference);
    if (!reachable.reached) throw std::invalid_argument(reachable.message);
  }
  // Cells aim for 30% of the hold tolerance (3 mm, 0.45 kg), leaving room for the
  // Gauss-Newton steps that stop as soon as they are inside it.
  return std::make_shared<BodyHolds>(
      std::make_shared<const body::MeasurementConstraints>(std::move(model), targets, 0.3));
}

}  // namespace spaces
