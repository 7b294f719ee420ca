// A search plane P(c, u, v): the rhombus with vertices c +- u and c +- v (DESIGN.md).
#pragma once

#include <Eigen/Core>

namespace sps {

struct Plane {
  Eigen::VectorXd c;  // centre: the current best point x+ (unless best_s, best_t say otherwise)
  Eigen::VectorXd u;  // first half-diagonal: x_EI - x+ (c + u is x_EI)
  Eigen::VectorXd v;  // second half-diagonal, orthogonal to u; zero for a line (SLS)
  // The paper's opposite-vertex correction: when c - u would leave [0,1]^n, that vertex is
  // moved along the diagonal to the boundary, i.e. it becomes c - u_neg_scale * u. The plane
  // stays flat; only the half on the c - u side is scaled along u.
  double u_neg_scale = 1.0;
  // Where on the plane the current best lies (the point the plane was built around, the
  // estimate of the design in mind or x+), in the grid coordinates of point(): (0, 0), c,
  // unless the plane was moved to keep its cells apart inside the box (then usually an edge
  // or a corner of its first grid).
  double best_s = 0.0;
  double best_t = 0.0;

  int dims() const { return static_cast<int>(c.size()); }
  bool is_line() const { return v.size() == 0 || v.isZero(0.0); }

  // Grid coordinates (s, t) in [-1, 1]^2 at the coarsest zoom level: the corners are the
  // vertices ((1,1) -> c+u, (-1,-1) -> c-u, (1,-1) -> c+v, (-1,1) -> c-v) and (0,0) is c.
  // Without the correction the map is affine, so rows of cells are straight lines.
  Eigen::VectorXd point(double s, double t) const {
    const double a = 0.5 * (s + t);  // coordinate along u
    const double b = 0.5 * (s - t);  // coordinate along v
    Eigen::VectorXd x = c + (a >= 0.0 ? a : a * u_neg_scale) * u;
    if (v.size() == c.size()) x += b * v;
    return x;
  }
  Eigen::VectorXd best() const { return point(best_s, best_t); }
  bool best_is_centre() const { return best_s == 0.0 && best_t == 0.0; }
};

}  // namespace sps
