#include "sps/expected_improvement.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "sps/bounded_maximizer.hpp"
#include "sps/parallel_for.hpp"

namespace sps {

namespace {

constexpr double kInvSqrt2Pi = 0.39894228040143267794;

double normal_pdf(double z) {
  return kInvSqrt2Pi * std::exp(-0.5 * z * z);
}
double normal_cdf(double z) {
  return 0.5 * std::erfc(-z / std::sqrt(2.0));
}

// The box-clamped point space.through(origin, y), and which coordinates the clamp left as
// they were (1) or moved (0). y itself for the whole space (y is then inside the box).
Eigen::VectorXd on_plane(const TangentSpace& space, const Eigen::VectorXd& origin,
                         const Eigen::VectorXd& y, Eigen::VectorXd* inside = nullptr) {
  if (space.whole()) {
    if (inside != nullptr) *inside = Eigen::VectorXd::Ones(y.size());
    return y;
  }
  const Eigen::VectorXd raw = space.through(origin, y);
  const Eigen::VectorXd x = raw.cwiseMax(0.0).cwiseMin(1.0);
  if (inside != nullptr) *inside = ((x - raw).cwiseAbs().array() < 1e-15).cast<double>().matrix();
  return x;
}

// argmax of f over the box-clamped plane through `origin` along `space` (the box itself for
// the whole space), by local searches from `starts` (points of that plane): the optimizer
// moves y in [0,1]^n and f sees x = origin + P (y - origin), so its gradient is P times f's
// on the coordinates the clamp left free.
Eigen::VectorXd maximize_on_plane(const Objective& f, const Eigen::VectorXd& origin,
                                  const TangentSpace& space,
                                  const std::vector<Eigen::VectorXd>& starts, int max_iterations,
                                  int threads) {
  const Eigen::Index d = origin.size();
  const Eigen::VectorXd lower = Eigen::VectorXd::Zero(d);
  const Eigen::VectorXd upper = Eigen::VectorXd::Ones(d);
  const int count = static_cast<int>(starts.size());
  std::vector<MaximizeResult> results(starts.size());
  parallel_for(count, threads, [&](int s) {
    const Objective fn = [&](const Eigen::VectorXd& y, Eigen::VectorXd& grad) {
      Eigen::VectorXd inside;
      const Eigen::VectorXd x = on_plane(space, origin, y, &inside);
      Eigen::VectorXd g;
      const double value = f(x, g);
      grad = space.project(g.cwiseProduct(inside));  // P is symmetric
      return value;
    };
    results[static_cast<std::size_t>(s)] = maximize_bounded(fn, starts[static_cast<std::size_t>(s)],
                                                            lower, upper, max_iterations, 1e-9);
  });
  const auto best = std::max_element(
      results.begin(), results.end(),
      [](const MaximizeResult& a, const MaximizeResult& b) { return a.value < b.value; });
  return on_plane(space, origin, best->x);
}

Objective posterior_mean_objective(const PreferenceModel& model) {
  return [&model](const Eigen::VectorXd& x, Eigen::VectorXd& grad) {
    double mean = 0.0, variance = 0.0;
    model.predict(x, mean, variance, &grad, nullptr);
    return mean;
  };
}

}  // namespace

double expected_improvement(const PreferenceModel& model, const Eigen::VectorXd& x,
                            double best_mean, Eigen::VectorXd* gradient) {
  Eigen::MatrixXd grad;
  const Eigen::VectorXd ei =
      expected_improvement_batch(model, x, best_mean, gradient != nullptr ? &grad : nullptr);
  if (gradient != nullptr) *gradient = grad.col(0);
  return ei(0);
}

Eigen::VectorXd expected_improvement_batch(const PreferenceModel& model, const Eigen::MatrixXd& xs,
                                           double best_mean, Eigen::MatrixXd* gradient) {
  Eigen::VectorXd mean;
  Eigen::VectorXd variance;
  Eigen::MatrixXd d_mean;
  Eigen::MatrixXd d_variance;
  model.predict_batch(xs, mean, variance, gradient != nullptr ? &d_mean : nullptr,
                      gradient != nullptr ? &d_variance : nullptr);
  const Eigen::Index m = xs.cols();
  Eigen::VectorXd ei(m);
  if (gradient != nullptr) gradient->resize(xs.rows(), m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const double sigma = std::sqrt(variance(j));
    const double diff = mean(j) - best_mean;
    if (sigma < 1e-12) {
      ei(j) = std::max(diff, 0.0);
      if (gradient != nullptr) {
        gradient->col(j) =
            diff > 0.0 ? Eigen::VectorXd(d_mean.col(j)) : Eigen::VectorXd::Zero(xs.rows());
      }
      continue;
    }
    const double z = diff / sigma;
    const double cdf = normal_cdf(z);
    const double pdf = normal_pdf(z);
    ei(j) = diff * cdf + sigma * pdf;
    if (gradient != nullptr) {
      gradient->col(j) = cdf * d_mean.col(j) + (pdf / (2.0 * sigma)) * d_variance.col(j);
    }
  }
  return ei;
}

Eigen::VectorXd maximize_expected_improvement(const PreferenceModel& model, double best_mean,
                                              const Eigen::VectorXd& x_plus, std::mt19937_64& rng,
                                              const EiSearchSettings& settings,
                                              const TangentSpace& space) {
  const int d = model.dims();
  const int candidate_count =
      settings.candidates > 0 ? settings.candidates : std::min(2000, 100 + 50 * d);
  const int start_count = settings.starts > 0 ? settings.starts : 6;

  // Candidates: uniform samples, x+ and small perturbations of observed points (EI often
  // peaks just next to the best observations).
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Eigen::VectorXd> candidates;
  candidates.reserve(static_cast<std::size_t>(candidate_count + model.point_count() + 1));
  candidates.push_back(x_plus);
  // Perturbations of the observed points with the largest posterior means.
  Eigen::VectorXd observed_means;
  Eigen::VectorXd observed_variances;
  model.predict_batch(model.points(), observed_means, observed_variances, nullptr, nullptr);
  std::vector<int> observed(static_cast<std::size_t>(model.point_count()));
  std::iota(observed.begin(), observed.end(), 0);
  const int seeds = std::min<int>(20, model.point_count());
  std::partial_sort(observed.begin(), observed.begin() + seeds, observed.end(), [&](int a, int b) {
    return observed_means(a) > observed_means(b) ||
           (observed_means(a) == observed_means(b) && a < b);
  });
  for (int s = 0; s < seeds; ++s) {
    Eigen::VectorXd x = model.points().col(observed[static_cast<std::size_t>(s)]);
    for (int k = 0; k < d; ++k) x(k) += 0.05 * normal(rng);
    candidates.push_back(x.cwiseMax(0.0).cwiseMin(1.0));
  }
  for (int i = 0; i < candidate_count; ++i) {
    Eigen::VectorXd x(d);
    for (int k = 0; k < d; ++k) x(k) = uniform(rng);
    candidates.push_back(std::move(x));
  }
  const int total = static_cast<int>(candidates.size());
  std::vector<double> scores(static_cast<std::size_t>(total));
  parallel_for(total, settings.threads, [&](int i) {
    auto& x = candidates[static_cast<std::size_t>(i)];
    if (!space.whole()) x = on_plane(space, x_plus, x);  // a point of the plane is its own image
    scores[static_cast<std::size_t>(i)] = expected_improvement(model, x, best_mean);
  });
  std::vector<int> order(static_cast<std::size_t>(total));
  std::iota(order.begin(), order.end(), 0);
  const int starts = std::min(start_count, total);
  std::partial_sort(order.begin(), order.begin() + starts, order.end(), [&](int a, int b) {
    return scores[static_cast<std::size_t>(a)] > scores[static_cast<std::size_t>(b)] ||
           (scores[static_cast<std::size_t>(a)] == scores[static_cast<std::size_t>(b)] && a < b);
  });
  std::vector<Eigen::VectorXd> best_candidates;
  for (int s = 0; s < starts; ++s) {
    best_candidates.push_back(
        candidates[static_cast<std::size_t>(order[static_cast<std::size_t>(s)])]);
  }
  return maximize_on_plane(
      [&](const Eigen::VectorXd& x, Eigen::VectorXd& grad) {
        return expected_improvement(model, x, best_mean, &grad);
      },
      x_plus, space, best_candidates, settings.max_iterations, settings.threads);
}

std::vector<int> best_observed_points(const PreferenceModel& model, int count) {
  const int n = model.point_count();
  if (n == 0) return {};
  Eigen::VectorXd means, variances;
  model.predict_batch(model.points(), means, variances, nullptr, nullptr);
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  count = std::max(1, std::min(count, n));
  std::partial_sort(order.begin(), order.begin() + count, order.end(), [&](int a, int b) {
    return means(a) > means(b) || (means(a) == means(b) && a < b);
  });
  order.resize(static_cast<std::size_t>(count));
  return order;
}

Eigen::VectorXd maximize_posterior_mean(const PreferenceModel& model,
                                        const Eigen::VectorXd& fallback, int starts,
                                        int max_iterations, int threads) {
  const std::vector<int> order = best_observed_points(model, starts);
  if (order.empty()) return fallback;
  std::vector<Eigen::VectorXd> from;
  for (const int i : order) from.push_back(model.points().col(i));
  return maximize_on_plane(posterior_mean_objective(model), fallback, TangentSpace(), from,
                           max_iterations, threads);
}

Eigen::VectorXd maximize_posterior_mean_on_tangent(const PreferenceModel& model,
                                                   const Eigen::VectorXd& anchor,
                                                   const TangentSpace& space, int starts,
                                                   int threads) {
  const std::vector<int> order = best_observed_points(model, starts);
  if (order.empty()) return anchor;
  std::vector<Eigen::VectorXd> from{anchor};
  for (const int i : order) from.push_back(on_plane(space, anchor, model.points().col(i)));
  return maximize_on_plane(posterior_mean_objective(model), anchor, space, from, 60, threads);
}

}  // namespace sps
