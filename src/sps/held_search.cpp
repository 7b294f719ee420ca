#include "sps/held_search.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "sps/bounded_maximizer.hpp"
#include "sps/expected_improvement.hpp"
#include "sps/parallel_for.hpp"
#include "sps/plane_construction.hpp"

namespace sps {

namespace {

// Scales d down so that c +- d stays in the box.
Eigen::VectorXd fit_both_sides(const Eigen::VectorXd& c, const Eigen::VectorXd& d) {
  return std::min(fit_in_box(c, d), fit_in_box(c, -d)) * d;
}

double visible_length(const Eigen::VectorXd& d, const Eigen::VectorXd& scale) {
  return scale.size() == d.size() ? d.cwiseProduct(scale).norm() : d.norm();
}

// A random unit tangent direction (zero when the tangent space is empty).
Eigen::VectorXd random_tangent(const Eigen::MatrixXd& projector, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Index d = projector.rows();
  for (int attempt = 0; attempt < 20; ++attempt) {
    Eigen::VectorXd r(d);
    for (Eigen::Index k = 0; k < d; ++k) r(k) = normal(rng);
    r = projector * r;
    if (r.norm() > 1e-9) return r.normalized();
  }
  return Eigen::VectorXd::Zero(d);
}

// The box-clamped point x+ + P (y - x+), and which coordinates the clamp held.
Eigen::VectorXd on_tangent(const Eigen::VectorXd& x_plus, const Eigen::MatrixXd& projector,
                           const Eigen::VectorXd& y, Eigen::VectorXd* inside = nullptr) {
  const Eigen::VectorXd raw = x_plus + projector * (y - x_plus);
  const Eigen::VectorXd x = raw.cwiseMax(0.0).cwiseMin(1.0);
  if (inside != nullptr) *inside = ((x - raw).cwiseAbs().array() < 1e-15).cast<double>().matrix();
  return x;
}

// argmax of f over the box-clamped tangent plane through x_plus, by local searches from
// `starts` (points of that plane): the optimizer moves y in [0,1]^n and f sees
// x+ + P (y - x+), so its gradient is P times f's on the coordinates the clamp left free.
Eigen::VectorXd maximize_on_tangent(
    const std::function<double(const Eigen::VectorXd&, Eigen::VectorXd&)>& f,
    const Eigen::VectorXd& x_plus, const Eigen::MatrixXd& projector,
    const std::vector<Eigen::VectorXd>& starts, int threads) {
  const Eigen::Index d = x_plus.size();
  const Eigen::VectorXd lower = Eigen::VectorXd::Zero(d);
  const Eigen::VectorXd upper = Eigen::VectorXd::Ones(d);
  const int count = static_cast<int>(starts.size());
  std::vector<MaximizeResult> results(starts.size());
  parallel_for(count, threads, [&](int s) {
    const Objective fn = [&](const Eigen::VectorXd& y, Eigen::VectorXd& grad) {
      Eigen::VectorXd inside;
      const Eigen::VectorXd x = on_tangent(x_plus, projector, y, &inside);
      Eigen::VectorXd g;
      const double value = f(x, g);
      grad = projector * g.cwiseProduct(inside);  // P is symmetric
      return value;
    };
    results[static_cast<std::size_t>(s)] =
        maximize_bounded(fn, starts[static_cast<std::size_t>(s)], lower, upper, 60, 1e-9);
  });
  const auto best = std::max_element(
      results.begin(), results.end(),
      [](const MaximizeResult& a, const MaximizeResult& b) { return a.value < b.value; });
  return on_tangent(x_plus, projector, best->x);
}

}  // namespace

Eigen::MatrixXd tangent_projector(const Eigen::MatrixXd& normals, Eigen::Index dims) {
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(dims, dims);
  if (normals.rows() == 0 || normals.cols() != dims) return identity;
  const Eigen::MatrixXd nnt = normals * normals.transpose();
  const Eigen::MatrixXd inv = nnt.completeOrthogonalDecomposition().pseudoInverse();
  return identity - normals.transpose() * inv * normals;
}

Eigen::MatrixXd most_visible_tangent_directions(const Eigen::MatrixXd& projector,
                                                const Eigen::VectorXd& scale, int k) {
  const Eigen::Index d = projector.rows();
  const Eigen::VectorXd s2 =
      scale.size() == d ? Eigen::VectorXd(scale.cwiseProduct(scale)) : Eigen::VectorXd::Ones(d);
  const Eigen::MatrixXd m = projector * s2.asDiagonal() * projector;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(0.5 * (m + m.transpose()));
  const int count = static_cast<int>(std::min<Eigen::Index>(k, d));
  Eigen::MatrixXd dirs(d, count);
  for (int i = 0; i < count; ++i) {
    Eigen::VectorXd e = eigen.eigenvalues()(d - 1 - i) > 1e-12 * std::max(1.0, m.trace())
                            ? Eigen::VectorXd(eigen.eigenvectors().col(d - 1 - i))
                            : Eigen::VectorXd::Zero(d);
    // A fixed sign (the largest entry positive), so the plane does not depend on the solver.
    Eigen::Index largest = 0;
    e.cwiseAbs().maxCoeff(&largest);
    if (e(largest) < 0.0) e = -e;
    dirs.col(i) = e;
  }
  return dirs;
}

Plane held_first_plane(const SearchHold& hold, const Eigen::VectorXd& scale, double extent) {
  const Eigen::Index d = scale.size();
  Plane p;
  p.c = hold.project(Eigen::VectorXd::Constant(d, 0.5));
  const Eigen::MatrixXd projector = tangent_projector(hold.normals(p.c), d);
  const Eigen::MatrixXd dirs = most_visible_tangent_directions(projector, scale, 2);
  p.u = fit_both_sides(p.c, extent * dirs.col(0));
  p.v = dirs.cols() > 1 ? fit_both_sides(p.c, extent * dirs.col(1)) : Eigen::VectorXd::Zero(d);
  if (p.is_line()) {
    // One tangent direction left: a segment through the centre (c .. c + u for a line).
    p.c -= p.u;
    p.u *= 2.0;
    p.u_neg_scale = 0.0;
  }
  return p;
}

Eigen::VectorXd maximize_expected_improvement_on_tangent(const PreferenceModel& model,
                                                         double best_mean,
                                                         const Eigen::VectorXd& x_plus,
                                                         const Eigen::MatrixXd& projector,
                                                         std::mt19937_64& rng, int starts,
                                                         int candidates, int threads) {
  const int d = model.dims();
  const int candidate_count = candidates > 0 ? candidates : std::min(2000, 100 + 50 * d);
  // Candidates as maximize_expected_improvement draws them (x+, the best observed points
  // perturbed, uniform samples), each mapped onto the tangent plane.
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Eigen::VectorXd> ys{x_plus};
  if (model.point_count() > 0) {
    Eigen::VectorXd means, variances;
    model.predict_batch(model.points(), means, variances, nullptr, nullptr);
    std::vector<int> order(static_cast<std::size_t>(model.point_count()));
    std::iota(order.begin(), order.end(), 0);
    const int seeds = std::min<int>(20, model.point_count());
    std::partial_sort(order.begin(), order.begin() + seeds, order.end(), [&](int a, int b) {
      return means(a) > means(b) || (means(a) == means(b) && a < b);
    });
    for (int s = 0; s < seeds; ++s) {
      Eigen::VectorXd y = model.points().col(order[static_cast<std::size_t>(s)]);
      for (int k = 0; k < d; ++k) y(k) += 0.05 * normal(rng);
      ys.push_back(y.cwiseMax(0.0).cwiseMin(1.0));
    }
  }
  for (int i = 0; i < candidate_count; ++i) {
    Eigen::VectorXd y(d);
    for (int k = 0; k < d; ++k) y(k) = uniform(rng);
    ys.push_back(std::move(y));
  }
  const int total = static_cast<int>(ys.size());
  std::vector<double> scores(static_cast<std::size_t>(total));
  parallel_for(total, threads, [&](int i) {
    auto& y = ys[static_cast<std::size_t>(i)];
    y = on_tangent(x_plus, projector, y);  // a point of the tangent plane is its own image
    scores[static_cast<std::size_t>(i)] = expected_improvement(model, y, best_mean);
  });
  std::vector<int> order(static_cast<std::size_t>(total));
  std::iota(order.begin(), order.end(), 0);
  const int count = std::min(std::max(1, starts), total);
  std::partial_sort(order.begin(), order.begin() + count, order.end(), [&](int a, int b) {
    return scores[static_cast<std::size_t>(a)] > scores[static_cast<std::size_t>(b)] ||
           (scores[static_cast<std::size_t>(a)] == scores[static_cast<std::size_t>(b)] && a < b);
  });
  std::vector<Eigen::VectorXd> best_starts;
  for (int i = 0; i < count; ++i) {
    best_starts.push_back(ys[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])]);
  }
  return maximize_on_tangent(
      [&](const Eigen::VectorXd& x, Eigen::VectorXd& g) {
        return expected_improvement(model, x, best_mean, &g);
      },
      x_plus, projector, best_starts, threads);
}

Eigen::VectorXd maximize_posterior_mean_on_tangent(const PreferenceModel& model,
                                                   const Eigen::VectorXd& anchor,
                                                   const Eigen::MatrixXd& projector, int starts,
                                                   int threads) {
  const std::vector<int> order = best_observed_points(model, starts);
  if (order.empty()) return anchor;
  std::vector<Eigen::VectorXd> from{anchor};
  for (const int i : order) from.push_back(on_tangent(anchor, projector, model.points().col(i)));
  return maximize_on_tangent(
      [&](const Eigen::VectorXd& x, Eigen::VectorXd& g) {
        double mean = 0.0, variance = 0.0;
        model.predict(x, mean, variance, &g, nullptr);
        return mean;
      },
      anchor, projector, from, threads);
}

namespace {

// v maximizing the plane's mean EI over the 5x5 lattice (as sps_plane) among tangent
// directions: the optimizer moves w in the box of c +- w and the plane uses P w.
Eigen::VectorXd best_tangent_v(const PreferenceModel& model, const Plane& base,
                               const Eigen::MatrixXd& projector, double best_mean,
                               std::mt19937_64& rng, const HeldPlaneSettings& settings) {
  const Eigen::Index d = base.c.size();
  const Eigen::VectorXd bound = base.c.cwiseMin(Eigen::VectorXd::Ones(d) - base.c).cwiseMax(0.0);
  const Eigen::VectorXd& u = base.u;
  const int restarts = std::max(1, settings.plane_restarts);
  std::vector<Eigen::VectorXd> starts;
  std::uniform_real_distribution<double> uniform(0.2, 1.0);
  for (int r = 0; r < restarts; ++r) {
    Eigen::VectorXd dir = random_tangent(projector, rng);
    if (u.squaredNorm() > 0.0) dir -= (dir.dot(u) / u.squaredNorm()) * u;
    starts.push_back(uniform(rng) * fit_both_sides(base.c, 10.0 * dir));
  }
  std::vector<MaximizeResult> results(static_cast<std::size_t>(restarts));
  parallel_for(restarts, settings.threads, [&](int r) {
    PlaneEiObjective objective(model, base, best_mean);
    Eigen::VectorXd g;
    const Objective fn = [&](const Eigen::VectorXd& w, Eigen::VectorXd& grad) {
      const double value = objective(projector * w, g);
      grad = projector * g;
      return value;
    };
    results[static_cast<std::size_t>(r)] = maximize_bounded(
        fn, starts[static_cast<std::size_t>(r)], -bound, bound, settings.max_iterations, 1e-10);
  });
  const auto best = std::max_element(
      results.begin(), results.end(),
      [](const MaximizeResult& a, const MaximizeResult& b) { return a.value < b.value; });
  Eigen::VectorXd v = projector * best->x;
  if (u.squaredNorm() > 0.0) v -= (v.dot(u) / u.squaredNorm()) * u;
  return fit_both_sides(base.c, v);
}

// The tangent direction orthogonal to u in the perceptual metric with the most visible room
// (zero if none): the leading visible tangent directions tried in turn.
Eigen::VectorXd visible_tangent_v(const Eigen::VectorXd& c, const Eigen::VectorXd& u,
                                  const Eigen::MatrixXd& projector, const Eigen::VectorXd& scale) {
  const Eigen::Index d = c.size();
  const Eigen::VectorXd s2 = scale.cwiseProduct(scale);
  const double uu = u.dot(s2.cwiseProduct(u));
  const Eigen::MatrixXd dirs = most_visible_tangent_directions(projector, scale, 3);
  Eigen::VectorXd best = Eigen::VectorXd::Zero(d);
  for (Eigen::Index i = 0; i < dirs.cols(); ++i) {
    Eigen::VectorXd dir = dirs.col(i);
    if (uu > 0.0) dir -= (dir.dot(s2.cwiseProduct(u)) / uu) * u;
    if (dir.norm() < 1e-9) continue;
    const Eigen::VectorXd fitted = fit_both_sides(c, dir.normalized());
    if (visible_length(fitted, scale) > visible_length(best, scale)) best = fitted;
  }
  return best;
}

}  // namespace

Plane held_sps_plane(const PreferenceModel& model, const Eigen::VectorXd& x_plus,
                     const Eigen::MatrixXd& projector, double best_mean, std::mt19937_64& rng,
                     const HeldPlaneSettings& settings) {
  const Eigen::Index d = x_plus.size();
  Plane plane;
  plane.c = x_plus;
  const Eigen::VectorXd x_ei = maximize_expected_improvement_on_tangent(
      model, best_mean, x_plus, projector, rng, settings.ei_starts, settings.ei_candidates,
      settings.threads);
  plane.u = projector * (x_ei - x_plus);
  if (plane.u.norm() < 1e-6) {
    // EI peaks at x+ itself: still show a neighbourhood on the surface.
    const Eigen::VectorXd dir = 0.25 * random_tangent(projector, rng);
    const double forward = fit_in_box(x_plus, dir);
    const double backward = fit_in_box(x_plus, -dir);
    plane.u = (forward >= backward ? forward : -backward) * dir;
  }
  plane.u *= fit_in_box(plane.c, plane.u);  // c + u inside the box (x_EI may have been clamped)
  correct_opposite_vertex(plane);
  plane.v = d > 1 ? best_tangent_v(model, plane, projector, best_mean, rng, settings)
                  : Eigen::VectorXd::Zero(d);
  const Eigen::VectorXd& scale = settings.perceptual_scale;
  if (scale.size() != d) return plane;

  // Shaped for a person as shape_for_person does, in the tangent space.
  if (!settings.keep_centre && plane.u_neg_scale < 0.5 && plane.u.norm() > 1e-9) {
    plane.c = plane.c + 0.5 * plane.u;  // c .. c + u, both inside the box
    plane.u = 0.5 * plane.u;
    plane.u_neg_scale = 1.0;
  }
  const double min_length = settings.min_plane_length;
  const double u_len = visible_length(plane.u, scale);
  if (u_len > 1e-12 && u_len < min_length) {
    const Eigen::VectorXd longer = fit_both_sides(plane.c, (min_length / u_len) * plane.u);
    if (visible_length(longer, scale) > u_len) plane.u = longer;
  }
  if (visible_length(plane.u, scale) < 0.5 * min_length) {
    // x_EI differs from x+ only where the eye cannot tell: the most visible tangent direction.
    const Eigen::VectorXd dir = most_visible_tangent_directions(projector, scale, 1).col(0);
    const double dir_len = visible_length(dir, scale);
    if (dir_len > 1e-12) {
      const Eigen::VectorXd visible = fit_both_sides(plane.c, (min_length / dir_len) * dir);
      if (visible_length(visible, scale) > visible_length(plane.u, scale)) plane.u = visible;
    }
  }
  correct_opposite_vertex(plane);
  if (d < 2) return plane;
  // v orthogonal to u in the perceptual metric, as long as min_length and half of u.
  const Eigen::VectorXd s2 = scale.cwiseProduct(scale);
  const double uu = plane.u.dot(s2.cwiseProduct(plane.u));
  Eigen::VectorXd v = plane.v;
  if (uu > 0.0) v -= (v.dot(s2.cwiseProduct(plane.u)) / uu) * plane.u;
  if (visible_length(v, scale) < 1e-9) v = visible_tangent_v(plane.c, plane.u, projector, scale);
  const double v_len = visible_length(v, scale);
  if (v_len > 1e-12) {
    const double wanted = std::max(
        {visible_length(plane.v, scale), 0.5 * visible_length(plane.u, scale), min_length});
    plane.v = fit_both_sides(plane.c, (wanted / v_len) * v);
  }
  return plane;
}

}  // namespace sps
