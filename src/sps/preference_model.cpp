#include "sps/preference_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <utility>

#include <Eigen/LU>

#include "sps/bounded_maximizer.hpp"
#include "sps/btl_likelihood.hpp"

namespace sps {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Log density of the log-normal priors, in terms of log theta (a Gaussian in log space), and
// its gradient. The Jacobian of the log transform is left out, as a MAP estimate in log
// space wants.
double log_prior(const Eigen::VectorXd& log_theta, const Eigen::VectorXd& mean, double variance,
                 Eigen::VectorXd* gradient) {
  const Eigen::VectorXd diff = log_theta - mean;
  if (gradient != nullptr) *gradient = -diff / variance;
  return -0.5 * diff.squaredNorm() / variance -
         0.5 * static_cast<double>(diff.size()) * std::log(2.0 * kPi * variance);
}

Eigen::MatrixXd covariance(const MaternKernel& kernel, const Eigen::MatrixXd& points,
                           double noise) {
  Eigen::MatrixXd c = kernel.gram(points);
  c.diagonal().array() += noise;
  return c;
}

}  // namespace

Eigen::VectorXd ModelSettings::prior_log_mean(int dims) const {
  Eigen::VectorXd mean(dims + 1);
  mean(0) = std::log(amplitude_prior);
  mean.tail(dims).setConstant(std::log(length_scale_prior));
  return mean;
}

PreferenceData model_window(const PreferenceData& data, const ModelSettings& settings) {
  if (data.point_count() <= settings.max_points) return data;
  std::set<int> used;
  std::size_t first = data.preferences().size();
  while (first > 0) {
    const Preference& p = data.preferences()[first - 1];
    std::set<int> with = used;
    with.insert(p.chosen);
    with.insert(p.others.begin(), p.others.end());
    if (static_cast<int>(with.size()) > settings.max_points && !used.empty()) break;
    used = std::move(with);
    --first;
  }
  // Indices come from stored files too: one past the points would write out of bounds below.
  const auto in_range = [&](int i) { return i >= 0 && i < data.point_count(); };
  if (!used.empty() && (!in_range(*used.begin()) || !in_range(*used.rbegin()))) {
    throw std::invalid_argument("a preference refers to a point that does not exist");
  }
  PreferenceData window(data.dims(), data.merge_distance());
  std::vector<int> new_index(static_cast<std::size_t>(data.point_count()), -1);
  for (int i : used) {
    new_index[static_cast<std::size_t>(i)] = window.point_count();
    window.add_point_exact(data.points().col(i));
  }
  for (std::size_t k = first; k < data.preferences().size(); ++k) {
    const Preference& p = data.preferences()[k];
    Preference q;
    q.chosen = new_index[static_cast<std::size_t>(p.chosen)];
    for (int o : p.others) q.others.push_back(new_index[static_cast<std::size_t>(o)]);
    window.add_preference_indices(std::move(q));
  }
  return window;
}

MapObjective::MapObjective(const PreferenceData& data, const ModelSettings& settings)
    : data_(data), settings_(settings) {}

double MapObjective::joint(const Eigen::VectorXd& log_theta, const Eigen::VectorXd& f) const {
  const MaternKernel kernel(KernelParams::from_log(log_theta));
  const Eigen::LLT<Eigen::MatrixXd> llt(
      covariance(kernel, data_.points(), settings_.noise_variance));
  const Eigen::MatrixXd l = llt.matrixL();
  const double log_det = 2.0 * l.diagonal().array().log().sum();
  const double n = static_cast<double>(f.size());
  return btl_log_likelihood(data_.preferences(), f, settings_.btl_scale) -
         0.5 * f.dot(llt.solve(f)) - 0.5 * log_det - 0.5 * n * std::log(2.0 * kPi) +
         log_prior(log_theta, settings_.prior_log_mean(data_.dims()), settings_.prior_log_variance,
                   nullptr);
}

namespace {

// C = K + bI factorized once per hyperparameter value: the inverse serves the Newton steps,
// the objective and its gradient alike.
struct Factorized {
  Eigen::MatrixXd c_inv;
  double log_det = 0.0;
};

Factorized factorize(const MaternKernel& kernel, const Eigen::MatrixXd& points, double noise) {
  const Eigen::LLT<Eigen::MatrixXd> llt(covariance(kernel, points, noise));
  const Eigen::Index n = points.cols();
  Factorized out;
  out.c_inv = llt.solve(Eigen::MatrixXd::Identity(n, n));
  out.log_det = 2.0 * llt.matrixLLT().diagonal().array().log().sum();
  return out;
}

// Inner problem: argmax_f log p(D|f) - f'C^-1 f / 2. It is concave (BTL is log-concave, the
// prior Gaussian), so Newton with step halving converges in a few steps from a warm start.
Eigen::VectorXd newton_latent(const std::vector<Preference>& preferences, const Factorized& fac,
                              double scale, Eigen::VectorXd f) {
  const Eigen::Index n = fac.c_inv.rows();
  const auto psi = [&](const Eigen::VectorXd& latent) {
    return btl_log_likelihood(preferences, latent, scale) - 0.5 * latent.dot(fac.c_inv * latent);
  };
  if (f.size() != n) f = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd grad;
  Eigen::MatrixXd w;
  double current = psi(f);
  for (int iteration = 0; iteration < 50; ++iteration) {
    btl_log_likelihood(preferences, f, scale, &grad, &w);
    // Newton step: (C^-1 + W) f_new = W f + grad, with C^-1 + W symmetric positive definite.
    const Eigen::VectorXd target = (fac.c_inv + w).llt().solve(w * f + grad);
    const Eigen::VectorXd step = target - f;
    if (!step.allFinite()) break;
    double t = 1.0;
    bool improved = false;
    for (int halving = 0; halving < 20; ++halving, t *= 0.5) {
      const Eigen::VectorXd candidate = f + t * step;
      const double value = psi(candidate);
      if (value >= current - 1e-12 * std::abs(current)) {
        f = candidate;
        improved = value > current;
        current = value;
        break;
      }
    }
    if (!improved || (t * step).lpNorm<Eigen::Infinity>() < 1e-10) break;
  }
  return f;
}

}  // namespace

Eigen::VectorXd MapObjective::optimal_latent(const Eigen::VectorXd& log_theta,
                                             Eigen::VectorXd f) const {
  const MaternKernel kernel(KernelParams::from_log(log_theta));
  return newton_latent(data_.preferences(),
                       factorize(kernel, data_.points(), settings_.noise_variance),
                       settings_.btl_scale, std::move(f));
}

double MapObjective::evaluate(const Eigen::VectorXd& log_theta, Eigen::VectorXd& f,
                              Eigen::VectorXd& gradient) const {
  const MaternKernel kernel(KernelParams::from_log(log_theta));
  const Factorized fac = factorize(kernel, data_.points(), settings_.noise_variance);
  f = newton_latent(data_.preferences(), fac, settings_.btl_scale, std::move(f));
  const Eigen::Index n = fac.c_inv.rows();
  const Eigen::VectorXd alpha = fac.c_inv * f;

  Eigen::VectorXd prior_gradient;
  const double value = btl_log_likelihood(data_.preferences(), f, settings_.btl_scale) -
                       0.5 * f.dot(alpha) - 0.5 * fac.log_det -
                       0.5 * static_cast<double>(n) * std::log(2.0 * kPi) +
                       log_prior(log_theta, settings_.prior_log_mean(data_.dims()),
                                 settings_.prior_log_variance, &prior_gradient);
  // d/dtheta_j [-1/2 f'C^-1 f - 1/2 log|C|] = 1/2 tr((alpha alpha' - C^-1) dC/dtheta_j).
  const Eigen::MatrixXd m = alpha * alpha.transpose() - fac.c_inv;
  gradient = 0.5 * kernel.contract_log_gradients(data_.points(), m) + prior_gradient;
  return value;
}

PreferenceModel::PreferenceModel(int dims, const ModelSettings& settings)
    : dims_(dims),
      kernel_(KernelParams::from_log(settings.prior_log_mean(dims))),
      points_(dims, 0) {}

PreferenceModel::PreferenceModel(const PreferenceData& data, const ModelSettings& settings,
                                 KernelParams params, Eigen::VectorXd latent)
    : dims_(data.dims()),
      kernel_(std::move(params)),
      points_(model_window(data, settings).points()),
      latent_(std::move(latent)) {
  if (latent_.size() != points_.cols()) {
    throw std::invalid_argument("latent values do not match the number of points");
  }
  if (points_.cols() > 0) {
    const Eigen::Index n = points_.cols();
    const Eigen::LLT<Eigen::MatrixXd> llt(covariance(kernel_, points_, settings.noise_variance));
    c_inv_ = llt.solve(Eigen::MatrixXd::Identity(n, n));
    alpha_ = c_inv_ * latent_;
  }
}

PreferenceModel PreferenceModel::fit(const PreferenceData& all_data, const ModelSettings& settings,
                                     const PreferenceModel& previous) {
  const PreferenceData data = model_window(all_data, settings);
  const int n = data.point_count();
  if (n == 0) return PreferenceModel(data.dims(), settings);
  // Warm start: previous MAP values where the points are the same (the data is append-only
  // until the window starts to slide), the previous posterior mean elsewhere.
  const bool same_prefix = previous.points_.cols() <= n &&
                           (previous.points_.cols() == 0 ||
                            data.points().leftCols(previous.points_.cols()) == previous.points_);
  Eigen::VectorXd f(n);
  for (int i = 0; i < n; ++i) {
    f(i) = same_prefix && i < previous.latent_.size() ? previous.latent_(i)
                                                      : previous.mean(data.points().col(i));
  }
  const MapObjective objective(data, settings);
  const Eigen::VectorXd prior_mean = settings.prior_log_mean(data.dims());
  // The log-normal priors are tight; +-5 prior SDs is a box MAP never wants to leave.
  const double radius = 5.0 * std::sqrt(settings.prior_log_variance);
  const Eigen::VectorXd lower = prior_mean.array() - radius;
  const Eigen::VectorXd upper = prior_mean.array() + radius;
  Eigen::VectorXd start = previous.params().to_log();
  if (start.size() != prior_mean.size()) start = prior_mean;
  start = start.cwiseMax(lower).cwiseMin(upper);

  // Each evaluation costs a few N^3 operations: cap the iterations so a large data set still
  // answers in well under a second (the warm start is close to the optimum anyway).
  const double cube = static_cast<double>(n) * n * n;
  const int iterations = std::max(
      2, std::min(settings.max_hyper_iterations, static_cast<int>(2.5e8 / std::max(cube, 1.0))));

  Eigen::VectorXd best_f = f;
  double best_value = -std::numeric_limits<double>::infinity();
  const Objective fn = [&](const Eigen::VectorXd& log_theta, Eigen::VectorXd& grad) {
    Eigen::VectorXd latent = f;
    const double value = objective.evaluate(log_theta, latent, grad);
    if (value > best_value) {
      best_value = value;
      best_f = latent;
    }
    f = latent;  // warm start the next inner solve
    return value;
  };
  const MaximizeResult result = maximize_bounded(fn, start, lower, upper, iterations, 1e-3);
  // The latent values at the returned theta (the tracked best belongs to the same point).
  return PreferenceModel(all_data, settings, KernelParams::from_log(result.x), std::move(best_f));
}

double PreferenceModel::mean(const Eigen::VectorXd& x) const {
  if (points_.cols() == 0) return 0.0;
  return kernel_.cross(points_, x).dot(alpha_);
}

double PreferenceModel::variance(const Eigen::VectorXd& x) const {
  if (points_.cols() == 0) return kernel_.variance();
  const Eigen::VectorXd k = kernel_.cross(points_, x);
  return std::max(0.0, kernel_.variance() - k.dot(c_inv_ * k));
}

void PreferenceModel::predict(const Eigen::VectorXd& x, double& mean, double& variance,
                              Eigen::VectorXd* d_mean, Eigen::VectorXd* d_variance) const {
  Eigen::VectorXd means;
  Eigen::VectorXd variances;
  Eigen::MatrixXd d_means;
  Eigen::MatrixXd d_variances;
  predict_batch(x, means, variances, d_mean != nullptr ? &d_means : nullptr,
                d_variance != nullptr ? &d_variances : nullptr);
  mean = means(0);
  variance = variances(0);
  if (d_mean != nullptr) *d_mean = d_means.col(0);
  if (d_variance != nullptr) *d_variance = d_variances.col(0);
}

void PreferenceModel::predict_batch(const Eigen::MatrixXd& xs, Eigen::VectorXd& mean,
                                    Eigen::VectorXd& variance, Eigen::MatrixXd* d_mean,
                                    Eigen::MatrixXd* d_variance) const {
  const Eigen::Index m = xs.cols();
  if (points_.cols() == 0) {
    mean.setZero(m);
    variance.setConstant(m, kernel_.variance());
    if (d_mean != nullptr) d_mean->setZero(xs.rows(), m);
    if (d_variance != nullptr) d_variance->setZero(xs.rows(), m);
    return;
  }
  Eigen::MatrixXd k;
  Eigen::MatrixXd q;
  kernel_.cross_batch(points_, xs, k, q);
  const Eigen::MatrixXd c_inv_k = c_inv_ * k;
  mean = k.transpose() * alpha_;
  const Eigen::VectorXd raw =
      kernel_.variance() - (k.array() * c_inv_k.array()).colwise().sum().transpose();
  variance = raw.cwiseMax(0.0);
  const Eigen::VectorXd& inv_l2 = kernel_.inverse_squared_lengths();
  // d k(p_i, x_j)/dx_j = q_ij (x_j - p_i) / l^2, so sum_i w_ij dk_ij / dx_j
  //   = (x_j * sum_i q_ij w_ij - P (q_.j .* w_.j)) / l^2.
  const auto contract = [&](const Eigen::MatrixXd& w) {
    const Eigen::MatrixXd qw = q.array() * w.array();
    Eigen::MatrixXd out = xs * qw.colwise().sum().asDiagonal();
    out.noalias() -= points_ * qw;
    return Eigen::MatrixXd(inv_l2.asDiagonal() * out);
  };
  if (d_mean != nullptr) *d_mean = contract(alpha_.replicate(1, m));
  if (d_variance != nullptr) {
    *d_variance = -2.0 * contract(c_inv_k);
    for (Eigen::Index j = 0; j < m; ++j) {
      if (raw(j) <= 0.0) d_variance->col(j).setZero();
    }
  }
}

int PreferenceModel::best_observed_index() const {
  if (points_.cols() == 0) return -1;
  // At observed points the posterior mean is C^-1-smoothed f; compare those, not raw f.
  int best = 0;
  double best_mean = -std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < points_.cols(); ++i) {
    const double m = mean(points_.col(i));
    if (m > best_mean) {
      best_mean = m;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace sps
