#include "testing/simulated_user.hpp"

#include <algorithm>
#include <limits>

#include "sps/zoom_grid.hpp"

namespace sps {

UserAnswer argmax_user(const TestFunction& g, const Plane& plane, int resolution) {
  const Eigen::Index d = plane.c.size();
  Eigen::VectorXd x(d);
  Eigen::VectorXd best_x = plane.c;
  double best = -std::numeric_limits<double>::infinity();
  const auto consider = [&](double a_u, double b_v) {
    x = plane.c + a_u * plane.u;
    if (b_v != 0.0) x += b_v * plane.v;
    x = x.cwiseMax(0.0).cwiseMin(1.0);
    const double value = g(x);
    if (value > best) {
      best = value;
      best_x = x;
    }
  };
  if (plane.is_line()) {
    for (int i = 0; i < resolution; ++i) {
      consider(static_cast<double>(i) / static_cast<double>(resolution - 1), 0.0);
    }
  } else {
    for (int i = 0; i < resolution; ++i) {
      const double s = -1.0 + 2.0 * static_cast<double>(i) / static_cast<double>(resolution - 1);
      for (int j = 0; j < resolution; ++j) {
        const double t = -1.0 + 2.0 * static_cast<double>(j) / static_cast<double>(resolution - 1);
        const double a = 0.5 * (s + t);
        consider(a >= 0.0 ? a : a * plane.u_neg_scale, 0.5 * (s - t));
      }
    }
  }
  return {best_x, {}};
}

namespace {

// Index of the best point and the comparison "best > the others".
std::vector<Eigen::VectorXd> compare(const TestFunction& g, const std::vector<Eigen::VectorXd>& xs,
                                     int& best_index) {
  best_index = 0;
  double best = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const double value = g(xs[i]);
    if (value > best) {
      best = value;
      best_index = static_cast<int>(i);
    }
  }
  std::vector<Eigen::VectorXd> comparison{xs[static_cast<std::size_t>(best_index)]};
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (static_cast<int>(i) != best_index) comparison.push_back(xs[i]);
  }
  return comparison;
}

}  // namespace

UserAnswer zoom_user(const TestFunction& g, const Plane& plane, int n, int levels) {
  UserAnswer answer;
  if (plane.is_line()) {
    const int count = n * n;
    double centre = 0.5;  // along the segment c -> c + u
    double spacing = 1.0 / static_cast<double>(count - 1);
    for (int level = 0; level < levels; ++level) {
      std::vector<Eigen::VectorXd> xs;
      std::vector<double> as;
      for (int i = 0; i < count; ++i) {
        const double a = centre + (static_cast<double>(i) - 0.5 * (count - 1)) * spacing;
        as.push_back(a);
        xs.push_back((plane.c + a * plane.u).cwiseMax(0.0).cwiseMin(1.0));
      }
      int best = 0;
      answer.comparisons.push_back(compare(g, xs, best));
      answer.chosen = xs[static_cast<std::size_t>(best)];
      centre = as[static_cast<std::size_t>(best)];
      spacing *= 0.5;
    }
    return answer;
  }
  std::vector<GridCell> path;
  for (int level = 0; level < levels; ++level) {
    const std::vector<GridPoint> cells = grid_points(plane, n, path);
    std::vector<Eigen::VectorXd> xs;
    for (const GridPoint& p : cells) xs.push_back(p.x);
    int best = 0;
    answer.comparisons.push_back(compare(g, xs, best));
    answer.chosen = xs[static_cast<std::size_t>(best)];
    path.push_back({best % n, best / n});
  }
  return answer;
}

}  // namespace sps
