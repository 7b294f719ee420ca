#include "body/measurement_solve.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

namespace body {

MeasurementTarget parse_target(const std::string& text, bool value_required) {
  const auto eq = text.find('=');
  const std::string name = text.substr(0, eq);
  const MeasurementKind* kind = find_measurement(name);
  if (kind == nullptr) {
    throw std::invalid_argument("unknown measurement '" + name + "' in '" + text +
                                "' (known: " + measurement_names() + ")");
  }
  if (eq == std::string::npos) {
    if (value_required) {
      throw std::invalid_argument("'" + text + "' needs a value, e.g. " + name +
                                  (kind->quantity == Quantity::kMass ? "=85" : "=1.80"));
    }
    return {kind, std::numeric_limits<double>::quiet_NaN()};
  }
  return {kind, parse_measurement_value(*kind, text.substr(eq + 1))};
}

namespace {

const MeasurementTarget* find_kind(const std::vector<MeasurementTarget>& targets,
                                   const char* name) {
  for (const auto& t : targets) {
    if (t.kind != nullptr && std::string(t.kind->name) == name) return &t;
  }
  return nullptr;
}

// BMI is mass / height^2, so the three cannot be chosen freely: refuse values that no body
// has, allowing for each one's tolerance (first-order propagation of the height and mass
// tolerances into BMI).
void check_bmi_agrees(const std::vector<MeasurementTarget>& targets) {
  const auto* h = find_kind(targets, "height");
  const auto* m = find_kind(targets, "mass");
  const auto* b = find_kind(targets, "bmi");
  if (h == nullptr || m == nullptr || b == nullptr) return;
  if (!(h->value > 0.0) || !(m->value > 0.0) || !std::isfinite(b->value)) return;
  const double implied = m->value / (h->value * h->value);
  const double allowed = b->kind->hold_tolerance + m->kind->hold_tolerance / (h->value * h->value) +
                         2.0 * implied * h->kind->hold_tolerance / h->value;
  if (std::abs(implied - b->value) <= allowed) return;
  throw std::invalid_argument(
      "height " + format_measurement(h->kind->quantity, h->value, Units::kMetric) + " and mass " +
      format_measurement(m->kind->quantity, m->value, Units::kMetric) + " make a BMI of " +
      format_measurement(b->kind->quantity, implied, Units::kMetric) + ", not " +
      format_measurement(b->kind->quantity, b->value, Units::kMetric) +
      ": no body has all three; give two of height, mass and bmi, or values that agree");
}

}  // namespace

std::vector<MeasurementTarget> targets_with_holds(std::vector<MeasurementTarget> targets,
                                                  const std::vector<MeasurementTarget>& holds) {
  const std::size_t typed = targets.size();
  for (const auto& hold : holds) {
    if (hold.kind == nullptr || std::isnan(hold.value)) continue;
    bool named = false;
    for (std::size_t i = 0; i < typed; ++i) {
      if (targets[i].kind != hold.kind) continue;
      named = true;
      if (std::abs(targets[i].value - hold.value) > hold.kind->hold_tolerance) {
        const auto q = hold.kind->quantity;
        throw std::invalid_argument("the target " + std::string(hold.kind->name) + " " +
                                    format_measurement(q, targets[i].value, Units::kMetric) +
                                    " contradicts the hold on " + hold.kind->name + " at " +
                                    format_measurement(q, hold.value, Units::kMetric) +
                                    ": release the hold or aim for the held value");
      }
    }
    if (!named) targets.push_back(hold);
  }
  return targets;
}

MeasurementConstraints::MeasurementConstraints(std::shared_ptr<const Model> model,
                                               std::vector<MeasurementTarget> targets,
                                               double tolerance_share)
    : model_(std::move(model)), targets_(std::move(targets)) {
  if (!model_) throw std::invalid_argument("measurement targets need a body model");
  tolerance_.resize(static_cast<Eigen::Index>(targets_.size()));
  for (std::size_t i = 0; i < targets_.size(); ++i) {
    const auto& t = targets_[i];
    if (t.kind == nullptr) throw std::invalid_argument("a measurement target has no name");
    if (!std::isfinite(t.value) || t.value <= 0.0) {
      throw std::invalid_argument(std::string("target ") + t.kind->name + " has no valid value");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (targets_[j].kind == t.kind) {
        throw std::invalid_argument(std::string(t.kind->name) + " is given twice");
      }
    }
    girths_ = girths_ || t.kind->needs_girths;
    bands_ |= girth_band(*t.kind);
    tolerance_[static_cast<Eigen::Index>(i)] = tolerance_share * t.kind->hold_tolerance;
  }
  check_bmi_agrees(targets_);
  if (!targets_.empty()) {
    const Eigen::VectorXd mean = values(Eigen::VectorXd::Constant(dims(), 0.5));
    for (std::size_t i = 0; i < targets_.size(); ++i) {
      if (!std::isfinite(mean[static_cast<Eigen::Index>(i)])) {
        throw std::invalid_argument(std::string(targets_[i].kind->name) +
                                    " cannot be measured on model \"" + model_->name +
                                    "\" (see src/body/measurements.hpp for what it needs)");
      }
    }
  }
}

Eigen::VectorXd MeasurementConstraints::values(const Eigen::VectorXd& x) const {
  const Measurements m = measure(*model_, betas_from_unit(x), girths_, bands_);
  Eigen::VectorXd v(static_cast<Eigen::Index>(targets_.size()));
  for (std::size_t i = 0; i < targets_.size(); ++i) {
    v[static_cast<Eigen::Index>(i)] = m.*(targets_[i].kind->field);
  }
  return v;
}

Eigen::MatrixXd MeasurementConstraints::jacobian(const Eigen::VectorXd& x) const {
  constexpr double h = 0.01;
  Eigen::MatrixXd J(static_cast<Eigen::Index>(targets_.size()), x.size());
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    Eigen::VectorXd lo = x, hi = x;
    lo[k] = std::max(0.0, x[k] - h);
    hi[k] = std::min(1.0, x[k] + h);
    J.col(k) = (values(hi) - values(lo)) / (hi[k] - lo[k]);
  }
  return J;
}

Eigen::MatrixXd MeasurementConstraints::tangent(const Eigen::VectorXd& x,
                                                const Eigen::MatrixXd& dirs) const {
  if (targets_.empty()) return dirs;
  return tangent(jacobian(x), dirs);
}

Eigen::MatrixXd MeasurementConstraints::tangent(const Eigen::MatrixXd& J,
                                                const Eigen::MatrixXd& dirs) {
  if (J.rows() == 0) return dirs;
  // P = I - J^T (J J^T)^+ J, with a pseudo-inverse so dependent targets (height and BMI and
  // mass together) do not blow up.
  const Eigen::MatrixXd JJt = J * J.transpose();
  const Eigen::MatrixXd inv = JJt.completeOrthogonalDecomposition().pseudoInverse();
  return dirs - J.transpose() * (inv * (J * dirs));
}

Eigen::VectorXd MeasurementConstraints::scaled_residual(const Eigen::VectorXd& values) const {
  Eigen::VectorXd r(values.size());
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    r[i] = (values[i] - targets_[static_cast<std::size_t>(i)].value) / tolerance_[i];
  }
  return r;
}

namespace {

// The residual's size for accepting steps: NaN (a landmark lost) counts as infinitely far.
double size_of(const Eigen::VectorXd& r) {
  return r.allFinite() ? r.norm() : std::numeric_limits<double>::infinity();
}

}  // namespace

SolveResult MeasurementConstraints::solve(const Eigen::VectorXd& start, int max_iterations,
                                          const Eigen::MatrixXd* jacobian_hint) const {
  if (start.size() != dims()) throw std::invalid_argument("solve: start point has the wrong size");
  const Eigen::Index K = start.size();
  const Eigen::VectorXd x0 = start.cwiseMax(0.0).cwiseMin(1.0);
  SolveResult result;
  result.x = x0;
  if (targets_.empty()) {
    result.reached = true;
    return result;
  }
  const Eigen::Index m = static_cast<Eigen::Index>(targets_.size());
  const Eigen::VectorXd tol_inv = tolerance_.cwiseInverse();
  Eigen::VectorXd x = x0;
  Eigen::VectorXd r = scaled_residual(values(x));
  ++result.evaluations;
  // The Jacobian is taken only when a step is needed: a start point that already meets the
  // targets (a plane's centre the optimizer put on them, a cell near it) costs one body.
  Eigen::MatrixXd J;
  bool fresh = false;
  const bool hinted =
      jacobian_hint != nullptr && jacobian_hint->rows() == m && jacobian_hint->cols() == K;
  if (hinted) J = tol_inv.asDiagonal() * *jacobian_hint;
  bool pull = true;
  for (int it = 0; it < max_iterations; ++it) {
    result.iterations = it + 1;
    // Within tolerance: done (the start point itself when it already meets the targets; each
    // step below moved towards the start point as far as the constraints allowed).
    if (r.allFinite() && r.cwiseAbs().maxCoeff() <= 1.0) break;
    if (J.size() == 0) {
      J = tol_inv.asDiagonal() * jacobian(x);
      result.evaluations += static_cast<int>(2 * K);
      fresh = true;
    }
    // Minimum-norm step towards x0 on the free coordinates: the linearized constraint
    // r + J (x' - x) = 0 with the smallest |x' - x0|. Coordinates that the step would push
    // through a face of the box are pinned there and the step is recomputed (an active set).
    std::vector<bool> pinned(static_cast<std::size_t>(K), false);
    Eigen::VectorXd next = x;
    for (int pass = 0; pass < 4; ++pass) {
      Eigen::MatrixXd Jf = J;
      Eigen::VectorXd fixed = Eigen::VectorXd::Zero(K);  // pinned coordinates go to the face
      // Desired move of the free coordinates: towards x0, unless that pull has stalled the
      // solve (below), then none.
      Eigen::VectorXd d0 = pull ? Eigen::VectorXd(x0 - x) : Eigen::VectorXd::Zero(K);
      for (Eigen::Index k = 0; k < K; ++k) {
        if (!pinned[static_cast<std::size_t>(k)]) continue;
        fixed[k] = (next[k] < 0.5 ? 0.0 : 1.0) - x[k];
        Jf.col(k).setZero(), d0[k] = 0.0;
      }
      // x' = x + fixed + d0 + Jf^T y with r + J (x' - x) = 0: the free part of the move is
      // the one nearest to d0. Damped so an ill-conditioned J takes a shorter step.
      const Eigen::MatrixXd A = Jf * Jf.transpose();
      const double damping = 1e-9 * std::max(1.0, A.trace() / static_cast<double>(m));
      const Eigen::VectorXd rhs = -r - J * fixed - Jf * d0;
      const Eigen::VectorXd y = (A + damping * Eigen::MatrixXd::Identity(m, m)).ldlt().solve(rhs);
      const Eigen::VectorXd step = fixed + d0 + Jf.transpose() * y;
      next = x + step;
      bool changed = false;
      for (Eigen::Index k = 0; k < K; ++k) {
        if (!pinned[static_cast<std::size_t>(k)] && (next[k] < 0.0 || next[k] > 1.0)) {
          pinned[static_cast<std::size_t>(k)] = true;
          changed = true;
        }
      }
      if (!changed) break;
    }
    next = next.cwiseMax(0.0).cwiseMin(1.0);
    // Backtracking on the residual (the constraints come first; the pull towards x0 is only
    // followed while it does not lose them).
    const double before = size_of(r);
    bool accepted = false;
    double alpha = 1.0;
    for (int ls = 0; ls < 6; ++ls, alpha *= 0.5) {
      const Eigen::VectorXd trial = x + alpha * (next - x);
      const Eigen::VectorXd rt = scaled_residual(values(trial));
      ++result.evaluations;
      if (size_of(rt) < before || (rt.allFinite() && rt.cwiseAbs().maxCoeff() <= 1.0)) {
        x = trial, r = rt, accepted = true;
        break;
      }
    }
    if (!accepted) {
      if (fresh && pull) {
        // Stalled by the pull towards x0 on a measurement that curves (a waist that moves
        // between slices): the constraints alone from here, a Gauss-Newton step of least size
        // (waist 108 cm on the neutral model, +1.8 SD, had stopped at 107.4 cm).
        pull = false;
        continue;
      }
      if (fresh) break;  // no descent even with a fresh Jacobian: the least-squares point
      J = tol_inv.asDiagonal() * jacobian(x);
      result.evaluations += static_cast<int>(2 * K);
      fresh = true;
      continue;
    }
    if (!hinted || alpha < 1.0) {
      J = tol_inv.asDiagonal() * jacobian(x);
      result.evaluations += static_cast<int>(2 * K);
      fresh = true;
    } else {
      fresh = false;
    }
  }
  result.x = x;
  // r is always the residual at x: its values without measuring the body again.
  Eigen::VectorXd v = r.cwiseProduct(tolerance_);
  for (Eigen::Index i = 0; i < m; ++i) v[i] += targets_[static_cast<std::size_t>(i)].value;
  result.values.assign(v.data(), v.data() + v.size());
  const Eigen::VectorXd& rf = r;
  result.reached = rf.allFinite() && rf.cwiseAbs().maxCoeff() <= 1.0;
  std::string missed, nearest;
  for (std::size_t i = 0; i < targets_.size(); ++i) {
    const auto& t = targets_[i];
    const auto q = t.kind->quantity;
    nearest += (nearest.empty() ? "" : ", ") + std::string(t.kind->name) + " " +
               format_measurement(q, v[static_cast<Eigen::Index>(i)], Units::kMetric);
    if (!(std::abs(rf[static_cast<Eigen::Index>(i)]) <= 1.0)) {
      missed += (missed.empty() ? "" : ", ") + std::string(t.kind->name) + " " +
                format_measurement(q, t.value, Units::kMetric);
    }
  }
  result.message = result.reached
                       ? "reached " + nearest
                       : "out of reach in the search range (+-3 SD of model \"" + model_->name +
                             "\"): " + missed + "; nearest reachable: " + nearest;
  return result;
}

}  // namespace body
