#include "sps/zoom_grid.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace sps {

namespace {

void check_grid(int n) {
  if (n < 1 || n % 2 == 0) {
    throw std::invalid_argument("grid size must be odd and positive, got " + std::to_string(n));
  }
}

}  // namespace

GridView grid_view(int n, const std::vector<GridCell>& path) {
  check_grid(n);
  GridView view;
  view.spacing = n > 1 ? 2.0 / static_cast<double>(n - 1) : 2.0;
  for (const GridCell& cell : path) {
    if (cell.col < 0 || cell.col >= n || cell.row < 0 || cell.row >= n) {
      throw std::invalid_argument("grid cell (" + std::to_string(cell.col) + ", " +
                                  std::to_string(cell.row) + ") is outside a " + std::to_string(n) +
                                  "x" + std::to_string(n) + " grid");
    }
    cell_coordinates(view, n, cell, view.s, view.t);
    view.spacing *= 0.5;
  }
  return view;
}

void cell_coordinates(const GridView& view, int n, const GridCell& cell, double& s, double& t) {
  const double half = 0.5 * static_cast<double>(n - 1);
  s = view.s + (static_cast<double>(cell.col) - half) * view.spacing;
  t = view.t + (half - static_cast<double>(cell.row)) * view.spacing;
}

std::vector<GridPoint> grid_points(const Plane& plane, int n, const GridView& view) {
  check_grid(n);
  std::vector<GridPoint> points;
  points.reserve(static_cast<std::size_t>(n * n));
  for (int row = 0; row < n; ++row) {
    for (int col = 0; col < n; ++col) {
      GridPoint p;
      cell_coordinates(view, n, {col, row}, p.s, p.t);
      const Eigen::VectorXd raw = plane.point(p.s, p.t);
      p.x = raw.cwiseMax(0.0).cwiseMin(1.0);
      // Tolerance: points on the boundary up to rounding are not "clamped".
      p.clamped = (p.x - raw).cwiseAbs().maxCoeff() > 1e-12;
      points.push_back(std::move(p));
    }
  }
  return points;
}

std::vector<GridPoint> grid_points(const Plane& plane, int n, const std::vector<GridCell>& path) {
  return grid_points(plane, n, grid_view(n, path));
}

GridView interpolate_views(const GridView& from, const GridView& to, double alpha) {
  alpha = std::min(1.0, std::max(0.0, alpha));
  GridView v;
  // Geometric interpolation of the scale; the centre moves so that the point which stays
  // fixed on screen is consistent with the scale change (a true zoom about a fixed point).
  const double ratio = to.spacing / from.spacing;
  v.spacing = from.spacing * std::pow(ratio, alpha);
  if (std::abs(ratio - 1.0) < 1e-12) {
    v.s = from.s + alpha * (to.s - from.s);
    v.t = from.t + alpha * (to.t - from.t);
  } else {
    // Fixed point p of the similarity mapping view `from` to view `to`:
    // p = from.centre + (to.centre - from.centre) / (1 - ratio).
    const double k = (v.spacing - from.spacing) / (to.spacing - from.spacing);
    v.s = from.s + k * (to.s - from.s);
    v.t = from.t + k * (to.t - from.t);
  }
  return v;
}

GridPoint chosen_point(const Plane& plane, int n, const std::vector<GridCell>& path) {
  if (path.empty()) throw std::invalid_argument("no cell has been clicked yet");
  const std::vector<GridCell> before(path.begin(), path.end() - 1);
  const GridView view = grid_view(n, before);
  GridPoint p;
  cell_coordinates(view, n, path.back(), p.s, p.t);
  const Eigen::VectorXd raw = plane.point(p.s, p.t);
  p.x = raw.cwiseMax(0.0).cwiseMin(1.0);
  p.clamped = (p.x - raw).cwiseAbs().maxCoeff() > 1e-12;
  return p;
}

}  // namespace sps
