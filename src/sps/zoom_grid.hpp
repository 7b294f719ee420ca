// Zoomable-grid geometry as pure functions: which parameter vector every visible cell shows,
// given a plane, the grid size n (odd) and the cells clicked so far.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "sps/plane.hpp"

namespace sps {

// A cell of the n x n grid: column (left to right) and row (top to bottom), 0-based.
struct GridCell {
  int col = 0;
  int row = 0;
  bool operator==(const GridCell& o) const { return col == o.col && row == o.row; }
};

// Where the grid centre sits in plane coordinates and how far apart cells are.
struct GridView {
  double s = 0.0;  // centre, plane coordinates
  double t = 0.0;
  double spacing = 1.0;  // distance between neighbouring cells in (s, t) units
};

struct GridPoint {
  Eigen::VectorXd x;  // parameter vector, always inside [0,1]^n
  double s = 0.0;     // plane coordinates before clamping
  double t = 0.0;
  bool clamped = false;  // the plane point left [0,1]^n and was clamped back
};

// The view after clicking `path` in order, starting from the coarsest level
// (spacing 2/(n-1); each click centres on the clicked cell and halves the spacing).
GridView grid_view(int n, const std::vector<GridCell>& path);

// Plane coordinates of a cell in a view (row 0 is the top: t grows upwards).
void cell_coordinates(const GridView& view, int n, const GridCell& cell, double& s, double& t);

// All n*n cells of the view, row-major from the top-left, clamped into the unit box.
std::vector<GridPoint> grid_points(const Plane& plane, int n, const GridView& view);
std::vector<GridPoint> grid_points(const Plane& plane, int n, const std::vector<GridCell>& path);

// A view between two views for animation (0 -> from, 1 -> to); spacing interpolates
// geometrically so the zoom feels uniform.
GridView interpolate_views(const GridView& from, const GridView& to, double alpha);

// The point finally chosen after clicking `path` (the last clicked cell), clamped.
GridPoint chosen_point(const Plane& plane, int n, const std::vector<GridCell>& path);

}  // namespace sps
