#include "spaces/body_holds.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "body/measurement_solve.hpp"

namespace spaces {

namespace {

// A plane held on measurements: the centre solved onto them, the directions in their tangent
// space (rescaled to the optimizer's lengths so the grid keeps its spread), and every cell
// projected by Gauss-Newton steps that reuse the centre's Jacobian.
class HeldBodyPlane : public app::HeldPlane {
 public:
  HeldBodyPlane(std::shared_ptr<const body::MeasurementConstraints> constraints,
                const sps::Plane& original)
      : constraints_(std::move(constraints)) {
    plane = original;
    plane.c = constraints_->solve(original.c).x;
    jacobian_ = constraints_->jacobian(plane.c);
    const auto tangent = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
      if (d.size() != plane.c.size() || d.isZero(0.0)) return d;
      return constraints_->tangent(jacobian_, d);
    };
    Eigen::VectorXd u = tangent(original.u);
    Eigen::VectorXd v = tangent(original.v);
    if (u.norm() > 1e-9) u *= original.u.norm() / u.norm();
    if (!plane.is_line() && v.norm() > 1e-9) {
      if (u.norm() > 1e-9) v -= v.dot(u) / u.squaredNorm() * u;  // keep the rhombus square
      if (v.norm() > 1e-9) v *= original.v.norm() / v.norm();
    }
    plane.u = u;
    plane.v = v;
    // The paper's opposite-vertex correction for the new directions: c - s u inside the box.
    plane.u_neg_scale = 1.0;
    for (Eigen::Index k = 0; k < u.size(); ++k) {
      if (plane.c[k] - u[k] < 0.0)
        plane.u_neg_scale = std::min(plane.u_neg_scale, plane.c[k] / u[k]);
      if (plane.c[k] - u[k] > 1.0) {
        plane.u_neg_scale = std::min(plane.u_neg_scale, (plane.c[k] - 1.0) / u[k]);
      }
    }
    plane.u_neg_scale = std::max(0.0, plane.u_neg_scale);
  }

  Eigen::VectorXd project(const Eigen::VectorXd& x) const override {
    return constraints_->solve(x, 10, &jacobian_).x;
  }

 private:
  std::shared_ptr<const body::MeasurementConstraints> constraints_;
  Eigen::MatrixXd jacobian_;
};

// The held measurements as the optimizer's surface: points solved onto them, normals their
// Jacobian (central differences, body/measurement_solve.hpp).
class MeasurementSurface : public sps::SearchHold {
 public:
  explicit MeasurementSurface(std::shared_ptr<const body::MeasurementConstraints> constraints)
      : constraints_(std::move(constraints)) {}
  Eigen::VectorXd project(const Eigen::VectorXd& x) const override {
    return constraints_->solve(x).x;
  }
  Eigen::MatrixXd normals(const Eigen::VectorXd& x) const override {
    return constraints_->jacobian(x);
  }

 private:
  std::shared_ptr<const body::MeasurementConstraints> constraints_;
};

class BodyHolds : public app::ConstraintProjector {
 public:
  explicit BodyHolds(std::shared_ptr<const body::MeasurementConstraints> constraints)
      : constraints_(constraints),
        surface_(std::make_shared<const MeasurementSurface>(std::move(constraints))) {}
  std::shared_ptr<const sps::SearchHold> search_hold() const override { return surface_; }
  std::shared_ptr<const app::HeldPlane> hold(const sps::Plane& plane) const override {
    return std::make_shared<HeldBodyPlane>(constraints_, plane);
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
  std::shared_ptr<const MeasurementSurface> surface_;
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
