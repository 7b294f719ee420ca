#include "sps/target_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "sps/bounded_maximizer.hpp"
#include "sps/perceptual_metric.hpp"

namespace sps {

namespace {

// Keeps the distance differentiable where t meets a data point (mm^2).
constexpr double kSmoothingMm2 = 1e-6;

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("target model: " + what);
}

// The rows of `normals` as held quantities' gradients in d dimensions (none: nothing held).
void require_normals(const Eigen::MatrixXd& normals, Eigen::Index d) {
  require(normals.rows() == 0 || (normals.cols() == d && normals.allFinite()),
          "the held normals need " + std::to_string(d) + " finite columns");
}

// Conditioning a Gaussian with covariance C on linear observations K x: the gain
// C K^T (K C K^T)^+, with the pseudo-inverse so that dependent or vanishing rows condition on
// what they do say. The mean moves by gain (values - K mean), the covariance loses gain K C.
Eigen::MatrixXd conditioning_gain(const Eigen::MatrixXd& covariance, const Eigen::MatrixXd& known) {
  const Eigen::MatrixXd ck = covariance * known.transpose();
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> kck(known * ck);
  return kck.solve(ck.transpose()).transpose();  // K C K^T is symmetric
}

}  // namespace

void validate_target_model(const TargetModel& model, int dims) {
  const auto n = static_cast<Eigen::Index>(dims);
  require(model.metric.dims() == n && model.population.mean.size() == n &&
              model.population.sd.size() == n,
          "the perceptual metric, population mean and SD need " + std::to_string(dims) +
              " dimensions each");
  require(model.population.sd.allFinite() && (model.population.sd.array() > 0.0).all(),
          "every population SD must be positive and finite");
  require(model.population.mean.allFinite() && (model.population.mean.array() >= 0.0).all() &&
              (model.population.mean.array() <= 1.0).all(),
          "the population mean must lie in [0, 1]");
  const Eigen::MatrixXd& r = model.population.correlation;
  if (r.size() > 0) {
    require(r.rows() == n && r.cols() == n, "the population correlation needs " +
                                                std::to_string(dims) + " x " +
                                                std::to_string(dims) + " entries");
    require(r.allFinite() && (r - r.transpose()).cwiseAbs().maxCoeff() < 1e-9 &&
                (r.diagonal().array() - 1.0).abs().maxCoeff() < 1e-9,
            "the population correlation must be finite and symmetric with ones on its diagonal");
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(r, Eigen::EigenvaluesOnly);
    require(eigen.eigenvalues().minCoeff() > 1e-6,
            "the population correlation must be positive definite");
  }
  require(std::isfinite(model.temperature_mm) && model.temperature_mm > 0.0 &&
              model.temperature_mm <= 1e4,
          "the choice temperature must lie in (0, 10000] mm");
  require(std::isfinite(model.region_slack_temperatures) && model.region_slack_temperatures <= 1e3,
          "the choice regions' slack must be finite and at most 1000 temperatures");
}

Eigen::MatrixXd population_covariance(const Population& population) {
  if (population.correlation.size() == 0) return population.sd.cwiseAbs2().asDiagonal();
  return population.sd.asDiagonal() * population.correlation * population.sd.asDiagonal();
}

Eigen::MatrixXd population_precision(const Population& population) {
  const Eigen::VectorXd inv_sd = population.sd.cwiseInverse();
  if (population.correlation.size() == 0) return inv_sd.cwiseAbs2().asDiagonal();
  const Eigen::Index d = population.sd.size();
  const Eigen::MatrixXd inv_r =
      population.correlation.ldlt().solve(Eigen::MatrixXd::Identity(d, d));
  const Eigen::MatrixXd precision = inv_sd.asDiagonal() * inv_r * inv_sd.asDiagonal();
  return 0.5 * (precision + precision.transpose());
}

namespace {

// Every shown point's utility for a person with t in mind, -distance / temperature, and its
// gradient in t (one column per point).
struct PointUtilities {
  Eigen::VectorXd value;
  Eigen::MatrixXd gradient;
};

PointUtilities point_utilities(const PreferenceData& data, const TargetModel& model,
                               const Eigen::VectorXd& t) {
  const Eigen::MatrixXd& points = data.points();
  const double inv_temp = 1.0 / model.temperature_mm;
  PointUtilities u{Eigen::VectorXd(points.cols()), Eigen::MatrixXd(t.size(), points.cols())};
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const Eigen::VectorXd diff = points.col(i) - t;
    const Eigen::VectorXd weighted = model.metric.weighted(diff);
    const double distance = std::sqrt(diff.dot(weighted) + kSmoothingMm2);
    u.value(i) = -distance * inv_temp;
    u.gradient.col(i) = weighted * (inv_temp / distance);
  }
  return u;
}

// The points compared in one choice (the chosen first) and the softmax of their utilities;
// returns the log of the softmax's normaliser.
double choice_softmax(const Preference& p, const Eigen::VectorXd& utility,
                      std::vector<int>& members, Eigen::VectorXd& weight) {
  members.assign(1, p.chosen);
  members.insert(members.end(), p.others.begin(), p.others.end());
  double top = -std::numeric_limits<double>::infinity();
  for (int j : members) top = std::max(top, utility(j));
  weight.resize(static_cast<Eigen::Index>(members.size()));
  for (std::size_t m = 0; m < members.size(); ++m) {
    weight(static_cast<Eigen::Index>(m)) = std::exp(utility(members[m]) - top);
  }
  const double sum = weight.sum();
  weight /= sum;
  return top + std::log(sum);
}

// target_log_posterior with the population's precision given (the estimate's optimizer
// calls it many times with one model).
double log_posterior(const PreferenceData& data, const TargetModel& model,
                     const Eigen::MatrixXd& precision, const Eigen::VectorXd& t,
                     Eigen::VectorXd* gradient) {
  const PointUtilities u = point_utilities(data, model, t);
  const Eigen::VectorXd offset = t - model.population.mean;
  const Eigen::VectorXd pulled = precision * offset;
  double value = -0.5 * offset.dot(pulled);
  if (gradient != nullptr) *gradient = -pulled;
  std::vector<int> members;
  Eigen::VectorXd weight;
  for (const Preference& p : data.preferences()) {
    value += u.value(p.chosen) - choice_softmax(p, u.value, members, weight);
    if (gradient != nullptr) {
      *gradient += u.gradient.col(p.chosen);
      for (std::size_t m = 0; m < members.size(); ++m) {
        *gradient -= weight(static_cast<Eigen::Index>(m)) * u.gradient.col(members[m]);
      }
    }
  }
  return value;
}

}  // namespace

double target_log_posterior(const PreferenceData& data, const TargetModel& model,
                            const Eigen::VectorXd& t, Eigen::VectorXd* gradient) {
  return log_posterior(data, model, population_precision(model.population), t, gradient);
}

Eigen::VectorXd estimate_target(const PreferenceData& data, const TargetModel& model,
                                const Eigen::VectorXd& start) {
  validate_target_model(model, data.dims());
  const Eigen::Index d = data.dims();
  const Eigen::VectorXd lower = Eigen::VectorXd::Zero(d);
  const Eigen::VectorXd upper = Eigen::VectorXd::Ones(d);
  const Eigen::VectorXd typical = model.population.mean.cwiseMax(0.0).cwiseMin(1.0);
  if (data.preference_count() == 0) return typical;
  const Eigen::MatrixXd precision = population_precision(model.population);
  const Objective objective = [&](const Eigen::VectorXd& t, Eigen::VectorXd& gradient) {
    return log_posterior(data, model, precision, t, &gradient);
  };
  MaximizeResult best;
  best.value = -std::numeric_limits<double>::infinity();
  for (const Eigen::VectorXd& from :
       {Eigen::VectorXd(start.cwiseMax(0.0).cwiseMin(1.0)), typical}) {
    if (from.size() != d || !from.allFinite()) continue;
    const MaximizeResult result = maximize_bounded(objective, from, lower, upper, 200, 1e-8);
    if (result.value > best.value) best = result;
  }
  return best.x.size() == d ? best.x : typical;
}

Eigen::MatrixXd target_posterior_covariance(const PreferenceData& data, const TargetModel& model,
                                            const Eigen::VectorXd& t) {
  validate_target_model(model, data.dims());
  const Eigen::Index d = data.dims();
  require(t.size() == d && t.allFinite(),
          "the estimate needs " + std::to_string(d) + " finite entries");
  const PointUtilities u = point_utilities(data, model, t);
  Eigen::MatrixXd information = population_precision(model.population);
  std::vector<int> members;
  Eigen::VectorXd weight;
  for (const Preference& p : data.preferences()) {
    choice_softmax(p, u.value, members, weight);
    Eigen::VectorXd mean_gradient = Eigen::VectorXd::Zero(d);
    for (std::size_t m = 0; m < members.size(); ++m) {
      mean_gradient += weight(static_cast<Eigen::Index>(m)) * u.gradient.col(members[m]);
    }
    for (std::size_t m = 0; m < members.size(); ++m) {
      const Eigen::VectorXd centred = u.gradient.col(members[m]) - mean_gradient;
      information.noalias() +=
          weight(static_cast<Eigen::Index>(m)) * (centred * centred.transpose());
    }
  }
  if (model.region_slack_temperatures >= 0.0) {
    const double slack = model.region_slack_temperatures * model.temperature_mm;
    const Eigen::MatrixXd& points = data.points();
    for (const Preference& p : data.preferences()) {
      for (const int other : p.others) {
        const Eigen::VectorXd apart = points.col(other) - points.col(p.chosen);
        const Eigen::VectorXd weighted = model.metric.weighted(apart);
        const double length = std::sqrt(std::max(0.0, apart.dot(weighted)));
        if (!(length > 1e-9)) continue;  // the same point shown twice says nothing
        // The seen distance along the joining line, per unit of t: weighted / length.
        const Eigen::VectorXd along = weighted / length;
        const double width = length + slack;
        information.noalias() += (6.0 / (width * width)) * (along * along.transpose());
      }
    }
  }
  const Eigen::MatrixXd symmetric = 0.5 * (information + information.transpose());
  return symmetric.ldlt().solve(Eigen::MatrixXd::Identity(d, d));
}

Eigen::MatrixXd covariance_given_holds(const Eigen::MatrixXd& covariance,
                                       const Eigen::MatrixXd& normals) {
  const Eigen::Index d = covariance.rows();
  require(covariance.cols() == d && covariance.allFinite(),
          "the covariance must be a finite square matrix");
  require_normals(normals, d);
  if (normals.rows() == 0) return covariance;
  const Eigen::MatrixXd conditioned =
      covariance - conditioning_gain(covariance, normals) * normals * covariance;
  return 0.5 * (conditioned + conditioned.transpose());
}

Eigen::VectorXd estimate_given_holds(const Eigen::VectorXd& t, const Eigen::VectorXd& nearest,
                                     const Eigen::MatrixXd& covariance,
                                     const Eigen::MatrixXd& normals) {
  const Eigen::Index d = t.size();
  require(t.allFinite() && nearest.size() == d && nearest.allFinite(),
          "the estimate and its nearest held point need " + std::to_string(d) + " finite entries");
  require(covariance.rows() == d && covariance.cols() == d && covariance.allFinite(),
          "the covariance must be a finite " + std::to_string(d) + " x " + std::to_string(d) +
              " matrix");
  require_normals(normals, d);
  if (normals.rows() == 0) return nearest;
  // Known: the held quantities, N x = N nearest, and then every coordinate that the move took
  // out of the box, at the face it crossed. Without the faces a hold changed far from the
  // choices (a new height 0.4 of the box away) moved correlated coordinates well outside it,
  // and the centre clamped back landed on four faces at once.
  Eigen::MatrixXd known = normals;
  Eigen::VectorXd values = normals * nearest;
  Eigen::VectorXd x = t;
  for (Eigen::Index pass = 0; pass <= d; ++pass) {
    x = t + conditioning_gain(covariance, known) * (values - known * t);
    std::vector<Eigen::Index> outside;
    for (Eigen::Index k = 0; k < d; ++k) {
      if (x(k) < 0.0 || x(k) > 1.0) outside.push_back(k);
    }
    if (outside.empty()) break;
    const Eigen::Index rows = known.rows();
    known.conservativeResize(rows + static_cast<Eigen::Index>(outside.size()), Eigen::NoChange);
    values.conservativeResize(known.rows());
    for (std::size_t i = 0; i < outside.size(); ++i) {
      const Eigen::Index row = rows + static_cast<Eigen::Index>(i);
      known.row(row) = Eigen::RowVectorXd::Unit(d, outside[i]);
      values(row) = std::clamp(x(outside[i]), 0.0, 1.0);
    }
  }
  return x.cwiseMax(0.0).cwiseMin(1.0);
}

}  // namespace sps
